// A bed's volumes: the solid between two heights, the void fraction and the band it is measured
// in, each a loop over the particles through their shape (particle_shape.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A horizontal band [z_low, z_high] of a bed.
struct Band {
    double z_low = 0.0;  ///< lower height (length)
    double z_high = 0.0; ///< upper height (length)
};

namespace detail {
/// \return volume(0) + volume(1) + ... + volume(n - 1), added in that order; the terms are
/// computed in parallel (a pellet's volume in a tube costs milliseconds), so the sum has the
/// same bits whatever the number of threads.
double sum_in_order(std::size_t n, const std::function<double(std::size_t)>& volume);
} // namespace detail

/// The particles' volume inside the container between two heights, summed in order (each
/// particle's ParticleShape::volume_in).
template <ParticleShape S>
double solid_volume(const ShapedBed<S>& bed, const Container& container, double z_low,
                    double z_high) {
    return detail::sum_in_order(bed.size(), [&](std::size_t i) {
        return bed.shape(i).volume_in(container, bed.placement(i), z_low, z_high);
    });
}

/// \throws InvalidInput unless z_low < z_high (the void fraction's band).
void check_band(double z_low, double z_high);

/// Overall void fraction of a bed in a container between two heights:
/// \f$\varepsilon = 1 - \sum_i V_i / (A (z_{high} - z_{low}))\f$, with A the container's
/// cross-section and V_i the exact volume of particle i inside it and the slab (solid_volume).
/// Overlaps between particles are counted twice; at the generator's 1e-4 Dp tolerance that is
/// below 1e-8 per contact in units of a sphere volume.
/// \param z_low,z_high the band (z_low < z_high, else InvalidInput)
/// \return the void fraction in [0, 1] (it can go below 0 only for heavily overlapping input).
template <ParticleShape S>
double void_fraction(const ShapedBed<S>& bed, const Container& container, double z_low,
                     double z_high) {
    check_band(z_low, z_high);
    return 1.0 - solid_volume(bed, container, z_low, z_high) /
                     (container.cross_section_area(z_low, z_high) * (z_high - z_low));
}

/// The void fraction of a packing of spheres (spheres(packing), sphere_shape.hpp).
double void_fraction(const Packing& packing, const Container& container, double z_low,
                     double z_high);

/// \return the height of the highest point of a particle (its support along +z; 0 for none).
template <ParticleShape S> double bed_top(const ShapedBed<S>& bed) {
    double top = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i)
        top = std::max(top, bed.shape(i).support(bed.placement(i), Vec3{0.0, 0.0, 1.0}).z);
    return top;
}

/// \return the height of the highest sphere top, max z_i + r_i (0 for no spheres).
double bed_top(const Packing& packing);

/// The band that keeps `clearance` away from the floor (z = 0) and from the top of the bed
/// (bed_top).
/// \param packing the spheres \param clearance distance from each end (length, >= 0)
/// \return the band, or nothing when the bed is not taller than 2 clearance.
std::optional<Band> band_clear_of_ends(const Packing& packing, double clearance);

} // namespace packbed
