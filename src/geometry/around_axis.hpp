// What the containers about the z axis ask of a convex body through its support function
// (Container::convex_wall_contacts, side_chord): its extremes over the directions around the
// axis, and where a line crosses a circle about it.
#pragma once

#include <cmath>
#include <numbers>

#include "packbed/shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed::detail {

/// Where f(phi) is largest over the directions around the axis, and its value there.
struct AroundAxis {
    double phi = 0.0;
    double value = 0.0;
};

/// \return the maximum of f(phi) over the directions phi around the axis: f at 64 directions
/// from phi0, then golden-section search on the two steps about the best to 1e-12 rad (a
/// function with one maximum there: the support function of a body small beside the wall's
/// curvature).
template <class F> AroundAxis maximum_around_axis(F&& f, double phi0) {
    constexpr int scan = 64;
    constexpr double step = 2.0 * std::numbers::pi / scan;
    double best_phi = phi0, best = f(phi0);
    for (int k = 1; k < scan; ++k) {
        const double phi = phi0 + step * k;
        if (const double v = f(phi); v > best) {
            best = v;
            best_phi = phi;
        }
    }
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = best_phi - step, b = best_phi + step;
    double c = b - ratio * (b - a), d = a + ratio * (b - a);
    double fc = f(c), fd = f(d);
    while (b - a > 1e-12) {
        if (fc > fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d);
        }
    }
    if (best >= fc && best >= fd)
        return {best_phi, best};
    return fc > fd ? AroundAxis{c, fc} : AroundAxis{d, fd};
}

/// The horizontal unit vector at angle phi.
inline Vec3 around_axis(double phi) {
    return {std::cos(phi), std::sin(phi), 0.0};
}

/// The tube of radius `radius` about the z axis seen from inside: the body's farthest point
/// from the axis, the maximum over the horizontal directions u of u . support(u), and its depth
/// beyond the tube, pushed back along -u.
inline ConvexWallContact beyond_tube(const SupportFunction& support, const Vec3& centre,
                                     double radius) {
    const AroundAxis far = maximum_around_axis(
        [&](double phi) {
            const Vec3 u = around_axis(phi);
            return dot(u, support(u));
        },
        std::atan2(centre.y, centre.x));
    const Vec3 u = around_axis(far.phi);
    return {far.value - radius, -1.0 * u, support(u)};
}

/// \return the parameters s where the line p + s u lies within distance `radius` of the z axis
/// (the roots of |p_xy + s u_xy|^2 = radius^2, in the form free of cancellation); the whole
/// line when it is vertical and inside, nothing when it misses.
inline Chord inside_circle(const Vec3& p, const Vec3& u, double radius) {
    const double a = u.x * u.x + u.y * u.y;
    const double b = p.x * u.x + p.y * u.y;
    const double c = p.x * p.x + p.y * p.y - radius * radius;
    if (a == 0.0)
        return c <= 0.0 ? Chord::whole() : Chord{};
    const double disc = b * b - a * c;
    if (!(disc > 0.0) || !(radius > 0.0))
        return {};
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    const double s1 = q / a, s2 = c / q;
    return Chord::between(std::min(s1, s2), std::max(s1, s2));
}

} // namespace packbed::detail
