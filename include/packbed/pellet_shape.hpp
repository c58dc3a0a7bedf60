// The pellets' shapes as one type: what the pellet solver, the pipeline, the analysis and the
// exports take, each answering through the shape's own class (std::visit).
#pragma once

#include <variant>

#include "packbed/multilobe_shape.hpp"
#include "packbed/spherocylinder_shape.hpp"

namespace packbed {

/// A pellet's shape at size 1 (volume-equivalent radius 1): a cylinder, a ring or a multilobe
/// (MultilobeShape, pressed by its surface's nodes) or a spherocylinder (SpherocylinderShape,
/// by its exact depth).
using PelletShape = std::variant<MultilobeShape, SpherocylinderShape>;

/// The pellet's smallest dimension in units of d_v (MultilobeShape::smallest_dimension,
/// SpherocylinderShape::smallest_dimension: d_v = 2 at size 1).
inline double smallest_dimension(const PelletShape& shape) {
    return std::visit([](const auto& s) { return s.smallest_dimension(); }, shape);
}
/// The pellet's bounding radius at `size`.
inline double bounding_radius(const PelletShape& shape, double size) {
    return std::visit([size](const auto& s) { return s.bounding_radius(size); }, shape);
}

} // namespace packbed
