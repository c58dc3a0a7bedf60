// read_lammps_job on job.json's text (a LAMMPS job's request, command and pair style, as
// `generate --engine lammps --write-only` writes it): a request within what the command line
// allows or InvalidInput; nested JSON bounded where it is read (no stack overflow), a command
// of at most 64 words.
#include "fuzz_support.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using packbed::fuzz::finding;
    const std::string text = packbed::fuzz::text_of(data, size);
    try {
        const packbed::LammpsJobFile job = packbed::read_lammps_job(text, "job");
        if (!job.command.is_array() || job.command.size() > 64)
            finding("read_lammps_job returned a command that is not a list of at most 64 words");
        if (!job.pair_style.empty() && job.pair_style != "gran/hooke" &&
            job.pair_style != "harmonic/cut")
            finding("read_lammps_job returned pair_style " + job.pair_style);
        // What import-lammps does next with the request: every check of a generation (for
        // requests small enough to draw their sizes within the fuzzer's time and memory).
        if (job.request.params.particles > 10000)
            return 0;
        const packbed::PreparedGeneration prepared = packbed::prepare_generation(job.request);
        if (!(prepared.params.particles >= 1 &&
              prepared.params.particles <= packbed::limits::max_spheres))
            finding("prepare_generation accepted particles = " +
                    std::to_string(prepared.params.particles));
    } catch (const packbed::InvalidInput&) {
    } catch (...) {
        packbed::fuzz::unexpected_exception();
    }
    return 0;
}
