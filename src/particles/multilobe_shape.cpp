#include "packbed/multilobe_shape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "packbed/box.hpp"
#include "section_volume.hpp"

namespace packbed {

namespace {

constexpr double pi = std::numbers::pi;

/// Where the ray at angle alpha from a lobe's direction, from the axis, leaves the lobe: the
/// lobe's disc of radius r about the point at distance c along alpha = 0 (c <= r).
double ray_exit(double r, double c, double alpha) {
    const double s = c * std::sin(alpha);
    return c * std::cos(alpha) + std::sqrt(std::max(0.0, r * r - s * s));
}

/// The lobe's part of the section between the angles 0 and alpha from its direction: the
/// integral of ray_exit^2 / 2 (MultilobeShape::section_area).
double wedge_area(double r, double c, double alpha) {
    const double s = c * std::sin(alpha);
    return 0.5 * (r * r * alpha + 0.5 * c * c * std::sin(2.0 * alpha) +
                  s * std::sqrt(std::max(0.0, r * r - s * s)) + r * r * std::asin(s / r));
}

} // namespace

MultilobeShape MultilobeShape::of(int n, double lobe_diameter, double circle_diameter,
                                  double length) {
    MultilobeShape unit{{0.5 * lobe_diameter, 0.5 * length}, n, 0.5 * circle_diameter};
    // pi d_v^3 / 6 = the section's area times the length.
    const double dv = std::cbrt(6.0 * unit.section_area() * length / pi);
    const double scale = 2.0 / dv;
    return {{unit.lobe.radius * scale, unit.lobe.half_length * scale}, n, unit.circle * scale};
}

Vec3 MultilobeShape::lobe_centre(int k) const {
    if (lobes == 1)
        return {};
    const double angle = 2.0 * pi * k / lobes;
    return {circle * std::cos(angle), circle * std::sin(angle), 0.0};
}

Placement MultilobeShape::lobe_placement(const Placement& p, int k) const {
    return {p.position + rotate(p.orientation, lobe_centre(k)) * p.size, p.orientation, p.size};
}

double MultilobeShape::section_area() const {
    if (lobe.bore > 0.0)
        return lobe.section_area();
    if (lobes == 1)
        return pi * lobe.radius * lobe.radius;
    return 2.0 * lobes * wedge_area(lobe.radius, circle, pi / lobes);
}

double MultilobeShape::section_radius(double phi) const {
    if (lobes == 1)
        return lobe.radius;
    const double wedge = 2.0 * pi / lobes;
    const double alpha = std::remainder(phi, wedge); // from the nearest lobe's direction
    return ray_exit(lobe.radius, circle, alpha);
}

double MultilobeShape::arc_half_angle() const {
    if (lobes == 1)
        return pi;
    const double alpha = pi / lobes;
    const double t = ray_exit(lobe.radius, circle, alpha);
    return std::atan2(t * std::sin(alpha), t * std::cos(alpha) - circle);
}

double MultilobeShape::volume(double size) const {
    if (lobes == 1)
        return lobe.volume(size);
    return section_area() * 2.0 * lobe.half_length * size * size * size;
}

double MultilobeShape::surface_area(double size) const {
    double side = lobes * 2.0 * arc_half_angle() * lobe.radius * 2.0 * lobe.half_length;
    if (lobe.bore > 0.0)
        side += 2.0 * pi * lobe.bore * 2.0 * lobe.half_length;
    return (2.0 * section_area() + side) * size * size;
}

Vec3 MultilobeShape::support(const Placement& p, const Vec3& v) const {
    if (lobes == 1)
        return lobe.support(p, v);
    const Vec3 w = rotate(conjugate(p.orientation), v);
    Vec3 best;
    double farthest = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < lobes; ++k) {
        const Vec3 s = lobe.support({lobe_centre(k), Quaternion{}, 1.0}, w);
        if (dot(s, w) > farthest) {
            farthest = dot(s, w);
            best = s;
        }
    }
    return p.position + rotate(p.orientation, best) * p.size;
}

double MultilobeShape::wall_overlap(const Container& c, const Placement& p, double grow) const {
    if (lobes == 1)
        return lobe.wall_overlap(c, p, grow);
    double deepest = 0.0;
    for (int k = 0; k < lobes; ++k)
        deepest = std::max(deepest, lobe.wall_overlap(c, lobe_placement(p, k), grow));
    return deepest;
}

void MultilobeShape::wall_contacts(const Container& c, const Placement& p,
                                   const ConvexWallFunction& f) const {
    if (lobes == 1)
        return lobe.wall_contacts(c, p, f);
    for (int k = 0; k < lobes; ++k)
        lobe.wall_contacts(c, lobe_placement(p, k), f);
}

PairOverlap MultilobeShape::pair_overlap(const Placement& a, const MultilobeShape& other,
                                         const Placement& b, const Vec3& ab) const {
    if (lobes == 1 && other.lobes == 1)
        return lobe.pair_overlap(a, other.lobe, b, ab);
    const double distance = norm(ab);
    PairOverlap best{0.0, distance > 0.0 ? ab * (1.0 / distance) : Vec3{0.0, 0.0, 1.0}, {}};
    if (distance >= bounding_radius(a.size) + other.bounding_radius(b.size))
        return best;
    for (int k = 0; k < lobes; ++k) {
        const Vec3 from_a = rotate(a.orientation, lobe_centre(k)) * a.size;
        for (int l = 0; l < other.lobes; ++l) {
            const Vec3 from_b = rotate(b.orientation, other.lobe_centre(l)) * b.size;
            const Vec3 between = ab + from_b - from_a;
            const PairOverlap o =
                lobe.pair_overlap({a.position + from_a, a.orientation, a.size}, other.lobe,
                                  {a.position + from_a + between, b.orientation, b.size}, between);
            if (o.depth > best.depth)
                best = {o.depth, o.normal, o.point + from_a};
        }
    }
    return best;
}

double MultilobeShape::pair_gap(const Placement& a, const MultilobeShape& other, const Placement& b,
                                const Vec3& ab) const {
    if (lobes == 1 && other.lobes == 1)
        return lobe.pair_gap(a, other.lobe, b, ab);
    const double reach = lobe.bounding_radius(a.size) + other.lobe.bounding_radius(b.size);
    double least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < lobes; ++k) {
        const Vec3 from_a = rotate(a.orientation, lobe_centre(k)) * a.size;
        for (int l = 0; l < other.lobes; ++l) {
            const Vec3 from_b = rotate(b.orientation, other.lobe_centre(l)) * b.size;
            const Vec3 between = ab + from_b - from_a;
            // Their gap is at least the distance of their bounding spheres.
            if (norm(between) - reach >= least)
                continue;
            least = std::min(least,
                             lobe.pair_gap({a.position + from_a, a.orientation, a.size}, other.lobe,
                                           {a.position + from_a + between, b.orientation, b.size},
                                           between));
        }
    }
    return least;
}

std::pair<double, double> MultilobeShape::wall_extent(const Container& c, std::size_t wall,
                                                      const Placement& p) const {
    if (lobes == 1)
        return lobe.wall_extent(c, wall, p);
    return c.wall_distances_from(wall, p.position, bounding_radius(p.size));
}

double MultilobeShape::volume_in(const Container& c, const Placement& p, double z_low,
                                 double z_high) const {
    if (lobes == 1)
        return lobe.volume_in(c, p, z_low, z_high);
    const double reach = bounding_radius(p.size);
    const double low = std::max(z_low, p.position.z - reach);
    const double high = std::min(z_high, p.position.z + reach);
    if (!(high > low))
        return 0.0;
    // Whole where its bounding sphere lies between the heights, clear of the side.
    if (low == p.position.z - reach && high == p.position.z + reach &&
        c.wall_overlap(p.position, reach) <= 0.0 && c.contains(p.position))
        return volume(p.size);
    // The angle split at the wedges' edges, (2k + 1) pi / N, where the section's edge turns.
    std::vector<double> cuts{0.0};
    for (int k = 0; k < lobes; ++k)
        cuts.push_back((2.0 * k + 1.0) * pi / lobes);
    cuts.push_back(2.0 * pi);
    return detail::region_volume(
        detail::frame_of(p), p.position, lobe.half_length * p.size, low, high,
        [&](const Vec3& q, const Vec3& u) { return c.side_chord(q, u); },
        [&](double phi) { return section_radius(phi) * p.size; }, cuts, 4, 1e-6);
}

double MultilobeShape::volume_from_wall(const Container& c, std::size_t wall, double d,
                                        const Placement& p, double z_low, double z_high) const {
    if (lobes == 1)
        return lobe.volume_from_wall(c, wall, d, p, z_low, z_high);
    // None where its bounding sphere lies within d of the wall, all of it in the container
    // where the sphere lies farther.
    const auto [nearest, farthest] = wall_extent(c, wall, p);
    if (farthest <= d)
        return 0.0;
    if (nearest >= d)
        return volume_in(c, p, z_low, z_high);
    return volume_in(c.shrunk_from(wall, d), p, z_low, z_high);
}

double MultilobeShape::volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const {
    if (lobes == 1)
        return lobe.volume_in_box(p, low, high);
    // Lobe k's disc in its wedge (the angles within pi / N of its direction): the wedges' parts
    // tile the section (section_area), and each wedge is convex (N >= 2), so its part of the
    // box's polygon is the polygon clipped by the wedge's two edges.
    const double half = pi / lobes;
    detail::SectionLaws laws;
    for (int k = 0; k < lobes; ++k) {
        const Vec3 c = lobe_centre(k);
        laws.circles.push_back({c.x, c.y, lobe.radius});
        const double edge = 2.0 * pi * k / lobes + half;
        laws.rays.push_back({edge, section_radius(edge)});
    }
    return detail::volume_in_box(
        *this, p, low, high, -lobe.half_length, lobe.half_length, circle + lobe.radius, laws,
        [&](double, const detail::SectionPolygon& poly) {
            double sum = 0.0;
            for (int k = 0; k < lobes; ++k) {
                const double middle = 2.0 * pi * k / lobes;
                const double a1 = middle - half, a2 = middle + half;
                detail::SectionPolygon part = poly;
                detail::clip(part, std::sin(a1), -std::cos(a1), 0.0); // counter-clockwise of a1
                detail::clip(part, -std::sin(a2), std::cos(a2), 0.0); // clockwise of a2
                const Vec3 c = lobe_centre(k);
                sum += detail::disc_polygon_area(c.x, c.y, lobe.radius, part);
            }
            return sum;
        });
}

TriangleMesh MultilobeShape::unit_surface(int level) const {
    if (lobes == 1)
        return lobe.unit_surface(level);
    // Each lobe's arc in m segments of at most the cylinder's 2 pi / n about its axis, from
    // the groove before it; the groove after it is the next lobe's first vertex.
    const double n = static_cast<double>(12u << std::clamp(level, 0, 8));
    const double half = arc_half_angle();
    const auto m = static_cast<std::uint32_t>(std::max(2.0, std::ceil(n * half / pi - 1e-9)));
    std::vector<Vec3> outline;
    for (int k = 0; k < lobes; ++k) {
        const Vec3 c = lobe_centre(k);
        const double middle = 2.0 * pi * k / lobes;
        for (std::uint32_t j = 0; j < m; ++j) {
            const double phi = middle - half + 2.0 * half * j / m;
            outline.push_back(
                {c.x + lobe.radius * std::cos(phi), c.y + lobe.radius * std::sin(phi), 0.0});
        }
    }
    const auto count = static_cast<std::uint32_t>(outline.size());
    TriangleMesh mesh;
    for (const double z : {-lobe.half_length, lobe.half_length})
        for (const Vec3& v : outline)
            mesh.vertices.push_back({v.x, v.y, z});
    const std::uint32_t bottom = 2 * count, top = 2 * count + 1;
    mesh.vertices.push_back({0.0, 0.0, -lobe.half_length});
    mesh.vertices.push_back({0.0, 0.0, lobe.half_length});
    for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t next = (k + 1) % count;
        mesh.triangles.push_back({bottom, next, k});
        mesh.triangles.push_back({top, count + k, count + next});
        mesh.triangles.push_back({k, next, count + next});
        mesh.triangles.push_back({k, count + next, count + k});
    }
    return mesh;
}

std::vector<SurfaceNode> MultilobeShape::surface_nodes(double spacing, bool rows) const {
    if (lobes == 1)
        return lobe.surface_nodes(spacing, rows);
    std::vector<SurfaceNode> out;
    const std::vector<SurfaceNode> own = lobe.surface_nodes(spacing, rows);
    for (int k = 0; k < lobes; ++k) {
        const Vec3 c = lobe_centre(k);
        const double middle = 2.0 * pi * k / lobes;
        for (SurfaceNode node : own) {
            node.point += c;
            // In lobe k's wedge, its lower edge kept and its upper one left to the next lobe.
            const double alpha =
                std::remainder(std::atan2(node.point.y, node.point.x) - middle, 2.0 * pi);
            if (alpha >= -pi / lobes && alpha < pi / lobes)
                out.push_back(node);
        }
    }
    return out;
}

std::vector<SurfaceCircle> MultilobeShape::surface_circles(double spacing,
                                                           double row_spacing) const {
    if (lobes == 1)
        return lobe.surface_circles(spacing, row_spacing);
    std::vector<SurfaceCircle> out;
    const double half = arc_half_angle();
    for (int k = 0; k < lobes; ++k) {
        const Vec3 c = lobe_centre(k);
        for (SurfaceCircle row : lobe.surface_circles(spacing)) {
            row.x = c.x;
            row.y = c.y;
            row.arc_middle = 2.0 * pi * k / lobes;
            row.arc_half = half;
            out.push_back(row);
        }
    }
    return out;
}

} // namespace packbed
