// The volume of a pellet whose sections across its axis are star-shaped about it (a cylinder,
// a multilobe) inside a region, by integration over its sections (cylinder_shape.cpp,
// multilobe_shape.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
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

/// Adaptive 15-point Gauss-Kronrod (Boost.Math's, whose halving it repeats node for node) with
/// an absolute floor under its relative tolerance: a piece is halved while its error estimate
/// exceeds `tolerance` times its own estimate, the same share of the whole's, and `floor` (each
/// halved with the piece). Boost's alone asks a vanishing integral (a sliver of a pellet in a
/// region) for an error below its integrand's rounding and halves to `depth` everywhere; where
/// the floor is not reached the two give the same bits.
template <class F>
double integrate_with_floor(F&& f, double a, double b, unsigned depth, double tolerance,
                            double floor) {
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    const auto piece = [&](auto&& self, double lo, double hi, unsigned levels, double whole,
                           double least) -> double {
        double error = 0.0;
        const double estimate = Kronrod::integrate(f, lo, hi, 0, tolerance, &error);
        const double own = std::abs(estimate * tolerance);
        if (whole == 0.0)
            whole = own;
        if (levels > 0 && own < error && whole < error && least < error) {
            const double mid = 0.5 * (lo + hi);
            const double left = self(self, lo, mid, levels - 1, 0.5 * whole, 0.5 * least);
            return left + self(self, mid, hi, levels - 1, 0.5 * whole, 0.5 * least);
        }
        return estimate;
    };
    return piece(piece, a, b, depth, 0.0, floor);
}

/// The integral of the section `area` over the heights from the least to the greatest of
/// `cuts` (which hold both ends and the heights between where the section changes its kind),
/// integrate_with_floor on each piece between neighbouring cuts (ten halvings, relative
/// tolerance 1e-9 above the absolute `floor`), added from the bottom.
template <class F> double integrate_between_cuts(F&& area, std::vector<double> cuts, double floor) {
    std::sort(cuts.begin(), cuts.end());
    double total = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
        if (cuts[k + 1] > cuts[k])
            total += integrate_with_floor(area, cuts[k], cuts[k + 1], 10, 1e-9, floor);
    return total;
}

/// f(a, b) for each piece [a, b] of the turn [0, 2 pi] between the angles `cuts` (each in
/// [0, 2 pi]), in order.
template <class F> void for_each_arc(std::vector<double> cuts, F&& f) {
    cuts.push_back(0.0);
    cuts.push_back(2.0 * std::numbers::pi);
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
        if (cuts[k + 1] > cuts[k])
            f(cuts[k], cuts[k + 1]);
}

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

/// A direction across a pellet's axis, w(phi) = cos(phi) e1 + sin(phi) e2, by its cosine and
/// sine, and the section's radius along it.
struct AngleAt {
    double cos, sin, radius;
};

/// The AngleAt of each angle a prism's region integral asks, remembered by the angle's bits:
/// its angle integral meets the same nodes at every section along the axis, and a cosine, a
/// sine and a multilobe's radius cost more than the rest of a node. The same values as
/// computed afresh, so the same bits.
class AngleCache {
public:
    template <class RadiusOf> const AngleAt& at(double phi, RadiusOf&& radius_of) {
        if (2 * (m_count + 1) > m_slots.size())
            grow();
        const std::uint64_t key = std::bit_cast<std::uint64_t>(phi);
        std::size_t i = slot_of(key);
        for (;; i = (i + 1) & (m_slots.size() - 1)) {
            Slot& slot = m_slots[i];
            if (!slot.used) {
                slot = {key, {std::cos(phi), std::sin(phi), radius_of(phi)}, true};
                ++m_count;
                return slot.value;
            }
            if (slot.key == key)
                return slot.value;
        }
    }

private:
    struct Slot {
        std::uint64_t key = 0;
        AngleAt value{};
        bool used = false;
    };
    std::size_t slot_of(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & (m_slots.size() - 1);
    }
    void grow() {
        std::vector<Slot> old(m_slots.empty() ? 1024 : 2 * m_slots.size());
        old.swap(m_slots);
        for (const Slot& slot : old)
            if (slot.used)
                for (std::size_t i = slot_of(slot.key);; i = (i + 1) & (m_slots.size() - 1))
                    if (!m_slots[i].used) {
                        m_slots[i] = slot;
                        break;
                    }
    }
    std::vector<Slot> m_slots;
    std::size_t m_count = 0;
};

/// region_volume_over with the direction and the radius at (t, phi) from `angle_at(t, phi)`
/// (an AngleAt).
template <class ChordOf, class AngleOf>
double region_volume_by(const Frame& f, const Vec3& centre, double t_low, double t_high,
                        int axis_pieces, double z_low, double z_high, ChordOf&& chord,
                        AngleOf&& angle_at, const std::vector<double>& cuts, int pieces_per_cut,
                        double tolerance) {
    auto ring = [&](double t, double phi) {
        const Vec3 c = centre + t * f.axis;
        const AngleAt& angle = angle_at(t, phi);
        const Vec3 w = angle.cos * f.e1 + angle.sin * f.e2;
        double lo = 0.0, hi = angle.radius;
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
    // goes unseen by the rule's first nodes. Under the relative tolerance, an absolute floor
    // (integrate_with_floor): 1e-13 of s^2 per radian about the axis and of s^3 per unit of
    // its length, s the section's largest radius at the ends and the middle of the axis.
    double s = 0.0;
    for (const double t : {t_low, 0.5 * (t_low + t_high), t_high})
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            s = std::max(s, angle_at(t, 0.5 * (cuts[k] + cuts[k + 1])).radius);
    auto pieces = [tolerance](auto&& integrand, double a, double b, int n, double floor) {
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
            const double lo = a + (b - a) * k / n, hi = a + (b - a) * (k + 1) / n;
            sum += integrate_with_floor(integrand, lo, hi, 6, tolerance, floor * (hi - lo));
        }
        return sum;
    };
    auto section = [&](double t) {
        double sum = 0.0;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            sum += pieces([&](double phi) { return ring(t, phi); }, cuts[k], cuts[k + 1],
                          pieces_per_cut, 1e-13 * s * s);
        return sum;
    };
    return pieces(section, t_low, t_high, axis_pieces, 1e-13 * s * s * s);
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
    AngleAt angle{};
    return region_volume_by(
        f, centre, t_low, t_high, axis_pieces, z_low, z_high, chord,
        [&](double t, double phi) -> const AngleAt& {
            angle = {std::cos(phi), std::sin(phi), radius_at(t, phi)};
            return angle;
        },
        cuts, pieces_per_cut, tolerance);
}

/// region_volume_over the prism's whole length, -h .. h in 16 pieces, its section the same at
/// every t (each angle's direction and radius computed once: AngleCache).
template <class ChordOf, class RadiusOf>
double region_volume(const Frame& f, const Vec3& centre, double h, double z_low, double z_high,
                     ChordOf&& chord, RadiusOf&& radius_at, const std::vector<double>& cuts,
                     int pieces_per_cut, double tolerance = 1e-8) {
    AngleCache cache;
    return region_volume_by(
        f, centre, -h, h, 16, z_low, z_high, chord,
        [&](double, double phi) -> const AngleAt& { return cache.at(phi, radius_at); }, cuts,
        pieces_per_cut, tolerance);
}

/// A convex polygon in a pellet's cross-section, (u, v) along its frame's e1 and e2 from the
/// axis, counter-clockwise: a box's section, clipped.
struct SectionPolygon {
    std::array<std::array<double, 2>, 24> point{};
    int count = 0;
};

/// Keep the part of `poly` where a u + b v <= c (Sutherland-Hodgman: each edge kept, cut or
/// dropped; convexity and the turning sense are kept). a = b = 0 keeps all of it for c >= 0 and
/// none below.
inline void clip(SectionPolygon& poly, double a, double b, double c) {
    SectionPolygon out;
    for (int i = 0; i < poly.count; ++i) {
        const auto& p = poly.point[static_cast<std::size_t>(i)];
        const auto& q = poly.point[static_cast<std::size_t>((i + 1) % poly.count)];
        const double fp = a * p[0] + b * p[1] - c, fq = a * q[0] + b * q[1] - c;
        if (fp <= 0.0)
            out.point[static_cast<std::size_t>(out.count++)] = p;
        if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
            const double s = fp / (fp - fq);
            out.point[static_cast<std::size_t>(out.count++)] = {p[0] + s * (q[0] - p[0]),
                                                                p[1] + s * (q[1] - p[1])};
        }
    }
    poly = out;
}

/// The signed area of the disc of radius r about the origin inside the triangle (origin, p, q):
/// the edge p..q is cut where it crosses the circle (|p + s (q - p)| = r, a quadratic in s);
/// each piece inside adds its triangle with the origin, cross(a, b) / 2, each piece outside
/// the sector it sees, r^2 / 2 times the angle atan2(cross(a, b), a.b). Positive where p, q
/// turn counter-clockwise.
inline double disc_triangle_area(const std::array<double, 2>& p, const std::array<double, 2>& q,
                                 double r) {
    const double du = q[0] - p[0], dv = q[1] - p[1];
    const double a = du * du + dv * dv;
    if (!(a > 0.0))
        return 0.0;
    const double b = p[0] * du + p[1] * dv, c = p[0] * p[0] + p[1] * p[1] - r * r;
    std::array<double, 4> s{0.0, 0.0, 0.0, 1.0};
    int n = 1;
    if (const double d = b * b - a * c; d > 0.0) {
        const double root = std::sqrt(d);
        for (const double t : {(-b - root) / a, (-b + root) / a})
            if (t > 0.0 && t < 1.0)
                s[static_cast<std::size_t>(n++)] = t;
    }
    s[static_cast<std::size_t>(n++)] = 1.0;
    double sum = 0.0;
    for (int k = 0; k + 1 < n; ++k) {
        const double s0 = s[static_cast<std::size_t>(k)], s1 = s[static_cast<std::size_t>(k + 1)];
        const double au = p[0] + s0 * du, av = p[1] + s0 * dv;
        const double bu = p[0] + s1 * du, bv = p[1] + s1 * dv;
        const double mu = 0.5 * (au + bu), mv = 0.5 * (av + bv);
        const double cross = au * bv - av * bu;
        if (mu * mu + mv * mv < r * r)
            sum += 0.5 * cross;
        else
            sum += 0.5 * r * r * std::atan2(cross, au * bu + av * bv);
    }
    return sum;
}

/// The area of the disc of radius r about (cu, cv) inside the convex polygon: the sum of
/// disc_triangle_area over its edges, seen from the disc's centre.
inline double disc_polygon_area(double cu, double cv, double r, const SectionPolygon& poly) {
    if (poly.count < 3 || !(r > 0.0))
        return 0.0;
    double sum = 0.0;
    for (int i = 0; i < poly.count; ++i) {
        const auto& p = poly.point[static_cast<std::size_t>(i)];
        const auto& q = poly.point[static_cast<std::size_t>((i + 1) % poly.count)];
        sum += disc_triangle_area({p[0] - cu, p[1] - cv}, {q[0] - cu, q[1] - cv}, r);
    }
    return sum;
}

/// Where a pellet's sections change as the plane across its axis moves, for
/// box_volume_by_sections: the circles of its prism's sections (centre (u, v) about the axis,
/// radius), the spheres of its caps (centre at axial position t, radius), the rays from the
/// axis that part its lobes' wedges (angle, and where they meet the section's edge), and the
/// axial positions where the section changes its law.
struct SectionLaws {
    struct Circle {
        double u, v, r;
    };
    struct Sphere {
        double t, r;
    };
    struct Ray {
        double angle, reach;
    };
    std::vector<Circle> circles;
    std::vector<Sphere> spheres;
    std::vector<Ray> rays;
    std::vector<double> kinks;
};

/// The volume of a pellet in the axis-aligned box [low, high] from its sections across its
/// axis, at size 1 in its body frame and then scaled: the box's section at axial position t is
/// the convex polygon of the (u, v) with low <= c + t a + u e1 + v e2 <= high (a square of
/// half-width `across`, which holds every section, clipped by the box's six faces), and
/// `area(t, polygon)` the pellet's section inside it, in closed form. The integral over t, from
/// t_low to t_high where the box's corners reach, is cut where the area stops being analytic:
/// where the plane passes a corner of the box (the polygon gains or loses a vertex); where a
/// face's line turns tangent to a section's circle (a quadratic in t for a cap's sphere);
/// where an edge of the box crosses a circle or a sphere (a quadratic along the edge) or a
/// wedge's ray; where a face's line passes the axis or a groove; and at the laws' kinks. Each
/// piece, analytic, by the 15-point Kronrod rule, halved (at most eight times) while its error
/// estimate is above 1e-10 of the box's volume, which an event missed would take: on
/// voxel-sized boxes about cylinders, trilobes and spherocylinders one rule per piece, and a
/// box's volume within 1e-14 of it of the sum over its eight halves (docs/voxels.md).
template <class Area>
double box_volume_by_sections(const Placement& p, const Vec3& low, const Vec3& high, double t_low,
                              double t_high, double across, const SectionLaws& laws, Area&& area) {
    const Frame f = frame_of(p);
    const double s = p.size;
    const Vec3 lo = (low - p.position) * (1.0 / s), hi = (high - p.position) * (1.0 / s);
    const std::array<double, 3> a{f.axis.x, f.axis.y, f.axis.z}, e1{f.e1.x, f.e1.y, f.e1.z},
        e2{f.e2.x, f.e2.y, f.e2.z}, l{lo.x, lo.y, lo.z}, h{hi.x, hi.y, hi.z};
    auto section = [&](double t) {
        SectionPolygon poly;
        poly.count = 4;
        const double w = 2.0 * across; // its edges clear of every section
        poly.point = {{{-w, -w}, {w, -w}, {w, w}, {-w, w}}};
        for (std::size_t i = 0; i < 3 && poly.count > 0; ++i) {
            clip(poly, e1[i], e2[i], h[i] - t * a[i]);
            clip(poly, -e1[i], -e2[i], t * a[i] - l[i]);
        }
        return poly.count < 3 ? 0.0 : area(t, poly);
    };
    double from = t_high, to = t_low; // the box's reach along the axis
    for (int k = 0; k < 8; ++k) {
        const double t =
            dot(Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}, f.axis);
        from = std::min(from, t);
        to = std::max(to, t);
    }
    from = std::max(from, t_low);
    to = std::min(to, t_high);
    if (!(to > from))
        return 0.0;
    std::vector<double> cuts{from, to};
    const auto add = [&](double t) {
        if (t > from && t < to)
            cuts.push_back(t);
    };
    const auto roots = [](double qa, double qb, double qc, auto&& use) { // qa s^2 + 2 qb s + qc
        if (!(qa > 0.0))
            return;
        // A double root (a face tangent to a section's circle along the whole piece, a pellet
        // lying on the floor) may come out a rounding below zero: kept as one.
        const double d = qb * qb - qa * qc;
        if (d >= -1e-9 * (qb * qb + std::abs(qa * qc))) {
            const double root = std::sqrt(std::max(0.0, d));
            use((-qb - root) / qa);
            use((-qb + root) / qa);
        }
    };
    for (int k = 0; k < 8; ++k)
        add(dot(Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}, f.axis));
    for (const double t : laws.kinks)
        add(t);
    for (std::size_t i = 0; i < 3; ++i) {
        const double g2 = e1[i] * e1[i] + e2[i] * e2[i], g = std::sqrt(g2);
        if (!(std::abs(a[i]) > 1e-14) || !(g > 1e-14))
            continue; // the faces across the axis meet the plane only at the corners' t
        for (const double b : {l[i], h[i]}) {
            // The face's line in the plane at t: e1_i u + e2_i v = b - t a_i.
            for (const auto& c : laws.circles) {
                const double w = e1[i] * c.u + e2[i] * c.v;
                add((b - w - c.r * g) / a[i]);
                add((b - w + c.r * g) / a[i]);
            }
            // (b - t a_i)^2 / g^2 = r^2 - (t - t_c)^2, with a_i^2 + g^2 = 1.
            for (const auto& c : laws.spheres)
                roots(1.0, -(a[i] * b + g2 * c.t), b * b + g2 * (c.t * c.t - c.r * c.r), add);
            if (!laws.rays.empty())
                add(b / a[i]);
            for (const auto& ray : laws.rays)
                add((b - ray.reach * (e1[i] * std::cos(ray.angle) + e2[i] * std::sin(ray.angle))) /
                    a[i]);
        }
    }
    // The twelve edges: from the corner P along axis j, s in [0, h_j - l_j].
    for (std::size_t j = 0; j < 3; ++j) {
        if (!(std::abs(a[j]) > 1e-14))
            continue; // parallel to the plane: it crosses nothing as t moves
        const std::size_t j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double length = h[j] - l[j];
        for (int k = 0; k < 4; ++k) {
            std::array<double, 3> corner{};
            corner[j] = l[j];
            corner[j1] = k & 1 ? h[j1] : l[j1];
            corner[j2] = k & 2 ? h[j2] : l[j2];
            const Vec3 c0{corner[0], corner[1], corner[2]};
            const double t0 = dot(c0, f.axis), u0 = dot(c0, f.e1), v0 = dot(c0, f.e2);
            const auto at = [&](double along) {
                if (along > 0.0 && along < length)
                    add(t0 + along * a[j]);
            };
            for (const auto& c : laws.circles) {
                const double du = u0 - c.u, dv = v0 - c.v;
                roots(e1[j] * e1[j] + e2[j] * e2[j], du * e1[j] + dv * e2[j],
                      du * du + dv * dv - c.r * c.r, at);
            }
            for (const auto& c : laws.spheres) {
                const Vec3 d = c0 - f.axis * c.t;
                roots(1.0, corner[j] - c.t * a[j], dot(d, d) - c.r * c.r, at);
            }
            for (const auto& ray : laws.rays) {
                const double cs = std::cos(ray.angle), sn = std::sin(ray.angle);
                const double rate = cs * e2[j] - sn * e1[j];
                if (rate != 0.0)
                    at(-(cs * v0 - sn * u0) / rate);
            }
        }
    }
    std::sort(cuts.begin(), cuts.end());
    // Each piece by the 15-point Kronrod rule, halved while its error estimate (|Kronrod -
    // Gauss|) is above 1e-10 of the box's volume: an absolute bound, where a relative one
    // would halve to the end a piece on which the pellet barely reaches into the box.
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    const double bound = 1e-10 * (h[0] - l[0]) * (h[1] - l[1]) * (h[2] - l[2]);
    const auto piece = [&](const auto& self, double from_t, double to_t, int depth) -> double {
        double error = 0.0;
        const double value = Kronrod::integrate(section, from_t, to_t, 0, 0.0, &error);
        // A piece a millionth of the box's reach (a pellet's axis within 1e-7 of a box's
        // axis: the plane sweeps a face in that) holds at most that share of the box, and its
        // error estimate is the rounding of t there, which no halving lowers.
        if (error <= bound || depth == 0 || to_t - from_t < 1e-6 * (to - from))
            return value;
        const double middle = 0.5 * (from_t + to_t);
        return self(self, from_t, middle, depth - 1) + self(self, middle, to_t, depth - 1);
    };
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
        if (cuts[i + 1] > cuts[i])
            total += piece(piece, cuts[i], cuts[i + 1], 8);
    return total * s * s * s;
}

/// A pellet's volume in an axis-aligned box (a voxel's cover): none where its bounding sphere
/// misses the box, the whole where the box holds that sphere, else
/// box_volume_by_sections with the shape's `area`.
template <class Shape, class Area>
double volume_in_box(const Shape& shape, const Placement& p, const Vec3& low, const Vec3& high,
                     double t_low, double t_high, double across, const SectionLaws& laws,
                     Area&& area) {
    const double reach = shape.bounding_radius(p.size);
    const Vec3& o = p.position;
    if (o.x + reach <= low.x || o.x - reach >= high.x || o.y + reach <= low.y ||
        o.y - reach >= high.y || o.z + reach <= low.z || o.z - reach >= high.z)
        return 0.0;
    if (o.x - reach >= low.x && o.x + reach <= high.x && o.y - reach >= low.y &&
        o.y + reach <= high.y && o.z - reach >= low.z && o.z + reach <= high.z)
        return shape.volume(p.size);
    return box_volume_by_sections(p, low, high, t_low, t_high, across, laws, area);
}

} // namespace packbed::detail
