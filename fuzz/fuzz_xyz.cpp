// read_particles on XYZ (frames of a count, a comment, `name x y z [radius]`; plain or
// gzip-compressed), without and with a radius given for files without a radius column, one
// frame and all: a valid bed (valid frames) or InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    fuzz::read_particles_or_invalid(data, size, "fuzz.xyz", ParticleFormat::xyz);
    fuzz::read_particles_or_invalid(data, size, "fuzz.xyz", ParticleFormat::xyz,
                                    fuzz::other_options());
    fuzz::read_frames_or_invalid(data, size, "fuzz.xyz", ParticleFormat::xyz,
                                 fuzz::other_options());
    return 0;
}
