// A rotation about an axis for the shape tests: quaternion.hpp's exponential map.
#pragma once

#include "packbed/quaternion.hpp"
#include "packbed/vec3.hpp"

/// The rotation by `angle` radians about the unit vector `axis`.
inline packbed::Quaternion about(const packbed::Vec3& axis, double angle) {
    return packbed::rotation_by(axis * angle);
}
