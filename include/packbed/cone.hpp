// The cone: a frustum about the z axis whose diameter changes linearly with height (a hopper,
// the conical outlet of a pebble bed, or a tube narrowing upwards).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/shape.hpp"

namespace packbed {

/// A frustum about the z axis: a floor of radius Rb at z = 0, a lateral wall whose radius
/// R(z) = Rb + k z (k = (Rt - Rb) / H) reaches Rt at z = H, open at the top. The wall is the
/// cone's whole surface (below the floor and above H as well); a bed must stay below H, where
/// the frustum ends (top()). Distances from the wall are along its normal: in the half-plane
/// through the axis and a point at distance rho from it, d = cos(theta) (R(z) - rho), theta the
/// wall's angle from the vertical (cos theta = H / L, sin theta = (Rt - Rb) / L, L the slant
/// height sqrt(H^2 + (Rt - Rb)^2)). With Rb = Rt it is a cylinder, and its answers are the
/// cylinder's to the bit where they decide a bed (the wall law, the initial height and
/// points). Immutable after construction: safe to share between threads.
class Cone : public OneProfileWall<Cone> {
public:
    /// \param floor_radius Rb (> 0) \param top_radius Rt (> 0) \param height H (> 0)
    Cone(double floor_radius, double top_radius, double height);

    double floor_radius() const { return m_rb; }
    double top_radius() const { return m_rt; }
    double height() const { return m_h; }
    /// \return the radius of the wall at height z, Rb + k z (negative beyond the apex).
    double radius_at(double z) const { return m_rb + m_slope * z; }

    /// \return true if p lies above the floor within the wall (rho <= R(z)).
    bool contains(const Vec3& p) const {
        const double r = radius_at(p.z);
        return p.z >= 0.0 && r >= 0.0 && p.x * p.x + p.y * p.y <= r * r;
    }

    /// Overlap of a sphere with the slanted wall, the paper's deformable wall: how far the
    /// sphere reaches beyond it along its normal, delta = cos(theta) (rho - R(z)) + r, formed
    /// as (cos rho + r) - cos R(z) (the cylinder's (rho + r) - Rt when cos = 1), and the push
    /// along the inward normal (-cos x / rho, -cos y / rho, sin theta): up the wall of a hopper,
    /// down the wall of a cone that narrows. \return the overlap (<= 0: no contact) and the
    /// push (zero vector on the axis).
    WallContact wall_contact(const Vec3& p, double radius) const {
        return contact_at(p, radius, radius_at(p.z));
    }

    /// The wall law: f(overlap, push) when the sphere presses into the wall. Spheres clearly
    /// inside (closer to the axis than R(z) - r / cos - 1e-9 (R + 1)) skip the square root.
    /// Inlined as the cylinder's is: this is the solvers' innermost call.
    template <class F>
    [[gnu::always_inline]] void wall_contacts(const Vec3& p, double radius, F&& f) const {
        const double wall = radius_at(p.z);
        const double inner = wall - radius * m_inv_cos - 1e-9 * (m_reach + 1.0);
        if (inner > 0.0 && p.x * p.x + p.y * p.y < inner * inner)
            return;
        if (const WallContact w = contact_at(p, radius, wall); w.overlap > 0.0)
            f(w.overlap, w.push);
    }

    /// \return the distance of p from the wall along its normal, cos (R(z) - rho) (negative
    /// outside).
    double wall_distance(const Vec3& p) const {
        return m_cos * (radius_at(p.z) - std::hypot(p.x, p.y));
    }
    /// \return the nearest and farthest distance from the wall of the points of the sphere
    /// (c, r): d(c) - r and d(c) + r (d changes at most as fast as the distance travelled).
    std::pair<double, double> wall_distances(const Vec3& c, double r) const {
        const double d = wall_distance(c);
        return {d - r, d + r};
    }
    /// \return the largest distance from the wall at the heights z_low to z_high: cos
    /// max(R(z_low), R(z_high), 0), on the axis.
    double depth(double z_low, double z_high) const {
        return m_cos * std::max({radius_at(z_low), radius_at(z_high), 0.0});
    }

    /// The plane tangent to the wall at its point nearest the centre, normal (cos x / rho,
    /// cos y / rho, -sin), offset cos Rb, when d(c) - r < gap; none on the axis.
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;

    /// \return the mean over the heights z_low to z_high of the cross-section pi R(z)^2 (0
    /// beyond the apex): the frustum's volume between them over z_high - z_low, in closed
    /// form; pi R(z_low)^2 when z_high <= z_low.
    double cross_section_area(double z_low, double z_high) const;
    /// \return the mean over the heights of the area between the distances d_low <= d_high
    /// from the wall: the difference of the cross-sections of shrunk(d_low), shrunk(d_high).
    double shell_area(double d_low, double d_high, double z_low, double z_high) const;
    /// \return the points at least d from the wall: the cone of the same slope whose radii
    /// are d / cos smaller.
    Cone shrunk(double d) const;

    /// Volume of the sphere (c, r) inside the cone between z_low and z_high, by
    /// sphere_volume_in_cone_slab (volume.hpp: relative error below 1e-8).
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
        return sphere_volume(c, r, z_low, z_high);
    }

    /// "cone:DB,DT,H", the numbers as the shortest text that reads back to the same bits
    /// (`exact` or not).
    std::string spec(bool exact = false) const;
    /// How a message names it: "a cone (cone:4,8,20)".
    std::string describe() const;
    /// --container's word for the shape, "cone:DB,DT,H" its SPEC.
    static constexpr std::string_view kind = "cone";
    /// The SPEC in letters, as messages list it.
    static constexpr std::string_view form = "cone:DB,DT,H";
    /// The hydraulic diameter 4 A / P in the SPEC's letters ("": none).
    static constexpr std::string_view hydraulic_formula = "";
    std::string_view name() const { return kind; }
    PACKBED_SHAPE_ANSWERS(Cone);
    std::string_view axis() const { return "z through x = y = 0"; }
    /// The square about the wall's widest circle between the floor and H.
    Rectangle bounds() const { return {-m_reach, m_reach, -m_reach, m_reach}; }
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }
    /// \return how far the sphere (c, r) reaches beyond the wall (<= 0 inside).
    double sticks_out(const Vec3& c, double r) const { return -wall_distances(c, r).first; }

private:
    Cone(double floor_radius, double top_radius, double height, double slope, double cos_theta,
         double sin_theta);
    /// wall_contact with the wall's radius at the sphere's height, `wall` = R(p.z).
    WallContact contact_at(const Vec3& p, double radius, double wall) const {
        const double r = std::sqrt(p.x * p.x + p.y * p.y);
        const double overlap = (m_cos * r + radius) - m_cos * wall;
        if (overlap <= 0.0 || r == 0.0)
            return {overlap, {}};
        return {overlap, {-m_cos * p.x / r, -m_cos * p.y / r, m_sin}};
    }

    double m_rb, m_rt, m_h;
    double m_slope; // k = (Rt - Rb) / H
    double m_cos, m_sin;
    double m_inv_cos; // 1 / cos theta
    double m_reach;   // max(Rb, Rt)
};

/// Volume of the cone x^2 + y^2 <= R(z)^2, R(z) = rb + slope z (none where R(z) < 0), between
/// the heights z_low and z_high: \f$\frac{\pi}{3} h (R_1^2 + R_1 R_2 + R_2^2)\f$ (the frustum,
/// R_1 and R_2 the radii at its ends, cut at the apex); 0 when z_high <= z_low.
double frustum_volume(double rb, double slope, double z_low, double z_high);

/// Volume of the part of a sphere inside the cone x^2 + y^2 <= R(z)^2, R(z) = rb + slope z,
/// and between the planes z = z_low and z = z_high: as sphere_volume_in_cylinder_slab, with
/// the wall's radius linear in z. The slice at each height is the lens of two disks
/// (disk_intersection_area), integrated over z by the same mapped 20-point Gauss-Legendre rule
/// on the pieces between the heights where the slice's circle touches the wall's (the roots
/// of two quadratics), the equator and the apex; planes-only and wall-only pieces in closed
/// form. Relative error below 1e-8 (measured against tanh-sinh at 1e-14 over random cones
/// and spheres: at most 2.7e-9, test_cone).
/// \param center,radius the sphere (radius > 0) \param rb the wall's radius at z = 0 (may be
/// negative: a cone whose apex is above the floor) \param slope dR/dz
double sphere_volume_in_cone_slab(const Vec3& center, double radius, double rb, double slope,
                                  double z_low, double z_high);

} // namespace packbed
