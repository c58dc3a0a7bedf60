// read_particles on CSV (x,y,z,r with optional id and extra columns): a valid bed or
// InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    packbed::fuzz::read_particles_or_invalid(data, size, "fuzz.csv", packbed::ParticleFormat::csv);
    return 0;
}
