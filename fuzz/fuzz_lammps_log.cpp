// lammps_result on a folder whose log.lammps is the input (import-lammps reads a job folder
// that LAMMPS filled elsewhere) and whose bed.dump is a valid bed of 3 spheres: the
// log's stage lines read, or ConvergenceError (a run that failed, a log that is not the job's);
// what is read: three stages named initial, intermediate, final, with finite numbers, overlaps
// >= 0, and the whole run's steps those of the last stage line.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "fuzz_support.hpp"
#include "packbed/lammps_engine.hpp"

namespace {

std::filesystem::path folder;

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::string name = (std::filesystem::temp_directory_path() / "packbed-fuzz-lammps-XXXXXX");
    if (!::mkdtemp(name.data()))
        packbed::fuzz::finding("no temporary folder");
    folder = name;
    std::ofstream(folder / "bed.dump") << "ITEM: TIMESTEP\n6000\nITEM: NUMBER OF ATOMS\n3\n"
                                          "ITEM: BOX BOUNDS ff ff mm\n-5 5\n-5 5\n-2 10\n"
                                          "ITEM: ATOMS id type x y z radius\n"
                                          "1 1 0 0 0.5\n2 1 1.2 0 0.5\n3 1 0.6 0 1.5\n";
    std::atexit([] { std::filesystem::remove_all(folder); });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace packbed;
    using fuzz::finding;
    std::ofstream(folder / "log.lammps", std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    SoftSphereParameters p;
    p.particles = 3;
    try {
        const SoftSphereResult r = lammps_result(p, folder);
        if (r.stages.size() != 3 || r.stages[0].name != "initial" ||
            r.stages[1].name != "intermediate" || r.stages[2].name != "final")
            finding("lammps_result returned stages other than initial, intermediate, final");
        std::uint64_t steps = 0;
        for (const StageRecord& s : r.stages) {
            if (!std::isfinite(s.cg) || !(s.max_overlap_pair >= 0.0) ||
                !(s.max_overlap_wall >= 0.0) || !std::isfinite(s.max_overlap_pair) ||
                !std::isfinite(s.max_overlap_wall) || !std::isfinite(s.mass_centre_z))
                finding("lammps_result returned a stage with a number not finite or an overlap "
                        "below 0");
            steps += s.iterations;
        }
        if (steps > r.iterations)
            finding("lammps_result's stages hold more steps than the run");
        if (r.packing.size() != 3)
            finding("lammps_result returned a bed other than the dump's");
    } catch (const ConvergenceError&) {
    } catch (const InvalidInput&) {
    } catch (...) {
        fuzz::unexpected_exception();
    }
    return 0;
}
