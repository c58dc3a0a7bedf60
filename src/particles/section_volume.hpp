// The volume of a pellet whose sections across its axis are star-shaped about it (a cylinder,
// a multilobe) inside a region, by integration over its sections (cylinder_shape.cpp,
// multilobe_shape.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

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

/// The volume of a prism of half-length h about the axis f.axis through `centre`, its section
/// the points at rho <= radius_at(phi) along w(phi) = cos(phi) e1 + sin(phi) e2 from the axis,
/// inside a region: the heights z_low..z_high and the side whose chords `chord(p, u)` gives
/// (Chord). By polar coordinates on each cross-section: the part of the ray from the axis point
/// c(t) along w(phi) inside the region is a few intervals of rho, their integral of rho d rho
/// in closed form; the angle and the axis by adaptive Gauss-Kronrod (15 points, Boost.Math),
/// the angle from `pieces` pieces of each interval between the angles `cuts` (where
/// radius_at has a kink), the axis from 16 pieces, relative tolerance `tolerance` and six
/// halvings each.
template <class ChordOf, class RadiusOf>
double region_volume(const Frame& f, const Vec3& centre, double h, double z_low, double z_high,
                     ChordOf&& chord, RadiusOf&& radius_at, const std::vector<double>& cuts,
                     int pieces_per_cut, double tolerance = 1e-8) {
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    auto ring = [&](double t, double phi) {
        const Vec3 c = centre + t * f.axis;
        const Vec3 w = std::cos(phi) * f.e1 + std::sin(phi) * f.e2;
        double lo = 0.0, hi = radius_at(phi);
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
    return pieces(section, -h, h, 16);
}

} // namespace packbed::detail
