// Pack spheres in a cylinder with the library and print the overall void fraction.
// Build: part of the project (PACKBED_BUILD_EXAMPLES); run: build/examples/generate_bed
#include <cstdio>

#include "packbed/bed_volume.hpp"
#include "packbed/soft_sphere.hpp"

int main() {
    // The bed: a = 4, 150 spheres of 3 mm, seed 7.
    packbed::SoftSphereParameters params;
    params.container = packbed::Container::tube(4.0);
    params.particles = 150;
    params.diameter = 0.003;
    params.seed = 7;

    // Run the four stages of Salvat et al. (2005).
    const packbed::SoftSphereResult bed = packbed::generate_soft_sphere(params);

    // Measure the void fraction one diameter clear of the floor and of the top.
    const auto band = packbed::band_clear_of_ends(bed.packing, params.diameter);
    if (!band)
        return 1;
    const double e = packbed::void_fraction(bed.packing, bed.container, band->z_low, band->z_high);

    std::printf("%zu spheres, %llu iterations, void fraction %.4f\n", bed.packing.size(),
                static_cast<unsigned long long>(bed.iterations), e);
    return 0;
}
