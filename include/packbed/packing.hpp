// The data model: a set of spheres, one array per property.
#pragma once

#include <cstddef>
#include <vector>

#include "packbed/vec3.hpp"

namespace packbed {

/// A set of spheres: centre and radius per sphere (radii are per particle so that a
/// particle-size distribution needs no new data model). Lengths are in the caller's units.
/// Not synchronised: share read-only between threads, or give each thread its own.
struct Packing {
    std::vector<Vec3> centers; ///< sphere centres
    std::vector<double> radii; ///< sphere radii, > 0, same length as `centers`

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
