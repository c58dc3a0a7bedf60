// A soft-sphere bed from a request to its files (pipeline.hpp).
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include <omp.h>

#include <fmt/format.h>

#include "packbed/checkpoint.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/memory.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/pipeline.hpp"

namespace packbed {

namespace {

/// The seed of the sizes' random numbers: --seed XOR the golden-ratio constant 0x9E3779B97F4A7C15,
/// a stream of its own, so that the centres of the generation stage are drawn from the same
/// numbers whatever the sizes.
std::uint64_t sizes_seed(std::uint64_t seed) {
    return seed ^ 0x9E3779B97F4A7C15ull;
}

} // namespace

int use_threads(unsigned long long threads) {
    omp_set_num_threads(static_cast<int>(threads));
    return threads_in_use();
}

int threads_in_use() {
    int team = 1;
#pragma omp parallel
    {
#pragma omp single
        team = omp_get_num_threads();
    }
    return team;
}

PreparedGeneration prepare_generation(GenerateRequest request) {
    const LammpsLauncher& launcher = request.launcher;
    if (request.engine != Engine::lammps && (launcher.ranks != 1 || !launcher.mpi_command.empty() ||
                                             launcher.lmp != "lmp" || request.write_only))
        throw InvalidInput(fmt::format("--ranks, --mpi-command, --lmp and --write-only are not "
                                       "allowed with --engine {}; allowed: with --engine lammps",
                                       to_string(request.engine)));
    PreparedGeneration prepared{request, request.params, std::nullopt,
                                generation_memory(request.params.particles)};
    SoftSphereParameters& p = prepared.params;
    // Before anything is allocated for it (the sizes drawn below are 8 bytes a sphere).
    check_memory(fmt::format("--particles {}", p.particles), prepared.memory,
                 "fewer spheres, or a machine with more memory");
    // Spheres of many sizes (docs/sizes.md): the diameters drawn from --sizes, the reference
    // diameter Dp their Sauter mean d32, each sphere's size in units of it. `mono` draws
    // nothing and changes nothing: the bed of --diameter, bit for bit.
    if (request.sizes != "mono") {
        const SizeDistribution distribution = parse_sizes(request.sizes, p.diameter);
        const std::vector<double> diameters =
            draw_diameters(distribution, p.particles, request.fractions, sizes_seed(p.seed));
        prepared.drawn = size_statistics(diameters);
        p.diameter = prepared.drawn->sauter_mean;
        p.sizes.clear();
        for (const double d : diameters)
            p.sizes.push_back(d / prepared.drawn->sauter_mean);
        if (!request.checkpoint.empty())
            throw InvalidInput(fmt::format("--checkpoint {} is not allowed with --sizes {}; "
                                           "allowed: --checkpoint with mono-sized beds (a "
                                           "checkpoint does not record the sizes yet)",
                                           printable(request.checkpoint), request.sizes));
    }
    const std::optional<Container> spec =
        request.container.empty() ? std::nullopt : parse_container(request.container);
    if (!request.container.empty() && !spec)
        throw InvalidInput(container_not_allowed("--container", request.container));
    const std::optional<double> tube = spec ? spec->tube_diameter() : std::nullopt;
    if (spec && !tube) {
        // Another container, in units of Dp (with --sizes, d32), checked in the user's units.
        const Container in_dp = spec->scaled(1.0 / p.diameter);
        const std::string problem = in_dp.fit_problem(p.largest_size());
        if (!problem.empty())
            throw InvalidInput(fmt::format(
                "--container {} is not allowed with Dp = {:.6g}{}; allowed: {}", request.container,
                p.diameter, prepared.drawn ? " (the sizes' Sauter mean d32)" : "", problem));
        p.container = in_dp;
        if (!request.checkpoint.empty())
            throw InvalidInput(fmt::format("--checkpoint {} is not allowed with --container {}; "
                                           "allowed: --checkpoint with a cylinder (a checkpoint "
                                           "does not record the container yet)",
                                           printable(request.checkpoint), request.container));
    } else if (spec) {
        // a = D / Dp, both in the unit of --diameter (with --sizes, Dp is d32).
        const double a = *tube / p.diameter;
        const std::string_view dp = prepared.drawn ? "the sizes' Sauter mean d32" : "--diameter";
        if (!(a >= 1.0 && a <= 1e4))
            throw InvalidInput(
                fmt::format("--container {}: the tube's diameter over {} ({}) is a = {:.6g}; "
                            "allowed: a from 1 to 10000 (D from {:.6g} to {:.6g})",
                            request.container, dp, p.diameter, a, p.diameter, 1e4 * p.diameter));
        p.container = Container::tube(a);
    } else {
        p.container = Container::tube(request.aspect_ratio); // the shorthand
    }
    if (request.engine == Engine::lammps && p.solver == Solver::fire)
        p = lammps_parameters(p); // its own band unless one is given
    p.validate();
    // The void fraction's band, clear of the floor and the top: refused before the run where
    // no bed of this request can hold one (as analyze refuses it for a bed it reads). The
    // settled bed is lower than twice the loose height L0 of eq. (6) and two of its largest
    // spheres; where it settles lower than twice the clearance, summary.json says so.
    const double tallest = 2.0 * initial_bed_height(p) + 2.0 * p.largest_size();
    if (!(2.0 * request.band_clearance < tallest))
        throw InvalidInput(fmt::format("--band-clearance {} Dp is not allowed for this bed (at "
                                       "most {:.6g} Dp tall); allowed: less than half its height",
                                       request.band_clearance, tallest));
    if (request.engine == Engine::lammps) {
        if (p.solver != Solver::fire)
            throw InvalidInput("--solver paper is not allowed with --engine lammps; allowed: "
                               "--solver fire (LAMMPS runs the fire solver's energy and "
                               "schedule)");
        if (!request.checkpoint.empty())
            throw InvalidInput(fmt::format("--checkpoint {} is not allowed with --engine lammps; "
                                           "allowed: --checkpoint with --engine packbed",
                                           printable(request.checkpoint)));
    }
    if (!request.checkpoint.empty()) {
        check_path("--checkpoint", request.checkpoint);
        if (p.solver != Solver::fire || fire_layers(p) == 1)
            throw InvalidInput(fmt::format(
                "--checkpoint {}: only a fire run in layers can be resumed, this run is {}; "
                "allowed: --solver fire with an initial height L0 = {:.4g} Dp above twice "
                "--layer-height (now {})",
                printable(request.checkpoint),
                p.solver == Solver::fire ? "in one piece" : "paper mode", initial_bed_height(p),
                p.layer_height));
    }
    if (request.engine == Engine::lammps)
        lammps_launch(launcher); // --mpi-command and --lmp checked before anything is written
    return prepared;
}

GeneratedBed generate_bed(const PreparedGeneration& prepared, RunControl control, int threads,
                          OutputDirectory* folder,
                          const std::function<void(std::uint32_t)>& on_resume) {
    if (prepared.request.engine == Engine::packbed)
        return run_generation(prepared, std::move(control), threads, on_resume);
    if (folder == nullptr)
        throw std::logic_error("generate_bed: the LAMMPS engine runs in an output folder");
    return run_lammps_generation(prepared, prepared.request.launcher, control, *folder);
}

GeneratedBed run_generation(const PreparedGeneration& prepared, RunControl control, int threads,
                            const std::function<void(std::uint32_t)>& on_resume) {
    const SoftSphereParameters& p = prepared.params;
    const std::string& checkpoint = prepared.request.checkpoint;
    std::optional<LayerCheckpoint> resume;
    if (!checkpoint.empty()) {
        // Now, not after the first layer; an output of the job from here on (JobScope).
        check_writable_file("--checkpoint", checkpoint);
        std::error_code missing;
        if (std::filesystem::exists(std::filesystem::symlink_status(checkpoint, missing))) {
            resume = read_checkpoint(checkpoint, p);
            control.resume = &*resume;
            if (on_resume)
                on_resume(resume->layers_done);
        }
        control.on_layer = [&](const LayerCheckpoint& state) {
            write_checkpoint(checkpoint, p, state);
        };
    }
    GeneratedBed bed;
    bed.result = generate_soft_sphere(p, control);
    bed.summary = generation_summary(prepared, bed.result, threads);
    return bed;
}

nlohmann::json generation_summary(const PreparedGeneration& prepared,
                                  const SoftSphereResult& result, int threads) {
    nlohmann::json summary =
        soft_sphere_summary(prepared.params, result, prepared.request.band_clearance, threads);
    if (prepared.drawn)
        summary["sizes"] = {{"spec", prepared.request.sizes},
                            {"fractions", to_string(prepared.request.fractions)},
                            {"reference_diameter",
                             "the Sauter mean d32: a = D / d32, and lengths in Dp are in "
                             "units of it"},
                            {"statistics", size_statistics_summary(*prepared.drawn)}};
    return summary;
}

void stage_bed(OutputDirectory& out, const Packing& packing, const Container& container,
               double band_clearance, bool analyse, nlohmann::json& summary) {
    out.stage("particles.csv", particles_csv(packing));
    out.stage("particles.vtu", particles_vtu(packing));
    if (analyse)
        stage_analysis(out, packing, container, band_clearance, summary);
    out.stage("summary.json", json_file_text(summary, "summary.json"));
}

} // namespace packbed
