// `packbed cfd-report`: a run OpenFOAM case's pressure gradient next to Ergun's and Eisfeld &
// Schnitzlein's (issue 20).
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "packbed/json_text.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

struct CfdReportOptions {
    std::string case_dir;
    std::string out; // default: CASE/cfd-report
    bool force = false;
    bool json = false;
    bool quiet = false;
};

int run_cfd_report(const CfdReportOptions& o) {
    const std::filesystem::path case_dir(o.case_dir);
    check_cfd_case(case_dir);
    const std::filesystem::path out_dir =
        o.out.empty() ? case_dir / "cfd-report" : std::filesystem::path(o.out);
    OutputDirectory out(out_dir, "--out", OutputKind::directory, o.force); // before the work
    const Report report = cfd_report(case_dir);
    const std::string why = stage_cfd_report(out, report);
    out.commit();
    for (const auto& w : report.warnings)
        fmt::print(stderr, "packbed cfd-report: warning: {}\n", w);
    if (!why.empty() && !o.quiet)
        fmt::print(stderr, "packbed cfd-report: {}\n", why);
    const nlohmann::json& v = report.values;
    if (o.json) {
        fmt::print("{}", json_file_text(v, "the report"));
        return 0;
    }
    if (o.quiet)
        return 0;
    const auto& g = v["pressure_gradient_Pa_m"];
    const auto& c = v["correlations"];
    const auto& f = v["flow"];
    const auto& s = v["solver"];
    const auto& e = v["void_fraction"];
    const double cfd = g["cfd"].get<double>();
    fmt::print("simpleFoam: {} after {} iterations; fluxes in {:.6g}, out {:.6g} m^3/s "
               "(imbalance {:.2g})\n",
               s["converged"].get<bool>() ? "converged" : "NOT converged",
               s["iterations"].get<long>(), v["fluxes_m3_s"]["inlet"].get<double>(),
               v["fluxes_m3_s"]["outlet"].get<double>(),
               v["fluxes_m3_s"]["imbalance"].get<double>());
    fmt::print("superficial velocity {:.6g} m/s, Re_p = {:.4g}, d = {:.6g} m; void fraction "
               "between the planes {:.5f}",
               f["superficial_velocity_m_s"].get<double>(), f["reynolds"].get<double>(),
               f["diameter_m"].get<double>(), e["band"].get<double>());
    if (e.contains("container_treated"))
        fmt::print(" (container: {:.5f} untouched, {:.5f} treated{})",
                   e["container_untouched"].get<double>(), e["container_treated"].get<double>(),
                   e.contains("mesh") ? fmt::format(", {:.5f} meshed", e["mesh"].get<double>())
                                      : std::string());
    fmt::print("\npressure gradient over z = {:.6g} to {:.6g} m ({} planes):\n",
               g["from_m"].get<double>(), g["to_m"].get<double>(), v["planes"].size());
    fmt::print("  {:<34} {:>12} {:>10}\n", "", "Pa/m", "CFD / it");
    fmt::print("  {:<34} {:>12.5g} {:>10}   (standard error {:.2g})\n", "CFD (fitted line)", cfd,
               "", g["standard_error"].get<double>());
    fmt::print("  {:<34} {:>12.5g} {:>10.4f}\n", "Ergun (1952)", c["ergun_Pa_m"].get<double>(),
               c["cfd_over_ergun"].get<double>());
    if (c.contains("eisfeld_schnitzlein_Pa_m"))
        fmt::print(
            "  {:<34} {:>12.5g} {:>10.4f}\n",
            fmt::format("Eisfeld & Schnitzlein (a = {:.4g})", c["aspect_ratio"].get<double>()),
            c["eisfeld_schnitzlein_Pa_m"].get<double>(),
            c["cfd_over_eisfeld_schnitzlein"].get<double>());
    fmt::print("table, plot and JSON: {}\n", out_dir.string());
    return 0;
}

} // namespace

Command register_cfd_report(CLI::App& parent) {
    auto options = std::make_shared<CfdReportOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "cfd-report", "The pressure gradient of a case from export --format openfoam, run by "
                      "its Allrun, next to Ergun's and Eisfeld & Schnitzlein's at the bed's own "
                      "void fraction; a table, pressure.csv and a plot (docs/surfaces.md)");
    app->option_defaults()->always_capture_default();
    app->fallthrough();
    app->add_option("case", o.case_dir, "the case directory (after ./Allrun)")
        ->required()
        ->check(path_text());
    add_output_directory(*app, o.out, o.force, "CASE/cfd-report");
    app->add_flag("--json", o.json, "print the whole report as JSON");
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->footer("Exit status: 0 success, 2 bad input (not a run case, a missing table).");
    return {app, [options] { return run_cfd_report(*options); }};
}

} // namespace packbed::cli
