// The cylinder: a tube about the z axis (the paper's container).
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/shape.hpp"

namespace packbed {

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
    template <class F>
    [[gnu::always_inline]] void wall_contacts(const Vec3& p, double radius, F&& f) const {
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

    /// "cylinder:D", the form --container takes (D = 2 Rt, 9 significant digits; `exact`: the
    /// shortest text that reads back as the same double).
    std::string spec(bool exact = false) const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// --container's word for the shape, "cylinder:D" its SPEC.
    static constexpr std::string_view kind = "cylinder";
    /// The SPEC in letters, as messages list it.
    static constexpr std::string_view form = "cylinder:D";
    /// The hydraulic diameter 4 A / P in the SPEC's letters ("": none).
    static constexpr std::string_view hydraulic_formula = "D";
    std::string_view name() const { return kind; }
    PACKBED_SHAPE_ANSWERS(Cylinder);
    PACKBED_PRISM_HEIGHTS
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

} // namespace packbed
