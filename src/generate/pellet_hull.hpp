// Internal: the cylinder that holds a level-set pellet (a cylinder, a ring, a multilobe), and
// the tests by which the pellet solver skips a pair, a circle or a group of nodes that lies
// outside a neighbour's hull and so presses nothing (pellet_bed.cpp, forces()).
//
// A pellet's hull here is the right circular cylinder about its axis with its length and the
// radius of the lobes' circle widened by a lobe's radius (the lobe's own radius for a cylinder
// or a ring): every point of the pellet, and so every node and circle on its surface, lies in
// it. A point outside a neighbour's hull is in no part of the neighbour, so its signed depth
// there is at most zero and it adds nothing to the pair's push.
#pragma once

#include <algorithm>
#include <cmath>

#include "packbed/vec3.hpp"

namespace packbed::detail {

/// A pellet's hull cylinder, in the bed's lengths.
struct HullCylinder {
    double half_length = 0.0, radius = 0.0;

    /// How far it reaches from its centre along the unit vector n, its axis `axis`:
    /// h |axis . n| + r sqrt(1 - (axis . n)^2), the support function of a cylinder.
    double extent(const Vec3& axis, const Vec3& n) const {
        const double c = dot(axis, n);
        return half_length * std::abs(c) + radius * std::sqrt(std::max(0.0, 1.0 - c * c));
    }
};

/// Whether a plane parts two hulls (`first` about the axis a, `second` about b, b's centre at u
/// from a's) with more than `margin` between them. Tried across the centres' line, each axis and
/// the axes' cross product: the planes that part two cylinders end to end, end to side and side
/// across side. A false answer does not say that they meet.
inline bool hulls_apart(const HullCylinder& first, const HullCylinder& second, const Vec3& a,
                        const Vec3& b, const Vec3& u, double margin) {
    const auto apart_across = [&](const Vec3& v) {
        const double length = norm(v);
        if (!(length > 1e-9))
            return false;
        const Vec3 n = v * (1.0 / length);
        return std::abs(dot(n, u)) - first.extent(a, n) - second.extent(b, n) > margin;
    };
    return apart_across(u) || apart_across(a) || apart_across(b) || apart_across(cross(a, b));
}

/// Whether every point within `radius` of `centre` (a point measured from the hull's centre)
/// whose extent along the hull's axis `axis` is at most `spread` lies outside the hull by more
/// than `margin`: beyond an end plane (|centre . axis| - spread) or farther from the axis than
/// its radius (the centre's distance less `radius`). A sphere has spread = radius; a circle of
/// radius R about the unit normal m, R sqrt(1 - (m . axis)^2).
inline bool clear_of_hull(const HullCylinder& hull, const Vec3& axis, const Vec3& centre,
                          double radius, double spread, double margin) {
    const double along = dot(centre, axis);
    if (std::abs(along) - spread > hull.half_length + margin)
        return true;
    return norm(centre - axis * along) - radius > hull.radius + margin;
}

} // namespace packbed::detail
