#include "packbed/spherocylinder_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "packbed/box.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/volume.hpp"
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

/// The area of the part of the disc of radius ra about a (in a plane) on the side n . (p - a)
/// <= k of a line (n a unit vector) that lies inside the disc of radius rb about the origin:
/// one horizontal section of a cap in a tube. In closed form by Green's theorem, the integral
/// of (x dy - y dx) / 2 about the origin over the boundary of the region, counter-clockwise:
/// the arcs of each circle that lie inside the other circle and on the line's side (each
/// circle split at its crossings with the other and with the line, each arc tested at its
/// middle), (ra^2 dphi + ra (a_x d sin - a_y d cos)) / 2 and rb^2 dphi / 2; and the line's
/// segment inside both discs, from P to Q along (-n_y, n_x) (the region on its left),
/// (P_x Q_y - P_y Q_x) / 2.
double cap_section_in_disc(double ax, double ay, double ra, double nx, double ny, double k,
                           double rb) {
    if (!(ra > 0.0) || k <= -ra)
        return 0.0;
    const double d = std::hypot(ax, ay);
    if (d >= ra + rb)
        return 0.0;
    if (k >= ra)
        return disk_intersection_area(ra, rb, d);
    // The arcs of a circle between its cut angles (taken into [0, 2 pi)), each as f(from, to).
    const auto arcs = [](std::vector<double>& cuts, auto&& f) {
        for (double& phi : cuts)
            phi = phi < 0.0 ? phi + 2.0 * pi : (phi >= 2.0 * pi ? phi - 2.0 * pi : phi);
        detail::for_each_arc(std::move(cuts), f);
    };
    const double phi_n = std::atan2(ny, nx), phi_a = std::atan2(ay, ax);
    const auto in_half = [&](double x, double y) { return nx * (x - ax) + ny * (y - ay) <= k; };
    double area = 0.0;
    // Circle a: the line at cos(phi - phi_n) = k / ra, circle b at cos(phi - phi_a) =
    // (rb^2 - d^2 - ra^2) / (2 ra d).
    {
        const double across = std::acos(std::clamp(k / ra, -1.0, 1.0));
        std::vector<double> cuts{phi_n - across, phi_n + across};
        if (d > 0.0)
            if (const double c = (rb * rb - d * d - ra * ra) / (2.0 * ra * d); std::abs(c) < 1.0) {
                const double t = std::acos(c);
                cuts.insert(cuts.end(), {phi_a - t, phi_a + t});
            }
        arcs(cuts, [&](double p1, double p2) {
            const double m = 0.5 * (p1 + p2);
            const double x = ax + ra * std::cos(m), y = ay + ra * std::sin(m);
            if (x * x + y * y <= rb * rb && in_half(x, y))
                area += 0.5 * (ra * ra * (p2 - p1) + ra * (ax * (std::sin(p2) - std::sin(p1)) -
                                                           ay * (std::cos(p2) - std::cos(p1))));
        });
    }
    // Circle b: the line at cos(theta - phi_n) = (k + n . a) / rb, circle a at
    // cos(theta - phi_a) = (rb^2 + d^2 - ra^2) / (2 rb d).
    {
        std::vector<double> cuts;
        if (const double c = (k + nx * ax + ny * ay) / rb; std::abs(c) < 1.0) {
            const double t = std::acos(c);
            cuts.insert(cuts.end(), {phi_n - t, phi_n + t});
        }
        if (d > 0.0)
            if (const double c = (rb * rb + d * d - ra * ra) / (2.0 * rb * d); std::abs(c) < 1.0) {
                const double t = std::acos(c);
                cuts.insert(cuts.end(), {phi_a - t, phi_a + t});
            }
        arcs(cuts, [&](double p1, double p2) {
            const double m = 0.5 * (p1 + p2);
            const double x = rb * std::cos(m), y = rb * std::sin(m);
            if ((x - ax) * (x - ax) + (y - ay) * (y - ay) <= ra * ra && in_half(x, y))
                area += 0.5 * rb * rb * (p2 - p1);
        });
    }
    // The line: from its foot p0 = a + k n along t = (-n_y, n_x), within sqrt(ra^2 - k^2) of
    // p0 (circle a) and where |p0 + tau t| <= rb (circle b).
    {
        const double x0 = ax + k * nx, y0 = ay + k * ny, tx = -ny, ty = nx;
        const double half = std::sqrt(std::max(0.0, (ra - k) * (ra + k)));
        const double b = x0 * tx + y0 * ty, disc = b * b - (x0 * x0 + y0 * y0 - rb * rb);
        if (disc > 0.0) {
            const double lo = std::max(-half, -b - std::sqrt(disc));
            const double hi = std::min(half, -b + std::sqrt(disc));
            if (hi > lo)
                area += 0.5 * ((x0 + lo * tx) * (y0 + hi * ty) - (y0 + lo * ty) * (x0 + hi * tx));
        }
    }
    return area;
}

/// The volume of a cap (the half of the ball of radius r about q on the side of the unit
/// vector w) inside the tube of radius `radius` about the z axis between two heights: its
/// horizontal sections (cap_section_in_disc: a disc cut by the line where the flat face
/// meets the plane) integrated over the height by adaptive Gauss-Kronrod (15 points, relative
/// tolerance 1e-9 above an absolute floor `floor`, ten halvings) on the pieces between the
/// heights where the section changes its kind (the ball's top and bottom, the face's rim's
/// highest and lowest points).
double cap_in_tube(const Vec3& q, const Vec3& w, double r, double radius, double z_low,
                   double z_high, double floor) {
    const double low = std::max(z_low, q.z - r), high = std::min(z_high, q.z + r);
    if (!(high > low))
        return 0.0;
    const double g = std::hypot(w.x, w.y);
    const double nx = g > 0.0 ? -w.x / g : 1.0, ny = g > 0.0 ? -w.y / g : 0.0;
    // At height z the cap's side of its face is w_xy . (p - q_xy) >= -w_z (z - q_z), that is
    // n . (p - q_xy) <= w_z (z - q_z) / g; a level face (g = 0) keeps all or nothing.
    const auto area = [&](double z) {
        const double dz = z - q.z;
        const double rho = std::sqrt(std::max(0.0, (r - dz) * (r + dz)));
        const double k = g > 0.0 ? w.z * dz / g : (w.z * dz >= 0.0 ? rho : -rho);
        return cap_section_in_disc(q.x, q.y, rho, nx, ny, k, radius);
    };
    std::vector<double> cuts{low, high};
    for (const double z : {q.z - r * g, q.z + r * g})
        if (z > low && z < high)
            cuts.push_back(z);
    return detail::integrate_between_cuts(area, std::move(cuts), floor);
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
    const double side =
        half_length > 0.0 ? CylinderShape{radius, half_length}.volume_in(c, p, z_low, z_high) : 0.0;
    // In a tube, each cap's sections in closed form (cap_in_tube; the floor 1e-13 of the
    // pellet's volume, as the cylinder's).
    if (const std::optional<double> tube = c.tube_diameter()) {
        const double floor = 1e-13 * volume(p.size);
        return side +
               cap_in_tube(p.position + h * f.axis, f.axis, r, 0.5 * *tube, low, high, floor) +
               cap_in_tube(p.position - h * f.axis, -1.0 * f.axis, r, 0.5 * *tube, low, high,
                           floor);
    }
    // Elsewhere the cylinder's own (the region's integral), and each cap's sections by the
    // region's integral (8 pieces along the axis, 32 about it,
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
