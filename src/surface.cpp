#include "packbed/surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/volume.hpp"
#include "require.hpp"

namespace packbed {

namespace {

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

/// Mean edge of the unit icosphere of a level: the icosahedron's edge 1.0515 halved per level
/// (the projection onto the sphere lengthens it a little; this is a bound from below).
double unit_edge(int level) {
    return 1.0515 / std::ldexp(1.0, level);
}

} // namespace

void TriangleMesh::append(const TriangleMesh& other) {
    const auto shift = static_cast<std::uint32_t>(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const auto& t : other.triangles)
        triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
}

double TriangleMesh::volume() const {
    double six_v = 0.0;
    for (const auto& t : triangles)
        six_v += dot(vertices[t[0]], cross(vertices[t[1]], vertices[t[2]]));
    return six_v / 6.0;
}

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

int icosphere_level_for_edge(double radius, double edge) {
    int level = 0;
    while (level < 7 && radius * unit_edge(level) > edge)
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

const std::vector<std::pair<std::string, ContactTreatment>>& contact_treatments() {
    static const std::vector<std::pair<std::string, ContactTreatment>> names{
        {"none", ContactTreatment::none},
        {"shrink", ContactTreatment::shrink},
        {"caps", ContactTreatment::caps}};
    return names;
}

Contacts parse_contacts(std::string_view text) {
    const std::string allowed = "none, shrink:F or caps:H with F, H fractions of Dp in (0, 0.5)";
    const auto colon = text.find(':');
    const std::string_view name = text.substr(0, colon);
    Contacts c;
    bool known = false;
    for (const auto& [n, t] : contact_treatments())
        if (n == name) {
            c.treatment = t;
            known = true;
        }
    const auto refuse = [&] {
        return InvalidInput(
            fmt::format("--contacts '{}' is not allowed; allowed: {}", text, allowed));
    };
    if (!known || (c.treatment == ContactTreatment::none) != (colon == std::string_view::npos))
        throw refuse();
    if (c.treatment != ContactTreatment::none) {
        const std::string value(text.substr(colon + 1));
        char* end = nullptr;
        c.parameter = std::strtod(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size() || !(c.parameter > 0.0) ||
            !(c.parameter < 0.5))
            throw refuse();
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

std::vector<TreatedBody> treat_contacts(const Packing& packing, const Contacts& contacts,
                                        const std::optional<SurfaceContainer>& container) {
    const std::size_t n = packing.size();
    std::vector<TreatedBody> bodies(n);
    for (std::size_t i = 0; i < n; ++i)
        bodies[i] = {packing.centers[i], packing.radii[i], {}};
    if (contacts.treatment == ContactTreatment::none || n == 0)
        return bodies;
    const double dp = packing.mean_diameter();
    const double length = contacts.parameter * dp;
    const double rt = container ? container->cylinder.radius() : 0.0;

    if (contacts.treatment == ContactTreatment::shrink) {
        for (TreatedBody& b : bodies)
            b.radius *= 1.0 - contacts.parameter;
        NeighborList list;
        std::vector<double> radii(n);
        for (std::size_t i = 0; i < n; ++i)
            radii[i] = bodies[i].radius;
        list.build(packing.centers, radii, 1e-9 * dp);
        for (std::size_t i = 0; i < n; ++i) {
            for (const std::uint32_t j : list.upper_neighbors_of(i)) {
                const double d = norm(packing.centers[j] - packing.centers[i]);
                if (!(d > radii[i] + radii[j]))
                    throw InvalidInput(fmt::format(
                        "--contacts shrink:{} leaves spheres {} and {} overlapping (centres {:.6g} "
                        "apart, shrunk radii {:.6g} and {:.6g}); allowed: F above the bed's "
                        "largest "
                        "overlap in Dp",
                        contacts.parameter, i + 1, j + 1, d, radii[i], radii[j]));
            }
            const Vec3& x = packing.centers[i];
            if ((container && std::hypot(x.x, x.y) + radii[i] >= rt) || x.z - radii[i] <= 0.0)
                throw InvalidInput(fmt::format(
                    "--contacts shrink:{} leaves sphere {} at ({:.6g}, {:.6g}, {:.6g}) touching "
                    "the container; allowed: F above its overlap with the wall or floor",
                    contacts.parameter, i + 1, x.x, x.y, x.z));
        }
        return bodies;
    }

    // Caps: every pair closer than `length` is cut by two planes `length` apart, placed
    // symmetrically about the middle of the gap (or overlap) between the two surfaces.
    NeighborList list;
    list.build(packing.centers, packing.radii, length);
    for (std::size_t i = 0; i < n; ++i)
        for (const std::uint32_t j : list.upper_neighbors_of(i)) {
            const Vec3 r = packing.centers[j] - packing.centers[i];
            const double d = norm(r);
            const double gap = d - packing.radii[i] - packing.radii[j];
            if (!(gap < length))
                continue;
            if (!(d > 0.0))
                throw InvalidInput(fmt::format(
                    "spheres {} and {} have the same centre; allowed: distinct centres for "
                    "--contacts caps",
                    i + 1, j + 1));
            const Vec3 u = r * (1.0 / d);
            const double si = packing.radii[i] + 0.5 * (gap - length);
            const double sj = packing.radii[j] + 0.5 * (gap - length);
            bodies[i].cuts.push_back({u, dot(u, packing.centers[i]) + si});
            bodies[j].cuts.push_back({u * -1.0, dot(u * -1.0, packing.centers[j]) + sj});
        }
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& x = packing.centers[i];
        const double r = packing.radii[i];
        const double floor_gap = x.z - r;
        if (floor_gap < length) // plane z = length
            bodies[i].cuts.push_back({{0.0, 0.0, -1.0}, -length});
        if (container) {
            const double rho = std::hypot(x.x, x.y);
            if (rt - rho - r < length && rho > 0.0) // plane at rt - length from the axis
                bodies[i].cuts.push_back({{x.x / rho, x.y / rho, 0.0}, rt - length});
        }
        // The caps of one sphere must not meet: each removes exactly its spherical cap.
        const auto& cuts = bodies[i].cuts;
        for (std::size_t a = 0; a < cuts.size(); ++a) {
            const double sa = cuts[a].offset - dot(cuts[a].normal, x);
            if (!(sa > 0.0))
                throw InvalidInput(fmt::format(
                    "--contacts caps:{} cuts sphere {} at ({:.6g}, {:.6g}, {:.6g}) beyond its "
                    "centre; allowed: H below the sphere's gap to its neighbours plus its radius",
                    contacts.parameter, i + 1, x.x, x.y, x.z));
            for (std::size_t b = 0; b < a; ++b) {
                const double sb = cuts[b].offset - dot(cuts[b].normal, x);
                const double angle =
                    std::acos(std::clamp(dot(cuts[a].normal, cuts[b].normal), -1.0, 1.0));
                if (!(angle > std::acos(std::min(1.0, sa / r)) + std::acos(std::min(1.0, sb / r))))
                    throw InvalidInput(fmt::format(
                        "--contacts caps:{} gives sphere {} at ({:.6g}, {:.6g}, {:.6g}) two caps "
                        "that meet; allowed: a smaller H",
                        contacts.parameter, i + 1, x.x, x.y, x.z));
            }
        }
    }
    return bodies;
}

TreatmentVolumes treatment_volumes(const Packing& packing, const std::vector<TreatedBody>& bodies,
                                   const SurfaceContainer& container) {
    TreatmentVolumes v;
    const double rt = container.cylinder.radius();
    v.container_volume = std::numbers::pi * rt * rt * container.height;
    const std::size_t n = packing.size();
    for (std::size_t i = 0; i < n; ++i)
        v.untouched_solid += sphere_volume_in_cylinder_slab(packing.centers[i], packing.radii[i],
                                                            rt, 0.0, container.height);
    if (n > 0) {
        NeighborList list;
        list.build(packing.centers, packing.radii, 1e-9 * packing.mean_diameter());
        for (std::size_t i = 0; i < n; ++i)
            for (const std::uint32_t j : list.upper_neighbors_of(i))
                v.untouched_solid -= lens_volume(packing.radii[i], packing.radii[j],
                                                 norm(packing.centers[j] - packing.centers[i]));
    }
    bool untreated = true;
    for (std::size_t i = 0; i < n; ++i)
        untreated = untreated && bodies[i].radius == packing.radii[i] && bodies[i].cuts.empty();
    if (untreated) {
        v.treated_solid = v.untouched_solid;
    } else {
        for (const TreatedBody& b : bodies) {
            double volume = 4.0 / 3.0 * std::numbers::pi * b.radius * b.radius * b.radius;
            for (const HalfSpace& h : b.cuts)
                volume -= spherical_cap_volume(b.radius, h.offset - dot(h.normal, b.center));
            v.treated_solid += volume;
        }
    }
    v.untouched_void_fraction = 1.0 - v.untouched_solid / v.container_volume;
    v.treated_void_fraction = 1.0 - v.treated_solid / v.container_volume;
    return v;
}

std::vector<Solid> container_solids(const Cylinder& cylinder, double z_low, double z_high,
                                    double edge) {
    // A prism circumscribed about the cylinder: its faces are tangent to the cylinder from
    // outside, with sides about `edge` long.
    const double rt = cylinder.radius();
    const double h = z_high - z_low;
    const int sides =
        std::clamp(static_cast<int>(std::ceil(2.0 * std::numbers::pi * rt / edge)), 48, 100000);
    const double corner = rt / std::cos(std::numbers::pi / sides);
    // The wall in rows about as tall as a side is wide, every other row turned by half a
    // side, so that no two triangles are coplanar (the bottom and top are fans from the
    // axis). Each wall triangle projects onto the plane between a chord at distance Rt from
    // the axis and the circle through the corners: the wall stays outside the cylinder.
    const int rows = std::clamp(
        static_cast<int>(std::ceil(h / (2.0 * corner * std::sin(std::numbers::pi / sides)))), 1,
        4096);
    const auto s = static_cast<std::uint32_t>(sides);
    auto ring_point = [&](int row, std::uint32_t k) {
        const double angle = 2.0 * std::numbers::pi * (k + 0.5 * (row % 2)) / sides;
        return Vec3{corner * std::cos(angle), corner * std::sin(angle),
                    row == rows ? z_high : z_low + h * row / rows};
    };
    Solid wall{"wall", {}}, bottom{"bottom", {}}, top{"top", {}};
    for (int row = 0; row <= rows; ++row)
        for (std::uint32_t k = 0; k < s; ++k)
            wall.mesh.vertices.push_back(ring_point(row, k));
    for (std::uint32_t k = 0; k < s; ++k) {
        bottom.mesh.vertices.push_back(ring_point(0, k));
        top.mesh.vertices.push_back(ring_point(rows, k));
    }
    bottom.mesh.vertices.push_back({0.0, 0.0, z_low});
    top.mesh.vertices.push_back({0.0, 0.0, z_high});
    for (std::uint32_t row = 0; row < static_cast<std::uint32_t>(rows); ++row)
        for (std::uint32_t k = 0; k < s; ++k) {
            // The upper vertex between lower k and k + 1, and the next one.
            const std::uint32_t j = (k + row % 2) % s, j1 = (j + 1) % s;
            const std::uint32_t a = row * s + k, b = row * s + (k + 1) % s;
            wall.mesh.triangles.push_back({a, b, (row + 1) * s + j});
            wall.mesh.triangles.push_back({(row + 1) * s + j, b, (row + 1) * s + j1});
        }
    for (std::uint32_t k = 0; k < s; ++k) {
        const std::uint32_t k1 = (k + 1) % s;
        bottom.mesh.triangles.push_back({s, k1, k});
        top.mesh.triangles.push_back({s, k, k1});
    }
    std::vector<Solid> solids;
    solids.push_back(std::move(wall));
    solids.push_back(std::move(bottom));
    solids.push_back(std::move(top));
    return solids;
}

std::vector<Solid> bed_surface(const std::vector<TreatedBody>& bodies,
                               const SurfaceOptions& options) {
    const TriangleMesh unit = icosphere(options.level);
    double largest = 0.0;
    for (const TreatedBody& b : bodies)
        largest = std::max(largest, b.radius);
    const double snap = 0.02 * largest * unit_edge(options.level);
    std::vector<TriangleMesh> meshes(bodies.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        TriangleMesh m = unit;
        for (Vec3& v : m.vertices)
            v = bodies[i].center + v * bodies[i].radius;
        for (const HalfSpace& h : bodies[i].cuts)
            m = clip_convex(m, h, snap);
        meshes[i] = std::move(m);
    }
    std::vector<Solid> solids(1);
    solids[0].name = "particles";
    std::size_t nv = 0, nt = 0;
    for (const TriangleMesh& m : meshes) {
        nv += m.vertices.size();
        nt += m.triangles.size();
    }
    solids[0].mesh.vertices.reserve(nv);
    solids[0].mesh.triangles.reserve(nt);
    for (const TriangleMesh& m : meshes)
        solids[0].mesh.append(m);

    if (options.container && options.write_container) {
        double radius = 0.0;
        for (const TreatedBody& b : bodies)
            radius = std::max(radius, b.radius);
        const double rt = options.container->cylinder.radius();
        const double edge = (radius > 0.0 ? radius : rt) * unit_edge(options.level);
        for (Solid& s :
             container_solids(options.container->cylinder, 0.0, options.container->height, edge))
            solids.push_back(std::move(s));
    }
    return solids;
}

namespace {

Vec3 facet_normal(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t) {
    const Vec3 n = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
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
        throw std::runtime_error(fmt::format("cannot write {}", path.string()));
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
        throw std::runtime_error(fmt::format("writing {} failed", path.string()));
}

} // namespace packbed
