// `packbed generate`: the soft-sphere bed of Salvat et al. (2005) in a cylinder.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <span>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include "command.hpp"
#include "interrupt.hpp"
#include "packbed/analysis.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/lammps_engine.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"
#include "progress.hpp"

namespace packbed::cli {

namespace {

struct GenerateOptions {
    SoftSphereParameters params;
    std::string update = to_string(SoftSphereParameters{}.update);
    std::string solver = to_string(SoftSphereParameters{}.solver);
    std::string out = "packbed-out";
    std::string checkpoint;    // empty: none
    double aspect_ratio = 5.0; // -a: the shorthand of a tube
    std::string container;     // --container cylinder:D, instead of --aspect-ratio
    std::string sizes = "mono";
    std::string fractions = to_string(FractionBasis::volume);
    double band_clearance = 1.0;
    std::optional<double> target_void_fraction;
    std::string engine = to_string(Engine::packbed);
    LammpsLauncher lammps;
    std::string write_only; // --write-only DIR: the LAMMPS job, not run
    unsigned long long threads = static_cast<unsigned long long>(omp_get_num_procs());
    bool no_analysis = false; // --no-analysis: the spheres and the summary only
    bool quiet = false;
    bool force = false;
    std::string shape = "sphere";  // --shape: a pellet instead (parse_pellet_shape)
    const CLI::App* app = nullptr; // which options were given (those a pellet bed refuses)
};

/// The options a pellet bed takes; every other generate option is the spheres' alone.
constexpr std::array pellet_options{
    "--aspect-ratio", "--container", "--particles",    "--seed",          "--shape",
    "--out",          "--force",     "--threads",      "--quiet",         "--band-clearance",
    "--no-analysis",  "--config",    "--friction",     "--wall-friction", "--max-iterations",
    "--sizes",        "--fractions", "--layer-height", "--checkpoint"};

/// --shape PELLET: a bed of pellets (docs/generate.md, "Pellets").
int run_pellets(const GenerateOptions& o) {
    for (const CLI::Option* option : o.app->get_options()) {
        const std::string name = option->get_name();
        if (option->count() == 0 || name.rfind("--", 0) != 0 ||
            std::find(pellet_options.begin(), pellet_options.end(), name) != pellet_options.end())
            continue;
        throw InvalidInput(fmt::format(
            "{} is not allowed with --shape {}; allowed with a pellet: {} (docs/generate.md, "
            "\"Pellets\")",
            name, printable(o.shape), fmt::join(pellet_options, ", ")));
    }
    PelletRequest request;
    request.shape = o.shape;
    request.particles = o.params.particles;
    request.seed = o.params.seed;
    request.aspect_ratio = o.aspect_ratio;
    request.container = o.container;
    request.band_clearance = o.band_clearance;
    request.friction = o.params.friction;
    request.wall_friction = o.params.wall_friction;
    if (o.app->count("--max-iterations") > 0)
        request.max_steps = o.params.max_iterations;
    request.sizes = o.sizes;
    request.fractions = fraction_bases().at(o.fractions);
    // A pellet bed is relaxed in one piece unless --layer-height is given (the spheres' default
    // of 30 Dp does not apply).
    if (o.app->count("--layer-height") > 0)
        request.layer_height = o.params.layer_height;
    request.checkpoint = o.checkpoint;
    const PreparedPellets prepared = prepare_pellets(request);
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);
    const int threads = use_threads(o.threads);
    const bool drawing = progress_wanted(o.quiet);
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    bool drawn = false;
    RunControl control;
    control.on_progress = [&](const Progress& p) {
        const auto now = std::chrono::steady_clock::now();
        if (!drawing || now - last < std::chrono::milliseconds(100))
            return;
        last = now;
        drawn = true;
        progress_line_drawn(true); // the interrupt handler erases it
        draw_status_line(
            {fmt::format("{} pellets", request.particles), std::string(p.stage),
             fmt::format("step {}", p.iteration),
             fmt::format("depth {:.2e} d_v", std::max(p.max_overlap_pair, p.max_overlap_wall)),
             fmt::format("gravity {:.2e}", p.cg)});
    };
    set_interrupt_checkpoint(o.checkpoint); // kept by an interrupted run
    const GeneratedPellets pellets =
        run_pellets(prepared, control, threads, [&](std::uint32_t done, std::uint32_t layers) {
            if (!o.quiet)
                fmt::print(stderr, "packbed generate: resuming from {} after layer {} of {}\n",
                           o.checkpoint, done, layers);
        });
    if (drawn) {
        fmt::print(stderr, "\r\033[K");
        std::fflush(stderr);
        progress_line_drawn(false);
    }
    stage_pellet_bed(out, pellets);
    out.commit();
    if (!o.quiet) {
        const auto& s = pellets.summary;
        fmt::print("packbed generate: {} pellets {}, {}, seed {}: {} steps\n", request.particles,
                   prepared.pellet.text,
                   s.contains("aspect_ratio")
                       ? fmt::format("a = {:g} (tube over d_v = {:.6g})",
                                     s["aspect_ratio"].get<double>(), prepared.unit)
                       : pellets.container.spec(),
                   request.seed, pellets.bed.steps);
        fmt::print("largest penetration: pellet-pellet {:.3e}, pellet-wall {:.3e} (tolerance "
                   "{:.3e}); forces left {:.3g} weights, torques {:.3g}\n",
                   s["max_penetration_pair"].get<double>(), s["max_penetration_wall"].get<double>(),
                   s["tolerance"].get<double>(), pellets.bed.residual_force,
                   pellets.bed.residual_torque);
        if (s.contains("void_fraction"))
            fmt::print("void fraction: {:.4f} (between z = {:.4g} and z = {:.4g})\n",
                       s["void_fraction"].get<double>(), s["void_fraction_band"][0].get<double>(),
                       s["void_fraction_band"][1].get<double>());
        else
            fmt::print("void fraction: not computed: {}\n",
                       s["void_fraction_note"].get<std::string>());
        fmt::print("results in {}/ (particles.csv with orientations, particles.vtu, "
                   "summary.json)\n",
                   out.path().string());
        if (s.contains("warnings"))
            for (const auto& warning : s["warnings"])
                fmt::print(stderr, "packbed generate: warning: {}\n", warning.get<std::string>());
    }
    return 0;
}

/// The print-out of a generated bed (generate, import-lammps). \param command the subcommand
/// \param engine " (LAMMPS)" or "" \param more what else `out` holds, or ""
void report_bed(const PreparedGeneration& prepared, const GeneratedBed& bed,
                const OutputDirectory& out, std::string_view command, std::string_view engine,
                std::string_view more, bool analysed = true) {
    const SoftSphereParameters& params = prepared.params;
    const SoftSphereResult& result = bed.result;
    const auto& summary = bed.summary;
    fmt::print("packbed {}: {} spheres, {}, seed {}{}: {} iterations, {:.2f} s\n", command,
               params.particles,
               params.aspect_ratio() ? fmt::format("a = {}", *params.aspect_ratio())
                                     : result.container.spec(),
               params.seed, engine, result.iterations, result.seconds);
    fmt::print("largest overlaps: sphere-sphere {:.3e} Dp, sphere-wall {:.3e} Dp\n",
               result.max_overlap_pair, result.max_overlap_wall);
    if (summary["void_fraction"].is_number())
        fmt::print("void fraction: {:.4f} (between z = {:.4g} and z = {:.4g})\n",
                   summary["void_fraction"].get<double>(),
                   summary["void_fraction_band"][0].get<double>(),
                   summary["void_fraction_band"][1].get<double>());
    else
        fmt::print("void fraction: not computed: {}\n",
                   summary["void_fraction_note"].get<std::string>());
    if (const auto target = summary.find("target_void_fraction"); target != summary.end())
        fmt::print("friction: {:.4g} at spheres and walls, found for the target {} on {} "
                   "calibration beds of {} spheres and {} whole bed{}\n",
                   (*target)["friction"].get<double>(), (*target)["target"].get<double>(),
                   (*target)["calibration"].size(),
                   (*target)["calibration_particles"].get<std::uint64_t>(),
                   (*target)["runs"].size(), (*target)["runs"].size() == 1 ? "" : "s");
    fmt::print("results in {}/ (particles.csv, particles.vtu, summary.json{}{})\n",
               out.path().string(), analysed ? " and the analysis tables" : "", more);
}

/// --engine lammps --write-only: the LAMMPS job staged in its own folder, not run.
int write_lammps_job(const GenerateOptions& o, const PreparedGeneration& prepared) {
    OutputDirectory out(o.write_only, "--write-only", OutputKind::directory, o.force);
    const std::vector<std::string> command =
        stage_lammps_job(out, "", prepared, o.lammps, LammpsPairStyle::gran_hooke);
    out.commit();
    // the launcher's words (without -in in.packbed -log log.lammps), to be pasted
    const std::string launcher = shell_line(std::span(command).first(command.size() - 4));
    if (!o.quiet)
        fmt::print("packbed generate: the LAMMPS job for {} spheres is in {}/; run it there "
                   "with `{} -in in.packbed` (README.md has a cluster's script), then "
                   "`packbed import-lammps {}`\n",
                   prepared.params.particles, printable(out.path().native()), launcher,
                   shell_word(out.path().native()));
    return 0;
}

int run_generate(GenerateOptions& o) {
    if (o.shape != "sphere")
        return run_pellets(o);
    GenerateRequest request;
    request.params = o.params;
    request.params.update = update_orders().at(o.update);
    request.params.solver = solvers().at(o.solver);
    request.fractions = fraction_bases().at(o.fractions);
    request.sizes = o.sizes;
    request.aspect_ratio = o.aspect_ratio;
    request.container = o.container;
    request.checkpoint = o.checkpoint;
    request.band_clearance = o.band_clearance;
    request.target_void_fraction = o.target_void_fraction;
    request.engine = engines().at(o.engine);
    request.launcher = o.lammps;
    request.write_only = !o.write_only.empty();
    // Options this run would not use, given by hand, are refused rather than dropped.
    if (request.write_only && o.app && o.app->count("--out") > 0)
        throw InvalidInput(fmt::format(
            "--out {} is not allowed with --write-only; allowed: --write-only DIR alone (the "
            "job's folder; `packbed import-lammps DIR --out OUT` writes the bed)",
            printable(o.out)));
    if (request.params.solver != Solver::fire && o.app && o.app->count("--layer-height") > 0)
        throw InvalidInput(fmt::format("--layer-height {} is not allowed with --solver paper; "
                                       "allowed: --layer-height with --solver fire (the paper's "
                                       "iteration relaxes the bed in one piece)",
                                       request.params.layer_height));
    const PreparedGeneration prepared = prepare_generation(request);
    if (request.write_only)
        return write_lammps_job(o, prepared);
    const SoftSphereParameters& params = prepared.params;
    const bool lammps = request.engine == Engine::lammps;
    // Every check before the run: the output directory, the checkpoint.
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);
    const int threads = lammps ? 0 : use_threads(o.threads);

    TerminalProgress progress(progress_wanted(o.quiet), params, prepared.memory, threads,
                              lammps ? "LAMMPS" : "");
    RunControl control;
    control.on_progress = [&](const Progress& p) { progress(p); };
    set_interrupt_checkpoint(o.checkpoint); // kept by an interrupted run
    GeneratedBed bed =
        generate_bed(prepared, control, threads, &out, [&](std::uint32_t layers_done) {
            if (!o.quiet)
                fmt::print(stderr, "packbed generate: resuming from {} after layer {} of {}\n",
                           o.checkpoint, layers_done, fire_layers(params));
        });
    progress.finish();
    // The same analysis as `packbed analyze`, when the bed is tall enough for the band and
    // not declined.
    const bool analyse = !o.no_analysis && bed.summary["void_fraction"].is_number();
    stage_bed(out, bed.result.packing, bed.result.container, o.band_clearance, analyse,
              bed.summary);
    out.commit();
    if (!o.quiet)
        report_bed(prepared, bed, out, "generate", lammps ? " (LAMMPS)" : "",
                   lammps ? "; lammps/: the job and LAMMPS's log" : "", analyse);
    return 0;
}

struct ImportOptions {
    std::string folder;
    std::string out = "packbed-out";
    bool quiet = false;
    bool force = false;
};

int run_import(const ImportOptions& o) {
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);
    ImportedLammps imported = import_lammps(o.folder);
    GeneratedBed& bed = imported.bed;
    stage_bed(out, bed.result.packing, bed.result.container,
              imported.prepared.request.band_clearance, bed.summary["void_fraction"].is_number(),
              bed.summary);
    out.commit();
    if (!o.quiet)
        report_bed(imported.prepared, bed, out, "import-lammps", " (LAMMPS)", "");
    return 0;
}

} // namespace

Command register_import_lammps(CLI::App& parent) {
    auto options = std::make_shared<ImportOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "import-lammps",
        "Bring back a bed LAMMPS relaxed from a job of `generate --engine lammps --write-only`: "
        "read bed.dump and log.lammps, check the bed and write what generate writes");
    app->option_defaults()->always_capture_default();
    app->add_option("folder", o.folder,
                    "the job's folder (job.json, log.lammps and bed.dump in it)")
        ->required()
        ->check(path_text());
    add_output_directory(*app, o.out, o.force);
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->fallthrough();
    app->footer("Exit status: 0 success, 1 the LAMMPS run failed or its bed fails a check, 2 bad "
                "input, 130 interrupted.");
    return {app, [options] { return run_import(*options); }};
}

Command register_generate(CLI::App& parent) {
    auto options = std::make_shared<GenerateOptions>();
    auto& o = *options;
    auto& p = o.params;
    CLI::App* app = parent.add_subcommand(
        "generate", "Pack spheres in a container with the soft-sphere algorithm of Salvat et al. "
                    "(2005) and write particles.csv, particles.vtu and summary.json");
    app->option_defaults()->always_capture_default();

    CLI::Option* aspect =
        app->add_option("-a,--aspect-ratio", o.aspect_ratio,
                        "a = 2 Rt / Dp, tube over sphere diameter (shorthand of --container)")
            ->check(real_in(option_range::aspect_ratio));
    add_container_option(*app, o.container,
                         "lengths in the unit of --diameter; a tube: a = D / Dp; instead of "
                         "--aspect-ratio")
        ->excludes(aspect);
    o.app = app;
    app->add_option("--shape", o.shape,
                    "the particles: sphere, or pellets: cylinder:D,L, ring:D,DI,L, "
                    "trilobe:DL,DC,L, multilobe:N,DL,DC,L or spherocylinder:D,L (lengths in the "
                    "bed's unit, -a over "
                    "their volume-equivalent diameter d_v; docs/generate.md, \"Pellets\")");
    app->add_option("-n,--particles", p.particles, "Np, number of spheres")
        ->check(whole_in(option_range::particles));
    app->add_option("-s,--seed", p.seed, "seed of the random generation stage")
        ->check(whole_in(option_range::seed));
    app->add_option("-d,--diameter", p.diameter,
                    "sphere diameter Dp; the unit of every length "
                    "in the outputs")
        ->check(real_in(option_range::diameter));
    std::vector<std::string> kinds;
    for (const auto& entry : size_kinds())
        kinds.push_back(std::string(size_syntax(entry.second)));
    app->add_option("--sizes", o.sizes,
                    fmt::format("the spheres' diameters (length units): {}; docs/sizes.md. "
                                "With sizes, Dp is their Sauter mean d32",
                                fmt::join(kinds, ", ")));
    app->add_option("--fractions", o.fractions,
                    "what the fractions and densities of --sizes count: volume (mass, as sieve "
                    "analyses) or number")
        ->check(one_of(fraction_bases().names()));
    add_output_directory(*app, o.out, o.force);
    app->add_option("--e0", p.e0, "initial overall void fraction for L0, eq. (6)")
        ->check(real_in(option_range::e0));
    app->add_option("--ck", p.ck, "elasticity parameter Ck of eq. (4)")
        ->check(real_in(option_range::ck));
    app->add_option("--cg-step", p.cg_step, "step of the gravity parameter Cg, eq. (7)")
        ->check(real_in(option_range::cg_step));
    constexpr auto paper = SoftSphereParameters::paper_schedule;
    constexpr auto fire = SoftSphereParameters::fire_schedule;
    app->add_option("--overlap-low", p.overlap_low,
                    fmt::format("lower bound of the largest overlap in the intermediate stage, "
                                "eq. (7), Dp (default: {:g} with --solver fire, {:g} paper)",
                                fire.overlap_low, paper.overlap_low))
        ->check(real_in(option_range::overlap_bound));
    app->add_option("--overlap-high", p.overlap_high,
                    fmt::format("upper bound of the largest overlap in the intermediate stage, "
                                "eq. (7), Dp (default: {:g} with --solver fire, {:g} paper)",
                                fire.overlap_high, paper.overlap_high))
        ->check(real_in(option_range::overlap_bound));
    app->add_option("--tolerance", p.tolerance,
                    "largest sphere-sphere and sphere-wall overlap allowed at the end, Dp")
        ->check(real_in(option_range::tolerance));
    app->add_option("--mc-period", p.mc_period, "iterations between mass-centre records")
        ->check(whole_in(option_range::mc_period));
    app->add_option("--mc-window", p.mc_window, "successive mass-centre records that must agree")
        ->check(whole_in(option_range::mc_window));
    app->add_option("--mc-tolerance", p.mc_tolerance,
                    fmt::format("allowed spread of those records, percent of their mean "
                                "(default: {:g} with --solver fire, {:g} paper)",
                                fire.mc_tolerance, paper.mc_tolerance))
        ->check(real_in(option_range::mc_tolerance));
    app->add_option("--update", o.update,
                    "in-place: each sphere moves in turn (Gauss-Seidel); simultaneous: all move "
                    "from the old positions (Jacobi, uses --threads)")
        ->check(one_of(update_orders().names()));
    app->add_option("--solver", o.solver,
                    "paper: the iteration of Salvat et al. (2005); fire: the same energy "
                    "minimised with FIRE under its own settling schedule, the paper's beds in "
                    "far fewer iterations (docs/performance.md)")
        ->check(one_of(solvers().names()));
    CLI::Option* engine =
        app->add_option("--engine", o.engine,
                        "packbed: relax here (OpenMP threads); lammps: the fire solver's energy "
                        "and schedule run by LAMMPS (MPI ranks), the bed read back and checked "
                        "(docs/lammps.md)")
            ->check(one_of(engines().names()));
    app->add_option("--ranks", o.lammps.ranks,
                    "--engine lammps: MPI ranks, `mpirun -np RANKS lmp` (1: lmp alone)")
        ->check(whole_in(option_range::lammps_ranks));
    app->add_option("--mpi-command", o.lammps.mpi_command,
                    "--engine lammps: a launcher's words instead of `mpirun -np RANKS` (e.g. "
                    "'srun -n 64'); no shell runs them");
    app->add_option("--lmp", o.lammps.lmp,
                    "--engine lammps: the LAMMPS program (lmp, lmp_mpi or a path)");
    app->add_option("--write-only", o.write_only,
                    "--engine lammps: write the LAMMPS job (data file, input, README with a "
                    "cluster's script) to this new directory and stop; `packbed import-lammps "
                    "DIR` brings the bed back")
        ->check(path_text());
    (void)engine;
    app->add_option("--skin", p.skin,
                    "Verlet neighbour-list skin, Dp (default: fire 0.2; paper, LAMMPS 0.1)")
        ->check(real_in(option_range::skin));
    app->add_option("--layer-height", p.layer_height,
                    "fire solver: a bed whose initial height L0 exceeds twice this is relaxed in "
                    "layers about this tall, bottom first; 0: in one piece (Dp; 0 or 10 to 1e6)")
        ->check(real_in(option_range::layer_height));
    CLI::Option* friction =
        app->add_option(
               "--friction", p.friction,
               "Coulomb friction between spheres: tangential springs capped by mu F_n and "
               "the spheres' rotations; 0 (default): the paper's frictionless, dense beds; "
               "more: looser, poured beds (fire solver; docs/generate.md, \"Friction\")")
            ->check(real_in(option_range::friction));
    CLI::Option* wall_friction =
        app->add_option("--wall-friction", p.wall_friction,
                        "Coulomb friction between a sphere and the walls and floor (default 0)")
            ->check(real_in(option_range::friction));
    app->add_option("--target-void-fraction", o.target_void_fraction,
                    "reach this void fraction (summary.json's, within 0.005) by the friction of "
                    "spheres and walls, found by short calibration runs; a target out of reach "
                    "is refused with the range; not with --friction or --wall-friction "
                    "(docs/generate.md, \"A target void fraction\")")
        ->check(real_in(option_range::void_fraction_target))
        ->excludes(friction)
        ->excludes(wall_friction);
    app->add_option("--checkpoint", o.checkpoint,
                    "fire solver in layers: save the state to this file after each layer, and "
                    "resume from it when it exists (the same options give the same bytes)")
        ->check(path_text());
    app->add_option("--max-iterations", p.max_iterations,
                    "give up after this many iterations (with --shape: steps, 2000000 unless "
                    "given)")
        ->check(whole_in(option_range::max_iterations));
    app->add_option("--band-clearance", o.band_clearance,
                    "the void fraction is measured between this distance above the floor and "
                    "below the bed top, Dp")
        ->check(real_in(option_range::band_clearance));
    add_threads_option(*app, o.threads);
    app->add_flag("--no-analysis", o.no_analysis,
                  "only the spheres (particles.csv, particles.vtu) and summary.json with the void "
                  "fraction: no profiles, plots or analysis tables (a DEM start; 500 spheres in "
                  "40-55 % less time, docs/performance.md)");
    app->add_flag("-q,--quiet", o.quiet, "no progress and no report on the terminal");
    app->fallthrough(); // --config belongs to the top-level app
    app->footer("Options may also come from a TOML file: packbed generate --config FILE.toml "
                "(keys are the long option names, e.g. aspect-ratio = 5; the command line "
                "wins).\nExit status: 0 success, 1 the run failed (divergence, no convergence), "
                "2 bad input, 130 interrupted.");
    return {app, [options] { return run_generate(*options); }};
}

} // namespace packbed::cli
