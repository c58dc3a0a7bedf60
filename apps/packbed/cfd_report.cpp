// `packbed cfd-report`: a run OpenFOAM case's pressure gradient next to the band of published
// correlations.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "packbed/json_text.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

/// "converged (residuals)", "converged (steady pressure drop)" or "NOT converged".
std::string solver_end(const nlohmann::ordered_json& solver) {
    if (!solver["converged"].get<bool>())
        return "NOT converged";
    return fmt::format("converged ({})", solver["stopped_by"].get<std::string>());
}

struct CfdReportOptions {
    std::vector<std::string> cases;
    std::string out; // default: CASE/cfd-report
    bool force = false;
    bool json = false;
    bool quiet = false;
};

/// The report's warnings (and `why` there is no plot, unless --quiet) on stderr, the JSON with
/// --json. \return whether the table is still to be printed (neither --json nor --quiet)
bool warned_and_shown(const Report& report, const std::string& why, const CfdReportOptions& o) {
    for (const auto& w : report.warnings)
        fmt::print(stderr, "packbed cfd-report: warning: {}\n", w);
    if (!why.empty() && !o.quiet)
        fmt::print(stderr, "packbed cfd-report: {}\n", why);
    if (o.json)
        fmt::print("{}", json_file_text(report.values, "the report"));
    return !o.json && !o.quiet;
}

/// A cell periodic along z: the gradient, the drag per sphere and the references.
void print_periodic(const nlohmann::json& v) {
    const auto& p = v["periodic"];
    const auto& f = v["flow"];
    const auto& s = v["solver"];
    const auto& e = v["void_fraction"];
    const auto& r = p["references"];
    fmt::print("simpleFoam: {} after {} iterations; a cell periodic along z, {} spheres of "
               "d = {:.6g} m\n",
               solver_end(s), s["iterations"].get<long>(), p["spheres"].get<long long>(),
               f["diameter_m"].get<double>());
    fmt::print("void fraction {:.5f} exact, {:.5f} meshed; superficial velocity {:.6g} m/s (the "
               "mesh's), Re_p = {:.4g}\n",
               e["exact"].get<double>(), e["mesh"].get<double>(),
               f["superficial_velocity_m_s"].get<double>(), f["reynolds"].get<double>());
    fmt::print("pressure gradient {:.6g} Pa/m; drag per sphere {:.6g} N\n",
               p["pressure_gradient_Pa_m"].get<double>(), p["drag_per_sphere_N"].get<double>());
    fmt::print("  K = F_total / (6 pi mu a U_s) = {:.5g}", p["K"].get<double>());
    if (r.contains("zick_homsy_simple_cubic_K"))
        fmt::print("   Zick & Homsy (1982), simple cubic at phi = {:.4g}: {:.4g} (CFD / it "
                   "{:.4f})",
                   r["zick_homsy_solid_fraction"].get<double>(),
                   r["zick_homsy_simple_cubic_K"].get<double>(),
                   r["K_over_zick_homsy"].get<double>());
    fmt::print("\n  F = (1 - phi) K = {:.5g}   van der Hoef et al. (2005), random arrays: {:.4g} "
               "(CFD / it {:.4f})\n",
               p["F"].get<double>(), r["van_der_hoef_random_F"].get<double>(),
               r["F_over_van_der_hoef"].get<double>());
}

/// Several cases: the mesh series (cfd_series), to LAST/cfd-series unless --out.
int run_cfd_series(const CfdReportOptions& o) {
    if (o.cases.size() < 3) // before the output is claimed
        throw InvalidInput(fmt::format("{} case(s) given for a mesh series; allowed: 3 or more "
                                       "cases of one bed, meshed at different resolutions",
                                       o.cases.size()));
    std::vector<std::filesystem::path> cases;
    for (const std::string& c : o.cases) {
        cases.emplace_back(c);
        check_cfd_case(cases.back());
    }
    const std::filesystem::path out_dir =
        o.out.empty() ? cases.back() / "cfd-series" : std::filesystem::path(o.out);
    OutputDirectory out(out_dir, "--out", OutputKind::directory, o.force); // before the work
    const Report report = cfd_series(cases);
    stage_cfd_series(out, report);
    out.commit();
    if (!warned_and_shown(report, {}, o))
        return 0;
    const nlohmann::json& v = report.values;
    const std::string quantity = v["quantity"].get<std::string>();
    const std::string name = quantity == "K" ? "K" : "Pa/m";
    fmt::print("  {:>10} {:>8} {:>10} {:>12}{}\n", "cells", "h / d", "mesh e", name,
               v["levels"][0].contains("over_reference") ? "   / reference" : "");
    for (const auto& row : v["levels"]) {
        fmt::print("  {:>10} {:>8.4f} {:>10.5f} {:>12.6g}", row["cells"].get<long long>(),
                   row["h_over_d"].get<double>(), row["mesh_void_fraction"].get<double>(),
                   row[quantity].get<double>());
        if (row.contains("over_reference"))
            fmt::print("   {:.4f}", row["over_reference"].get<double>());
        fmt::print("{}\n", row["converged"].get<bool>() ? "" : "   (NOT converged)");
    }
    const auto& c = v["celik"];
    fmt::print("three finest (Celik et al. 2008): apparent order {:.3g}{}, extrapolated {:.6g}, "
               "GCI of the finest {:.2f} %",
               c["order"].get<double>(), c["oscillating"].get<bool>() ? " (oscillating)" : "",
               c["extrapolated"].get<double>(), 100.0 * c["gci_fine"].get<double>());
    if (c.contains("reference"))
        fmt::print("; reference {:.4g}, extrapolated / reference {:.4f}",
                   c["reference"].get<double>(), c["extrapolated_over_reference"].get<double>());
    fmt::print("\ntable and JSON: {}\n", out_dir.string());
    return 0;
}

int run_cfd_report(const CfdReportOptions& o) {
    if (o.cases.size() > 1)
        return run_cfd_series(o);
    const std::filesystem::path case_dir(o.cases.front());
    check_cfd_case(case_dir);
    const std::filesystem::path out_dir =
        o.out.empty() ? case_dir / "cfd-report" : std::filesystem::path(o.out);
    OutputDirectory out(out_dir, "--out", OutputKind::directory, o.force); // before the work
    const Report report = cfd_report(case_dir);
    const std::string why = stage_cfd_report(out, report);
    out.commit();
    if (!warned_and_shown(report, why, o))
        return 0;
    const nlohmann::json& v = report.values;
    if (v.contains("periodic")) {
        print_periodic(v);
        fmt::print("JSON: {}\n", (out_dir / "cfd_report.json").string());
        return 0;
    }
    const auto& g = v["pressure_gradient_Pa_m"];
    const auto& c = v["correlations"];
    const auto& f = v["flow"];
    const auto& s = v["solver"];
    const auto& e = v["void_fraction"];
    const double cfd = g["cfd"].get<double>();
    fmt::print("simpleFoam: {} after {} iterations; fluxes in {:.6g}, out {:.6g} m^3/s "
               "(imbalance {:.2g})\n",
               solver_end(s), s["iterations"].get<long>(), v["fluxes_m3_s"]["inlet"].get<double>(),
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
    fmt::print("  {:<38} {:>12} {:>10}\n", "", "Pa/m", "CFD / it");
    fmt::print("  {:<38} {:>12.5g} {:>10}   (standard error {:.2g})\n", "CFD (fitted line)", cfd,
               "", g["standard_error"].get<double>());
    // The band of correlations (Ergun's and Eisfeld & Schnitzlein's among them); * marks a
    // value outside the correlation's stated range.
    bool outside = false;
    for (const auto& b : c["band"]) {
        const bool beyond = !b["outside_range"].is_null();
        outside = outside || beyond;
        const std::string label = b["label"].get<std::string>();
        fmt::print("  {:<38} {:>12.5g} {:>10.4f}{}\n",
                   b["wall"].get<bool>()
                       ? fmt::format("{} (a = {:.4g})", label, c["aspect_ratio"].get<double>())
                       : label,
                   b["Pa_m"].get<double>(), b["cfd_over"].get<double>(), beyond ? " *" : "");
    }
    const double low = c["band_Pa_m"][0].get<double>(), high = c["band_Pa_m"][1].get<double>();
    fmt::print("  the {} correlations span {:.5g} to {:.5g} Pa/m: the CFD is {}{}\n",
               c["band"].size(), low, high,
               cfd < low ? "below them" : (cfd > high ? "above them" : "among them"),
               outside ? "; * outside its stated range (--json says which)" : "");
    if (c.contains("van_der_hoef_random_F"))
        fmt::print("  F = (1 - phi) K = {:.5g} (K = F_total / (3 pi mu d U_s) = {:.5g});   van der "
                   "Hoef et al. (2005), random arrays: {:.4g} (CFD / it {:.4f})\n",
                   c["F"].get<double>(), c["K"].get<double>(),
                   c["van_der_hoef_random_F"].get<double>(),
                   c["F_over_van_der_hoef"].get<double>());
    fmt::print("table, plot and JSON: {}\n", out_dir.string());
    return 0;
}

} // namespace

Command register_cfd_report(CLI::App& parent) {
    auto options = std::make_shared<CfdReportOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "cfd-report", "The pressure gradient of a case from export --format openfoam, run by "
                      "its Allrun, next to the band of published correlations (Ergun, Carman, "
                      "KTA, Erdim et al., and with a wall Harrison et al. and Eisfeld & "
                      "Schnitzlein) at the bed's own void fraction; a table, pressure.csv and a "
                      "plot (docs/surfaces.md); a "
                      "periodic cell's drag beside Zick & Homsy's and van der Hoef's; of several "
                      "cases, the mesh series: apparent order, extrapolated value and grid "
                      "convergence index");
    app->option_defaults()->always_capture_default();
    app->fallthrough();
    app->add_option("case", o.cases,
                    "the case directory (after ./Allrun); three or more: a mesh series of one "
                    "bed, in any order (docs/validation.md)")
        ->required()
        ->check(path_text());
    add_output_directory(*app, o.out, o.force,
                         "CASE/cfd-report; a series: cfd-series in the last case given");
    app->add_flag("--json", o.json, "print the whole report as JSON");
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->footer("Exit status: 0 success, 2 bad input (not a run case, a missing table).");
    return {app, [options] { return run_cfd_report(*options); }};
}

} // namespace packbed::cli
