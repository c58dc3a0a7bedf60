// Internal: the union of closed triangle meshes, by CGAL's corefinement (the one place packbed
// does mesh booleans; kept in its own translation unit because CGAL's headers are heavy).
#pragma once

#include <vector>

#include "packbed/surface.hpp"

namespace packbed::detail {

/// The union of closed, outward, non-self-intersecting meshes: CGAL::Polygon_mesh_processing::
/// corefine_and_compute_union (exact predicates) over a balanced tree of the parts in the
/// given order (neighbours in the order should be neighbours in space), the pairs of one level
/// of the tree in parallel: the same result for any number of threads. Exact constructions
/// (CGAL's Epeck), then rounded to doubles, with slivers whose shortest edge is below
/// `shortest` removed (CGAL's experimental remove_almost_degenerate_faces).
/// \throws std::runtime_error when CGAL reports a union it could not build as a manifold
TriangleMesh mesh_union(std::vector<TriangleMesh> parts, double shortest);

} // namespace packbed::detail
