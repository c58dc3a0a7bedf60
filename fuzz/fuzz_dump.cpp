// read_particles on LAMMPS/LIGGGHTS text dumps (ITEM: sections; x y z, xu yu zu or the
// scaled xs ys zs, xsu ysu zsu with orthogonal or triclinic boxes; plain or gzip-compressed):
// the last snapshot, with other_options() (a radius, the snapshot before the last, an axis),
// and every snapshot: a valid bed (valid frames) or InvalidInput.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    fuzz::read_particles_or_invalid(data, size, "fuzz.dump", ParticleFormat::lammps_dump);
    fuzz::read_particles_or_invalid(data, size, "fuzz.dump", ParticleFormat::lammps_dump,
                                    fuzz::other_options());
    fuzz::read_frames_or_invalid(data, size, "fuzz.dump", ParticleFormat::lammps_dump);
    return 0;
}
