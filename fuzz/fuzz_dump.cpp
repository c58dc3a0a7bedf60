// read_particles on LAMMPS/LIGGGHTS text dumps (ITEM: sections, the last snapshot): a valid bed
// or InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    packbed::fuzz::read_particles_or_invalid(data, size, "fuzz.dump",
                                             packbed::ParticleFormat::lammps_dump);
    return 0;
}
