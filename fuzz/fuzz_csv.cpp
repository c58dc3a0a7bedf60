// read_particles on delimited tables (CSV with x,y,z,r, optional id and extra columns;
// ParaView's quoted Points:0..2; ;, tab or space separated; gzip-compressed): a valid bed or
// InvalidInput, with the default options and with other_options().
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    fuzz::read_particles_or_invalid(data, size, "fuzz.csv", ParticleFormat::csv);
    fuzz::read_particles_or_invalid(data, size, "fuzz.csv", ParticleFormat::csv,
                                    fuzz::other_options());
    return 0;
}
