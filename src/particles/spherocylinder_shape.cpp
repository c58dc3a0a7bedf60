#include "packbed/spherocylinder_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "packbed/box.hpp"
#include "packbed/cylinder_shape.hpp"
#include "section_volume.hpp"

namespace packbed {

namespace {

constexpr double pi = std::numbers::pi;
using detail::Frame;
using detail::frame_of;

/// The parameters s of segment a (centre ca, unit axis ua, half-length ha) and t of segment b
/// whose points ca + s ua and cb + t ub are nearest. With w = ca - cb, b = ua.ub, d = ua.w,
/// e = ub.w, the squared distance |w + s ua - t ub|^2 is least on the lines at s = (b e - d) /
/// (1 - b^2), t = e + s b. Clamping s to [-ha, ha], taking b's nearest t to that point and,
/// where t leaves [-hb, hb], clamping it and taking a's nearest s again gives the segments'
/// least (the distance is convex in (s, t): its minimum over the rectangle lies on its edge
/// nearest the lines' minimum). Parallel axes: s in the middle of the part of a that b's
/// projection overlaps (the nearest end where none), so that the contact of two rods side by
/// side lies between them.
std::pair<double, double> nearest_parameters(const Vec3& ca, const Vec3& ua, double ha,
                                             const Vec3& cb, const Vec3& ub, double hb) {
    const Vec3 w = ca - cb;
    const double b = dot(ua, ub), d = dot(ua, w), e = dot(ub, w);
    const double across = 1.0 - b * b;
    double s = 0.0;
    if (across > 1e-12) {
        s = std::clamp((b * e - d) / across, -ha, ha);
    } else {
        // b's ends projected on a's line: -d + b t at t = -hb, hb.
        const double p1 = -d - b * hb, p2 = -d + b * hb;
        const double lo = std::max(-ha, std::min(p1, p2)), hi = std::min(ha, std::max(p1, p2));
        s = lo <= hi ? 0.5 * (lo + hi) : std::clamp(0.5 * (p1 + p2), -ha, ha);
    }
    double t = e + s * b;
    if (t < -hb || t > hb) {
        t = std::clamp(t, -hb, hb);
        s = std::clamp(-d + t * b, -ha, ha);
    }
    return {s, t};
}

/// The part of a cap (radius r, its flat face at axial position `base`, reaching to base +
/// `toward` r, toward = +-1) between the heights z_low and z_high: its sections are discs of
/// radius sqrt(r^2 - s^2) at s = |t - base|, each cut by the two planes (detail::disc_below),
/// integrated over s by adaptive Gauss-Kronrod (the area is smooth but where a plane meets a
/// section's rim; 15 points, ten halvings). Upright, the section's area pi (r^2 - s^2)
/// integrated between the planes in closed form.
double cap_in_slab(const Frame& f, const Vec3& centre, double r, double base, double toward,
                   double z_low, double z_high) {
    const double az = f.axis.z * toward; // the cap's height per unit s
    const double g = std::sqrt(std::max(0.0, 1.0 - az * az));
    const double z0 = centre.z + base * f.axis.z; // the flat face's centre
    if (g < 1e-12) {
        if (az == 0.0)
            return 0.0;
        const double s1 = (z_low - z0) / az, s2 = (z_high - z0) / az;
        const double lo = std::clamp(std::min(s1, s2), 0.0, r);
        const double hi = std::clamp(std::max(s1, s2), 0.0, r);
        const auto primitive = [r](double s) { return pi * (r * r * s - s * s * s / 3.0); };
        return hi > lo ? primitive(hi) - primitive(lo) : 0.0;
    }
    auto area = [&](double s) {
        const double rho = std::sqrt(std::max(0.0, (r - s) * (r + s)));
        const double cz = z0 + s * az;
        return detail::disc_below(rho, (z_high - cz) / g) -
               detail::disc_below(rho, (z_low - cz) / g);
    };
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    return Kronrod::integrate(area, 0.0, r, 10, 1e-12);
}

} // namespace

SpherocylinderShape SpherocylinderShape::of_aspect(double aspect) {
    const double r = 1.0 / std::cbrt(1.0 + 1.5 * aspect);
    return {r, r * aspect};
}

double SpherocylinderShape::volume(double size) const {
    return (2.0 * pi * radius * radius * half_length + 4.0 / 3.0 * pi * radius * radius * radius) *
           size * size * size;
}

double SpherocylinderShape::surface_area(double size) const {
    return (4.0 * pi * radius * half_length + 4.0 * pi * radius * radius) * size * size;
}

Vec3 SpherocylinderShape::support(const Placement& p, const Vec3& v) const {
    const Vec3 axis = rotate(p.orientation, Vec3{0.0, 0.0, 1.0});
    const double along = dot(axis, v);
    const double end = along > 0.0 ? half_length : (along < 0.0 ? -half_length : 0.0);
    return p.position + axis * (end * p.size) + v * (radius * p.size / norm(v));
}

double SpherocylinderShape::wall_overlap(const Container& c, const Placement& p,
                                         double grow) const {
    return c.convex_wall_overlap(
        [&](const Vec3& v) { return support(p, v) + v * (grow / norm(v)); }, p.position,
        bounding_radius(p.size) + grow);
}

void SpherocylinderShape::wall_contacts(const Container& c, const Placement& p,
                                        const ConvexWallFunction& f) const {
    c.convex_wall_contacts([&](const Vec3& v) { return support(p, v); }, p.position,
                           bounding_radius(p.size), f);
}

PairOverlap SpherocylinderShape::pair_overlap(const Placement& a, const SpherocylinderShape& other,
                                              const Placement& b, const Vec3& ab) const {
    return segments_overlap(
        {rotate(a.orientation, Vec3{0.0, 0.0, 1.0}), radius * a.size, half_length * a.size},
        {rotate(b.orientation, Vec3{0.0, 0.0, 1.0}), other.radius * b.size,
         other.half_length * b.size},
        ab);
}

PairOverlap SpherocylinderShape::segments_overlap(const Placed& a, const Placed& b,
                                                  const Vec3& ab) {
    const Vec3 &ua = a.axis, &ub = b.axis;
    const double ra = a.radius, rb = b.radius;
    const auto [s, t] = nearest_parameters({}, ua, a.half_length, ab, ub, b.half_length);
    const Vec3 pa = ua * s, pb = ab + ub * t;
    const Vec3 between = pb - pa;
    const double distance = norm(between);
    const double depth = ra + rb - distance;
    Vec3 normal;
    if (distance > 1e-12 * (ra + rb)) {
        normal = between * (1.0 / distance);
    } else {
        // The segments meet: out across both axes (either way along ab), or across a's alone.
        Vec3 n = cross(ua, ub);
        if (norm2(n) < 1e-24)
            n = cross(ua, std::abs(ua.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0});
        normal = n * (1.0 / norm(n));
        if (dot(normal, ab) < 0.0)
            normal = -1.0 * normal;
    }
    return {depth, normal, pa + normal * (ra - 0.5 * depth)};
}

std::pair<double, double> SpherocylinderShape::wall_extent(const Container& c, std::size_t wall,
                                                           const Placement& p) const {
    return c.wall_distances_from(wall, p.position, bounding_radius(p.size));
}

double SpherocylinderShape::volume_in(const Container& c, const Placement& p, double z_low,
                                      double z_high) const {
    const double reach = bounding_radius(p.size);
    const double low = std::max(z_low, p.position.z - reach);
    const double high = std::min(z_high, p.position.z + reach);
    if (!(high > low))
        return 0.0;
    const Frame f = frame_of(p);
    const double r = radius * p.size, h = half_length * p.size;
    // Inside the side walls (its own wall overlap, not its bounding sphere's: most of a
    // narrow tube's pellets lie within a bounding radius of the wall).
    if (wall_overlap(c, p) <= 0.0) {
        const double extent = std::abs(f.axis.z) * h + r; // its half-height
        if (p.position.z - extent >= z_low && p.position.z + extent <= z_high)
            return volume(p.size);
        return detail::slab_volume(f, p.position, r, h, low, high) +
               cap_in_slab(f, p.position, r, h, 1.0, low, high) +
               cap_in_slab(f, p.position, r, -h, -1.0, low, high);
    }
    // The cylinder's own (closed-form sections in a tube, the region's integral otherwise),
    // and each cap's sections by the region's integral (8 pieces along the axis, 32 about it,
    // relative tolerance 1e-8). A cap that barely reaches into the region can be missed in part
    // between the rule's first nodes: on 12 placements cut by a tube's or a box's wall, the
    // caps were at most 1.7e-6 d_v^3 (3e-6 of the pellet) below the same integral from 32 and
    // 128 pieces at 1e-11.
    const auto chord = [&](const Vec3& q, const Vec3& u) { return c.side_chord(q, u); };
    const std::vector<double> whole{0.0, 2.0 * pi};
    const auto cap = [&](double t_low, double t_high, double base) {
        return detail::region_volume_over(
            f, p.position, t_low, t_high, 8, low, high, chord,
            [&](double t, double) {
                const double s = t - base;
                return std::sqrt(std::max(0.0, (r - s) * (r + s)));
            },
            whole, 32);
    };
    const double side =
        half_length > 0.0 ? CylinderShape{radius, half_length}.volume_in(c, p, z_low, z_high) : 0.0;
    return side + cap(h, h + r, h) + cap(-h - r, -h, -h);
}

double SpherocylinderShape::volume_from_wall(const Container& c, std::size_t wall, double d,
                                             const Placement& p, double z_low,
                                             double z_high) const {
    return volume_in(c.shrunk_from(wall, d), p, z_low, z_high);
}

double SpherocylinderShape::volume_in_box(const Placement& p, const Vec3& low,
                                          const Vec3& high) const {
    const double h = half_length, r = radius;
    detail::SectionLaws laws;
    laws.circles = {{0.0, 0.0, r}};
    laws.spheres = {{-h, r}, {h, r}};
    laws.kinks = {-h, h};
    return detail::volume_in_box(*this, p, low, high, -h - r, h + r, r, laws,
                                 [h, r](double t, const detail::SectionPolygon& poly) {
                                     const double past = std::max(0.0, std::abs(t) - h);
                                     const double rho =
                                         std::sqrt(std::max(0.0, (r - past) * (r + past)));
                                     return detail::disc_polygon_area(0.0, 0.0, rho, poly);
                                 });
}

TriangleMesh SpherocylinderShape::unit_surface(int level) const {
    const int lv = std::clamp(level, 0, 8);
    const auto n = static_cast<std::uint32_t>(12u << lv);
    const int m = 3 << lv; // latitude steps on each cap, pi / 2 / m = 2 pi / n apart
    TriangleMesh mesh;
    // Rings from the bottom cap's (nearest its tip) to the top cap's, then the two tips.
    std::vector<std::pair<double, double>> rings; // (z, ring radius)
    for (int k = m - 1; k >= 0; --k) {
        const double lat = 0.5 * pi * k / m;
        rings.emplace_back(-half_length - radius * std::sin(lat), radius * std::cos(lat));
    }
    for (int k = half_length > 0.0 ? 0 : 1; k < m; ++k) { // one equator where L = 0
        const double lat = 0.5 * pi * k / m;
        rings.emplace_back(half_length + radius * std::sin(lat), radius * std::cos(lat));
    }
    for (const auto& [z, rho] : rings)
        for (std::uint32_t k = 0; k < n; ++k) {
            const double phi = 2.0 * pi * k / n;
            mesh.vertices.push_back({rho * std::cos(phi), rho * std::sin(phi), z});
        }
    const auto count = static_cast<std::uint32_t>(rings.size());
    const std::uint32_t bottom = count * n, top = bottom + 1;
    mesh.vertices.push_back({0.0, 0.0, -half_length - radius});
    mesh.vertices.push_back({0.0, 0.0, half_length + radius});
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t next = (k + 1) % n;
        mesh.triangles.push_back({bottom, next, k}); // seen from below
        mesh.triangles.push_back({top, (count - 1) * n + k, (count - 1) * n + next});
        for (std::uint32_t j = 0; j + 1 < count; ++j) { // each band, seen from outside
            const std::uint32_t lo = j * n, hi = (j + 1) * n;
            mesh.triangles.push_back({lo + k, lo + next, hi + next});
            mesh.triangles.push_back({lo + k, hi + next, hi + k});
        }
    }
    return mesh;
}

} // namespace packbed
