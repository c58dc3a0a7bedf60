// Containers: the walls a bed is packed against. voro++'s vocabulary: contains(), the overlap
// of a sphere with the wall and the wall normal. Every container has a rigid flat floor at z = 0
// and an open top. `Container` is the one place the rest of the library asks about a container
// (inside test, distance from the wall, cross-section, exact volumes, bounds); each shape
// (`Cylinder`, `Box`) answers for itself, and `Container` hands each question to its shape.
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "packbed/vec3.hpp"

namespace packbed {

/// How deep a sphere presses into a deformable wall and which way the wall pushes back.
struct WallContact {
    double overlap = 0.0; ///< penetration depth (length); <= 0 means no contact
    Vec3 push; ///< unit vector along which the wall pushes the sphere (into the container)
};

/// The rectangle [x_low, x_high] x [y_low, y_high] a container's cross-section lies in.
struct Rectangle {
    double x_low = 0.0;
    double x_high = 0.0;
    double y_low = 0.0;
    double y_high = 0.0;
};

/// A plane tangent to a container's lateral wall from inside: the points x with
/// dot(normal, x) <= offset are on the container's side of it (normal of unit length, pointing
/// out of the container, horizontal).
struct WallPlane {
    Vec3 normal;
    double offset = 0.0;
};

/// What the soft-sphere loops need from a container. The loops are templated on it, so the
/// wall law inlines. Another container (annulus, box) is another type meeting this concept.
template <class C>
concept LateralWall = requires(const C& c, const Vec3& p, double radius) {
    { c.wall_contact(p, radius) } -> std::same_as<WallContact>;
    { c.contains(p) } -> std::same_as<bool>;
};

/// A vertical cylinder of radius `radius` whose axis is the z axis (x = y = 0); the floor is
/// z = 0 and it is open at the top. Immutable after construction: safe to share between threads.
class Cylinder {
public:
    /// \param radius container radius Rt (length, > 0)
    explicit Cylinder(double radius)
        : m_radius(radius) {}

    /// \return the container radius Rt.
    double radius() const { return m_radius; }

    /// \return true if the point lies inside the cylinder above the floor (z >= 0, r <= Rt).
    bool contains(const Vec3& p) const {
        return p.z >= 0.0 && p.x * p.x + p.y * p.y <= m_radius * m_radius;
    }

    /// Overlap of a sphere with the lateral wall, Salvat et al. (2005) nomenclature:
    /// \f$\delta_{iw} = (r_i + D_p/2) - R_t\f$, with the push along \f$-\hat r\f$ (towards the
    /// axis). \param p sphere centre \param radius sphere radius (length, > 0) \return the overlap
    /// (<= 0: no contact) and the push direction (zero vector on the axis).
    WallContact wall_contact(const Vec3& p, double radius) const {
        const double r = std::sqrt(p.x * p.x + p.y * p.y);
        const double overlap = r + radius - m_radius;
        if (overlap <= 0.0 || r == 0.0)
            return {overlap, {}};
        return {overlap, {-p.x / r, -p.y / r, 0.0}};
    }

    /// \return the distance of p from the wall, Rt - sqrt(x^2 + y^2) (negative outside).
    double wall_distance(const Vec3& p) const { return m_radius - std::hypot(p.x, p.y); }

    /// \return the nearest and farthest distance from the wall of the points of the sphere
    /// (c, r): Rt - (rho + r) and Rt - (rho - r), rho the centre's distance from the axis.
    std::pair<double, double> wall_distances(const Vec3& c, double r) const {
        const double rho = std::hypot(c.x, c.y);
        return {m_radius - (rho + r), m_radius - (rho - r)};
    }

    /// \return the largest distance from the wall inside, Rt (on the axis).
    double depth() const { return m_radius; }

    /// The wall where it comes within `gap` of the sphere (c, r), as planes: the one tangent
    /// to the cylinder at the wall's point nearest the centre, normal (x, y, 0) / rho, offset
    /// Rt, when Rt - rho - r < gap; none for a centre on the axis (rho = 0).
    /// \param gap length (may be 0 or negative: walls the sphere reaches into)
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;

    /// \return the cross-section, pi Rt^2.
    double cross_section_area() const;

    /// \return the area of the cross-section between the distances d_low <= d_high from the
    /// wall: pi (a^2 - b^2), a = max(Rt - d_low, 0), b = max(Rt - d_high, 0).
    double shell_area(double d_low, double d_high) const;

    /// \return the points at least d >= 0 from the wall: the cylinder of radius max(Rt - d, 0).
    Cylinder shrunk(double d) const { return Cylinder(std::max(m_radius - d, 0.0)); }

    /// Exact volume of the sphere (c, r) inside the cylinder between z_low and z_high
    /// (sphere_volume_in_cylinder_slab; 0 when the radius is 0).
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// The same volume, by ball_volume_in_cylinder (5 times faster) when the planes do not cut
    /// the ball: what g(r)'s shells use. The two routines agree to 3e-9 relative, not to the bit.
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// "cylinder:D", the form --container takes (D = 2 Rt, 9 significant digits).
    std::string spec() const;
    std::string_view name() const { return "cylinder"; }
    Rectangle bounds() const { return {-m_radius, m_radius, -m_radius, m_radius}; }
    /// The wall profiles' first column: the distance from the axis, Rt - d.
    std::string_view profile_position_name() const { return "radial_position"; }
    double profile_position(double d) const { return m_radius - d; }

private:
    double m_radius;
};

static_assert(LateralWall<Cylinder>);

/// A rectangular box with four flat walls, x in [x_low, x_high], y in [y_low, y_high]; the
/// floor is z = 0 and it is open at the top. `--container box:LX,LY` is the box from (0, 0) to
/// (LX, LY). The distance from the wall is the distance from the nearest of the four faces, so
/// the set of points at least d from the wall is the box shrunk by d on every side, and a
/// profile against it counts a corner region with the face nearer to it (docs/analysis.md).
/// Not yet a LateralWall: a sphere in a corner presses two walls at once, and the generators
/// come with issue 17. Immutable after construction.
class Box {
public:
    /// The box from (0, 0) to (lx, ly). \param lx,ly widths (length, >= 0)
    Box(double lx, double ly)
        : Box(0.0, lx, 0.0, ly) {}
    /// The box [x_low, x_high] x [y_low, y_high] (x_low <= x_high, y_low <= y_high).
    Box(double x_low, double x_high, double y_low, double y_high)
        : m_x_low(x_low)
        , m_x_high(x_high)
        , m_y_low(y_low)
        , m_y_high(y_high) {}

    double x_low() const { return m_x_low; }
    double x_high() const { return m_x_high; }
    double y_low() const { return m_y_low; }
    double y_high() const { return m_y_high; }

    /// \return true if the point lies inside the box above the floor.
    bool contains(const Vec3& p) const {
        return p.z >= 0.0 && p.x >= m_x_low && p.x <= m_x_high && p.y >= m_y_low && p.y <= m_y_high;
    }

    /// \return the distance of p from the nearest face (negative outside).
    double wall_distance(const Vec3& p) const {
        return std::min(std::min(p.x - m_x_low, m_x_high - p.x),
                        std::min(p.y - m_y_low, m_y_high - p.y));
    }

    /// \return the nearest and farthest distance from the wall of the points of the sphere
    /// (c, r), bounded by the depth: d - r and min(d + r, depth), d the centre's.
    std::pair<double, double> wall_distances(const Vec3& c, double r) const {
        const double d = wall_distance(c);
        return {d - r, std::min(d + r, depth())};
    }

    /// \return the largest distance from the wall inside: half the narrower width.
    double depth() const { return 0.5 * std::min(m_x_high - m_x_low, m_y_high - m_y_low); }

    /// The faces that come within `gap` of the sphere (c, r) (the centre's distance from the
    /// face less r below gap), in the order x_low, x_high, y_low, y_high: a sphere in a corner
    /// gets two. Normals -x, +x, -y, +y; offsets -x_low, x_high, -y_low, y_high.
    /// \param gap length (may be 0 or negative)
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;

    /// \return the cross-section, LX LY.
    double cross_section_area() const;

    /// \return the area between the distances d_low <= d_high from the wall: the rectangle
    /// shrunk by d_low less the one shrunk by d_high.
    double shell_area(double d_low, double d_high) const;

    /// \return the points at least d >= 0 from every face: the box shrunk by d on each side
    /// (a segment or a point at the middle when d reaches the depth).
    Box shrunk(double d) const;

    /// Exact volume of the sphere (c, r) inside the box between z_low and z_high
    /// (sphere_volume_in_box; 0 when the box has no area).
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// The same as sphere_volume (there is no faster routine for a box).
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
        return sphere_volume(c, r, z_low, z_high);
    }

    /// "box:LX,LY" (9 significant digits); a box not at the origin adds "@X,Y", its corner.
    std::string spec() const;
    std::string_view name() const { return "box"; }
    Rectangle bounds() const { return {m_x_low, m_x_high, m_y_low, m_y_high}; }
    /// The wall profiles' first column: the distance from the nearest face itself.
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

private:
    double m_x_low, m_x_high, m_y_low, m_y_high;
};

/// A container of any shape: what generation, analysis and export ask. A Cylinder or a Box
/// converts to it implicitly. Every question goes to the shape (one std::visit each, in
/// container.cpp); code that only handles one shape so far asks `cylinder()` or `box()` and
/// refuses the others with a message naming the container. Plain value type.
class Container {
public:
    using Shape = std::variant<Cylinder, Box>;

    Container(const Cylinder& cylinder) // NOLINT(google-explicit-constructor): a cylinder is one
        : m_shape(cylinder) {}
    Container(const Box& box) // NOLINT(google-explicit-constructor)
        : m_shape(box) {}

    const Shape& shape() const { return m_shape; }
    /// \return the cylinder, or nullptr for another shape.
    const Cylinder* cylinder() const { return std::get_if<Cylinder>(&m_shape); }
    /// \return the box, or nullptr for another shape.
    const Box* box() const { return std::get_if<Box>(&m_shape); }

    /// "cylinder" or "box".
    std::string_view name() const;
    /// The --container form: "cylinder:D", "box:LX,LY".
    std::string spec() const;

    bool contains(const Vec3& p) const;
    /// Distance of p from the nearest lateral wall (negative outside): the coordinate of the
    /// wall profiles.
    double wall_distance(const Vec3& p) const;
    /// Nearest and farthest distance from the wall of the points of a sphere.
    std::pair<double, double> wall_distances(const Vec3& c, double r) const;
    /// The largest distance from the wall inside.
    double depth() const;
    /// The wall within `gap` of the sphere (c, r) as tangent planes (the cylinder's at the
    /// nearest point, each box face that near): where the contact treatments cut.
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;
    double cross_section_area() const;
    /// Area of the cross-section between two distances from the wall.
    double shell_area(double d_low, double d_high) const;
    /// The points at least d from the wall, as a container of the same shape.
    Container shrunk(double d) const;
    /// Exact volume of a sphere inside the container between two heights.
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    /// The same, by the faster routine where there is one (g(r); agrees to 3e-9 relative).
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const;
    /// The rectangle the cross-section lies in.
    Rectangle bounds() const;

    /// The first column of the wall profiles' tables: "radial_position" (the distance from
    /// the axis, Rt - d) for a cylinder, "wall_distance" (d) for a box.
    std::string_view profile_position_name() const;
    /// The position written in that column for the distance d from the wall.
    double profile_position(double d) const;

private:
    Shape m_shape;
};

} // namespace packbed
