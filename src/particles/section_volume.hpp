// The volume of a pellet whose sections across its axis are star-shaped about it (a cylinder,
// a multilobe) inside a region, by integration over its sections (cylinder_shape.cpp,
// multilobe_shape.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include "packbed/box.hpp"
#include "packbed/container.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed::detail {

/// A pellet's body frame in the bed: its axis and two directions across it.
struct Frame {
    Vec3 e1, e2, axis;
};

inline Frame frame_of(const Placement& p) {
    return {rotate(p.orientation, {1.0, 0.0, 0.0}), rotate(p.orientation, {0.0, 1.0, 0.0}),
            rotate(p.orientation, {0.0, 0.0, 1.0})};
}

/// The area of the part of a disc of radius r with in-plane coordinate w <= x along a
/// direction: r^2 acos(-x / r) + x sqrt(r^2 - x^2), 0 below -r and pi r^2 above r.
inline double disc_below(double r, double x) {
    if (x <= -r)
        return 0.0;
    if (x >= r)
        return std::numbers::pi * r * r;
    return r * r * std::acos(-x / r) + x * std::sqrt((r - x) * (r + x));
}

/// The volume of a cylinder (radius r, half-length h, placed by p) between the heights z_low
/// and z_high: each cross-section is a disc cut by two parallel chords, its area in closed form
/// (disc_below); integrated along the axis by tanh-sinh quadrature on the pieces between the
/// positions where a chord meets the rim (the area is analytic inside each piece, with square-
/// root ends that tanh-sinh takes at full accuracy).
inline double slab_volume(const Frame& f, const Vec3& centre, double r, double h, double z_low,
                          double z_high) {
    const double az = f.axis.z;
    const double g = std::sqrt(std::max(0.0, 1.0 - az * az)); // the disc's steepest slope
    if (g < 1e-12) {
        // Upright: each disc at one height; the axis' part between the planes.
        if (std::abs(az) == 0.0)
            return 0.0;
        const double t1 = (z_low - centre.z) / az, t2 = (z_high - centre.z) / az;
        const double lo = std::max(-h, std::min(t1, t2)), hi = std::min(h, std::max(t1, t2));
        return hi > lo ? std::numbers::pi * r * r * (hi - lo) : 0.0;
    }
    auto area = [&](double t) {
        const double cz = centre.z + t * az;
        return disc_below(r, (z_high - cz) / g) - disc_below(r, (z_low - cz) / g);
    };
    std::vector<double> cuts{-h, h};
    if (az != 0.0)
        for (const double plane : {z_low, z_high})
            for (const double side : {-1.0, 1.0})
                if (const double t = (plane - centre.z - side * r * g) / az; t > -h && t < h)
                    cuts.push_back(t);
    std::sort(cuts.begin(), cuts.end());
    const std::size_t n = cuts.size();
    thread_local boost::math::quadrature::tanh_sinh<double> rule;
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i)
        if (cuts[i + 1] > cuts[i])
            total += rule.integrate(area, cuts[i], cuts[i + 1], 1e-13);
    return total;
}

/// The volume of a solid about the axis f.axis through `centre` between the axial positions
/// t_low and t_high, its section at t the points at rho <= radius_at(t, phi) along w(phi) =
/// cos(phi) e1 + sin(phi) e2 from the axis, inside a region: the heights z_low..z_high and the side
/// whose chords `chord(p, u)` gives (Chord). By polar coordinates on each cross-section: the part
/// of the ray from the axis point c(t) along w(phi) inside the region is a few intervals of rho,
/// their integral of rho d rho in closed form; the angle and the axis by adaptive Gauss-Kronrod (15
/// points, Boost.Math), the angle from `pieces` pieces of each interval between the angles `cuts`
/// (where radius_at has a kink), the axis from `axis_pieces` pieces, relative tolerance `tolerance`
/// and six halvings each.
template <class ChordOf, class RadiusOf>
double region_volume_over(const Frame& f, const Vec3& centre, double t_low, double t_high,
                          int axis_pieces, double z_low, double z_high, ChordOf&& chord,
                          RadiusOf&& radius_at, const std::vector<double>& cuts, int pieces_per_cut,
                          double tolerance = 1e-8) {
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    auto ring = [&](double t, double phi) {
        const Vec3 c = centre + t * f.axis;
        const Vec3 w = std::cos(phi) * f.e1 + std::sin(phi) * f.e2;
        double lo = 0.0, hi = radius_at(t, phi);
        if (w.z > 0.0) {
            lo = std::max(lo, (z_low - c.z) / w.z);
            hi = std::min(hi, (z_high - c.z) / w.z);
        } else if (w.z < 0.0) {
            lo = std::max(lo, (z_high - c.z) / w.z);
            hi = std::min(hi, (z_low - c.z) / w.z);
        } else if (c.z < z_low || c.z > z_high) {
            return 0.0;
        }
        if (!(hi > lo))
            return 0.0;
        const Chord side = chord(c, w);
        double sum = 0.0;
        for (std::size_t k = 0; k < side.count; ++k) {
            const double a = std::max(lo, side.parts[k].low), b = std::min(hi, side.parts[k].high);
            if (b > a)
                sum += 0.5 * (b - a) * (b + a);
        }
        return sum;
    };
    // Each integral starts from pieces so that no part of the region narrower than a piece
    // goes unseen by the rule's first nodes.
    auto pieces = [tolerance](auto&& integrand, double a, double b, int n) {
        double sum = 0.0;
        for (int k = 0; k < n; ++k)
            sum += Kronrod::integrate(integrand, a + (b - a) * k / n, a + (b - a) * (k + 1) / n, 6,
                                      tolerance);
        return sum;
    };
    auto section = [&](double t) {
        double sum = 0.0;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            sum += pieces([&](double phi) { return ring(t, phi); }, cuts[k], cuts[k + 1],
                          pieces_per_cut);
        return sum;
    };
    return pieces(section, t_low, t_high, axis_pieces);
}

/// region_volume_over the prism's whole length, -h .. h in 16 pieces, its section the same at
/// every t.
template <class ChordOf, class RadiusOf>
double region_volume(const Frame& f, const Vec3& centre, double h, double z_low, double z_high,
                     ChordOf&& chord, RadiusOf&& radius_at, const std::vector<double>& cuts,
                     int pieces_per_cut, double tolerance = 1e-8) {
    return region_volume_over(
        f, centre, -h, h, 16, z_low, z_high, chord,
        [&](double, double phi) { return radius_at(phi); }, cuts, pieces_per_cut, tolerance);
}

/// A pellet's volume in an axis-aligned box (a voxel's cover): none where its bounding sphere
/// misses the box's columns, else its volume_in the box as a container between the box's
/// heights.
template <class Shape>
double volume_in_box(const Shape& shape, const Placement& p, const Vec3& low, const Vec3& high) {
    const double reach = shape.bounding_radius(p.size);
    const Vec3& o = p.position;
    if (o.x + reach <= low.x || o.x - reach >= high.x || o.y + reach <= low.y ||
        o.y - reach >= high.y)
        return 0.0;
    const Container box(Box(low.x, high.x, low.y, high.y));
    return shape.volume_in(box, p, low.z, high.z);
}

} // namespace packbed::detail
