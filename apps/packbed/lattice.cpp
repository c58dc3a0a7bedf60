// `packbed lattice`: a regular packing (Tsayger's tetrahedral one, sc, bcc, fcc, hcp) filling
// a box or a cylinder, as the initial state of a DEM simulation.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "command.hpp"
#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/lattice.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

struct LatticeOptions {
    LatticeParameters params;
    std::string type = "diamond";
    std::string region = "box:10,10,10";
    std::string origin;
    std::string keep = "whole";
    std::string rotate;
    std::string out = "packbed-lattice";
    double band_clearance = 1.0;
    bool no_analysis = false;
    bool quiet = false;
    bool force = false;
};

int run_lattice(LatticeOptions& o) {
    o.params.type = lattice_types().at(o.type);
    o.params.region = parse_lattice_region(o.region);
    if (!o.origin.empty())
        o.params.origin = parse_lattice_origin(o.origin);
    o.params.keep = lattice_keeps().at(o.keep);
    o.params.rotations = parse_rotations(o.rotate);
    o.params.validate();
    // Every check before the work.
    OutputDirectory out(o.out, "--out", OutputKind::directory, o.force);

    const Packing packing = fill_lattice(o.params);
    auto summary = lattice_summary(o.params, packing);
    // A lattice is a bed: the same analysis as `generate` in its container, when tall enough.
    stage_lattice(out, o.params, packing, o.band_clearance, !o.no_analysis, summary);
    out.commit();
    if (!o.quiet) {
        fmt::print("packbed lattice: {} balls of a {} packing (coordination {}, porosity {:.5f})\n",
                   packing.size(), o.type, summary["lattice"]["coordination"].get<int>(),
                   summary["lattice"]["porosity"].get<double>());
        if (summary["porosity_region"].is_number())
            fmt::print("porosity in the region: {:.5f}; mean contacts found: {:.3f}\n",
                       summary["porosity_region"].get<double>(),
                       summary["contacts"]["mean"].get<double>());
        if (summary.contains("analysis_note"))
            fmt::print("analysis: {}\n", summary["analysis_note"].get<std::string>());
        fmt::print("results in {}/ (particles.csv, particles.vtu, summary.json{})\n",
                   out.path().string(),
                   summary.contains("analysis") ? " and the analysis tables" : "");
    }
    return 0;
}

} // namespace

Command register_lattice(CLI::App& parent) {
    auto options = std::make_shared<LatticeOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "lattice", "Fill a container's region with a regular packing of touching balls: "
                   "tetrahedral (diamond, Tsayger 2013), sc, bcc, fcc or hcp");
    app->option_defaults()->always_capture_default();
    app->add_option("-t,--type", o.type,
                    "diamond: coordination 4, porosity 0.660; sc: 6, 0.476; bcc: 8, 0.320; "
                    "fcc and hcp: 12, 0.260")
        ->check(one_of(lattice_types().names()));
    app->add_option("-d,--diameter", o.params.diameter, "ball diameter d; the unit of the outputs")
        ->check(real_in(option_range::diameter));
    app->add_option("-r,--region", o.region,
                    fmt::format("a container's spec and the region's height after its "
                                "numbers ({},HEIGHT; docs/containers.md), the floor at z = 0; "
                                "periodic: LX, LY whole multiples of the lattice's periods, no "
                                "--rotate; lengths up to 1e15",
                                fmt::join(all_forms, ",HEIGHT, ")));
    app->add_option("--origin", o.origin,
                    "x,y,z of the first ball of cell (0,0,0) (ball A of Tsayger's Table 1), "
                    "within 1e6 d of the region; default: d/2 from each wall at the low corner "
                    "of a box, on the axis d/2 above the floor of a cylinder");
    app->add_option("--rotate", o.rotate,
                    "turn the lattice about the origin: AXIS:DEGREES pairs applied in order, "
                    "e.g. z:30,x:10");
    app->add_option("--keep", o.keep,
                    "whole: only balls wholly inside the region; centres: every ball whose "
                    "centre is inside")
        ->check(one_of(lattice_keeps().names()));
    add_output_directory(*app, o.out, o.force);
    app->add_option("--band-clearance", o.band_clearance,
                    "the analysis band starts and ends this far from floor and top, d")
        ->check(real_in(option_range::lattice_band_clearance));
    app->add_flag("--no-analysis", o.no_analysis,
                  "only the balls and their summary: no profiles, plots or analysis (a million "
                  "balls: 1.1 s instead of 5.9 s, docs/performance.md)");
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->fallthrough();
    app->footer("Exit status: 0 success, 2 bad input.");
    return {app, [options] { return run_lattice(*options); }};
}

} // namespace packbed::cli
