// A soft-sphere bed from a request to its files (pipeline.hpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include <omp.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "packbed/bed_volume.hpp"
#include "packbed/checkpoint.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/memory.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/pipeline.hpp"

namespace packbed {

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
    PreparedGeneration prepared{
        request, request.params, std::nullopt,
        generation_memory(request.params.particles,
                          request.params.frictional() || request.target_void_fraction.has_value())};
    SoftSphereParameters& p = prepared.params;
    // Options that would be recorded in summary.json and change nothing.
    const SoftSphereParameters defaults;
    if (p.solver == Solver::fire && p.update != defaults.update)
        throw InvalidInput(fmt::format("--update {} is not allowed with --solver fire; allowed: "
                                       "--update with --solver paper (FIRE moves every sphere "
                                       "at once)",
                                       to_string(p.update)));
    if (request.sizes != "mono" && p.diameter != defaults.diameter)
        throw InvalidInput(fmt::format("--diameter {} is not allowed with --sizes '{}'; allowed: "
                                       "one of the two (the sizes give the diameters in length "
                                       "units, Dp is their Sauter mean d32)",
                                       p.diameter, shown_sizes(request.sizes)));
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
                                           printable(request.checkpoint),
                                           shown_sizes(request.sizes)));
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
        if (p.frictional())
            throw InvalidInput(fmt::format(
                "{} {} not allowed with --engine lammps; allowed: 0 (LAMMPS minimises the "
                "frictionless energy; friction needs damped dynamics with contact history, "
                "docs/lammps.md) or friction with --engine packbed",
                p.friction_options(), p.friction > 0.0 && p.wall_friction > 0.0 ? "are" : "is"));
        if (!request.checkpoint.empty())
            throw InvalidInput(fmt::format("--checkpoint {} is not allowed with --engine lammps; "
                                           "allowed: --checkpoint with --engine packbed",
                                           printable(request.checkpoint)));
    }
    if (const std::optional<double> target = request.target_void_fraction) {
        const std::string given = fmt::format("--target-void-fraction {}", *target);
        if (!(*target > 0.0 && *target < 1.0))
            throw InvalidInput(given + " is not allowed; allowed: 0 < E < 1");
        if (p.frictional())
            throw InvalidInput(fmt::format(
                "{} with {} is not allowed; allowed: one of the two (the target sets the "
                "friction of spheres and walls alike)",
                given, p.friction_options()));
        if (p.solver != Solver::fire || request.engine != Engine::packbed)
            throw InvalidInput(given + " is not allowed with --solver paper or --engine lammps; "
                                       "allowed: with --solver fire and --engine packbed (the "
                                       "target is reached by friction)");
        if (!request.checkpoint.empty())
            throw InvalidInput(fmt::format("{} with --checkpoint {} is not allowed; allowed: one "
                                           "of the two (the runs that find the friction are not "
                                           "saved)",
                                           given, printable(request.checkpoint)));
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

namespace {

/// The void fraction summary.json reports: over the band `clearance` Dp clear of the floor and
/// the top (bed lengths in Dp); NaN where the bed is too short for one.
double band_void_fraction(const SoftSphereResult& result, double clearance, double diameter) {
    const auto band = band_clear_of_ends(result.packing, clearance * diameter);
    return band ? void_fraction(result.packing, result.container, band->z_low, band->z_high)
                : std::numeric_limits<double>::quiet_NaN();
}

/// A friction coefficient and the void fraction of the bed it gave.
struct Trial {
    double friction;
    double void_fraction;
};

// The friction the target's search spans: from 0 (the dense, frictionless bed) to 1, past which
// a bed gets looser by less than 0.005 (a = 10: e = 0.4736 at mu = 1, 0.4772 at 3, 0.4771 at 10;
// docs/validation.md, "Friction").
constexpr double target_max_friction = 1.0;
// The calibration bed: the request's container and sizes, its first spheres up to an initial
// height of this many Dp (eq. 6), at least calibration_min of them.
constexpr double calibration_height = 15.0;
constexpr std::uint64_t calibration_min = 500;
// The calibration stops within this of the target (its beds scatter by about 0.004 at a = 10).
constexpr double calibration_tolerance = 0.004;
// A frictional calibration bed ends looser than the whole bed, by about this times the share of
// the whole it is not: at mu = 0.05, 0.007 at a = 5 (500 of 3 000 spheres), 0.0064 at a = 10
// (1 193 of 4 000), 0.003 at a = 20 (4 777 of 10 000); 0.003 at a = 10 without friction.
constexpr double calibration_offset = 0.007;
constexpr int calibration_runs = 2; // at most, besides the frictionless one
// How much looser the bed at target_max_friction is than without friction, before a trial
// says (friction_for): e(1) - e(0) = 0.051, 0.076 and 0.085 at a = 5, 10 and 20.
constexpr double prior_span = 0.075;
constexpr int full_runs = 3; // at most

/// The share of e(1) - e(0) that a bed gains at friction mu (spheres and walls alike): the mean
/// over calibration beds at a = 5, 10 and 20 (500, 1 193 and 4 777 spheres, seeds 1-3;
/// docs/generate.md, "A target void fraction"), piecewise linear in ln(mu + 0.01) between them;
/// 1 from mu = 1 on. It is the coordinate in which the search interpolates: e is close to
/// linear in it (each a within 0.052 of e(1) - e(0) of the mean at every measured mu;
/// bench/friction_loosening.sh).
double loosening(double mu) {
    struct Point {
        double mu, share;
    };
    static constexpr std::array<Point, 9> measured{{{0.0, 0.0},
                                                    {0.005, 0.020},
                                                    {0.01, 0.060},
                                                    {0.02, 0.130},
                                                    {0.03, 0.166},
                                                    {0.05, 0.254},
                                                    {0.1, 0.415},
                                                    {0.3, 0.747},
                                                    {1.0, 1.0}}};
    const auto x = [](double m) { return std::log(m + 0.01); };
    if (mu >= target_max_friction)
        return 1.0;
    std::size_t i = 1;
    while (measured[i].mu < mu)
        ++i;
    const Point& lo = measured[i - 1];
    const Point& hi = measured[i];
    return lo.share + (hi.share - lo.share) * (x(mu) - x(lo.mu)) / (x(hi.mu) - x(lo.mu));
}

/// The friction at which loosening() reaches `share` in [0, 1] (its inverse, by bisection).
double friction_at(double share) {
    double lo = 0.0, hi = target_max_friction;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (loosening(mid) < share ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// The friction, interpolated linearly in loosening(mu), at which the void fraction between two
/// trials reaches `target`.
double interpolate(const Trial& lo, const Trial& hi, double target) {
    if (!(hi.void_fraction > lo.void_fraction))
        return 0.5 * (lo.friction + hi.friction);
    const double t =
        std::clamp((target - lo.void_fraction) / (hi.void_fraction - lo.void_fraction), 0.0, 1.0);
    return friction_at(loosening(lo.friction) +
                       t * (loosening(hi.friction) - loosening(lo.friction)));
}

/// The friction at which the trials (any order) reach `target`: between the two trials of
/// neighbouring friction that straddle it, the least friction where several pairs do; beyond
/// the most frictional trial, by the prior: e rising by prior_span times loosening() from mu = 0
/// to target_max_friction.
double friction_for(std::vector<Trial> trials, double target) {
    std::sort(trials.begin(), trials.end(),
              [](const Trial& a, const Trial& b) { return a.friction < b.friction; });
    const Trial last = trials.back();
    if (last.friction < target_max_friction)
        trials.push_back({target_max_friction,
                          last.void_fraction + prior_span * (1.0 - loosening(last.friction))});
    if (target <= trials.front().void_fraction)
        return trials.front().friction;
    for (std::size_t i = 1; i < trials.size(); ++i)
        if (target <= trials[i].void_fraction)
            return interpolate(trials[i - 1], trials[i], target);
    return trials.back().friction;
}

/// --target-void-fraction: the friction of spheres and walls alike found by short runs, then
/// the bed itself (docs/generate.md, "A target void fraction"). The calibration bed (the
/// request's first spheres, calibration_height Dp of them) is relaxed without friction and at
/// target_max_friction: a target outside their void fractions (with the tolerance) is refused
/// with that range. Then regula falsi in loosening(mu) on calibration beds, until one ends
/// within calibration_tolerance; then the whole bed at that friction. A whole bed that misses
/// the target by more than the tolerance moves the calibration's target by its miss and runs
/// again, at most full_runs times.
GeneratedBed run_to_target(const PreparedGeneration& prepared, const RunControl& control,
                           int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    const double target = *prepared.request.target_void_fraction;
    const double tolerance = GenerateRequest::target_tolerance;
    const double clearance = prepared.request.band_clearance;
    // The calibration and the bed report progress, each run named (Progress::run), nothing
    // else.
    std::string run_name;
    RunControl quiet;
    if (control.on_progress)
        quiet.on_progress = [&](const Progress& p) {
            Progress named = p;
            named.run = run_name;
            control.on_progress(named);
        };
    quiet.should_stop = control.should_stop;

    SoftSphereParameters calibration = prepared.params;
    const double height = initial_bed_height(prepared.params);
    calibration.particles = std::min<std::uint64_t>(
        prepared.params.particles,
        std::max<std::uint64_t>(
            calibration_min,
            static_cast<std::uint64_t>(std::ceil(static_cast<double>(prepared.params.particles) *
                                                 calibration_height / height))));
    if (!calibration.sizes.empty())
        calibration.sizes.resize(calibration.particles);
    std::vector<Trial> calibrated;
    const auto calibrate = [&](double mu) {
        calibration.friction = calibration.wall_friction = mu;
        run_name = fmt::format("calibration bed {}, friction {:.3g}", calibrated.size() + 1, mu);
        const SoftSphereResult r = generate_soft_sphere(calibration, quiet);
        calibrated.push_back({mu, band_void_fraction(r, clearance, calibration.diameter)});
        if (!std::isfinite(calibrated.back().void_fraction))
            throw InvalidInput(fmt::format(
                "--target-void-fraction {}: the calibration bed of {} spheres is too short for "
                "the void fraction's band; allowed: a lower --band-clearance (now {})",
                target, calibration.particles, clearance));
        return calibrated.back();
    };
    // The densest bed first; the loosest only where the target lies beyond every trial.
    const Trial lo = calibrate(0.0);
    double densest = lo.void_fraction, loosest = std::numeric_limits<double>::quiet_NaN();
    // The calibration bed aims above the target by what a frictional calibration bed is
    // expected to be looser than the whole bed (calibration_offset); the loosest whole bed is
    // expected as much below the loosest calibration bed.
    const double share =
        static_cast<double>(calibration.particles) / static_cast<double>(prepared.params.particles);
    const double looser = calibration_offset * (1.0 - share);
    const double aim = target + looser;
    const auto refuse = [&] {
        if (std::isnan(loosest))
            loosest = calibrate(target_max_friction).void_fraction;
        return InvalidInput(fmt::format(
            "--target-void-fraction {} is not reachable in this container with these sizes; "
            "allowed: {:.3f} (no friction) to {:.3f} (friction {}), as measured on a bed of {} "
            "of its spheres{}",
            target, densest, loosest - looser, target_max_friction, calibration.particles,
            looser > 0.0 ? fmt::format(" (it gave {:.3f} at friction {}; the whole bed is "
                                       "expected {:.3f} denser)",
                                       loosest, target_max_friction, looser)
                         : ""));
    };
    if (target < densest - tolerance)
        throw refuse();
    double mu = 0.0;
    if (aim > densest + calibration_tolerance) {
        // The first guess by the prior (friction_for), then regula falsi on the trials.
        mu = friction_for(calibrated, aim);
        for (int i = 0; i < calibration_runs; ++i) {
            const Trial t = calibrate(mu);
            if (std::abs(t.void_fraction - aim) <= calibration_tolerance)
                break;
            if (t.void_fraction < aim && mu >= target_max_friction) {
                loosest = t.void_fraction;
                if (target > loosest - looser + tolerance)
                    throw refuse();
                break;
            }
            mu = friction_for(calibrated, aim);
        }
    }

    SoftSphereParameters p = prepared.params;
    std::vector<Trial> runs;
    GeneratedBed best;
    double miss = std::numeric_limits<double>::infinity(), best_mu = mu;
    for (int run = 0; run < full_runs; ++run) {
        p.friction = p.wall_friction = mu;
        run_name = fmt::format("whole bed {}, friction {:.3g}", runs.size() + 1, mu);
        SoftSphereResult result = generate_soft_sphere(p, quiet);
        const double e = band_void_fraction(result, clearance, p.diameter);
        runs.push_back({mu, e});
        if (std::abs(e - target) < miss) {
            miss = std::abs(e - target);
            best_mu = mu;
            best.result = std::move(result);
        }
        if (miss <= tolerance)
            break;
        // The whole bed is off the calibration's curve by (e - its value there): aim the
        // calibration's curve at the target moved by as much.
        const double offset = e - [&] {
            std::vector<Trial> near = calibrated;
            std::sort(near.begin(), near.end(), [mu](const Trial& a, const Trial& b) {
                return std::abs(a.friction - mu) < std::abs(b.friction - mu);
            });
            return near.front().void_fraction;
        }();
        mu = std::clamp(friction_for(calibrated, target - offset), 0.0, target_max_friction);
        const auto below = [target](const Trial& t) { return t.void_fraction < target; };
        if (std::any_of(runs.begin(), runs.end(), below) &&
            !std::all_of(runs.begin(), runs.end(), below)) // whole beds on both sides
            mu = friction_for(runs, target);
        if (mu == runs.back().friction) // the same bed again (friction at an end of its range)
            break;
    }
    if (miss > tolerance) {
        std::vector<double> frictions, voids;
        for (const Trial& t : runs) {
            frictions.push_back(t.friction);
            voids.push_back(t.void_fraction);
        }
        throw ConvergenceError(fmt::format(
            "--target-void-fraction {}: the beds at friction {} ended at void fractions {} "
            "(tolerance {}); the calibration bed of {} spheres reached {:.3f} without friction: "
            "another --seed, more --particles or a target farther from the ends of the range",
            target, fmt::join(frictions, ", "), fmt::join(voids, ", "), tolerance,
            calibration.particles, densest));
    }
    p.friction = p.wall_friction = best_mu;
    best.result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    PreparedGeneration ran = prepared;
    ran.params = p;
    best.summary = generation_summary(ran, best.result, threads);
    auto trials = [](const std::vector<Trial>& list) {
        nlohmann::json out = nlohmann::json::array();
        for (const Trial& t : list)
            out.push_back({{"friction", t.friction}, {"void_fraction", t.void_fraction}});
        return out;
    };
    best.summary["target_void_fraction"] = {
        {"target", target},
        {"tolerance", tolerance},
        {"friction", p.friction},
        {"method",
         "the friction of spheres and walls alike, found on calibration beds of the "
         "first spheres (regula falsi in the measured loosening curve), then the whole bed"},
        {"calibration_particles", calibration.particles},
        {"calibration_aim", aim},
        {"frictionless", densest},
        {"calibration", trials(calibrated)},
        {"runs", trials(runs)}};
    return best;
}

} // namespace

GeneratedBed run_generation(const PreparedGeneration& prepared, RunControl control, int threads,
                            const std::function<void(std::uint32_t)>& on_resume) {
    if (prepared.request.target_void_fraction)
        return run_to_target(prepared, control, threads);
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

void stage_lattice(OutputDirectory& out, const LatticeParameters& lattice, const Packing& packing,
                   double band_clearance, bool analysis, nlohmann::json& summary) {
    const double height = lattice.region.height / lattice.diameter; // d
    const bool tall_enough = height > 2.0 * band_clearance;
    analysis = analysis && !packing.centers.empty();
    if (analysis && !tall_enough)
        summary["analysis_note"] =
            fmt::format("not analysed: the region is {:g} d tall, not taller than twice "
                        "--band-clearance ({:g} d); lower --band-clearance",
                        height, band_clearance);
    stage_bed(out, packing, lattice.region.container, band_clearance, analysis && tall_enough,
              summary);
}

} // namespace packbed
