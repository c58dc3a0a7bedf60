#include "packbed/cylinder_shape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include <ccd/ccd.h>

#include "packbed/box.hpp"
#include "packbed/volume.hpp"
#include "section_volume.hpp"
#include "surface_search.hpp"

namespace packbed {

namespace {

constexpr double pi = std::numbers::pi;
using detail::disc_below;
using detail::Frame;
using detail::frame_of;
using detail::region_volume;
using detail::slab_volume;

/// One pellet as libccd sees it: its shape and placement.
struct CcdBody {
    const CylinderShape* shape;
    Placement placement;
};

void ccd_support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto* body = static_cast<const CcdBody*>(object);
    const Vec3 s =
        body->shape->support(body->placement, {direction->v[0], direction->v[1], direction->v[2]});
    ccdVec3Set(out, s.x, s.y, s.z);
}

void ccd_centre(const void* object, ccd_vec3_t* out) {
    const auto* body = static_cast<const CcdBody*>(object);
    const Vec3& c = body->placement.position;
    ccdVec3Set(out, c.x, c.y, c.z);
}

void ccd_first_direction(const void* a, const void* b, ccd_vec3_t* out) {
    const Vec3 d = static_cast<const CcdBody*>(b)->placement.position -
                   static_cast<const CcdBody*>(a)->placement.position;
    if (dot(d, d) > 0.0)
        ccdVec3Set(out, d.x, d.y, d.z);
    else
        ccdVec3Set(out, 1.0, 0.0, 0.0);
}

/// The area of the section at height z of a cylinder (radius r, half-length h, frame f, centre
/// c) inside the disc of radius `radius` about the z axis, in closed form.
/// - An upright axis: the section is a disc of radius r (or nothing), its lens with the disc.
/// - A level axis: a rectangle (half-width sqrt(r^2 - (z - c_z)^2) across, L/2 along), met
///   with the disc by disk_rectangle_area in the rectangle's frame.
/// - Otherwise the section is the ellipse of semi-axes r / |a_z| along the axis' horizontal
///   direction u and r across it, about the point where the axis meets the plane, cut by the
///   end planes' two lines across u; its part inside the disc is summed by Green's theorem,
///   the integral of (x dy - y dx) / 2 about the disc's centre over each piece of the three
///   boundaries (ellipse arcs, each as its segment and chord; end chords; circle arcs) that
///   lies inside the other two, the pieces split where the boundaries cross. (About the
///   ellipse's centre, 1e4 radii away for a pellet lying 1e-5 from level, the rounding of the
///   arcs' angles came out 1e-7 of the area.) The ellipse meets the circle where a trigonometric
///   polynomial of degree two vanishes: 96 pieces of the turn, each halved until its tangent and a
///   bound on its second derivative show it holds no root or one (then found by Newton's steps
///   within the bracket), so that two crossings close together (a pellet poking a little through
///   the wall) are found.
double section_in_disc(const Frame& f, const Vec3& c, double r, double h, double z, double radius) {
    const Vec3& a = f.axis;
    const double g = std::hypot(a.x, a.y);
    if (g < 1e-12) {
        if (std::abs(z - c.z) > h)
            return 0.0;
        return disk_intersection_area(r, radius, std::hypot(c.x, c.y));
    }
    const Vec3 u{a.x / g, a.y / g, 0.0}, v{-u.y, u.x, 0.0};
    // Nearly level (|a_z| below 1e-7): the ellipse's part between the end lines is an arc of
    // the turn about 2 h |a_z| / r wide, beyond what its angle resolves; the level cylinder
    // about the same centre is the true one turned by at most 1e-7, its surface moved by less
    // than 1e-7 of the bounding radius.
    if (std::abs(a.z) < 1e-7) {
        const double dz = z - c.z;
        if (std::abs(dz) >= r)
            return 0.0;
        const double w = std::sqrt((r - dz) * (r + dz));
        // The rectangle about the centre's projection, the disc's centre (the axis) at
        // (-c . u, -c . v) in its frame: shift to put the disc at the origin.
        const double cu = c.x * u.x + c.y * u.y, cv = c.x * v.x + c.y * v.y;
        return disk_rectangle_area(radius, cu - h, cu + h, cv - w, cv + w);
    }
    // The ellipse: centre q, semi-axes big along u and r along v; the end lines at x_lo, x_hi
    // (x along u from q): |t + x g| <= h with t the axis parameter at height z.
    const double t = (z - c.z) / a.z;
    const double qx = c.x + t * a.x, qy = c.y + t * a.y;
    const double big = r / std::abs(a.z);
    const double x_lo = std::max(-big, (-h - t) / g), x_hi = std::min(big, (h - t) / g);
    if (!(x_hi > x_lo))
        return 0.0;
    // The disc's centre (the z axis) in the ellipse's frame.
    const double dx = -(qx * u.x + qy * u.y), dy = -(qx * v.x + qy * v.y);
    bool clear = false;
    // The section lies in the box [x_lo, x_hi] x [-r, r]. A box all outside the disc (by 1e-9
    // of its radius squared) holds none of it; one all inside has no crossing that bounds a
    // piece of the section, and the search below is skipped (the sum is the same: the
    // crossings it would find lie outside the strip, on arcs not counted).
    {
        const double near_x = std::clamp(dx, x_lo, x_hi), near_y = std::clamp(dy, -r, r);
        const double far_x = std::max(std::abs(x_lo - dx), std::abs(x_hi - dx));
        const double far_y = std::max(std::abs(-r - dy), std::abs(r - dy));
        const double nearest = (near_x - dx) * (near_x - dx) + (near_y - dy) * (near_y - dy);
        const double radius2 = radius * radius;
        if (nearest > radius2 * (1.0 + 1e-9))
            return 0.0;
        clear = far_x * far_x + far_y * far_y < radius2 * (1.0 - 1e-9);
    }
    auto in_ellipse = [&](double x, double y) {
        return (x / big) * (x / big) + (y / r) * (y / r) <= 1.0;
    };
    auto in_strip = [&](double x) { return x >= x_lo && x <= x_hi; };
    auto in_disc = [&](double x, double y) {
        return (x - dx) * (x - dx) + (y - dy) * (y - dy) <= radius * radius;
    };
    // Where the ellipse (angle theta) meets the circle: the roots of
    // meet = (big cos - dx)^2 + (r sin - dy)^2 - radius^2
    //      = (big^2 - r^2) cos(2 theta) / 2 - 2 big dx cos - 2 r dy sin + const.
    // meet and its derivative from one sine and cosine of the angle.
    // With its second and third derivatives:
    // meet'' = -2 A cos(2 theta) + 2 big dx cos + 2 r dy sin,
    // meet''' = 4 A sin(2 theta) - 2 big dx sin + 2 r dy cos, A = big^2 - r^2.
    struct Value {
        double f, df, d2, d3;
    };
    const double a2 = big * big - r * r, bx = 2.0 * big * dx, ry = 2.0 * r * dy;
    const auto at = [&](double cos_t, double sin_t) {
        const double x = big * cos_t - dx, y = r * sin_t - dy;
        const double cos2 = (cos_t - sin_t) * (cos_t + sin_t), sin2 = 2.0 * sin_t * cos_t;
        return Value{x * x + y * y - radius * radius, 2.0 * (r * cos_t * y - big * sin_t * x),
                     -2.0 * a2 * cos2 + bx * cos_t + ry * sin_t,
                     4.0 * a2 * sin2 - bx * sin_t + ry * cos_t};
    };
    const auto meet = [&](double theta) { return at(std::cos(theta), std::sin(theta)); };
    // A bound on |meet''| over an interval of width w about its middle m: the least of its
    // amplitudes' sum, `second`, and Taylor's |meet''(m)| + |meet'''(m)| w / 2 + fourth w^2 / 8,
    // `fourth` the amplitudes' bound on |meet''''| (with a margin of 1e-12 second for the
    // rounding of meet''(m)). Taylor's is far the smaller near the tip of a long ellipse (a
    // pellet lying 1e-6 from level: big 4.6e5 r, where the cos(2 theta) and cos terms of meet''
    // cancel; there `second` alone had each section halved thousands of times). meet differs
    // from its tangent at m by at most that bound times w^2 / 8, so the interval holds no root
    // where |meet(m)| exceeds |meet'(m)| w / 2 + bound w^2 / 8, and at most one where meet'
    // keeps its sign (|meet'(m)| > bound w / 2), found by Newton's steps kept inside the bracket
    // (halving it where a step would leave it) where the ends' signs differ. Others are halved:
    // a pellet that pokes a little through the wall meets it twice within a small angle,
    // between any fixed samples. (A bounded count of halvings: a circle that is the ellipse
    // itself has meet = 0 throughout.)
    const double amplitude = std::hypot(bx, ry);
    const double second = 2.0 * std::abs(a2) + amplitude;
    const double fourth = 8.0 * std::abs(a2) + amplitude;
    const auto curvature = [&](const Value& m, double w) {
        return std::min(second, std::abs(m.d2) + 0.5 * std::abs(m.d3) * w + 0.125 * fourth * w * w +
                                    1e-12 * second);
    };
    std::vector<double> crossings; // ellipse angles
    const auto root = [&](double lo, double hi, double flo, double x, Value val) {
        for (int it = 0; it < 100 && val.f != 0.0 && hi - lo > 1e-15; ++it) {
            if ((val.f < 0.0) == (flo < 0.0)) {
                lo = x;
                flo = val.f;
            } else {
                hi = x;
            }
            const double step = val.df != 0.0 ? x - val.f / val.df : lo - 1.0;
            const double next = step > lo && step < hi ? step : 0.5 * (lo + hi);
            if (next == x)
                break;
            x = next;
            val = meet(x);
        }
        crossings.push_back(x);
    };
    // The angles of the ellipse's part in the strip, [first, last] and its mirror
    // [2 pi - last, 2 pi - first] (grown by 1e-9 rad): a crossing elsewhere lies on arcs that
    // are not counted, so pieces of the turn outside them are not searched.
    const double first = std::acos(std::clamp(x_hi / big, -1.0, 1.0)) - 1e-9;
    const double last = std::acos(std::clamp(x_lo / big, -1.0, 1.0)) + 1e-9;
    const auto in_strip_turn = [&](double lo, double hi) {
        return (hi >= first && lo <= last) || (hi >= 2.0 * pi - last && lo <= 2.0 * pi - first);
    };
    int budget = 20000; // halvings, for the whole turn
    const auto search = [&](auto&& self, double lo, double hi, double flo, double fhi, Value m,
                            int depth) -> void {
        if (!in_strip_turn(lo, hi))
            return;
        const double width = hi - lo, mid = 0.5 * (lo + hi);
        const bool change = (flo < 0.0) != (fhi < 0.0);
        const double bound = curvature(m, width);
        if (!change && std::abs(m.f) > 0.5 * std::abs(m.df) * width + 0.125 * bound * width * width)
            return;
        if (std::abs(m.df) > 0.5 * bound * width || depth >= 48 || --budget < 0) {
            if (change)
                root(lo, hi, flo, mid, m);
            return;
        }
        const double left = 0.5 * (lo + mid), right = 0.5 * (mid + hi);
        self(self, lo, mid, flo, m.f, meet(left), depth + 1);
        self(self, mid, hi, m.f, fhi, meet(right), depth + 1);
    };
    // The 96 pieces' ends and middles: the turn in 192 steps, their sines and cosines once.
    constexpr int samples = 96;
    static const std::array<std::pair<double, double>, 2 * samples + 1> turn = [] {
        std::array<std::pair<double, double>, 2 * samples + 1> table{};
        for (int k = 0; k <= 2 * samples; ++k)
            table[static_cast<std::size_t>(k)] = {std::cos(pi * k / samples),
                                                  std::sin(pi * k / samples)};
        return table;
    }();
    const auto sample = [&](int k) {
        const auto& [cos_t, sin_t] = turn[static_cast<std::size_t>(k)];
        return at(cos_t, sin_t);
    };
    double previous = sample(0).f;
    for (int k = 1; k <= (clear ? 0 : samples); ++k) {
        const double lo = 2.0 * pi * (k - 1) / samples, hi = 2.0 * pi * k / samples;
        const double value = sample(2 * k).f;
        search(search, lo, hi, previous, value, sample(2 * k - 1), 0);
        previous = value;
    }
    double area = 0.0;
    // The ellipse's arcs: split at the end lines and the circle.
    {
        std::vector<double> cuts = crossings;
        for (const double x : {x_lo, x_hi})
            if (std::abs(x) < big) {
                const double theta = std::acos(x / big);
                cuts.push_back(theta);
                cuts.push_back(2.0 * pi - theta);
            }
        detail::for_each_arc(cuts, [&](double t1, double t2) {
            const double mid = 0.5 * (t1 + t2);
            const double x = big * std::cos(mid), y = r * std::sin(mid);
            if (in_strip(x) && in_disc(x, y)) { // the segment, then the chord about the centre
                const double x1 = big * std::cos(t1) - dx, y1 = r * std::sin(t1) - dy;
                const double x2 = big * std::cos(t2) - dx, y2 = r * std::sin(t2) - dy;
                area += 0.5 * big * r * ((t2 - t1) - std::sin(t2 - t1)) + 0.5 * (x1 * y2 - y1 * x2);
            }
        });
    }
    // The end chords: x = x_hi upwards, x = x_lo downwards, inside the ellipse; split where
    // they cross the circle.
    for (const double x : {x_hi, x_lo}) {
        if (!(std::abs(x) < big))
            continue;
        const double half = r * std::sqrt(std::max(0.0, 1.0 - (x / big) * (x / big)));
        std::vector<double> ys{-half, half};
        const double across = radius * radius - (x - dx) * (x - dx);
        if (across > 0.0)
            for (const double y : {dy - std::sqrt(across), dy + std::sqrt(across)})
                if (y > -half && y < half)
                    ys.push_back(y);
        std::sort(ys.begin(), ys.end());
        const double sign = x == x_hi ? 1.0 : -1.0; // upwards on the right, down on the left
        for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
            const double y1 = ys[k], y2 = ys[k + 1];
            if (in_disc(x, 0.5 * (y1 + y2)))
                area += 0.5 * sign * (x - dx) * (y2 - y1); // about the disc centre, along x = const
        }
    }
    // The circle's arcs: split at the ellipse and the end lines.
    {
        std::vector<double> cuts;
        for (const double theta : crossings)
            cuts.push_back(std::atan2(r * std::sin(theta) - dy, big * std::cos(theta) - dx));
        for (const double x : {x_lo, x_hi})
            if (std::abs(x - dx) < radius) {
                const double phi = std::acos((x - dx) / radius);
                cuts.push_back(phi);
                cuts.push_back(-phi);
            }
        for (double& phi : cuts)
            if (phi < 0.0)
                phi += 2.0 * pi;
        detail::for_each_arc(cuts, [&](double p1, double p2) {
            const double mid = 0.5 * (p1 + p2);
            const double x = dx + radius * std::cos(mid), y = dy + radius * std::sin(mid);
            if (in_strip(x) && in_ellipse(x, y))
                area += 0.5 * radius * radius * (p2 - p1);
        });
    }
    return area;
}

/// The volume of the cylinder between two heights inside the disc of radius `radius` about
/// the z axis: section_in_disc integrated over the height by adaptive Gauss-Kronrod (15
/// points, relative tolerance 1e-9 above 1e-13 of the pellet's volume: integrate_with_floor) on
/// the pieces between the heights where an end's rim has its highest and lowest point (where
/// the section changes its kind).
double disc_volume(const Frame& f, const Vec3& centre, double r, double h, double z_low,
                   double z_high, double radius) {
    const double g = std::hypot(f.axis.x, f.axis.y);
    std::vector<double> cuts{z_low, z_high};
    for (const double end : {-h, h})
        for (const double side : {-r, r})
            if (const double z = centre.z + end * f.axis.z + side * g; z > z_low && z < z_high)
                cuts.push_back(z);
    auto area = [&](double z) { return section_in_disc(f, centre, r, h, z, radius); };
    // An absolute floor of 1e-13 of the pellet's volume under the relative tolerance: a piece
    // holding 1e-9 of it (the thin pieces at the top and bottom of a pellet lying near level)
    // asks 1e-18, below the sections' rounding, and would run its whole tree of halvings.
    return detail::integrate_between_cuts(area, std::move(cuts), 1e-13 * 2.0 * pi * r * r * h);
}

/// Two cylinders as the penetration depth sees them: each one's axis, radius and half-length,
/// the first at the origin and the second's centre at c.
struct CylinderPair {
    Vec3 a, b, c;
    double ra, ha, rb, hb;

    /// The pellets a (at the origin) and b (its centre at ab) at their placements.
    static CylinderPair of(const CylinderShape& first, const Placement& a,
                           const CylinderShape& second, const Placement& b, const Vec3& ab) {
        return {rotate(a.orientation, {0.0, 0.0, 1.0}),
                rotate(b.orientation, {0.0, 0.0, 1.0}),
                ab,
                first.radius * a.size,
                first.half_length * a.size,
                second.radius * b.size,
                second.half_length * b.size};
    }
    /// The support of the Minkowski difference first - second along the unit u:
    /// R_a |u x a| + H_a |u . a| + R_b |u x b| + H_b |u . b| - u . c.
    double support(const Vec3& u) const {
        const double ua = dot(u, a), ub = dot(u, b);
        return ra * std::sqrt(std::max(0.0, 1.0 - ua * ua)) + ha * std::abs(ua) +
               rb * std::sqrt(std::max(0.0, 1.0 - ub * ub)) + hb * std::abs(ub) - dot(u, c);
    }
    /// Its gradient where it is smooth (u . a, u . b not 0, u not +-a, +-b).
    Vec3 gradient(const Vec3& u) const {
        const double ua = dot(u, a), ub = dot(u, b);
        const double sa = std::sqrt(std::max(1e-300, 1.0 - ua * ua));
        const double sb = std::sqrt(std::max(1e-300, 1.0 - ub * ub));
        return (ra / sa) * (u - ua * a) + (ha * (ua > 0.0 ? 1.0 : -1.0)) * a +
               (rb / sb) * (u - ub * b) + (hb * (ub > 0.0 ? 1.0 : -1.0)) * b - c;
    }
};

/// Two unit vectors across the unit vector n.
std::pair<Vec3, Vec3> across(const Vec3& n) {
    const Vec3 helper = std::abs(n.x) < 0.6 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const Vec3 e1 = cross(n, helper) * (1.0 / norm(cross(n, helper)));
    return {e1, cross(n, e1)};
}

/// The least of f over the great circle across n: 720 angles, then golden-section search about
/// each of the three lowest to 1e-13 rad. Returns the value and the direction.
template <class F> std::pair<double, Vec3> least_on_circle(F&& f, const Vec3& n) {
    const std::pair<Vec3, Vec3> frame = across(n);
    auto at = [&](double t) { return std::cos(t) * frame.first + std::sin(t) * frame.second; };
    constexpr int scan = 720;
    constexpr double step = 2.0 * pi / scan;
    std::array<std::pair<double, double>, scan> values;
    for (int k = 0; k < scan; ++k)
        values[k] = {f(at(k * step)), k * step};
    std::partial_sort(values.begin(), values.begin() + 3, values.end());
    std::pair<double, Vec3> best{values[0].first, at(values[0].second)};
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int m = 0; m < 3; ++m) {
        double lo = values[m].second - step, hi = values[m].second + step;
        double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
        double f1 = f(at(x1)), f2 = f(at(x2));
        while (hi - lo > 1e-13) {
            if (f1 < f2) {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - ratio * (hi - lo);
                f1 = f(at(x1));
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + ratio * (hi - lo);
                f2 = f(at(x2));
            }
        }
        if (f1 < best.first)
            best = {f1, at(x1)};
        if (f2 < best.first)
            best = {f2, at(x2)};
    }
    return best;
}

/// The penetration depth of two cylinders, exactly: the least over the unit directions u of
/// the support h(u) of their Minkowski difference (CylinderPair::support; the distance from the
/// origin, which it holds when they overlap, to its boundary; negative when they are apart, the
/// gap across the widest separating plane), and its direction. h is smooth but on the great
/// circles u . a = 0 and u . b = 0 (a side in contact) and at u = +-a, +-b (an end face), so its
/// least value lies at one of these: the ends' normals +-a, +-b; the circles' crossings
/// +-(a x b) / |a x b|; the least along each circle (least_on_circle); a smooth minimum
/// between, reached by gradient descent on the sphere (Armijo's backtracking) from `start` and
/// from the lowest of 400 directions spread over the sphere (a Fibonacci lattice).
std::pair<double, Vec3> cylinder_depth(const CylinderPair& pair, const Vec3& start) {
    auto h = [&](const Vec3& u) { return pair.support(u); };
    std::pair<double, Vec3> best{h(pair.a), pair.a};
    auto consider = [&](const Vec3& u) {
        const Vec3 unit = u * (1.0 / norm(u));
        if (const double v = h(unit); v < best.first)
            best = {v, unit};
    };
    for (const Vec3& u : {-1.0 * pair.a, pair.b, -1.0 * pair.b})
        consider(u);
    if (const Vec3 ab = cross(pair.a, pair.b); norm(ab) > 1e-12) {
        consider(ab);
        consider(-1.0 * ab);
    }
    for (const Vec3& axis : {pair.a, pair.b})
        if (const auto on = least_on_circle(h, axis); on.first < best.first)
            best = on;
    // Smooth minima: descend from the start and from the lowest of a spread of directions.
    constexpr int spread = 400;
    Vec3 lowest = start;
    double lowest_value = h(start);
    const double golden = pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < spread; ++k) {
        const double z = 1.0 - 2.0 * (k + 0.5) / spread, rho = std::sqrt(1.0 - z * z);
        const Vec3 u{rho * std::cos(golden * k), rho * std::sin(golden * k), z};
        if (const double v = h(u); v < lowest_value) {
            lowest_value = v;
            lowest = u;
        }
    }
    for (Vec3 u : {start, lowest}) {
        u = u * (1.0 / norm(u));
        double value = h(u), step = 0.1;
        for (int iteration = 0; iteration < 500 && step > 1e-16; ++iteration) {
            Vec3 g = pair.gradient(u);
            g = g - dot(g, u) * u;
            const double g2 = norm2(g);
            if (!(g2 > 1e-30))
                break;
            bool moved = false;
            for (; step > 1e-16; step *= 0.5) {
                Vec3 v = u - step * g;
                v = v * (1.0 / norm(v));
                if (const double w = h(v); w <= value - 1e-4 * step * g2) {
                    u = v;
                    value = w;
                    moved = true;
                    break;
                }
            }
            if (moved)
                step *= 2.0;
        }
        if (value < best.first)
            best = {value, u};
    }
    return best;
}

} // namespace

CylinderShape CylinderShape::of_aspect(double aspect) {
    const double r = std::cbrt(2.0 / (3.0 * aspect));
    return {r, r * aspect};
}

CylinderShape CylinderShape::ring(double d, double di, double l) {
    // At size 1, d_v = 2: the lengths times 2 / d_v.
    const double dv = std::cbrt(1.5 * (d * d - di * di) * l);
    const double scale = 2.0 / dv;
    return {0.5 * d * scale, 0.5 * l * scale, 0.5 * di * scale};
}

double CylinderShape::section_area() const {
    return pi * (radius * radius - bore * bore);
}

double CylinderShape::bounding_radius(double size) const {
    return size * std::hypot(radius, half_length);
}

double CylinderShape::volume(double size) const {
    if (bore > 0.0)
        return 2.0 * section_area() * half_length * size * size * size;
    return 2.0 * pi * radius * radius * half_length * size * size * size;
}

Vec3 CylinderShape::support(const Placement& p, const Vec3& v) const {
    const Vec3 w = rotate(conjugate(p.orientation), v);
    const double across = std::hypot(w.x, w.y);
    Vec3 body{0.0, 0.0, w.z > 0.0 ? half_length : (w.z < 0.0 ? -half_length : 0.0)};
    if (across > 0.0) {
        body.x = radius * w.x / across;
        body.y = radius * w.y / across;
    }
    return p.position + rotate(p.orientation, body) * p.size;
}

void CylinderShape::wall_contacts(const Container& c, const Placement& p,
                                  const ConvexWallFunction& f) const {
    c.convex_wall_contacts([&](const Vec3& v) { return support(p, v); }, p.position,
                           bounding_radius(p.size), f);
}

double CylinderShape::wall_overlap(const Container& c, const Placement& p, double grow) const {
    const double hull =
        grow > 0.0 ? c.convex_wall_overlap(
                         [&](const Vec3& v) { return support(p, v) + v * (grow / norm(v)); },
                         p.position, bounding_radius(p.size) + grow)
                   : c.convex_wall_overlap([&](const Vec3& v) { return support(p, v); }, p.position,
                                           bounding_radius(p.size));
    if (bore == 0.0 || !(hull > 0.0))
        return hull;
    const detail::SurfacePeak peak = detail::highest_on_surface(*this, [&](const Vec3& q) {
        return c.sticks_out(p.position + rotate(p.orientation, q) * p.size, grow);
    });
    return std::max(0.0, peak.value);
}

namespace {

/// The deepest point of either's surface inside the other (highest_on_surface of the other's
/// signed_depth), as a PairOverlap of a and b (b at ab from a): the depth (minus their distance
/// when they are apart), the normal from a towards b (the outward normal of the surface the
/// point is nearest, turned from b's surface into a's push), the point halfway between that
/// point and the surface.
PairOverlap deepest_surface_point(const CylinderShape& first, const Placement& a,
                                  const CylinderShape& second, const Placement& b, const Vec3& ab) {
    // q: a body-frame point of `from` (size 1) in the body frame of `into`, at `shift` from it.
    const auto peak_of = [](const CylinderShape& from, const Placement& pf,
                            const CylinderShape& into, const Placement& pt, const Vec3& shift) {
        // The signed depth in units of the size of `into`, in the bed's lengths.
        return detail::highest_on_surface(from, [&](const Vec3& q) {
            const Vec3 world = rotate(pf.orientation, q) * pf.size - shift;
            return into.signed_depth(rotate(conjugate(pt.orientation), world) * (1.0 / pt.size)) *
                   pt.size;
        });
    };
    const detail::SurfacePeak in_b = peak_of(first, a, second, b, ab);
    const detail::SurfacePeak in_a = peak_of(second, b, first, a, -1.0 * ab);
    const bool a_deeper = in_b.value >= in_a.value;
    const double depth = a_deeper ? in_b.value : in_a.value;
    // The point from a's position and the outward normal of the body it lies in.
    Vec3 point, out;
    if (a_deeper) {
        point = rotate(a.orientation, in_b.point) * a.size;
        const Vec3 local = rotate(conjugate(b.orientation), point - ab) * (1.0 / b.size);
        out = rotate(b.orientation, second.inside(local).normal);
    } else {
        point = rotate(b.orientation, in_a.point) * b.size + ab;
        const Vec3 local = rotate(conjugate(a.orientation), point) * (1.0 / a.size);
        out = rotate(a.orientation, first.inside(local).normal);
    }
    // a's point inside b leaves it along b's outward normal, so b moves the other way.
    const Vec3 normal = a_deeper ? -1.0 * out : out;
    return {depth, normal, point + out * (0.5 * std::max(depth, 0.0))};
}

} // namespace

PairOverlap CylinderShape::pair_overlap(const Placement& a, const CylinderShape& other,
                                        const Placement& b, const Vec3& ab) const {
    const double reach = bounding_radius(a.size) + other.bounding_radius(b.size);
    const double distance = norm(ab);
    const Vec3 along = distance > 0.0 ? ab * (1.0 / distance) : Vec3{0.0, 0.0, 1.0};
    if (distance >= reach)
        return {0.0, along, {}};
    const CcdBody first{this, {{0.0, 0.0, 0.0}, a.orientation, a.size}};
    const CcdBody second{&other, {ab, b.orientation, b.size}};
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = ccd_support;
    ccd.support2 = ccd_support;
    ccd.center1 = ccd_centre;
    ccd.center2 = ccd_centre;
    ccd.first_dir = ccd_first_direction;
    ccd.max_iterations = 1000;
    ccd.mpr_tolerance = 1e-12 * std::max(a.size, b.size);
    ccd_real_t depth = 0.0;
    ccd_vec3_t direction, position;
    if (ccdMPRPenetration(&first, &second, &ccd, &depth, &direction, &position) != 0)
        return {0.0, along, {}};
    // A ring's hull overlaps: its surface searched.
    if (bore > 0.0 || other.bore > 0.0) {
        const PairOverlap deepest = deepest_surface_point(*this, a, other, b, ab);
        if (!(deepest.depth > 0.0))
            return {0.0, along, {}};
        return deepest;
    }
    // MPR's depth is along one supporting plane of the Minkowski difference, up to 12 % more
    // than the least (docs/notes/pellets.md); the least from the closed-form support.
    const CylinderPair pair = CylinderPair::of(*this, a, other, b, ab);
    const auto [least, normal] =
        cylinder_depth(pair, {direction.v[0], direction.v[1], direction.v[2]});
    if (!(least > 0.0))
        return {0.0, along, {}};
    return {
        least, normal,
        0.5 * (support(first.placement, normal) + other.support(second.placement, -1.0 * normal))};
}

double CylinderShape::pair_gap(const Placement& a, const CylinderShape& other, const Placement& b,
                               const Vec3& ab) const {
    if (bore > 0.0 || other.bore > 0.0)
        return -deepest_surface_point(*this, a, other, b, ab).depth;
    const double distance = norm(ab);
    const CylinderPair pair = CylinderPair::of(*this, a, other, b, ab);
    return -cylinder_depth(pair, distance > 0.0 ? ab * (1.0 / distance) : Vec3{0.0, 0.0, 1.0})
                .first;
}

std::pair<double, double> CylinderShape::wall_extent(const Container& c, std::size_t wall,
                                                     const Placement& p) const {
    return c.wall_distances_from(wall, p.position, bounding_radius(p.size));
}

namespace {

/// The volume of the cylinder in the container `c` between two heights: none where its
/// bounding sphere misses the heights, the slab's closed-form sections where the sphere keeps
/// clear of the side, the region's otherwise (in a tube, its closed-form sections met with the
/// wall's circle).
double cylinder_in(const CylinderShape& shape, const Container& c, const Placement& p, double z_low,
                   double z_high) {
    const double reach = shape.bounding_radius(p.size);
    const double low = std::max(z_low, p.position.z - reach);
    const double high = std::min(z_high, p.position.z + reach);
    if (!(high > low))
        return 0.0;
    const Frame f = frame_of(p);
    const double r = shape.radius * p.size, h = shape.half_length * p.size;
    if (c.wall_overlap(p.position, reach) <= 0.0 &&
        c.contains({p.position.x, p.position.y, std::max(p.position.z, 0.0)}))
        return slab_volume(f, p.position, r, h, low, high);
    if (const std::optional<double> tube = c.tube_diameter())
        return disc_volume(f, p.position, r, h, low, high, 0.5 * *tube);
    return region_volume(
        f, p.position, h, low, high,
        [&](const Vec3& q, const Vec3& u) { return c.side_chord(q, u); }, [r](double) { return r; },
        {0.0, 2.0 * pi}, 32);
}

} // namespace

double CylinderShape::volume_in(const Container& c, const Placement& p, double z_low,
                                double z_high) const {
    // A ring: its outer cylinder less its bore.
    if (bore > 0.0)
        return cylinder_in({radius, half_length}, c, p, z_low, z_high) -
               cylinder_in({bore, half_length}, c, p, z_low, z_high);
    return cylinder_in(*this, c, p, z_low, z_high);
}

double CylinderShape::volume_from_wall(const Container& c, std::size_t wall, double d,
                                       const Placement& p, double z_low, double z_high) const {
    return volume_in(c.shrunk_from(wall, d), p, z_low, z_high);
}

double CylinderShape::volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const {
    detail::SectionLaws laws;
    laws.circles = {{0.0, 0.0, radius}};
    if (bore > 0.0)
        laws.circles.push_back({0.0, 0.0, bore});
    return detail::volume_in_box(
        *this, p, low, high, -half_length, half_length, radius, laws,
        [this](double, const detail::SectionPolygon& poly) {
            const double disc = detail::disc_polygon_area(0.0, 0.0, radius, poly);
            return bore > 0.0 ? disc - detail::disc_polygon_area(0.0, 0.0, bore, poly) : disc;
        });
}

namespace {

/// The steps of surface_nodes: nodes about the rim, rows along the side, rings on an end.
struct NodeSteps {
    int around, rows, rings;
    /// The area of a side row and of a rim (half a row and the end's outermost half ring).
    double row_area, rim_area;
};

/// n nodes on the circle of radius r at height z, the first at the angle offset 2 pi / n,
/// sharing `area`.
void push_circle(std::vector<SurfaceNode>& nodes, double r, double z, int n, double offset,
                 double area) {
    for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * pi * (i + offset) / n;
        nodes.push_back({{r * std::cos(phi), r * std::sin(phi), z}, area / n});
    }
}

/// The fewest steps of at most `spacing` over `span` (at least one).
int node_count(double span, double spacing) {
    return std::max(1, static_cast<int>(std::ceil(span / spacing - 1e-9)));
}

NodeSteps node_steps(const CylinderShape& c, double spacing) {
    const auto count = [spacing](double span) { return node_count(span, spacing); };
    NodeSteps s{std::max(6, count(2.0 * pi * c.radius)), count(2.0 * c.half_length),
                count(c.radius), 0.0, 0.0};
    const double ring_step = c.radius / s.rings;
    s.row_area = 2.0 * pi * c.radius * 2.0 * c.half_length / s.rows;
    s.rim_area =
        0.5 * s.row_area + pi * (c.radius * c.radius - std::pow(c.radius - 0.5 * ring_step, 2));
    return s;
}

/// A ring's surface_nodes (rows_too) or, without rows, the ends' inner rings; its circles
/// (surface_circles): the side's rows (rims first), then the bore's.
struct RingNodes {
    std::vector<SurfaceNode> nodes;
    std::vector<SurfaceCircle> circles;
};

RingNodes ring_nodes(const CylinderShape& c, double spacing, bool rows_too,
                     double row_spacing = 0.0) {
    const auto count = [spacing](double span) { return node_count(span, spacing); };
    const double length = 2.0 * c.half_length, r_in = c.bore, r_out = c.radius;
    const int rings = count(r_out - r_in);
    const double ring_step = (r_out - r_in) / rings;
    RingNodes out;
    const auto circle = [&](double r, double z, int n, double offset, double area) {
        push_circle(out.nodes, r, z, n, offset, area);
    };
    // The ends' inner rings, each the band of half a step either side.
    for (const double z : {-c.half_length, c.half_length})
        for (int j = 1; j < rings; ++j) {
            const double r = r_in + j * ring_step;
            const double low = r - 0.5 * ring_step, high = r + 0.5 * ring_step;
            circle(r, z, std::max(3, count(2.0 * pi * r)), 0.5 * (j % 2),
                   pi * (high * high - low * low));
        }
    // The side's and the bore's rows; the first and last of each are rims, with the ends'
    // half band beside them.
    const int rows = node_count(length, row_spacing > 0.0 ? row_spacing : spacing);
    for (const double r : {r_out, r_in}) {
        const int around = std::max(6, count(2.0 * pi * r));
        const double row_area = 2.0 * pi * r * length / rows;
        const double band = r == r_out ? r - 0.5 * ring_step : r + 0.5 * ring_step;
        const double rim_area = 0.5 * row_area + pi * std::abs(r * r - band * band);
        const double per_length = 1.0 / (2.0 * pi * r);
        out.circles.push_back({-c.half_length, r, rim_area * per_length});
        out.circles.push_back({c.half_length, r, rim_area * per_length});
        for (int k = 1; k < rows; ++k)
            out.circles.push_back({-c.half_length + length * k / rows, r, row_area * per_length});
        for (int k = 0; k <= rows && rows_too; ++k) {
            const bool rim = k == 0 || k == rows;
            circle(r, -c.half_length + length * k / rows, around, rim ? 0.0 : 0.5 * (k % 2),
                   rim ? rim_area : row_area);
        }
    }
    return out;
}

} // namespace

std::vector<SurfaceCircle> CylinderShape::surface_circles(double spacing,
                                                          double row_spacing) const {
    if (bore > 0.0)
        return ring_nodes(*this, spacing, false, row_spacing).circles;
    const NodeSteps steps = node_steps(*this, spacing);
    const double length = 2.0 * pi * radius;
    std::vector<SurfaceCircle> out{{-half_length, radius, steps.rim_area / length},
                                   {half_length, radius, steps.rim_area / length}};
    for (int k = 1; k < steps.rows; ++k)
        out.push_back(
            {-half_length + 2.0 * half_length * k / steps.rows, radius, steps.row_area / length});
    return out;
}

std::vector<SurfaceNode> CylinderShape::surface_nodes(double spacing, bool rows_too) const {
    if (bore > 0.0)
        return ring_nodes(*this, spacing, rows_too).nodes;
    const double length = 2.0 * half_length;
    const auto count = [spacing](double span) { return node_count(span, spacing); };
    const NodeSteps steps = node_steps(*this, spacing);
    const int around = steps.around, rows = steps.rows, rings = steps.rings;
    const double ring_step = radius / rings;
    std::vector<SurfaceNode> nodes;
    const auto circle = [&](double r, double z, int n, double offset, double area) {
        push_circle(nodes, r, z, n, offset, area);
    };
    // The ends' inner rings, each the band of half a step either side (the centre's a disc).
    for (const double z : {-half_length, half_length})
        for (int j = 0; j < rings; ++j) {
            const double r = j * ring_step;
            const double low = std::max(0.0, r - 0.5 * ring_step), high = r + 0.5 * ring_step;
            const int n = j == 0 ? 1 : std::max(3, count(2.0 * pi * r));
            circle(r, z, n, 0.5 * (j % 2), pi * (high * high - low * low));
        }
    // The side's rows; the first and last are the rims, with the ends' outer half band.
    for (int k = 0; k <= rows; ++k) {
        if (!rows_too)
            break;
        const bool rim = k == 0 || k == rows;
        circle(radius, -half_length + length * k / rows, around, rim ? 0.0 : 0.5 * (k % 2),
               rim ? steps.rim_area : steps.row_area);
    }
    return nodes;
}

TriangleMesh CylinderShape::unit_surface(int level) const {
    const auto n = static_cast<std::uint32_t>(12u << std::clamp(level, 0, 8));
    TriangleMesh mesh;
    if (bore > 0.0) {
        // Rings of n vertices: the side's bottom and top, then the bore's.
        for (const double r : {radius, bore})
            for (const double z : {-half_length, half_length})
                for (std::uint32_t k = 0; k < n; ++k) {
                    const double phi = 2.0 * pi * k / n;
                    mesh.vertices.push_back({r * std::cos(phi), r * std::sin(phi), z});
                }
        const std::uint32_t top = n, in_bottom = 2 * n, in_top = 3 * n;
        for (std::uint32_t k = 0; k < n; ++k) {
            const std::uint32_t next = (k + 1) % n;
            mesh.triangles.push_back({k, next, top + next}); // the side, seen from outside
            mesh.triangles.push_back({k, top + next, top + k});
            mesh.triangles.push_back({in_bottom + k, in_top + k, in_top + next}); // the bore
            mesh.triangles.push_back({in_bottom + k, in_top + next, in_bottom + next});
            mesh.triangles.push_back({in_bottom + k, in_bottom + next, next}); // from below
            mesh.triangles.push_back({in_bottom + k, next, k});
            mesh.triangles.push_back({in_top + k, top + k, top + next}); // from above
            mesh.triangles.push_back({in_top + k, top + next, in_top + next});
        }
        return mesh;
    }
    mesh.vertices.reserve(2 * n + 2);
    for (const double z : {-half_length, half_length})
        for (std::uint32_t k = 0; k < n; ++k) {
            const double phi = 2.0 * pi * k / n;
            mesh.vertices.push_back({radius * std::cos(phi), radius * std::sin(phi), z});
        }
    const std::uint32_t bottom = 2 * n, top = 2 * n + 1;
    mesh.vertices.push_back({0.0, 0.0, -half_length});
    mesh.vertices.push_back({0.0, 0.0, half_length});
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t next = (k + 1) % n;
        mesh.triangles.push_back({bottom, next, k});      // seen from below
        mesh.triangles.push_back({top, n + k, n + next}); // seen from above
        mesh.triangles.push_back({k, next, n + next});    // the side
        mesh.triangles.push_back({k, n + next, n + k});
    }
    return mesh;
}

} // namespace packbed
