// Containers: the walls a bed is packed against. voro++'s vocabulary: contains(), the overlap
// of a sphere with the wall and the wall normal. Every container has a rigid flat floor at z = 0
// and an open top. `Container` is the one place the rest of the library asks about a container
// (inside test, distance from the wall, cross-section, exact volumes, bounds); each shape
// (`Cylinder`, `Box`) answers for itself, and `Container` hands each question to its shape.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

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

/// Periodicity in x and y, a boundary of the cell [0, LX) x [0, LY) rather than a wall: a
/// sphere leaving one side comes back through the opposite one, and two spheres touch through
/// the sides by the minimum image (their nearest copies). What the searches, the solvers and
/// the exports ask of a periodic container (Container::periods). Immutable.
class Periods {
public:
    /// \param lx,ly the periods (length, > 0)
    Periods(double lx, double ly)
        : m_lx(lx)
        , m_ly(ly) {}

    double lx() const { return m_lx; }
    double ly() const { return m_ly; }

    /// \return p moved by whole periods into [0, LX) x [0, LY) (z unchanged).
    Vec3 wrapped(const Vec3& p) const {
        return {p.x - m_lx * std::floor(p.x / m_lx), p.y - m_ly * std::floor(p.y / m_ly), p.z};
    }
    /// \return the separation b - a between the nearest copies of a and b (minimum image),
    /// for |b - a| within one period and a half on each side: whole periods are taken off
    /// each of x and y while it exceeds half a period. -separation(a, b) == separation(b, a)
    /// to the bit.
    Vec3 separation(const Vec3& a, const Vec3& b) const {
        Vec3 d = b - a;
        const double hx = 0.5 * m_lx, hy = 0.5 * m_ly;
        if (d.x > hx)
            d.x -= m_lx;
        else if (d.x < -hx)
            d.x += m_lx;
        if (d.y > hy)
            d.y -= m_ly;
        else if (d.y < -hy)
            d.y += m_ly;
        return d;
    }

private:
    double m_lx, m_ly;
};

/// The hydraulic diameter 4 A / P of a container's cross-section (A its area, P its wetted
/// perimeter), with the formula in its spec's letters ("D - DI"); none for a container with
/// no wall, `formula` then says why ("is a periodic cell, it has no wall").
struct HydraulicDiameter {
    std::optional<double> value;
    std::string_view formula;
};

/// The length whose hundredth is the least margin of a data file's box beyond the container's
/// side (io.hpp's container_box_margin: max(Dp / 2, length / 100)), how the box's note words
/// that hundredth ("Rt/100") and names the container ("radius 5", or the spec); a length of 0
/// where the box is the container itself (a periodic cell).
struct BoxMargin {
    double length = 0.0;
    std::string_view words;
    std::string container;
};

/// A container's side as the LAMMPS engine's input writes it (docs/lammps.md): the x and y
/// boundary ("f f", or "p p" for a periodic cell), the data file's box in x and y (the side
/// and a margin of twice the set-back), the regions and harmonic wall fixes of each size
/// (type t + 1 of diameter diameters[t], each wall set back by `setback` and reaching the
/// radius and the set-back) and atom-style formulas of each wall's overlap (v_r the radius).
struct LammpsSide {
    std::string boundary = "f f";
    Rectangle box;
    std::string walls;
    std::vector<std::string> overlaps;
};

/// What every shape of `Container` answers (a part of it: the rest is in the class comments).
/// The wall law calls back f(overlap, push) once per wall a sphere presses into.
template <class C>
concept ContainerShape = requires(const C& c, const Vec3& p, double radius) {
    c.wall_contacts(p, radius, [](double, const Vec3&) {});
    { c.contains(p) } -> std::same_as<bool>;
    { c.wall_distance(p) } -> std::same_as<double>;
    { c.sphere_volume(p, radius, 0.0, 1.0) } -> std::same_as<double>;
    { c.cross_section_area() } -> std::same_as<double>;
    { c.spec() } -> std::same_as<std::string>;
};

/// The per-wall questions of the analysis (Container::profile_walls) for a shape whose
/// profiles are measured from one wall, "wall": its nearest-wall questions as they are (a box's
/// four faces count as one wall, the nearest; a corner counts with the nearer face).
template <class Shape> class OneProfileWall {
public:
    std::span<const std::string_view> profile_walls() const { return one_wall; }
    double wall_distance_from(std::size_t, const Vec3& p) const { return self().wall_distance(p); }
    std::pair<double, double> wall_distances_from(std::size_t, const Vec3& c, double r) const {
        return self().wall_distances(c, r);
    }
    Shape shrunk_from(std::size_t, double d) const { return self().shrunk(d); }
    double shell_area_from(std::size_t, double d_low, double d_high) const {
        return self().shell_area(d_low, d_high);
    }
    std::size_t nearest_wall(const Vec3&) const { return 0; }
    std::string_view profile_position_name_from(std::size_t) const {
        return self().profile_position_name();
    }
    double profile_position_from(std::size_t, double d) const { return self().profile_position(d); }

private:
    static constexpr std::array<std::string_view, 1> one_wall{"wall"};
    const Shape& self() const { return static_cast<const Shape&>(*this); }
};

/// A vertical cylinder of radius `radius` whose axis is the z axis (x = y = 0); the floor is
/// z = 0 and it is open at the top. Immutable after construction: safe to share between threads.
class Cylinder : public OneProfileWall<Cylinder> {
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

    /// The wall law as Box::wall_contacts has it: f(overlap, push) when the sphere presses
    /// into the wall (wall_contact's overlap > 0). Spheres clearly inside (centre closer to
    /// the axis than Rt - r - 1e-9 (Rt + 1)) skip the square root: the margin exceeds the
    /// rounding of wall_contact by far, so the answer is the same.
    template <class F> void wall_contacts(const Vec3& p, double radius, F&& f) const {
        const double inner = m_radius - radius - 1e-9 * (m_radius + 1.0);
        if (inner > 0.0 && p.x * p.x + p.y * p.y < inner * inner)
            return;
        if (const WallContact w = wall_contact(p, radius); w.overlap > 0.0)
            f(w.overlap, w.push);
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
    /// the ball: what g(r)'s shells and the wall profiles use. The two routines agree to 3e-9
    /// relative, not to the bit.
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// "cylinder:D", the form --container takes (D = 2 Rt, 9 significant digits).
    std::string spec() const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// The questions of the other stages, answered in container.cpp (see Container).
    std::optional<double> tube_diameter() const;
    std::optional<Periods> periods() const;
    HydraulicDiameter hydraulic_diameter() const;
    BoxMargin box_margin() const;
    std::string fit_problem(double largest) const;
    double fill_height(double solid, double e0) const;
    Vec3 uniform_point(double radius, double u, double v) const;
    std::vector<std::pair<double, double>> search_lines() const;
    nlohmann::json summary_json() const;
    nlohmann::ordered_json export_json(double height) const;
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;
    std::string_view name() const { return "cylinder"; }
    std::string_view axis() const { return "z through x = y = 0"; }
    Rectangle bounds() const { return {-m_radius, m_radius, -m_radius, m_radius}; }
    /// The wall profiles' first column: the distance from the axis, Rt - d.
    std::string_view profile_position_name() const { return "radial_position"; }
    double profile_position(double d) const { return m_radius - d; }

    /// \return how far the sphere (c, r) reaches beyond the wall, rho + r - Rt (<= 0 inside).
    double sticks_out(const Vec3& c, double r) const { return -wall_distances(c, r).first; }

private:
    double m_radius;
};

/// A rectangular box with four flat walls, x in [x_low, x_high], y in [y_low, y_high]; the
/// floor is z = 0 and it is open at the top. `--container box:LX,LY` is the box from (0, 0) to
/// (LX, LY). The distance from the wall is the distance from the nearest of the four faces, so
/// the set of points at least d from the wall is the box shrunk by d on every side, and a
/// profile against it counts a corner region with the face nearer to it (docs/analysis.md).
/// Immutable after construction.
class Box : public OneProfileWall<Box> {
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

    /// The wall law, face by face: call f(overlap, push) for each face the sphere (p, r)
    /// presses into, overlap = r - (distance of p from the face) > 0, push the face's inward
    /// normal. A sphere in a corner presses two faces; each pushes on its own, as each wall of
    /// the paper's eq. (4) would.
    template <class F> void wall_contacts(const Vec3& p, double radius, F&& f) const {
        if (const double o = radius - (p.x - m_x_low); o > 0.0)
            f(o, Vec3{1.0, 0.0, 0.0});
        if (const double o = radius - (m_x_high - p.x); o > 0.0)
            f(o, Vec3{-1.0, 0.0, 0.0});
        if (const double o = radius - (p.y - m_y_low); o > 0.0)
            f(o, Vec3{0.0, 1.0, 0.0});
        if (const double o = radius - (m_y_high - p.y); o > 0.0)
            f(o, Vec3{0.0, -1.0, 0.0});
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
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// The questions of the other stages, answered in container.cpp (see Container).
    std::optional<double> tube_diameter() const;
    std::optional<Periods> periods() const;
    HydraulicDiameter hydraulic_diameter() const;
    BoxMargin box_margin() const;
    std::string fit_problem(double largest) const;
    double fill_height(double solid, double e0) const;
    Vec3 uniform_point(double radius, double u, double v) const;
    std::vector<std::pair<double, double>> search_lines() const;
    nlohmann::json summary_json() const;
    nlohmann::ordered_json export_json(double height) const;
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;
    std::string_view name() const { return "box"; }
    std::string_view axis() const { return ""; }
    Rectangle bounds() const { return {m_x_low, m_x_high, m_y_low, m_y_high}; }
    /// The wall profiles' first column: the distance from the nearest face itself.
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

    /// \return how far the sphere (c, r) reaches beyond the nearest face, r - d (<= 0 inside).
    double sticks_out(const Vec3& c, double r) const { return -wall_distances(c, r).first; }

private:
    double m_x_low, m_x_high, m_y_low, m_y_high;
};

/// The space between a vertical tube of radius `outer_radius` and a coaxial rod (a
/// thermowell) of radius `inner_radius` < outer_radius, about the z axis; the floor is z = 0
/// and it is open at the top. Both walls are deformable as the paper's lateral wall.
/// `--container annulus:D,DI` is the annulus of D = 2 outer_radius, DI = 2 inner_radius. The
/// distance from the wall is the distance from the nearer of the two walls; the analysis also
/// measures each wall's own profile (docs/analysis.md). Immutable after construction.
class Annulus {
public:
    /// \param outer_radius the tube's inner radius R (length, > 0)
    /// \param inner_radius the rod's radius Ri (length, 0 <= Ri < R)
    Annulus(double outer_radius, double inner_radius)
        : m_outer(outer_radius)
        , m_inner(inner_radius) {}

    double outer_radius() const { return m_outer; }
    double inner_radius() const { return m_inner; }

    /// \return true if p lies between the rod and the tube above the floor.
    bool contains(const Vec3& p) const {
        const double rho2 = p.x * p.x + p.y * p.y;
        return p.z >= 0.0 && rho2 <= m_outer * m_outer && rho2 >= m_inner * m_inner;
    }

    /// The wall law of both walls, as Cylinder's for each: the tube, overlap rho + r - R,
    /// pushes towards the axis; the rod, overlap Ri + r - rho, pushes away from it (rho the
    /// centre's distance from the axis; no push on the axis itself).
    template <class F> void wall_contacts(const Vec3& p, double radius, F&& f) const {
        const double rho = std::sqrt(p.x * p.x + p.y * p.y);
        const Vec3 out = rho > 0.0 ? Vec3{p.x / rho, p.y / rho, 0.0} : Vec3{};
        if (const double o = rho + radius - m_outer; o > 0.0)
            f(o, out * -1.0);
        if (const double o = m_inner + radius - rho; o > 0.0)
            f(o, out);
    }

    /// \return the distance of p from the nearer wall, min(R - rho, rho - Ri).
    double wall_distance(const Vec3& p) const {
        const double rho = std::hypot(p.x, p.y);
        return std::min(m_outer - rho, rho - m_inner);
    }

    /// \return the nearest and farthest distance from the nearer wall of the points of the
    /// sphere (c, r): min(R - (rho + r), (rho - r) - Ri) and min(d + r, depth).
    std::pair<double, double> wall_distances(const Vec3& c, double r) const {
        const double rho = std::hypot(c.x, c.y);
        const double d = std::min(m_outer - rho, rho - m_inner);
        return {std::min(m_outer - (rho + r), (rho - r) - m_inner), std::min(d + r, depth())};
    }

    /// \return the largest distance from the walls inside: half the gap, (R - Ri) / 2.
    double depth() const { return 0.5 * (m_outer - m_inner); }

    /// The walls within `gap` of the sphere (c, r) as tangent planes at their points nearest
    /// the centre: the tube's (normal (x, y, 0) / rho, offset R) when R - rho - r < gap, the
    /// rod's (normal -(x, y, 0) / rho, offset -Ri) when rho - r - Ri < gap.
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;

    /// \return the cross-section, pi (R^2 - Ri^2).
    double cross_section_area() const;
    /// \return the area between the distances d_low <= d_high from the nearer wall.
    double shell_area(double d_low, double d_high) const;
    /// \return the points at least d >= 0 from both walls: the annulus of radii
    /// max(R - d, mid) and min(Ri + d, mid), mid = (R + Ri) / 2.
    Annulus shrunk(double d) const;

    /// Exact volume of the sphere (c, r) in the annulus between z_low and z_high: its volume
    /// inside the tube less its volume inside the rod (sphere_volume_in_cylinder_slab twice).
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    /// The same, by ball_volume_in_cylinder where the planes do not cut the ball.
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// "annulus:D,DI" (9 significant digits).
    std::string spec() const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// The questions of the other stages, answered in container.cpp (see Container).
    std::optional<double> tube_diameter() const;
    std::optional<Periods> periods() const;
    HydraulicDiameter hydraulic_diameter() const;
    BoxMargin box_margin() const;
    std::string fit_problem(double largest) const;
    double fill_height(double solid, double e0) const;
    Vec3 uniform_point(double radius, double u, double v) const;
    std::vector<std::pair<double, double>> search_lines() const;
    nlohmann::json summary_json() const;
    nlohmann::ordered_json export_json(double height) const;
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;
    std::string_view name() const { return "annulus"; }
    std::string_view axis() const { return "z through x = y = 0"; }
    Rectangle bounds() const { return {-m_outer, m_outer, -m_outer, m_outer}; }
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

    /// The walls the profiles are measured from: "outer" (the tube, wall 0) and "inner" (the
    /// rod, wall 1), each profile from its wall to the middle of the gap, (R + Ri) / 2.
    std::span<const std::string_view> profile_walls() const { return two_walls; }
    /// \return the distance of p from wall `wall`: R - rho (outer), rho - Ri (inner).
    double wall_distance_from(std::size_t wall, const Vec3& p) const {
        const double rho = std::hypot(p.x, p.y);
        return wall == 0 ? m_outer - rho : rho - m_inner;
    }
    /// \return the nearest and farthest distance from wall `wall` of the points of the sphere
    /// (c, r): R - (rho + r) and R - (rho - r) (outer); (rho - r) - Ri and (rho + r) - Ri
    /// (inner).
    std::pair<double, double> wall_distances_from(std::size_t wall, const Vec3& c, double r) const {
        const double rho = std::hypot(c.x, c.y);
        if (wall == 0)
            return {m_outer - (rho + r), m_outer - (rho - r)};
        return {(rho - r) - m_inner, (rho + r) - m_inner};
    }
    /// \return the points at least d >= 0 from wall `wall`, up to the middle of the gap:
    /// the annulus of radii max(R - d, mid) and Ri (outer), R and min(Ri + d, mid) (inner).
    /// Differences of volumes in these give the shells of that wall's profile only: the two
    /// profiles together cover the annulus once.
    Annulus shrunk_from(std::size_t wall, double d) const;
    /// \return the area between the distances d_low <= d_high from wall `wall` (up to the
    /// middle): shrunk_from(wall, d_low) less shrunk_from(wall, d_high).
    double shell_area_from(std::size_t wall, double d_low, double d_high) const;
    /// \return the wall nearer to p: 1 (inner) when rho - Ri < R - rho, else 0 (outer).
    std::size_t nearest_wall(const Vec3& p) const {
        const double rho = std::hypot(p.x, p.y);
        return rho - m_inner < m_outer - rho ? 1 : 0;
    }
    /// The first column of each wall's profiles: the distance from the axis.
    std::string_view profile_position_name_from(std::size_t) const { return "radial_position"; }
    /// \return the distance from the axis at d from wall `wall`: R - d or Ri + d.
    double profile_position_from(std::size_t wall, double d) const {
        return wall == 0 ? m_outer - d : m_inner + d;
    }
    /// \return how far the sphere (c, r) reaches beyond the nearer wall (<= 0 inside).
    double sticks_out(const Vec3& c, double r) const { return -wall_distances(c, r).first; }

private:
    static constexpr std::array<std::string_view, 2> two_walls{"outer", "inner"};
    double m_outer, m_inner;
};

/// A cell periodic in x and y, [0, LX) x [0, LY), with no side walls: a sphere leaving one
/// side comes back through the opposite one, and two spheres touch through the sides by the
/// minimum image (their nearest copies). The floor is z = 0 and it is open at the top. For
/// bulk statistics: the analysis measures it along z only. Every question about walls gets
/// "none": wall_distance is +infinity, depth 0 (no wall profile), no wall contacts. A sphere
/// cut by a side of the cell has its missing part inside through the opposite side, so its
/// volume in the cell is its whole volume between the heights. Immutable after construction.
class Periodic : public Periods {
public:
    /// \param lx,ly the cell's periods (length, > 0)
    Periodic(double lx, double ly)
        : Periods(lx, ly) {}

    /// \return true for every point above the floor: each is a copy of one in the cell.
    bool contains(const Vec3& p) const { return p.z >= 0.0; }
    /// No wall: f is never called.
    template <class F> void wall_contacts(const Vec3&, double, F&&) const {}
    /// The cell's periods.
    std::optional<Periods> periods() const { return Periods(*this); }

    double wall_distance(const Vec3&) const { return std::numeric_limits<double>::infinity(); }
    std::pair<double, double> wall_distances(const Vec3&, double) const {
        return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
    /// 0: there is no wall to measure a profile from.
    double depth() const { return 0.0; }
    std::vector<WallPlane> walls_within(const Vec3&, double, double) const { return {}; }
    /// \return the cross-section, LX LY.
    double cross_section_area() const { return lx() * ly(); }
    double shell_area(double, double) const { return 0.0; }
    Periodic shrunk(double) const { return *this; }
    /// The whole sphere between z_low and z_high (spherical segments): the parts beyond a
    /// side are inside through the opposite one. Exact for spheres narrower than the cell.
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
        return sphere_volume(c, r, z_low, z_high);
    }

    /// "periodic:LX,LY" (9 significant digits).
    std::string spec() const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// The questions of the other stages, answered in container.cpp (see Container).
    std::optional<double> tube_diameter() const;
    HydraulicDiameter hydraulic_diameter() const;
    BoxMargin box_margin() const;
    std::string fit_problem(double largest) const;
    double fill_height(double solid, double e0) const;
    Vec3 uniform_point(double radius, double u, double v) const;
    std::vector<std::pair<double, double>> search_lines() const;
    nlohmann::json summary_json() const;
    nlohmann::ordered_json export_json(double height) const;
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;
    std::string_view name() const { return "periodic"; }
    std::string_view axis() const { return ""; }
    Rectangle bounds() const { return {0.0, lx(), 0.0, ly()}; }
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

    /// No wall to measure a profile from: profile_walls is empty, and the questions about
    /// one wall (never asked) answer as for no wall.
    std::span<const std::string_view> profile_walls() const { return {}; }
    double wall_distance_from(std::size_t, const Vec3& p) const { return wall_distance(p); }
    std::pair<double, double> wall_distances_from(std::size_t, const Vec3& c, double r) const {
        return wall_distances(c, r);
    }
    Periodic shrunk_from(std::size_t, double) const { return *this; }
    double shell_area_from(std::size_t, double, double) const { return 0.0; }
    std::size_t nearest_wall(const Vec3&) const { return 0; }
    std::string_view profile_position_name_from(std::size_t) const { return "wall_distance"; }
    double profile_position_from(std::size_t, double d) const { return d; }
    /// \return how far the centre of the sphere lies outside the cell [0, LX] x [0, LY] (0
    /// inside; the radius does not count: a sphere across a side is inside through the other).
    double sticks_out(const Vec3& c, double) const {
        return std::max({0.0, -c.x, c.x - lx(), -c.y, c.y - ly()});
    }
};

static_assert(ContainerShape<Cylinder> && ContainerShape<Box> && ContainerShape<Annulus> &&
              ContainerShape<Periodic>);

/// A container of any shape: what generation, analysis and export ask. A Cylinder or a Box
/// converts to it implicitly. Every question goes to the shape (one std::visit each, in
/// container.cpp); code that only handles one shape so far asks `cylinder()` or `box()` and
/// refuses the others with a message naming the container. Plain value type.
class Container {
public:
    using Shape = std::variant<Cylinder, Box, Annulus, Periodic>;

    Container(const Cylinder& cylinder) // NOLINT(google-explicit-constructor): a cylinder is one
        : m_shape(cylinder) {}
    Container(const Box& box) // NOLINT(google-explicit-constructor)
        : m_shape(box) {}
    Container(const Annulus& annulus) // NOLINT(google-explicit-constructor)
        : m_shape(annulus) {}
    Container(const Periodic& periodic) // NOLINT(google-explicit-constructor)
        : m_shape(periodic) {}

    /// The shape itself, for the container's own files and for tests.
    const Shape& shape() const { return m_shape; }

    /// "cylinder", "box", "annulus" or "periodic".
    std::string_view name() const;
    /// The --container form: "cylinder:D", "box:LX,LY", "annulus:D,DI", "periodic:LX,LY".
    std::string spec() const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;

    /// The wall law of every wall: f(overlap, push) for each wall the sphere (p, radius)
    /// presses into (none in a periodic cell).
    template <class F> void wall_contacts(const Vec3& p, double radius, F&& f) const {
        std::visit([&](const auto& s) { s.wall_contacts(p, radius, f); }, m_shape);
    }
    /// \return the largest overlap of the sphere (p, radius) with a wall, 0 when it touches none.
    double wall_overlap(const Vec3& p, double radius) const {
        double largest = 0.0;
        wall_contacts(p, radius, [&](double o, const Vec3&) { largest = std::max(largest, o); });
        return largest;
    }
    /// \return the same container with every length times `factor` (> 0).
    Container scaled(double factor) const;

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

    /// The walls the wall profiles, centre distributions and wall contacts are measured from,
    /// each by name: {"wall"} for a cylinder and for a box (its four faces together: the
    /// distance from the nearest face), {"outer", "inner"} for an annulus (the tube and the
    /// rod, each to the middle of the gap), none for a periodic cell. A wall is named below by
    /// its index in this list.
    std::span<const std::string_view> profile_walls() const;
    /// \return the distance of p from wall `wall` (negative beyond it); for a container of
    /// one wall, wall_distance(p).
    double wall_distance_from(std::size_t wall, const Vec3& p) const;
    /// \return the nearest and farthest distance from wall `wall` of the points of the sphere
    /// (c, r); for a container of one wall, wall_distances(c, r).
    std::pair<double, double> wall_distances_from(std::size_t wall, const Vec3& c, double r) const;
    /// \return the points at least d from wall `wall` within that wall's part of the
    /// cross-section (up to the depth); for a container of one wall, shrunk(d).
    Container shrunk_from(std::size_t wall, double d) const;
    /// \return the area between the distances d_low <= d_high from wall `wall`; for a
    /// container of one wall, shell_area(d_low, d_high).
    double shell_area_from(std::size_t wall, double d_low, double d_high) const;
    /// \return the wall whose part of the cross-section holds p (the nearer wall; the first
    /// on a tie).
    std::size_t nearest_wall(const Vec3& p) const;
    /// The first column of wall `wall`'s profile tables and its value at d from that wall.
    std::string_view profile_position_name_from(std::size_t wall) const;
    double profile_position_from(std::size_t wall, double d) const;
    /// \return how far the sphere (c, r) sticks out of the container sideways (<= 0: not at
    /// all): beyond the nearest wall (the cylinder, a box face, the tube or the rod), or, in a
    /// periodic cell, how far its centre lies outside [0, LX] x [0, LY].
    double sticks_out(const Vec3& c, double r) const;

    /// The diameter D of a tube, where the published correlations for tubes apply as written
    /// at the aspect ratio a = D / Dp (the paper's eq. (6), Dixon's and de Klerk's void
    /// fractions, the radial profiles, the wall correction of pressure drops); nothing for
    /// another shape, which a front end then names by its spec.
    std::optional<double> tube_diameter() const;
    /// The periods of a container periodic in x and y (a boundary, not a wall: pairs by the
    /// minimum image, centres wrapped into the cell); nothing for one with side walls.
    std::optional<Periods> periods() const;
    /// The hydraulic diameter 4 A / P and its formula (none without a wall).
    HydraulicDiameter hydraulic_diameter() const;
    /// The length that sets a data file's box margin beyond the side, and its words.
    BoxMargin box_margin() const;
    /// Why a bed of spheres of diameter up to `largest` (lengths in Dp) cannot be packed in
    /// the container ("widths from 1 Dp ... to 10000 Dp": what is allowed), empty if it can.
    std::string fit_problem(double largest) const;
    /// The height of a bed of spheres whose diameters cubed (in Dp) add to `solid`, at void
    /// fraction e0: (pi / 6) solid / (A (1 - e0)); the paper's eq. (6) for a tube.
    double fill_height(double solid, double e0) const;
    /// A point of the floor uniform over the part of the cross-section a centre of radius
    /// `radius` reaches, from two uniform numbers u, v in [0, 1).
    Vec3 uniform_point(double radius, double u, double v) const;
    /// Eight vertical lines (x, y) inside the container, off its symmetries, along which to
    /// search for a point of the fluid far from every surface (the OpenFOAM case's
    /// locationInMesh).
    std::vector<std::pair<double, double>> search_lines() const;
    /// The axis of a container of revolution in summary.json's words ("z through x = y = 0"),
    /// empty for a prism.
    std::string_view axis() const;
    /// The container in summary.json: its shape, its lengths and spec.
    nlohmann::json summary_json() const;
    /// The container in an export's packbed.json: its shape, lengths and `height`.
    nlohmann::ordered_json export_json(double height) const;
    /// The side's walls in the LAMMPS engine's input, one fix per size.
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;

private:
    Shape m_shape;
};

/// A container as users write it, in length units, the one form every front end takes:
/// `cylinder:D`, a tube of inner diameter D (the axis is the z axis, the floor z = 0);
/// `box:LX,LY`, four flat walls at x = 0, LX and y = 0, LY; `annulus:D,DI`, the space between
/// the tube of diameter D and a coaxial rod of diameter DI < D; `periodic:LX,LY`, a cell
/// periodic in x and y, [0, LX) x [0, LY), with no side walls.
struct ContainerSpec {
    std::string shape;     ///< "cylinder", "box", "annulus" or "periodic"
    double diameter = 0.0; ///< a cylinder's or annulus's D, > 0
    double inner = 0.0;    ///< an annulus's DI, 0 < DI < D
    double lx = 0.0;       ///< a box's or cell's widths, > 0
    double ly = 0.0;
    /// \return the library's container.
    Container container() const;
};

/// \return the container of `text` ("cylinder:D", "box:LX,LY", "annulus:D,DI",
/// "periodic:LX,LY"; every length in (0, limits::max_length], diameters up to twice that), or
/// nothing when it is not one.
std::optional<ContainerSpec> parse_container(std::string_view text);

/// What --container allows, as both front ends word it (the command line's validator and
/// --help, the library's InvalidInput, so the Python module's ValueError): each of `shapes`
/// ("cylinder", "box", "annulus", "periodic", as all_shapes in container.hpp) as its SPEC,
/// what it is and its ranges, joined by "; or ".
std::string allowed_containers(std::span<const std::string_view> shapes);
/// The message for a --container SPEC that parse_container refuses, the command line's words:
/// "--container: 'SPEC' is not allowed; allowed: " and allowed_containers of every shape.
std::string container_not_allowed(std::string_view option, std::string_view spec);

/// "radius R" for a cylinder, its spec (box:LX,LY, ...) for the others: a container in messages.
std::string describe(const Container& container);

/// The shapes parse_container takes.
inline const std::vector<std::string_view> all_shapes{"cylinder", "box", "annulus", "periodic"};

} // namespace packbed
