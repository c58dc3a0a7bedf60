// read_particles on XYZ (count, comment, `name x y z [radius]`), without and with a radius
// given for files without a radius column: a valid bed or InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    fuzz::read_particles_or_invalid(data, size, "fuzz.xyz", ParticleFormat::xyz);
    ReadOptions with_radius;
    with_radius.radius = 0.5;
    fuzz::read_particles_or_invalid(data, size, "fuzz.xyz", ParticleFormat::xyz, with_radius);
    return 0;
}
