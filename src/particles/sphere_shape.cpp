#include "packbed/sphere_shape.hpp"

#include <cmath>
#include <tuple>

#include "packbed/surface.hpp"
#include "packbed/voxel.hpp"

namespace packbed {

double SphereShape::volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const {
    return ball_box_volume(p.position, p.size, low, high);
}

TriangleMesh SphereShape::unit_surface(int level) const {
    TriangleMesh unit = icosphere(level);
    for (Vec3& v : unit.vertices) {
        const auto turn = [](double a, double b, double angle) {
            return std::pair{a * std::cos(angle) - b * std::sin(angle),
                             a * std::sin(angle) + b * std::cos(angle)};
        };
        std::tie(v.x, v.y) = turn(v.x, v.y, 1.0);
        std::tie(v.z, v.x) = turn(v.z, v.x, 2.0);
        std::tie(v.y, v.z) = turn(v.y, v.z, 3.0);
    }
    return unit;
}

} // namespace packbed
