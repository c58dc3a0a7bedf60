#include "export/mesh_union.hpp"

#include <algorithm>
#include <stdexcept>

#include <cmath>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>

namespace packbed::detail {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Rounded = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

Mesh to_cgal(const TriangleMesh& m) {
    Mesh out;
    std::vector<Mesh::Vertex_index> v;
    v.reserve(m.vertices.size());
    for (const Vec3& p : m.vertices)
        v.push_back(out.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
    for (const auto& t : m.triangles)
        out.add_face(v[t[0]], v[t[1]], v[t[2]]);
    return out;
}

/// The union rounded to doubles, its needles (longest edge more than 10 times the shortest)
/// collapsed where the shortest edge is below `shortest` and its caps (an angle above 179
/// degrees) flipped: corefinement leaves such slivers where an intersection point falls next
/// to a vertex, and single-precision STL would turn them into degenerate facets.
/// The rounded mesh is built in a canonical order (vertices by their exact coordinates, faces by
/// their vertices' ranks), not in the order CGAL's corefinement numbers them: that order
/// depends on memory addresses (box_intersection_d, for one, breaks ties by box address, and
/// the pairs it reports fill unordered maps whose iteration numbers the intersection points),
/// so with several threads it changes from run to run. The collapses and flips, which go in
/// index order, then see the same mesh every run, and the output has one order.
TriangleMesh from_cgal(const Mesh& exact, double shortest) {
    std::vector<Mesh::Vertex_index> order(exact.vertices().begin(), exact.vertices().end());
    std::sort(order.begin(), order.end(), [&](Mesh::Vertex_index a, Mesh::Vertex_index b) {
        return CGAL::compare_xyz(exact.point(a), exact.point(b)) == CGAL::SMALLER;
    });
    Rounded m;
    std::vector<std::uint32_t> rank(exact.number_of_vertices() +
                                    exact.number_of_removed_vertices());
    for (std::size_t i = 0; i < order.size(); ++i) {
        rank[order[i]] = static_cast<std::uint32_t>(i);
        // From the exact value: the interval CGAL::to_double would take the middle of depends
        // on which constructions were refined before.
        const auto& p = CGAL::exact(exact.point(order[i]));
        m.add_vertex({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
    std::vector<std::array<std::uint32_t, 3>> faces;
    faces.reserve(exact.number_of_faces());
    for (const auto f : exact.faces()) {
        std::array<std::uint32_t, 3> t{};
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(exact.halfedge(f), exact))
            if (k < 3)
                t[k++] = rank[v];
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        faces.push_back(t);
    }
    std::sort(faces.begin(), faces.end());
    for (const auto& t : faces)
        m.add_face(Rounded::Vertex_index(t[0]), Rounded::Vertex_index(t[1]),
                   Rounded::Vertex_index(t[2]));
    CGAL::Polygon_mesh_processing::experimental::remove_almost_degenerate_faces(
        m, std::cos(179.0 / 180.0 * 3.141592653589793), 10.0, shortest);
    m.collect_garbage();
    TriangleMesh out;
    for (const auto v : m.vertices()) {
        const auto& p = m.point(v);
        out.vertices.push_back({p.x(), p.y(), p.z()});
    }
    for (const auto f : m.faces()) {
        std::array<std::uint32_t, 3> t{};
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m))
            if (k < 3)
                t[k++] = static_cast<std::uint32_t>(v.idx());
        out.triangles.push_back(t);
    }
    return out;
}

} // namespace

TriangleMesh mesh_union(std::vector<TriangleMesh> parts, double shortest) {
    if (parts.empty())
        return {};
    std::vector<Mesh> level(parts.size());
#pragma omp parallel for schedule(dynamic)
    for (std::size_t i = 0; i < parts.size(); ++i)
        level[i] = to_cgal(parts[i]);
    parts.clear();
    while (level.size() > 1) {
        std::vector<Mesh> next((level.size() + 1) / 2);
        bool ok = true;
#pragma omp parallel for schedule(dynamic) reduction(&& : ok)
        for (std::size_t i = 0; i < next.size(); ++i) {
            if (2 * i + 1 == level.size()) {
                next[i] = std::move(level[2 * i]);
                continue;
            }
            ok = CGAL::Polygon_mesh_processing::corefine_and_compute_union(
                     level[2 * i], level[2 * i + 1], next[i]) &&
                 ok;
        }
        if (!ok)
            throw std::runtime_error("the union of the treated bodies is not a manifold surface "
                                     "(CGAL corefinement)");
        level.swap(next);
    }
    return from_cgal(level[0], shortest);
}

} // namespace packbed::detail
