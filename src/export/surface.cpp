#include "packbed/surface.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <span>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "base/require.hpp"
#include "export/mesh_union.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/sphere_shape.hpp"
#include "packbed/text.hpp"
#include "packbed/volume.hpp"

namespace packbed {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

} // namespace

TriangleMesh icosphere(int level) {
    detail::require(level >= 0 && level <= 7, "icosphere level", level, "0 to 7");
    const double p = std::numbers::phi;
    TriangleMesh m;
    m.vertices = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                  {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
    for (Vec3& v : m.vertices)
        v *= 1.0 / norm(v);
    m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::unordered_map<std::uint64_t, std::uint32_t> middle;
        auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto [it, added] =
                middle.try_emplace(edge_key(a, b), static_cast<std::uint32_t>(m.vertices.size()));
            if (added) {
                const Vec3 c = m.vertices[a] + m.vertices[b];
                m.vertices.push_back(c * (1.0 / norm(c)));
            }
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> split;
        split.reserve(4 * m.triangles.size());
        for (const auto& [a, b, c] : m.triangles) {
            const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            split.push_back({a, ab, ca});
            split.push_back({b, bc, ab});
            split.push_back({c, ca, bc});
            split.push_back({ab, bc, ca});
        }
        m.triangles.swap(split);
    }
    return m;
}

double icosphere_edge(int level) {
    return 1.0515 / std::ldexp(1.0, level);
}

int icosphere_level_for_edge(double radius, double edge) {
    int level = 0;
    while (level < 7 && radius * icosphere_edge(level) > edge)
        ++level;
    return level;
}

TriangleMesh clip_convex(const TriangleMesh& mesh, const HalfSpace& half_space, double snap) {
    // Each vertex is in (d < -snap), out (d > snap) or on the plane (|d| <= snap; those
    // outside are moved onto it along the normal, which keeps them inside the ball, those
    // inside stay): crossing points are only made between an in and an out vertex, so none
    // falls within `snap` of a vertex and no sliver triangles appear at the cut.
    const std::size_t n = mesh.vertices.size();
    enum Side : unsigned char { in, on, out };
    std::vector<double> d(n);
    std::vector<Side> side(n);
    bool any_kept = false, any_out = false;
    for (std::size_t v = 0; v < n; ++v) {
        d[v] = dot(half_space.normal, mesh.vertices[v]) - half_space.offset;
        side[v] = d[v] < -snap ? in : d[v] > snap ? out : on;
        (side[v] == out ? any_out : any_kept) = true;
    }
    if (!any_out && snap == 0.0)
        return mesh;
    if (!any_kept)
        return {};

    TriangleMesh out_mesh;
    constexpr std::uint32_t none = ~std::uint32_t{0};
    std::vector<std::uint32_t> kept(n, none);
    for (std::size_t v = 0; v < n; ++v)
        if (side[v] != out) {
            kept[v] = static_cast<std::uint32_t>(out_mesh.vertices.size());
            out_mesh.vertices.push_back(d[v] > 0.0 ? mesh.vertices[v] - half_space.normal * d[v]
                                                   : mesh.vertices[v]);
        }
    std::unordered_map<std::uint64_t, std::uint32_t> crossing;
    auto cross_point = [&](std::uint32_t inside, std::uint32_t outside) {
        const auto [it, added] = crossing.try_emplace(
            edge_key(inside, outside), static_cast<std::uint32_t>(out_mesh.vertices.size()));
        if (added) {
            const double t = d[inside] / (d[inside] - d[outside]); // d[inside] < 0 < d[outside]
            out_mesh.vertices.push_back(mesh.vertices[inside] +
                                        (mesh.vertices[outside] - mesh.vertices[inside]) * t);
        }
        return it->second;
    };
    // The cut face's boundary edges a -> b, oriented against the clipped triangles' edges on
    // the plane so that every edge is used once each way.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;
    for (const auto& tri : mesh.triangles) {
        std::uint32_t poly[4];
        int count = 0;
        std::uint32_t leave = none, enter = none;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t p = tri[e], q = tri[(e + 1) % 3];
            if (side[p] != out)
                poly[count++] = kept[p];
            if (side[p] == in && side[q] == out)
                poly[count++] = leave = cross_point(p, q);
            else if (side[p] == on && side[q] == out)
                leave = kept[p];
            else if (side[p] == out && side[q] == in)
                poly[count++] = enter = cross_point(q, p);
            else if (side[p] == out && side[q] == on)
                enter = kept[q];
        }
        for (int k = 1; k + 1 < count; ++k)
            out_mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
        if (leave != none && enter != none && leave != enter)
            boundary.emplace_back(enter, leave); // the triangle runs leave -> enter on the plane
    }
    // Close the cut: a fan from the centroid of the boundary loop (convex).
    if (!boundary.empty()) {
        Vec3 centroid{};
        for (const auto& [a, b] : boundary)
            centroid += out_mesh.vertices[a];
        centroid *= 1.0 / static_cast<double>(boundary.size());
        const auto c = static_cast<std::uint32_t>(out_mesh.vertices.size());
        out_mesh.vertices.push_back(centroid);
        for (const auto& [a, b] : boundary)
            out_mesh.triangles.push_back({c, a, b});
    }
    return out_mesh;
}

const Registry<Facets>& facet_modes() {
    static const Registry<Facets> names("facets", {{"inscribed", Facets::inscribed},
                                                   {"volume", Facets::volume},
                                                   {"auto", Facets::automatic}});
    return names;
}

double volume_facets_scale(int level) {
    return std::cbrt(4.0 / 3.0 * std::numbers::pi / icosphere(level).volume());
}

const Registry<ContactTreatment>& contact_treatments() {
    static const Registry<ContactTreatment> names("contacts",
                                                  {{"none", ContactTreatment::none},
                                                   {"shrink", ContactTreatment::shrink},
                                                   {"enlarge", ContactTreatment::enlarge},
                                                   {"caps", ContactTreatment::caps},
                                                   {"bridges", ContactTreatment::bridges}});
    return names;
}

Contacts parse_contacts(std::string_view text) {
    const std::string allowed = "none, shrink:F, enlarge:F, caps:H or bridges:D with F, H, D "
                                "fractions of Dp in (0, 0.5)";
    const KindSpec parts = split_kind(text);
    const std::string_view name = parts.kind;
    Contacts c;
    const std::optional<ContactTreatment> treatment = contact_treatments().find(name);
    const bool known = treatment.has_value();
    if (known)
        c.treatment = *treatment;
    const auto refuse = [&] {
        return InvalidInput(fmt::format("--contacts '{}' is not allowed; allowed: {}",
                                        printable(text.substr(0, 80)), allowed));
    };
    if (!known || (c.treatment == ContactTreatment::none) != !parts.parameters)
        throw refuse();
    if (c.treatment != ContactTreatment::none) {
        const auto value = parse_finite(*parts.parameters);
        if (!value || !(*value > 0.0) || !(*value < 0.5))
            throw refuse();
        c.parameter = *value;
    }
    return c;
}

double spherical_cap_volume(double radius, double distance) {
    const double c = radius - distance;
    if (c <= 0.0)
        return 0.0;
    if (c >= 2.0 * radius)
        return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    return std::numbers::pi * c * c * (3.0 * radius - c) / 3.0;
}

double lens_volume(double r1, double r2, double d) {
    if (d >= r1 + r2)
        return 0.0;
    const double small = std::min(r1, r2);
    if (d <= std::abs(r1 - r2))
        return 4.0 / 3.0 * std::numbers::pi * small * small * small;
    // Two caps cut by the radical plane, at d1 = (d^2 + r1^2 - r2^2) / (2d) from centre 1.
    const double d1 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    return spherical_cap_volume(r1, d1) + spherical_cap_volume(r2, d - d1);
}

double half_ball_in_cylinder(double radius, double rho) {
    if (rho >= radius)
        return 2.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    const double t = std::sqrt(radius * radius - rho * rho);
    return std::numbers::pi * rho * rho * t +
           std::numbers::pi *
               (radius * radius * (radius - t) - (radius * radius * radius - t * t * t) / 3.0);
}

namespace {

/// Where something meets a sphere's surface: a disc about `axis` (unit) of angular radius
/// `angle`. Two footprints of one sphere must not meet for the volumes to be sums of closed
/// forms.
struct Footprint {
    Vec3 axis;
    double angle;
};

void refuse_meeting_footprints(const std::vector<Footprint>& f, std::size_t sphere, const Vec3& x,
                               const Contacts& contacts) {
    for (std::size_t a = 0; a < f.size(); ++a)
        for (std::size_t b = 0; b < a; ++b) {
            const double angle = std::acos(std::clamp(dot(f[a].axis, f[b].axis), -1.0, 1.0));
            if (!(angle > f[a].angle + f[b].angle))
                throw InvalidInput(fmt::format(
                    "--contacts {}:{} gives sphere {} at ({:.6g}, {:.6g}, {:.6g}) two caps, "
                    "lenses or bridge ends that meet; allowed: a smaller parameter",
                    contact_treatments().name(contacts.treatment), contacts.parameter, sphere + 1,
                    x.x, x.y, x.z));
        }
}

/// Cut body b by a plane `gap` from the floor and from the wall where it comes closer than
/// that: the plane tangent to the wall moved `gap` inwards (a cylinder's at the nearest
/// point; each box face that near, two in a corner). A cell periodic along z has no floor: a
/// contact across its bottom and top is a pair's.
void cut_at_walls(TreatedBody& b, double gap, const std::optional<SurfaceContainer>& container) {
    const bool floor = !(container && container->periodic_z);
    if (floor && b.center.z - b.radius < gap)
        b.cuts.push_back({{0.0, 0.0, -1.0}, -gap});
    if (container)
        for (const WallPlane& wall : container->container.walls_within(b.center, b.radius, gap))
            b.cuts.push_back({wall.normal, wall.offset - gap});
}

/// The footprint of a cut (its cap) on body b. \throws InvalidInput when the cut reaches past
/// the centre.
Footprint cut_footprint(const TreatedBody& b, const HalfSpace& h, std::size_t sphere,
                        const Contacts& contacts) {
    const double s = h.offset - dot(h.normal, b.center);
    if (!(s > 0.0))
        throw InvalidInput(fmt::format(
            "--contacts {}:{} cuts sphere {} at ({:.6g}, {:.6g}, {:.6g}) beyond its centre; "
            "allowed: a smaller parameter",
            contact_treatments().name(contacts.treatment), contacts.parameter, sphere + 1,
            b.center.x, b.center.y, b.center.z));
    return {h.normal, std::acos(std::min(1.0, s / b.radius))};
}

} // namespace

TreatedBed treat_contacts(const Packing& packing, const Contacts& contacts,
                          const std::optional<SurfaceContainer>& container) {
    const std::size_t n = packing.size();
    // In a periodic cell the centres moved into the cell, and pairs by the minimum image.
    const std::optional<Periods> cell = container ? container->periods() : std::nullopt;
    if (cell && (contacts.treatment == ContactTreatment::enlarge ||
                 contacts.treatment == ContactTreatment::bridges))
        throw InvalidInput(fmt::format(
            "--contacts {}:{} is not allowed in the periodic cell {}; allowed: caps:H, shrink:F "
            "or none (the unions of enlarge and bridges are not copied across the sides)",
            contact_treatments().name(contacts.treatment), contacts.parameter,
            container->container.spec()));
    if (cell && n > 0) {
        // The minimum image finds every contact only where no sphere can reach two copies of
        // another (caps reach `gap` beyond touching: contacts closer than that), and a sphere
        // crosses at most one side of each pair. A cell exactly 2 d wide of touching spheres
        // would lose the caps across its sides.
        const double widest = 2.0 * *std::max_element(packing.radii.begin(), packing.radii.end());
        const double gap = contacts.treatment == ContactTreatment::caps
                               ? contacts.parameter * packing.mean_diameter()
                               : 0.0;
        const double narrowest = cell->lz() > 0.0 ? std::min({cell->lx(), cell->ly(), cell->lz()})
                                                  : std::min(cell->lx(), cell->ly());
        if (!(narrowest >= 2.0 * (widest + gap)))
            throw InvalidInput(fmt::format(
                "--container {} is not allowed for spheres of diameter up to {}{}; allowed: "
                "periods at least twice the largest diameter{}, {} (the minimum image)",
                container->container.spec(), widest,
                gap > 0.0 ? fmt::format(" with --contacts caps:{}", contacts.parameter) : "",
                gap > 0.0 ? " and the caps' gap" : "", 2.0 * (widest + gap)));
    }
    std::vector<Vec3> wrapped;
    if (cell)
        for (const Vec3& c : packing.centers)
            wrapped.push_back(cell->wrapped(c));
    const std::span<const Vec3> centers =
        cell ? std::span<const Vec3>(wrapped) : std::span<const Vec3>(packing.centers);
    const auto separation = [cell](const Vec3& a, const Vec3& b) {
        return cell ? cell->separation(a, b) : b - a;
    };
    TreatedBed bed;
    bed.bodies.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        bed.bodies[i] = {centers[i], packing.radii[i], {}};
    if (contacts.treatment == ContactTreatment::none || n == 0)
        return bed;
    std::vector<TreatedBody>& bodies = bed.bodies;
    for (std::size_t i = 0; i < n; ++i)
        if (!(packing.centers[i].z > 0.0) && !(container && container->periodic_z))
            throw InvalidInput(fmt::format(
                "sphere {} at ({:.6g}, {:.6g}, {:.6g}) has its centre on or below the floor "
                "z = 0; allowed: centres above the floor for --contacts {}",
                i + 1, packing.centers[i].x, packing.centers[i].y, packing.centers[i].z,
                contact_treatments().name(contacts.treatment)));
    const double dp = packing.mean_diameter();
    const double length = contacts.parameter * dp;

    if (contacts.treatment == ContactTreatment::shrink) {
        for (TreatedBody& b : bodies)
            b.radius *= 1.0 - contacts.parameter;
        NeighborList list;
        if (cell)
            list.wrap(*cell);
        std::vector<double> radii(n);
        for (std::size_t i = 0; i < n; ++i)
            radii[i] = bodies[i].radius;
        list.build(centers, radii, 1e-9 * dp);
        for (std::size_t i = 0; i < n; ++i) {
            for (const std::uint32_t j : list.upper_neighbors_of(i)) {
                const double d = norm(separation(centers[i], centers[j]));
                if (!(d > radii[i] + radii[j]))
                    throw InvalidInput(fmt::format(
                        "--contacts shrink:{} leaves spheres {} and {} overlapping (centres {:.6g} "
                        "apart, shrunk radii {:.6g} and {:.6g}); allowed: F above the bed's "
                        "largest "
                        "overlap in Dp",
                        contacts.parameter, i + 1, j + 1, d, radii[i], radii[j]));
            }
            const Vec3& x = packing.centers[i];
            if ((container && container->container.wall_distances(x, radii[i]).first <= 0.0) ||
                (x.z - radii[i] <= 0.0 && !(container && container->periodic_z)))
                throw InvalidInput(fmt::format(
                    "--contacts shrink:{} leaves sphere {} at ({:.6g}, {:.6g}, {:.6g}) touching "
                    "the container; allowed: F above its overlap with the wall or floor",
                    contacts.parameter, i + 1, x.x, x.y, x.z));
        }
        return bed;
    }

    // The footprint of everything that meets each sphere, to refuse parameters for which the
    // closed-form volumes would not hold.
    std::vector<std::vector<Footprint>> footprints(n);
    if (contacts.treatment == ContactTreatment::enlarge)
        for (TreatedBody& b : bodies)
            b.radius *= 1.0 + contacts.parameter;
    std::vector<double> radii(n);
    for (std::size_t i = 0; i < n; ++i)
        radii[i] = bodies[i].radius;
    // Caps: pairs closer than `length`; bridges: closer than bridge_gap Dp; enlarge: the
    // enlarged bodies that overlap (their lenses).
    const double reach = contacts.treatment == ContactTreatment::caps      ? length
                         : contacts.treatment == ContactTreatment::bridges ? bridge_gap * dp
                                                                           : 1e-9 * dp;
    NeighborList list;
    if (cell)
        list.wrap(*cell);
    list.build(centers, radii, reach);
    for (std::size_t i = 0; i < n; ++i)
        for (const std::uint32_t j : list.upper_neighbors_of(i)) {
            const Vec3 r = separation(centers[i], centers[j]);
            const double d = norm(r);
            const double gap = d - radii[i] - radii[j];
            if (!(gap < reach) || (contacts.treatment == ContactTreatment::enlarge && gap >= 0.0))
                continue;
            if (!(d > std::max(radii[i], radii[j])))
                throw InvalidInput(fmt::format(
                    "spheres {} and {} overlap by more than a radius (centres {:.6g} apart); "
                    "allowed: beds whose centres are farther apart than a radius for --contacts "
                    "{}",
                    i + 1, j + 1, d, contact_treatments().name(contacts.treatment)));
            const Vec3 u = r * (1.0 / d);
            if (contacts.treatment == ContactTreatment::caps) {
                const double si = radii[i] + 0.5 * (gap - length);
                const double sj = radii[j] + 0.5 * (gap - length);
                bodies[i].cuts.push_back({u, dot(u, centers[i]) + si});
                bodies[j].cuts.push_back({u * -1.0, dot(u * -1.0, centers[j]) + sj});
                continue;
            }
            // The lens of an overlapping pair: its rim lies in the radical plane, d1 from i.
            const double d1 = (d * d + radii[i] * radii[i] - radii[j] * radii[j]) / (2.0 * d);
            const double lens_rim =
                gap < 0.0 ? std::sqrt(std::max(0.0, radii[i] * radii[i] - d1 * d1)) : 0.0;
            if (contacts.treatment == ContactTreatment::enlarge) {
                footprints[i].push_back({u, std::acos(std::clamp(d1 / radii[i], -1.0, 1.0))});
                footprints[j].push_back(
                    {u * -1.0, std::acos(std::clamp((d - d1) / radii[j], -1.0, 1.0))});
                continue;
            }
            const double rho = 0.5 * length; // bridges
            if (!(lens_rim <= rho))
                throw InvalidInput(fmt::format(
                    "--contacts bridges:{} is thinner than the overlap of spheres {} and {} (its "
                    "rim has radius {:.6g}); allowed: D above twice that, in Dp",
                    contacts.parameter, i + 1, j + 1, lens_rim));
            bed.bridges.push_back({static_cast<std::uint32_t>(i), j, rho});
            footprints[i].push_back({u, std::asin(std::min(1.0, rho / radii[i]))});
            footprints[j].push_back({u * -1.0, std::asin(std::min(1.0, rho / radii[j]))});
        }
    const double wall_gap =
        contacts.treatment == ContactTreatment::bridges ? bridge_gap * dp : length;
    for (std::size_t i = 0; i < n; ++i) {
        cut_at_walls(bodies[i], wall_gap, container);
        for (const HalfSpace& h : bodies[i].cuts)
            footprints[i].push_back(cut_footprint(bodies[i], h, i, contacts));
        refuse_meeting_footprints(footprints[i], i, packing.centers[i], contacts);
    }
    bed.unite = contacts.treatment == ContactTreatment::enlarge ||
                contacts.treatment == ContactTreatment::bridges;
    return bed;
}

namespace {

/// The volume of the sphere inside the container between its floor and height; the whole
/// sphere where it crosses the bottom or the top of a cell periodic along z (its parts beyond
/// are inside across the other).
double sphere_in_container(const SurfaceContainer& container, const Vec3& c, double r) {
    if (container.periodic_z && (c.z - r < 0.0 || c.z + r > container.height))
        return 4.0 / 3.0 * std::numbers::pi * r * r * r;
    return container.container.sphere_volume(c, r, 0.0, container.height);
}

} // namespace

TreatmentVolumes treatment_volumes(const Packing& packing, const TreatedBed& bed,
                                   const SurfaceContainer& container) {
    TreatmentVolumes v;
    v.container_volume =
        container.container.cross_section_area(0.0, container.height) * container.height;
    const std::size_t n = packing.size();
    const auto lenses = [&](const std::vector<double>& radii) {
        double sum = 0.0;
        if (n == 0)
            return sum;
        NeighborList list;
        const std::optional<Periods> cell = container.periods();
        if (cell)
            list.wrap(*cell);
        list.build(packing.centers, radii, 1e-9 * packing.mean_diameter());
        for (std::size_t i = 0; i < n; ++i)
            for (const std::uint32_t j : list.upper_neighbors_of(i))
                sum +=
                    lens_volume(radii[i], radii[j],
                                norm(cell ? cell->separation(packing.centers[i], packing.centers[j])
                                          : packing.centers[j] - packing.centers[i]));
        return sum;
    };
    for (std::size_t i = 0; i < n; ++i)
        v.untouched_solid += sphere_in_container(container, packing.centers[i], packing.radii[i]);
    v.untouched_solid -= lenses(packing.radii);
    bool untreated = bed.bridges.empty();
    for (std::size_t i = 0; i < n; ++i)
        untreated =
            untreated && bed.bodies[i].radius == packing.radii[i] && bed.bodies[i].cuts.empty();
    if (untreated) {
        v.treated_solid = v.untouched_solid;
    } else {
        std::vector<double> radii(n);
        for (std::size_t i = 0; i < n; ++i) {
            const TreatedBody& b = bed.bodies[i];
            radii[i] = b.radius;
            double volume = 4.0 / 3.0 * std::numbers::pi * b.radius * b.radius * b.radius;
            for (const HalfSpace& h : b.cuts)
                volume -= spherical_cap_volume(b.radius, h.offset - dot(h.normal, b.center));
            v.treated_solid += volume;
        }
        if (bed.unite)
            v.treated_solid -= lenses(radii);
        for (const Bridge& br : bed.bridges) {
            const TreatedBody& a = bed.bodies[br.first];
            const TreatedBody& b = bed.bodies[br.second];
            const double d = norm(b.center - a.center);
            v.treated_solid += std::numbers::pi * br.radius * br.radius * d -
                               half_ball_in_cylinder(a.radius, br.radius) -
                               half_ball_in_cylinder(b.radius, br.radius) +
                               lens_volume(a.radius, b.radius, d);
        }
    }
    v.untouched_void_fraction = 1.0 - v.untouched_solid / v.container_volume;
    v.treated_void_fraction = 1.0 - v.treated_solid / v.container_volume;
    return v;
}

namespace {

/// A prism of `sides` inscribed in the cylinder of radius `rho` about the segment a -> b, closed
/// by flat ends (fans from the end centres), outward.
TriangleMesh bridge_prism(const Vec3& a, const Vec3& b, double rho, int sides) {
    const Vec3 axis = (b - a) * (1.0 / norm(b - a));
    // A generic helper direction, so that the prisms of mirror-image bridges (in a lattice, or
    // three spheres in a triangle) are not mirror images of each other: their intersections
    // then never pass exactly through edges of both, which gives the union degenerate faces.
    const Vec3 generic{0.5477, 0.2823, 0.7876}, other{-0.6192, 0.7711, 0.1480};
    const Vec3 helper = std::abs(dot(axis, generic)) < 0.9 * norm(generic) ? generic : other;
    Vec3 u = cross(axis, helper);
    u *= 1.0 / norm(u);
    const Vec3 w = cross(axis, u);
    TriangleMesh m;
    const auto s = static_cast<std::uint32_t>(sides);
    for (const Vec3& end : {a, b})
        for (std::uint32_t k = 0; k < s; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / sides;
            m.vertices.push_back(end + (u * std::cos(angle) + w * std::sin(angle)) * rho);
        }
    m.vertices.push_back(a);
    m.vertices.push_back(b);
    for (std::uint32_t k = 0; k < s; ++k) {
        const std::uint32_t k1 = (k + 1) % s;
        m.triangles.push_back({k, k1, s + k1}); // (u, w, axis) right-handed: outward
        m.triangles.push_back({k, s + k1, s + k});
        m.triangles.push_back({2 * s, k1, k});             // end a, normal -axis
        m.triangles.push_back({2 * s + 1, s + k, s + k1}); // end b, normal +axis
    }
    return m;
}

} // namespace

TreatedBed periodic_images(const TreatedBed& bed, const Periods& cell) {
    if (!bed.bridges.empty() || bed.unite)
        throw std::logic_error("periodic_images: bridges and unions are not copied");
    TreatedBed out = bed;
    for (const TreatedBody& b : bed.bodies) {
        // The shifts that bring a copy into the cell: + a period where the sphere crosses
        // the low side, - one where it crosses the high side (both at once: narrower cells
        // are refused by the minimum image's rule, 2 Dp).
        std::vector<double> xs{0.0}, ys{0.0}, zs{0.0};
        if (b.center.x - b.radius < 0.0)
            xs.push_back(cell.lx());
        if (b.center.x + b.radius > cell.lx())
            xs.push_back(-cell.lx());
        if (b.center.y - b.radius < 0.0)
            ys.push_back(cell.ly());
        if (b.center.y + b.radius > cell.ly())
            ys.push_back(-cell.ly());
        if (cell.lz() > 0.0 && b.center.z - b.radius < 0.0)
            zs.push_back(cell.lz());
        if (cell.lz() > 0.0 && b.center.z + b.radius > cell.lz())
            zs.push_back(-cell.lz());
        for (const double sz : zs)
            for (const double sx : xs)
                for (const double sy : ys) {
                    if (sx == 0.0 && sy == 0.0 && sz == 0.0)
                        continue;
                    const Vec3 shift{sx, sy, sz};
                    TreatedBody copy = b;
                    copy.center = b.center + shift;
                    for (HalfSpace& h : copy.cuts)
                        h.offset += dot(h.normal, shift);
                    out.bodies.push_back(std::move(copy));
                }
    }
    return out;
}

namespace {

/// Whether a cut of `a` and one of `b` (moved by `shift`: its image across a periodic cell's
/// side) face each other, b's beyond a's: the two bodies lie on the two sides of the slab
/// between them (caps).
bool cut_apart(const TreatedBody& a, const TreatedBody& b, const Vec3& shift) {
    for (const HalfSpace& ha : a.cuts)
        for (const HalfSpace& hb : b.cuts)
            if (dot(ha.normal, hb.normal) < -1.0 + 1e-12 &&
                -(hb.offset + dot(hb.normal, shift)) >= ha.offset)
                return true;
    return false;
}

/// Whether `b` has a cut along `normal` whose plane lies at `offset` or inside it (a wall's or
/// the floor's cap).
bool cut_at(const TreatedBody& b, const Vec3& normal, double offset) {
    return std::ranges::any_of(b.cuts, [&](const HalfSpace& h) {
        return dot(h.normal, normal) > 1.0 - 1e-12 && h.offset <= offset;
    });
}

/// The first place where facets grown by `growth` (a fraction of each radius) would meet
/// another body or leave the container (volume_facets_conflict's contract).
std::optional<std::string> room_to_grow(const TreatedBed& bed,
                                        const std::optional<SurfaceContainer>& container,
                                        double growth) {
    const std::vector<TreatedBody>& bodies = bed.bodies;
    if (bodies.empty())
        return std::nullopt;
    double largest = 0.0;
    for (const TreatedBody& b : bodies)
        largest = std::max(largest, b.radius);
    const auto conflict = [&](std::size_t i, const std::string& what, double gap) {
        return fmt::format(
            "--facets volume is not allowed here: it grows sphere {}'s facets by {:.3g}, and its "
            "gap to {} is {:.3g}; allowed: a contact treatment that leaves wider gaps (caps:H, "
            "shrink:F), a finer --refine, or --facets inscribed or auto",
            i + 1, growth * bodies[i].radius, what, gap);
    };
    if (!bed.unite) {
        const std::optional<Periods> cell = container ? container->periods() : std::nullopt;
        std::vector<Vec3> centers;
        std::vector<double> radii;
        for (const TreatedBody& b : bodies) {
            centers.push_back(b.center);
            radii.push_back(b.radius);
        }
        NeighborList list;
        if (cell)
            list.wrap(*cell);
        list.build(centers, radii, 2.0 * growth * largest);
        for (std::size_t i = 0; i < bodies.size(); ++i)
            for (const std::uint32_t j : list.upper_neighbors_of(i)) {
                const Vec3 r =
                    cell ? cell->separation(centers[i], centers[j]) : centers[j] - centers[i];
                const double gap = norm(r) - radii[i] - radii[j];
                if (gap < growth * (radii[i] + radii[j]) &&
                    !cut_apart(bodies[i], bodies[j], centers[i] + r - centers[j]))
                    return conflict(i, fmt::format("sphere {}", j + 1), gap);
            }
    }
    if (!container)
        return std::nullopt;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const TreatedBody& b = bodies[i];
        const double grown = growth * b.radius;
        if (!container->periodic_z) {
            const double floor_gap = b.center.z - b.radius;
            if (floor_gap < grown && !cut_at(b, {0.0, 0.0, -1.0}, 0.0))
                return conflict(i, "the floor", floor_gap);
            const double top_gap = container->height - b.center.z - b.radius;
            if (top_gap < grown)
                return conflict(i, "the top", top_gap);
        }
        for (const WallPlane& wall : container->container.walls_within(b.center, b.radius, grown))
            if (!cut_at(b, wall.normal, wall.offset))
                return conflict(i, "the wall", wall.offset - dot(wall.normal, b.center) - b.radius);
    }
    return std::nullopt;
}

} // namespace

std::optional<std::string> volume_facets_conflict(const TreatedBed& bed,
                                                  const std::optional<SurfaceContainer>& container,
                                                  int level) {
    return room_to_grow(bed, container, volume_facets_scale(level) - 1.0);
}

Facets facets_for(const TreatedBed& bed, const SurfaceOptions& options) {
    if (options.facets != Facets::automatic)
        return options.facets;
    return volume_facets_conflict(bed, options.container, options.level) ? Facets::inscribed
                                                                         : Facets::volume;
}

std::vector<Solid> bed_surface(const TreatedBed& given, const SurfaceOptions& options) {
    // A periodic cell: every body cut by a side and its copies across the sides.
    const std::optional<Periods> cell =
        options.container ? options.container->periods() : std::nullopt;
    const TreatedBed imaged = cell ? periodic_images(given, *cell) : TreatedBed{};
    const TreatedBed& bed = cell ? imaged : given;
    const std::vector<TreatedBody>& bodies = bed.bodies;
    const SphereShape sphere;
    TriangleMesh unit = sphere.unit_surface(options.level);
    if (options.facets == Facets::volume) {
        if (const std::optional<std::string> conflict =
                volume_facets_conflict(given, options.container, options.level))
            throw InvalidInput(*conflict);
    }
    if (facets_for(given, options) == Facets::volume) {
        const double scale = volume_facets_scale(options.level);
        for (Vec3& v : unit.vertices)
            v = v * scale;
    }
    double largest = 0.0;
    for (const TreatedBody& b : bodies)
        largest = std::max(largest, b.radius);
    const double edge = largest * icosphere_edge(options.level);
    const double snap = 0.02 * edge;
    const auto body_mesh = [&](std::size_t i) {
        TriangleMesh m = unit;
        place_surface<SphereShape>(m, {bodies[i].center, {}, bodies[i].radius});
        for (const HalfSpace& h : bodies[i].cuts)
            m = clip_convex(m, h, snap);
        return m;
    };
    std::vector<Solid> solids(1);
    solids[0].name = "particles";
    if (!bed.unite) {
        // Separate bodies: made in parallel a block at a time and appended in order, so that
        // only one block's meshes exist next to the solid (memory about one copy).
        TriangleMesh& all = solids[0].mesh;
        // Caps add about an eighth to a level-3 sphere (1 442 triangles a body for the
        // 10 000-sphere bed with caps:0.01, against 1 280): room for a quarter more.
        all.vertices.reserve(bodies.size() * (unit.vertices.size() * 5 / 4 + 64));
        all.triangles.reserve(bodies.size() * (unit.triangles.size() * 5 / 4 + 64));
        constexpr std::size_t block = 4096;
        std::vector<TriangleMesh> meshes(block);
        for (std::size_t first = 0; first < bodies.size(); first += block) {
            const std::size_t count = std::min(block, bodies.size() - first);
#pragma omp parallel for schedule(dynamic, 64)
            for (std::size_t k = 0; k < count; ++k)
                meshes[k] = body_mesh(first + k);
            for (std::size_t k = 0; k < count; ++k)
                all.append(meshes[k]);
        }
    } else {
        std::vector<TriangleMesh> meshes(bodies.size() + bed.bridges.size());
#pragma omp parallel for schedule(dynamic, 64)
        for (std::size_t i = 0; i < bodies.size(); ++i)
            meshes[i] = body_mesh(i);
        for (std::size_t k = 0; k < bed.bridges.size(); ++k) {
            const Bridge& br = bed.bridges[k];
            const int sides = std::max(
                12, static_cast<int>(std::ceil(2.0 * std::numbers::pi * br.radius / edge)));
            // The prism ends inside the two spheres, halfway from each centre to where the
            // cylinder leaves it: not at the centres, where the ends of several bridges would
            // coincide (degenerate intersections for the union). The volume outside the
            // spheres is the same.
            const TreatedBody& a = bodies[br.first];
            const TreatedBody& b = bodies[br.second];
            const Vec3 axis = (b.center - a.center) * (1.0 / norm(b.center - a.center));
            const auto inset = [&](const TreatedBody& body) {
                return 0.5 * std::sqrt(body.radius * body.radius - br.radius * br.radius);
            };
            meshes[bodies.size() + k] = bridge_prism(a.center + axis * inset(a),
                                                     b.center - axis * inset(b), br.radius, sides);
        }
        // Neighbours in the tree of unions should be neighbours in space: bodies by height,
        // each bridge after the lower of its two bodies.
        std::vector<std::size_t> order(meshes.size());
        std::vector<double> key(meshes.size());
        for (std::size_t i = 0; i < bodies.size(); ++i)
            key[i] = bodies[i].center.z;
        for (std::size_t k = 0; k < bed.bridges.size(); ++k)
            key[bodies.size() + k] = std::min(bodies[bed.bridges[k].first].center.z,
                                              bodies[bed.bridges[k].second].center.z);
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
        std::vector<TriangleMesh> ordered;
        ordered.reserve(meshes.size());
        for (const std::size_t i : order)
            ordered.push_back(std::move(meshes[i]));
        // Edges below 1e-4 of a sphere's edge length would collapse in single precision.
        solids[0].mesh = detail::mesh_union(std::move(ordered), 1e-4 * edge);
    }

    if (options.container && options.write_container) {
        const Container& container = options.container->container;
        for (Solid& s :
             container.solids(0.0, options.container->height,
                              largest > 0.0 ? edge
                                            : container.depth(0.0, options.container->height) *
                                                  icosphere_edge(options.level)))
            solids.push_back(std::move(s));
    }
    return solids;
}

namespace {

/// The unit normal of a facet as STL stores it: from its corners rounded to single precision,
/// so that it agrees with the normal a reader computes from the file.
Vec3 facet_normal(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t) {
    const auto rounded = [&](std::uint32_t v) {
        const Vec3& p = m.vertices[v];
        return Vec3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
    };
    const Vec3 a = rounded(t[0]);
    const Vec3 n = cross(rounded(t[1]) - a, rounded(t[2]) - a);
    const double length = norm(n);
    return length > 0.0 ? n * (1.0 / length) : Vec3{};
}

void put_float(std::string& buffer, double value) {
    const auto f = static_cast<float>(value);
    char bytes[4];
    std::memcpy(bytes, &f, 4); // STL is little-endian, as every platform we build on
    buffer.append(bytes, 4);
}

} // namespace

void write_surface(const std::vector<Solid>& solids, SurfaceFormat format,
                   const std::filesystem::path& path) {
    std::ofstream file(path, std::ios::binary);
    if (!file)
        throw std::runtime_error(fmt::format("cannot write {} ({}); nothing was written",
                                             printable(path.native()), std::strerror(errno)));
    std::string buffer;
    const auto flush = [&](bool force) {
        if (force || buffer.size() > (1u << 20)) {
            file.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
            buffer.clear();
        }
    };
    if (format == SurfaceFormat::stl_binary) {
        std::string header = "packbed surface:";
        for (const Solid& s : solids)
            header += " " + s.name;
        header.resize(80, ' ');
        buffer += header;
        std::uint32_t count = 0;
        for (const Solid& s : solids)
            count += static_cast<std::uint32_t>(s.mesh.triangles.size());
        char bytes[4];
        std::memcpy(bytes, &count, 4);
        buffer.append(bytes, 4);
        for (const Solid& s : solids)
            for (const auto& t : s.mesh.triangles) {
                const Vec3 n = facet_normal(s.mesh, t);
                put_float(buffer, n.x);
                put_float(buffer, n.y);
                put_float(buffer, n.z);
                for (const std::uint32_t v : t) {
                    put_float(buffer, s.mesh.vertices[v].x);
                    put_float(buffer, s.mesh.vertices[v].y);
                    put_float(buffer, s.mesh.vertices[v].z);
                }
                buffer.append(2, '\0');
                flush(false);
            }
    } else if (format == SurfaceFormat::stl_ascii) {
        for (const Solid& s : solids) {
            buffer += fmt::format("solid {}\n", s.name);
            for (const auto& t : s.mesh.triangles) {
                const Vec3 n = facet_normal(s.mesh, t);
                buffer +=
                    fmt::format(" facet normal {} {} {}\n  outer loop\n", static_cast<float>(n.x),
                                static_cast<float>(n.y), static_cast<float>(n.z));
                for (const std::uint32_t v : t) {
                    const Vec3& p = s.mesh.vertices[v];
                    buffer += fmt::format("   vertex {} {} {}\n", static_cast<float>(p.x),
                                          static_cast<float>(p.y), static_cast<float>(p.z));
                }
                buffer += "  endloop\n endfacet\n";
                flush(false);
            }
            buffer += fmt::format("endsolid {}\n", s.name);
        }
    } else {
        buffer += "# packbed surface\n";
        std::size_t base = 1;
        for (const Solid& s : solids) {
            buffer += fmt::format("o {}\ng {}\n", s.name, s.name);
            for (const Vec3& p : s.mesh.vertices) {
                buffer += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
                flush(false);
            }
            for (const auto& t : s.mesh.triangles) {
                buffer += fmt::format("f {} {} {}\n", t[0] + base, t[1] + base, t[2] + base);
                flush(false);
            }
            base += s.mesh.vertices.size();
        }
    }
    flush(true);
    file.close();
    if (!file)
        throw std::runtime_error(fmt::format("cannot write {} ({}); nothing was written",
                                             printable(path.native()), std::strerror(errno)));
}

} // namespace packbed
