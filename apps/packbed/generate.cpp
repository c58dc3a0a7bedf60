// `packbed generate`: the soft-sphere bed of Salvat et al. (2005) in a cylinder.
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include "command.hpp"
#include "packbed/analysis.hpp"
#include "packbed/error.hpp"
#include "packbed/io.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/summary.hpp"
#include "progress.hpp"

namespace packbed::cli {

namespace {

struct GenerateOptions {
    SoftSphereParameters params;
    std::string update = to_string(SoftSphereParameters{}.update);
    std::string solver = to_string(SoftSphereParameters{}.solver);
    std::string out = "packbed-out";
    std::string checkpoint; // empty: none
    std::string container;  // --container cylinder:D, instead of --aspect-ratio
    std::string sizes = "mono";
    std::string fractions = to_string(FractionBasis::volume);
    double band_clearance = 1.0;
    unsigned long long threads = static_cast<unsigned long long>(omp_get_num_procs());
    bool quiet = false;
    bool force = false;
};

int run_generate(GenerateOptions& o) {
    GenerateRequest request;
    request.params = o.params;
    for (const auto& [name, value] : update_orders())
        if (name == o.update)
            request.params.update = value;
    for (const auto& [name, value] : solvers())
        if (name == o.solver)
            request.params.solver = value;
    for (const auto& [name, value] : fraction_bases())
        if (name == o.fractions)
            request.fractions = value;
    request.sizes = o.sizes;
    request.container = o.container;
    request.checkpoint = o.checkpoint;
    request.band_clearance = o.band_clearance;
    const PreparedGeneration prepared = prepare_generation(request);
    const SoftSphereParameters& params = prepared.params;
    // Every check before the run: the output directory, the checkpoint.
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);
    use_threads(o.threads);

    TerminalProgress progress(progress_wanted(o.quiet), params);
    RunControl control;
    control.on_progress = [&](const Progress& p) { progress(p); };
    GeneratedBed bed = run_generation(
        prepared, control, static_cast<int>(o.threads), &out, [&](std::uint32_t layers_done) {
            if (!o.quiet)
                fmt::print(stderr, "packbed generate: resuming from {} after layer {} of {}\n",
                           o.checkpoint, layers_done, fire_layers(params));
        });
    progress.finish();
    const SoftSphereResult& result = bed.result;
    auto& summary = bed.summary;
    // The same analysis as `packbed analyze`, when the bed is tall enough for the band.
    stage_bed(out, result.packing, result.container, o.band_clearance,
              summary["void_fraction"].is_number(), summary);
    out.commit();
    if (!o.quiet) {
        fmt::print("packbed generate: {} spheres, {}, seed {}: {} iterations, {:.2f} s\n",
                   params.particles,
                   params.container ? result.container.spec()
                                    : fmt::format("a = {}", params.aspect_ratio),
                   params.seed, result.iterations, result.seconds);
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
        fmt::print("results in {}/ (particles.csv, particles.vtu, summary.json and the "
                   "analysis tables)\n",
                   out.path().string());
    }
    return 0;
}

} // namespace

Command register_generate(CLI::App& parent) {
    auto options = std::make_shared<GenerateOptions>();
    auto& o = *options;
    auto& p = o.params;
    CLI::App* app = parent.add_subcommand(
        "generate", "Pack spheres in a container with the soft-sphere algorithm of Salvat et al. "
                    "(2005) and write particles.csv, particles.vtu and summary.json");
    app->option_defaults()->always_capture_default();

    CLI::Option* aspect =
        app->add_option("-a,--aspect-ratio", p.aspect_ratio,
                        "a = 2 Rt / Dp, tube over sphere diameter (shorthand of --container)")
            ->check(real_in(option_range::aspect_ratio));
    add_container_option(*app, o.container,
                         "lengths in the unit of --diameter; a tube: a = D / Dp; instead of "
                         "--aspect-ratio")
        ->excludes(aspect);
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
    std::vector<std::string> bases;
    for (const auto& entry : fraction_bases())
        bases.push_back(entry.first);
    app->add_option("--fractions", o.fractions,
                    "what the fractions and densities of --sizes count: volume (mass, as sieve "
                    "analyses) or number")
        ->check(one_of(bases));
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
    std::vector<std::string> update_names;
    for (const auto& entry : update_orders())
        update_names.push_back(entry.first);
    app->add_option("--update", o.update,
                    "in-place: each sphere moves in turn (Gauss-Seidel); simultaneous: all move "
                    "from the old positions (Jacobi, uses --threads)")
        ->check(one_of(update_names));
    std::vector<std::string> solver_names;
    for (const auto& entry : solvers())
        solver_names.push_back(entry.first);
    app->add_option("--solver", o.solver,
                    "paper: the iteration of Salvat et al. (2005); fire: the same energy "
                    "minimised with FIRE under its own settling schedule, the paper's beds in "
                    "far fewer iterations (docs/performance.md)")
        ->check(one_of(solver_names));
    app->add_option("--skin", p.skin, "Verlet neighbour-list skin, Dp")
        ->check(real_in(option_range::skin));
    app->add_option("--layer-height", p.layer_height,
                    "fire solver: a bed whose initial height L0 exceeds twice this is relaxed in "
                    "layers about this tall, bottom first; 0: in one piece (Dp; 0 or 10 to 1e6)")
        ->check(real_in(option_range::layer_height));
    app->add_option("--checkpoint", o.checkpoint,
                    "fire solver in layers: save the state to this file after each layer, and "
                    "resume from it when it exists (the same options give the same bytes)")
        ->check(path_text());
    app->add_option("--max-iterations", p.max_iterations, "give up after this many iterations")
        ->check(whole_in(option_range::max_iterations));
    app->add_option("--band-clearance", o.band_clearance,
                    "the void fraction is measured between this distance above the floor and "
                    "below the bed top, Dp")
        ->check(real_in(option_range::band_clearance));
    app->add_option("-j,--threads", o.threads,
                    "at most this many threads, fewer while the machine is busy (results do not "
                    "depend on it)")
        ->check(whole_in(option_range::threads));
    app->add_flag("-q,--quiet", o.quiet, "no progress and no report on the terminal");
    app->fallthrough(); // --config belongs to the top-level app
    app->footer("Options may also come from a TOML file: packbed generate --config FILE.toml "
                "(keys are the long option names, e.g. aspect-ratio = 5; the command line "
                "wins).\nExit status: 0 success, 1 the run failed (divergence, no convergence), "
                "2 bad input, 130 interrupted.");
    return {app, [options] { return run_generate(*options); }};
}

} // namespace packbed::cli
