// The plots of an analysis and the analysis generate and lattice stage (pipeline.hpp).
#include "packbed/pipeline.hpp"

#include "child.hpp"
#include "gnuplot.hpp"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "packbed/analysis_files.hpp"
#include "packbed/bed_checks.hpp"
#include "packbed/correlations.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"

namespace packbed {

namespace {

/// A gnuplot datablock named `name` with the bins' middles over Dp and their values.
std::string datablock(std::string_view name, const std::vector<ProfileBin>& bins, double dp) {
    std::string out = fmt::format("${} << EOD\n", name);
    for (const auto& b : bins)
        out += fmt::format("{} {}\n", 0.5 * (b.low + b.high) / dp, b.value);
    return out + "EOD\n";
}

} // namespace

std::string draw_plots(OutputDirectory& out, const std::vector<std::string>& names,
                       const std::vector<std::string>& scripts) {
    if (scripts.empty())
        return "no plot scripts: no plots";
    std::vector<std::filesystem::path> files;
    for (const auto& name : names)
        for (const auto& [extension, terminal] : plot_terminals)
            files.push_back(out.reserve(name + "." + extension));
    // Each script in a file of ours, run by its own gnuplot in the staging folder: the scripts
    // and the files they write are named relative to it, so no text of the user's (an output
    // path) ever reaches gnuplot. Their output is dropped.
    std::vector<std::string> script_names;
    std::vector<std::vector<std::string>> commands;
    std::filesystem::path folder;
    for (std::size_t k = 0; k < scripts.size(); ++k) {
        script_names.push_back(fmt::format("plots-{}.gp", k + 1));
        const auto path = out.reserve(script_names.back());
        std::ofstream(path) << scripts[k];
        folder = path.parent_path();
        commands.push_back({"gnuplot", script_names.back()});
    }
    int status = run_programs(commands, folder, "/dev/null");
    status = status < 0 ? 1 : status;
    for (const auto& name : script_names)
        out.discard(name);
    bool all = status == 0;
    for (const auto& file : files)
        all = all && std::filesystem::exists(file) && std::filesystem::file_size(file) > 0;
    if (all)
        return {};
    // No plots, but the rest of the output stands.
    for (const auto& file : files)
        out.discard(file.filename().string());
    return status == 127 ? "gnuplot not found (Debian package gnuplot-nox): no plots"
                         : fmt::format("gnuplot failed (exit status {}): no plots", status);
}

std::string stage_plots(OutputDirectory& out, const BedAnalysis& a, const Container& container) {
    const double dp = a.diameter;
    // The correlations of the radial profile are for cylinders, at their aspect ratio.
    // (for one size: a mixture's profile is not what they describe).
    const std::optional<double> tube = a.by_size.empty() ? container.tube_diameter() : std::nullopt;
    const double aspect_ratio = tube ? *tube / dp : 0.0;
    const double x_max = container.depth(a.band.z_low, a.band.z_high) / dp;
    // Profiles against the distance from the wall, z and the centre distance, all over Dp.
    // A container of one wall draws "this bed"; an annulus a curve per wall; a periodic cell
    // has no wall plots.
    std::string script, bed_curves, centre_curves;
    if (a.walls.size() == 1) {
        script = datablock("bed", a.radial_void_fraction, dp) +
                 datablock("centres", a.centre_distribution, dp);
        bed_curves = "$bed using 1:2 with lines lw 2 lc rgb 'black' title 'this bed'";
        centre_curves = "$centres using 1:2 with steps lw 2 lc rgb 'black' title 'this bed'";
    } else {
        for (const WallAnalysis& wall : a.walls) {
            script += datablock("bed_" + wall.name, wall.void_fraction, dp) +
                      datablock("centres_" + wall.name, wall.centre_distribution, dp);
            const std::string separator = bed_curves.empty() ? "" : ", ";
            bed_curves += fmt::format("{}$bed_{} using 1:2 with lines lw 2 title 'from the {} "
                                      "wall'",
                                      separator, wall.name, wall.name);
            centre_curves += fmt::format("{}$centres_{} using 1:2 with steps lw 2 title 'from "
                                         "the {} wall'",
                                         separator, wall.name, wall.name);
        }
    }
    script +=
        datablock("axial", a.axial_void_fraction, dp) + datablock("rdf", a.pair_correlation, dp);
    const std::string where = tube ? fmt::format("a = {:.4g}", aspect_ratio)
                                   : fmt::format("{} (Dp = {:.4g})", container.spec(), dp);
    const std::string x_label = tube                 ? "distance from the wall (Rt - r)/Dp"
                                : a.walls.size() > 1 ? "distance from each wall d/Dp"
                                                     : "distance from the nearest wall d/Dp";
    std::string curves;
    for (const auto& c : radial_void_fraction_correlations()) {
        if (!tube)
            break;
        script += fmt::format("${} << EOD\n", c.name.substr(0, c.name.find('-')));
        for (double z = 0.0; z <= x_max + 1e-12; z += 0.01)
            script += fmt::format("{} {}\n", z, c(z, aspect_ratio).value);
        script += "EOD\n";
        // The legend names the correlation as people cite it; in gnuplot's single-quoted
        // strings a quote is written twice.
        std::string title;
        for (char ch : c.label)
            title += ch == '\'' ? std::string("''") : std::string(1, ch);
        curves += fmt::format(", ${} using 1:2 with lines title '{}{}'",
                              c.name.substr(0, c.name.find('-')), title,
                              c(0.0, aspect_ratio).warning.empty() ? "" : " (outside range)");
    }
    // The centre distribution's peak at one radius from the wall is 10-40 times the mean at
    // fine bins: drawn to scale it flattens the rest. Above 4 the axis is cut and the peak's
    // height written beside it.
    double peak = 0.0, peak_at = 0.0;
    for (const WallAnalysis& wall : a.walls)
        for (const auto& b : wall.centre_distribution)
            if (b.value > peak) {
                peak = b.value;
                peak_at = 0.5 * (b.low + b.high) / dp;
            }
    const double centre_top = 4.0;
    const std::string centre_range =
        peak > centre_top
            ? fmt::format("set yrange [0:{}]\nset label 1 'peak {:.3g} at {:.3g} Dp (off scale)' "
                          "at {:.4g},{} left offset 1,0\n",
                          centre_top, peak, peak_at, peak_at, 0.93 * centre_top)
            : "set yrange [0:*]\n";
    // Every name gnuplot sees is one of ours, relative to the staging folder it runs in.
    std::vector<std::string> names{"radial_void_fraction", "radial_centre_distribution",
                                   "axial_void_fraction", "pair_correlation"};
    if (a.walls.empty())
        names.erase(names.begin(), names.begin() + 2);
    // A bed of several sizes: each size class's centre distribution, one curve each (for a
    // container of one wall: by_size has no distributions otherwise).
    std::string by_size;
    if (!a.by_size.empty() && !a.by_size.front().centre_distribution.empty()) {
        names.push_back("centre_distribution_by_size");
        // Drawn over shells of about 0.1 Dp (groups of the table's bins, each group's density
        // its centres over its area): a class has far fewer centres than the bed.
        const auto& bins = a.by_size.front().centre_distribution;
        const double bin_d = (bins.front().high - bins.front().low) / dp;
        const auto group = static_cast<std::size_t>(std::max(1.0, std::round(0.1 / bin_d)));
        script += "$sizes << EOD\n";
        for (std::size_t k = 0; k < bins.size(); k += group) {
            const std::size_t end = std::min(bins.size(), k + group);
            script += fmt::format("{}", 0.5 * (bins[k].low + bins[end - 1].high) / dp);
            for (const SizeClassAnalysis& c : a.by_size) {
                double centres = 0.0, area = 0.0;
                for (std::size_t j = k; j < end; ++j) {
                    const double shell = container.shell_area(bins[j].low, bins[j].high,
                                                              a.band.z_low, a.band.z_high);
                    centres += c.centre_distribution[j].value * shell;
                    area += shell;
                }
                script += fmt::format(" {}", area > 0.0 ? centres / area : 0.0);
            }
            script += "\n";
        }
        script += "EOD\n";
        std::string curves_by_size;
        for (std::size_t c = 0; c < a.by_size.size(); ++c) {
            const SizeClassAnalysis& k = a.by_size[c];
            const std::string title = k.low == k.high
                                          ? fmt::format("d = {:.4g}", k.low)
                                          : fmt::format("d = {:.4g} to {:.4g}", k.low, k.high);
            curves_by_size +=
                fmt::format("{}$sizes using 1:{} with steps lw 1 title '{} ({:.3g} of "
                            "the volume)'",
                            c == 0 ? "" : ", ", c + 2, title, k.volume_fraction);
        }
        by_size = fmt::format("set output 'centre_distribution_by_size.{{ext}}'\nset xlabel "
                              "'{{x_label}}'\nset xrange [0:{{x_max}}]\nset ylabel 'centre "
                              "density / the size class mean'\nset yrange [0:{{centre_top}}]\n"
                              "set title 'Distribution of centres from the wall by size, "
                              "{{where}}'\nplot {}\nset autoscale y\n",
                              curves_by_size);
    }
    // The wall plots (none in a periodic cell), then the axial profile and g(r).
    const std::string wall_plots =
        a.walls.empty()
            ? std::string()
            : std::string("set output 'radial_void_fraction.{ext}'\nset ylabel 'radial void "
                          "fraction'\n"
                          "set title 'Radial void fraction, {where}, band z = {low:.4g} to "
                          "{high:.4g}'\n"
                          "plot {bed_curves}{curves}\n"
                          "set output 'radial_centre_distribution.{ext}'\nset ylabel 'centre "
                          "density / mean'\n"
                          "set title 'Radial distribution of sphere centres, {where}'\n"
                          "{centre_range}plot {centre_curves}\n"
                          "unset label 1\nset autoscale y\n");
    // The same plots for each terminal: the wall plots, then the axial profile, g(r) and the
    // centres by size, which set every setting the wall plots change.
    const std::string head = "{terminal}\nunset label 1\nset key top right\nset autoscale y\n";
    const std::string walls = "set xlabel '{x_label}'\nset xrange [0:{x_max}]\n" + wall_plots;
    const std::string rest =
        "set output 'axial_void_fraction.{ext}'\nset xlabel 'height above the floor z/Dp'\n"
        "set xrange [0:*]\nset ylabel 'axial void fraction'\nset yrange [0:1]\n"
        "set title 'Axial void fraction; the band measured lies between the dashed lines'\n"
        "set arrow 1 from {low_d:.6g},0 to {low_d:.6g},1 nohead dt 2\n"
        "set arrow 2 from {high_d:.6g},0 to {high_d:.6g},1 nohead dt 2\n"
        "plot $axial using 1:2 with steps lw 1 lc rgb 'black' title 'this bed'\n"
        "unset arrow 1\nunset arrow 2\nset autoscale y\n"
        "set output 'pair_correlation.{ext}'\nset xlabel 'centre distance r/Dp'\n"
        "set xrange [0:*]\nset ylabel 'g(r)'\nset yrange [0:*]\n"
        "set title 'Pair correlation of centres in the band'\n"
        "plot $rdf using 1:2 with steps lw 1 lc rgb 'black' title 'this bed', 1 with lines "
        "dt 2 lc rgb 'grey' notitle\nset autoscale y\n{by_size}";
    auto commands = [&](const std::string& text, const char* extension, const char* terminal) {
        return fmt::format(
            fmt::runtime(text), fmt::arg("terminal", terminal), fmt::arg("ext", extension),
            fmt::arg("x_max", x_max), fmt::arg("where", where), fmt::arg("x_label", x_label),
            fmt::arg("low", a.band.z_low), fmt::arg("high", a.band.z_high),
            fmt::arg("low_d", a.band.z_low / dp), fmt::arg("high_d", a.band.z_high / dp),
            fmt::arg("curves", curves), fmt::arg("centre_range", centre_range),
            fmt::arg("bed_curves", bed_curves), fmt::arg("centre_curves", centre_curves),
            fmt::arg("by_size",
                     by_size.empty()
                         ? std::string()
                         : fmt::format(fmt::runtime(by_size), fmt::arg("ext", extension),
                                       fmt::arg("x_label", x_label), fmt::arg("x_max", x_max),
                                       fmt::arg("centre_top", centre_top),
                                       fmt::arg("where", where))));
    };
    // Two gnuplots at once: a PNG (cairo, compressed) costs four times an SVG, so one draws
    // the SVGs and the wall plots' PNGs, the other the other PNGs (0.15 s of a 500-sphere
    // bed's command in one gnuplot; docs/notes/analysis.md).
    const auto& [svg, svg_terminal] = plot_terminals[0];
    const auto& [png, png_terminal] = plot_terminals[1];
    const std::string first = script + commands(head + walls + rest, svg, svg_terminal) +
                              commands(head + walls, png, png_terminal);
    const std::string second = script + commands(head + rest, png, png_terminal);
    return draw_plots(out, names, {first, second});
}

namespace {

/// The record of an analysis (analysis_summary) and, with an output, its files staged there and
/// `plots` saying why the plots were not drawn (when they were not): what every analysis job
/// writes.
nlohmann::json analysis_record(const BedAnalysis& analysis, const AnalysisOptions& options,
                               const Container& container, OutputDirectory* out) {
    nlohmann::json record = analysis_summary(analysis, options);
    if (out)
        if (const std::string why = stage_analysis_files(*out, analysis, container); !why.empty())
            record["plots"] = why;
    return record;
}

} // namespace

namespace {

/// `options` with a default g(r) range no farther than a periodic cell's smaller period
/// (analyze_bed refuses a longer range, which `analyze --rdf-range` may ask for; a default
/// nobody asked for is shortened, as a cell may be as narrow as 2 Dp).
AnalysisOptions with_fitted_rdf_range(AnalysisOptions options, const Packing& packing,
                                      const Container& container) {
    if (const std::optional<Periods> cell = container.periods();
        cell && !options.rdf_range_given && !packing.radii.empty())
        options.rdf_range =
            std::min(options.rdf_range, std::min(cell->lx(), cell->ly()) / packing.mean_diameter());
    return options;
}

} // namespace

void stage_analysis(OutputDirectory& out, const Packing& packing, const Container& container,
                    double band_clearance, nlohmann::json& summary) {
    AnalysisOptions options;
    options.band_clearance = band_clearance;
    // A generated bed's friction (a lattice's summary has no parameters)
    const auto parameters = summary.find("parameters");
    options.frictional = parameters != summary.end() && parameters->is_object() &&
                         parameters->value("friction", 0.0) > 0.0;
    options = with_fitted_rdf_range(options, packing, container);
    summary["analysis"] =
        analysis_record(analyze_bed(packing, container, options), options, container, &out);
}

std::string stage_analysis_files(OutputDirectory& out, const BedAnalysis& analysis,
                                 const Container& container) {
    for (const auto& [name, text] : analysis_files(analysis, container))
        out.stage(name, text);
    return stage_plots(out, analysis, container);
}

AnalyzeJob analyze_job(const Packing& packing, const Container& container,
                       const AnalysisOptions& given, OutputDirectory* out) {
    const AnalysisOptions options = with_fitted_rdf_range(given, packing, container);
    AnalyzeJob job{analyze_bed(packing, container, options), {}, {}};
    job.warnings = analysis_warnings(packing, container, job.analysis);
    job.summary = analysis_record(job.analysis, options, container, out);
    job.summary["warnings"] = job.warnings;
    job.summary["container"] = container.summary_json();
    return job;
}

} // namespace packbed
