// read_particles on LAMMPS/LIGGGHTS data files (the header's `N atoms`, the Atoms section of
// atom_style sphere, granular or atomic; plain or gzip-compressed), without and with a radius
// given: a valid bed or InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    fuzz::read_particles_or_invalid(data, size, "fuzz.data", ParticleFormat::lammps_data);
    ReadOptions with_radius;
    with_radius.radius = 0.5;
    fuzz::read_particles_or_invalid(data, size, "fuzz.data", ParticleFormat::lammps_data,
                                    with_radius);
    return 0;
}
