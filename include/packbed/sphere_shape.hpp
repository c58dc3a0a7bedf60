// The sphere: the first model of the ParticleShape concept, every answer the one the product
// gave before the concept (the same functions, in the same order: the same bits).
#pragma once

#include <numbers>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/mesh.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A sphere of radius `size` about its position; no parameter of its own, no orientation.
struct SphereShape {
    static constexpr std::string_view kind = "sphere";
    static constexpr bool oriented = false;

    double bounding_radius(double size) const { return size; }
    /// 4/3 pi r^3.
    double volume(double size) const { return 4.0 / 3.0 * std::numbers::pi * size * size * size; }
    /// The point p + r v / |v|.
    Vec3 support(const Placement& p, const Vec3& v) const {
        return p.position + v * (p.size / norm(v));
    }
    /// The container's wall law: its deepest wall overlap (Container::wall_overlap).
    double wall_overlap(const Container& c, const Placement& p) const {
        return c.wall_overlap(p.position, p.size);
    }
    /// r_a + r_b - |ab| along ab / |ab|, touching r_a - depth / 2 from a's centre.
    PairOverlap pair_overlap(const Placement& a, const SphereShape&, const Placement& b,
                             const Vec3& ab) const {
        const double distance = norm(ab);
        const double depth = a.size + b.size - distance;
        const Vec3 normal = ab * (1.0 / distance);
        return {depth, normal, normal * (a.size - 0.5 * depth)};
    }
    std::pair<double, double> wall_extent(const Container& c, std::size_t wall,
                                          const Placement& p) const {
        return c.wall_distances_from(wall, p.position, p.size);
    }
    /// Container::sphere_volume: closed forms and converged quadrature.
    double volume_in(const Container& c, const Placement& p, double z_low, double z_high) const {
        return c.sphere_volume(p.position, p.size, z_low, z_high);
    }
    /// Container::ball_volume of the container shrunk from the wall by d (one integral over
    /// the radius where the band's planes do not cut the sphere).
    double volume_from_wall(const Container& c, std::size_t wall, double d, const Placement& p,
                            double z_low, double z_high) const {
        return c.shrunk_from(wall, d).ball_volume(p.position, p.size, z_low, z_high);
    }
    /// ball_box_volume (voxel.hpp): exact, from the ball's orthant volumes.
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const;
    /// The icosphere of `level` (surface.hpp) turned by a generic rotation (angles 1, 2 and 3
    /// radians about z, y and x): contact directions along the axes or lattice vectors then never
    /// pass through a vertex, so two touching spheres do not meet at a shared point of both
    /// tessellations.
    TriangleMesh unit_surface(int level) const;
    /// The sphere itself.
    template <class F> void dem_spheres(const Placement& p, F&& f) const {
        f(DemSphere{p.position, p.size});
    }
};

static_assert(ParticleShape<SphereShape>);

/// The spheres of a packing through the concept: one type, the sphere.
inline ShapedBed<SphereShape> spheres(const Packing& packing) {
    return {packing, {SphereShape{}}};
}
ShapedBed<SphereShape> spheres(const Packing&& packing) = delete;

} // namespace packbed
