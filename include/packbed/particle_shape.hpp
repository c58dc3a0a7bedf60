// What generation, analysis and export ask of a particle: the ParticleShape concept, and a
// bed's particles seen through the table of their shapes (docs/design.md, "Particles").
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/mesh.hpp"
#include "packbed/packing.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// Where one particle is: its reference point (a sphere's centre, a pellet's centroid), its
/// orientation (the identity for a shape without one) and its size, the scale of its type's
/// shape (a sphere's radius; a pellet's volume-equivalent radius d_v / 2).
struct Placement {
    Vec3 position;
    Quaternion orientation;
    double size = 1.0;
};

/// How deep two particles overlap and along which direction.
struct PairOverlap {
    double depth = 0.0; ///< > 0: they overlap by this much (the penetration depth)
    Vec3 normal;        ///< unit, from the first towards the second (undefined when they coincide)
    Vec3 point;         ///< where they touch, from the first's position (the middle of the overlap)
};

/// A point of a particle's surface in its body frame at size 1 and the area it stands for: the
/// nodes of the level-set contact (Kawamoto, Ando, Viggiani & Andrade, "Level set discrete
/// element method for three-dimensional computations with triaxial case study", J. Mech. Phys.
/// Solids 91 (2016) 1-13), each pressed out of a neighbour by a spring on its depth.
struct SurfaceNode {
    Vec3 point;
    double area = 0.0;
};

/// A circle of a particle's surface kept whole for the level-set contact: the body-frame
/// circle of radius `radius` about the axis parallel to z through (x, y) at height z (size 1),
/// and the area per unit length that stands for the surface beside it; where only an arc of it
/// is on the surface (a multilobe's lobe), the angles about its own axis within `arc_half` of
/// `arc_middle` (from the body x axis). A contact along an edge (two rims crossing) or between
/// two curved sides can be shorter than any spacing of nodes: such a circle is searched as a
/// curve.
struct SurfaceCircle {
    double z = 0.0;
    double radius = 0.0;
    double area_per_length = 0.0;
    double x = 0.0, y = 0.0;
    double arc_middle = 0.0, arc_half = std::numbers::pi; ///< pi: the whole circle
};

/// How deep a body-frame point lies inside a particle at size 1 (0 outside) and its way out:
/// the outward unit normal of the nearest part of the surface.
struct InsideDepth {
    double depth = 0.0;
    Vec3 normal;
};

/// One sphere of a particle's DEM representation (the particle itself for a sphere, the
/// spheres of a clump for a pellet).
struct DemSphere {
    Vec3 centre;
    double radius = 0.0;
};

/// What the product asks of a particle's shape: HOOMD-blue's HPMC shapes (`ShapeSphere`,
/// `ShapeConvexPolyhedron`) are the model, small classes whose loops (`IntegratorHPMCMono<S>`)
/// are templates on the shape. A shape holds what its type's particles share, in units of their
/// size; each question takes one particle's Placement. Lengths in the bed's units.
/// - `kind`: its name ("sphere"); `oriented`: whether its particles need an orientation.
/// - `bounding_radius(size)`: the radius of the smallest sphere about the position that holds
///   the particle (the neighbour search's radius); `volume(size)`.
/// - `support(p, v)`: the particle's point farthest along v (GJK's support function; its
///   lowest point is support(p, -z)).
/// - `wall_overlap(c, p)`: the deepest overlap with the container's walls (0 when clear; the
///   floor is the solver's).
/// - `pair_overlap(pa, b, pb, ab)`: with particle b, `ab` the vector from pa.position to
///   pb.position as the caller measures it (the minimum image in a periodic cell); a depth
///   <= 0 when they are apart.
/// - `wall_extent(c, wall, p)`: the nearest and farthest distance of its points from the
///   container's profile wall `wall` (Container::profile_walls), or bounds on them (the shells
///   between are measured by volume_from_wall).
/// - `volume_in(c, p, z_low, z_high)`: its volume inside the container between two heights
///   (the slabs of the axial profile and the void fraction); `volume_from_wall(c, wall, d, p,
///   z_low, z_high)`: the part at least d from wall `wall` (a shell of the wall profile is a
///   difference of two).
/// - `volume_in_box(p, low, high)`: its volume in an axis-aligned box (a voxel's cover).
/// - `unit_surface(level)`: its closed outward surface at size 1 in its body frame, finer with
///   `level` (placed by place_surface).
/// - `dem_spheres(p, f)`: f(DemSphere) for each of its spheres for a DEM code.
template <class S>
concept ParticleShape = std::copyable<S> &&
    requires(const S& s, const Placement& p, const Container& c, const Vec3& v, double d,
             std::size_t wall, int level) {
    { S::kind } -> std::convertible_to<std::string_view>;
    { S::oriented } -> std::convertible_to<bool>;
    { s.bounding_radius(d) } -> std::same_as<double>;
    { s.volume(d) } -> std::same_as<double>;
    { s.support(p, v) } -> std::same_as<Vec3>;
    { s.wall_overlap(c, p) } -> std::same_as<double>;
    { s.pair_overlap(p, s, p, v) } -> std::same_as<PairOverlap>;
    { s.wall_extent(c, wall, p) } -> std::same_as<std::pair<double, double>>;
    { s.volume_in(c, p, d, d) } -> std::same_as<double>;
    { s.volume_from_wall(c, wall, d, p, d, d) } -> std::same_as<double>;
    { s.volume_in_box(p, v, v) } -> std::same_as<double>;
    { s.unit_surface(level) } -> std::same_as<TriangleMesh>;
    s.dem_spheres(p, [](const DemSphere&) {});
};

/// A bed's particles of one shape class S, as HOOMD's `IntegratorHPMCMono<S>` sees them: the
/// particle data (Packing: positions, sizes, orientations, types) and the table of shapes the
/// types point into. Loops over a bed are templates on S and ask each particle's shape(i) at
/// placement(i). Holds a reference to the packing: keep it alive.
template <ParticleShape S> class ShapedBed {
public:
    /// \throws std::invalid_argument when the packing's orientations or types are neither empty
    /// nor one per particle, a type has no shape in `shapes`, or S has orientations and the
    /// packing none (a programming error: readers and generators fill them).
    ShapedBed(const Packing& particles, std::vector<S> shapes)
        : m_particles(particles)
        , m_shapes(std::move(shapes)) {
        const std::size_t n = particles.size();
        if (m_shapes.empty())
            throw std::invalid_argument("ShapedBed: no shape");
        if (!particles.types.empty() && particles.types.size() != n)
            throw std::invalid_argument("ShapedBed: types are not one per particle");
        for (const std::uint32_t t : particles.types)
            if (t >= m_shapes.size())
                throw std::invalid_argument("ShapedBed: a type with no shape");
        if (!particles.orientations.empty() && particles.orientations.size() != n)
            throw std::invalid_argument("ShapedBed: orientations are not one per particle");
        if (S::oriented && n > 0 && particles.orientations.empty())
            throw std::invalid_argument("ShapedBed: this shape needs orientations");
    }

    /// Not of a temporary packing: the bed holds a reference to it.
    ShapedBed(const Packing&& particles, std::vector<S> shapes) = delete;

    std::size_t size() const { return m_particles.size(); }
    const Packing& particles() const { return m_particles; }
    const std::vector<S>& shapes() const { return m_shapes; }

    /// Particle i's shape: its type's (type 0 where the packing has no types).
    const S& shape(std::size_t i) const {
        return m_shapes[m_particles.types.empty() ? 0 : m_particles.types[i]];
    }
    /// Particle i's placement (the identity orientation where the packing has none).
    Placement placement(std::size_t i) const {
        return {m_particles.centers[i],
                m_particles.orientations.empty() ? Quaternion{} : m_particles.orientations[i],
                m_particles.radii[i]};
    }
    /// Each particle's bounding radius, for the neighbour search.
    std::vector<double> bounding_radii() const {
        std::vector<double> out(size());
        for (std::size_t i = 0; i < size(); ++i)
            out[i] = shape(i).bounding_radius(m_particles.radii[i]);
        return out;
    }

private:
    const Packing& m_particles;
    std::vector<S> m_shapes;
};

/// A body-frame surface (ParticleShape::unit_surface) placed: each vertex scaled by the size,
/// turned by the orientation (for an oriented shape) and moved to the position.
template <ParticleShape S> void place_surface(TriangleMesh& mesh, const Placement& p) {
    for (Vec3& v : mesh.vertices) {
        if constexpr (S::oriented)
            v = p.position + rotate(p.orientation, v) * p.size;
        else
            v = p.position + v * p.size;
    }
}

} // namespace packbed
