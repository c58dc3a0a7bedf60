// `packbed random-array`: equal spheres at random in a cell periodic on all six faces, the
// hard-sphere fluid of the random-array drag laws and a bulk packing at a chosen solid fraction.
#include <chrono>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "command.hpp"
#include "packbed/container.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/periodic.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/random_array.hpp"
#include "progress.hpp"

namespace packbed::cli {

namespace {

struct RandomArrayOptions {
    RandomArrayParameters params;
    std::string out = "packbed-random-array";
    bool quiet = false;
    bool force = false;
};

int run_random_array(RandomArrayOptions& o) {
    o.params.validate();
    // Every check before the work.
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);

    const bool shown = progress_wanted(o.quiet);
    auto last = std::chrono::steady_clock::now();
    bool drawn = false;
    const RandomArray array =
        random_array(o.params, [&](std::uint64_t done, std::uint64_t planned) {
            const auto now = std::chrono::steady_clock::now();
            if (!shown || (drawn && now - last < std::chrono::milliseconds(100)))
                return;
            last = now;
            drawn = true;
            draw_status_line({fmt::format("random-array: sweep {} of ~{}", done, planned),
                              fmt::format("{} spheres", o.params.count)});
        });
    if (drawn)
        draw_status_line({});
    nlohmann::json summary = random_array_summary(o.params, array);
    stage_bed(out, array.packing, Periodic(array.cell, array.cell), 1.0, false, summary);
    out.commit();
    if (!o.quiet) {
        fmt::print("packbed random-array: {} spheres at solid fraction {} in a periodic cube of "
                   "edge {:.6g} (hard spheres of diameter {:.4g} d: {:.4f})\n",
                   o.params.count, o.params.solid_fraction, array.cell, 1.0 + o.params.gap,
                   o.params.hard_sphere_fraction());
        fmt::print("Monte Carlo: {} growth sweeps, {} sweeps at {:.0f} % accepted; spheres moved "
                   "{:.2f} d on average\n",
                   array.growth_sweeps, o.params.sweeps, 100.0 * array.acceptance,
                   array.mean_displacement);
        fmt::print("results in {}/ (particles.csv, particles.vtu, summary.json)\n",
                   out.path().string());
    }
    return 0;
}

} // namespace

Command register_random_array(CLI::App& parent) {
    auto options = std::make_shared<RandomArrayOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "random-array", "Equal spheres at random in a cube periodic on all six faces: hard "
                        "spheres in equilibrium (Monte Carlo), the random arrays of the drag "
                        "laws; export --flow periodic makes its CFD case");
    app->option_defaults()->always_capture_default();
    app->add_option("-n,--count", o.params.count, "spheres in the cell")
        ->required()
        ->check(whole_in(option_range::random_array_count));
    app->add_option("--solid-fraction", o.params.solid_fraction,
                    "N (pi/6) d^3 over the cube's volume, which sets its edge; hard spheres of "
                    "diameter (1 + gap) d fill at most 0.49 (their freezing point)")
        ->check(real_in(option_range::random_array_solid_fraction));
    app->add_option("-d,--diameter", o.params.diameter,
                    "sphere diameter d; the unit of the outputs")
        ->check(real_in(option_range::diameter));
    app->add_option("--gap", o.params.gap,
                    "least gap between two spheres' surfaces, in d (a mesh needs one: 0.05 d "
                    "is 1.6 cells at 32 cells per diameter)")
        ->check(real_in(option_range::random_array_gap));
    app->add_option("--sweeps", o.params.sweeps,
                    "Monte Carlo sweeps (a trial move of every sphere) after the spheres have "
                    "grown to their size")
        ->check(whole_in(option_range::random_array_sweeps));
    app->add_option("-s,--seed", o.params.seed, "seed of the start and of every trial move")
        ->check(whole_in(option_range::seed));
    add_output_directory(*app, o.out, o.force);
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->fallthrough();
    app->footer("Exit status: 0 success, 2 bad input.");
    return {app, [options] { return run_random_array(*options); }};
}

} // namespace packbed::cli
