// The annulus: a tube with a coaxial rod (a thermowell).
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/shape.hpp"
#include <array>

namespace packbed {

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

    /// "annulus:D,DI" (9 significant digits; `exact`: the shortest text of each double).
    std::string spec(bool exact = false) const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// --container's word for the shape, "annulus:D,DI" its SPEC.
    static constexpr std::string_view kind = "annulus";
    /// The SPEC in letters, as messages list it.
    static constexpr std::string_view form = "annulus:D,DI";
    /// The hydraulic diameter 4 A / P in the SPEC's letters ("": none).
    static constexpr std::string_view hydraulic_formula = "D - DI";
    std::string_view name() const { return kind; }
    PACKBED_SHAPE_ANSWERS(Annulus);
    PACKBED_PRISM_HEIGHTS
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
    double shell_area_from(std::size_t wall, double d_low, double d_high, double, double) const;
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

} // namespace packbed
