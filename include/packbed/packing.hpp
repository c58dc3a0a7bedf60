// The data model: a set of particles, one array per property.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "packbed/quaternion.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A set of particles, HOOMD-blue's particle data: a position and a size per particle (a
/// sphere's centre and radius: a size distribution needs no new data model), an orientation
/// where the shape has one and a type pointing into a table of shapes (particle_shape.hpp:
/// ShapedBed). A bed of spheres has `orientations` and `types` empty (one type, the sphere,
/// and no orientation); a bed of pellets (generate --shape, or a table read with its
/// qw, qx, qy, qz) one orientation per particle. What copies a part of a sphere bed keeps them
/// empty.
/// Lengths are in the caller's units. Not synchronised: share read-only between threads, or
/// give each thread its own.
struct Packing {
    std::vector<Vec3> centers; ///< positions: sphere centres
    std::vector<double> radii; ///< sizes: sphere radii, > 0, same length as `centers`
    /// one per particle where the shape has an orientation; empty: none
    std::vector<Quaternion> orientations;
    /// one per particle, an index into the bed's table of shapes; empty: every particle type 0
    std::vector<std::uint32_t> types;

    /// \return the number of spheres.
    std::size_t size() const { return centers.size(); }

    /// Append a sphere. \param center its centre \param radius its radius (> 0)
    void add(const Vec3& center, double radius) {
        centers.push_back(center);
        radii.push_back(radius);
    }

    /// \return the mean sphere diameter (0 for no spheres).
    double mean_diameter() const {
        double sum = 0.0;
        for (const double r : radii)
            sum += 2.0 * r;
        return radii.empty() ? 0.0 : sum / static_cast<double>(radii.size());
    }

    /// Multiply every coordinate and radius by `factor` (a change of length unit).
    void scale(double factor) {
        for (auto& c : centers)
            c *= factor;
        for (auto& r : radii)
            r *= factor;
    }
};

} // namespace packbed
