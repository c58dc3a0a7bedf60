#include "plots.hpp"

#include <cstdlib>
#include <fstream>

#include <fmt/format.h>
#include <unistd.h>

#include "packbed/correlations.hpp"

namespace packbed::cli {

namespace {

/// A gnuplot datablock named `name` with columns x_from_wall_d and one value per bin.
std::string datablock(std::string_view name, const std::vector<ProfileBin>& bins, double rt,
                      double dp) {
    std::string out = fmt::format("${} << EOD\n", name);
    for (const auto& b : bins)
        out += fmt::format("{} {}\n", (rt - 0.5 * (b.low + b.high)) / dp, b.value);
    return out + "EOD\n";
}

} // namespace

std::string stage_plots(OutputDirectory& out, const BedAnalysis& a, double rt) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
        return "gnuplot not found (Debian package gnuplot-nox): no plots";
    const double dp = a.diameter;
    const double aspect_ratio = 2.0 * rt / dp;
    const double x_max = rt / dp;
    std::string script = datablock("bed", a.radial_void_fraction, rt, dp) +
                         datablock("centres", a.centre_distribution, rt, dp);
    std::string curves;
    for (const auto& c : radial_void_fraction_correlations()) {
        script += fmt::format("${} << EOD\n", c.name.substr(0, c.name.find('-')));
        for (double z = 0.0; z <= x_max + 1e-12; z += 0.01)
            script += fmt::format("{} {}\n", z, c(z, aspect_ratio).value);
        script += "EOD\n";
        curves += fmt::format(", ${} using 1:2 with lines title '{}{}'",
                              c.name.substr(0, c.name.find('-')), c.name,
                              c(0.0, aspect_ratio).warning.empty() ? "" : " (outside range)");
    }
    const auto radial_svg = out.reserve("radial_void_fraction.svg");
    const auto centres_svg = out.reserve("radial_centre_distribution.svg");
    script += fmt::format(
        "set terminal svg size 800,450 background '#ffffff'\n"
        "set xlabel 'distance from the wall (Rt - r)/Dp'\nset xrange [0:{0}]\nset key top right\n"
        "set output '{1}'\nset ylabel 'radial void fraction'\n"
        "set title 'Radial void fraction, a = {3:.4g}, band z = {4:.4g} to {5:.4g}'\n"
        "plot $bed using 1:2 with lines lw 2 lc rgb 'black' title 'this bed'{6}\n"
        "set output '{2}'\nset ylabel 'centre density / mean'\n"
        "set title 'Radial distribution of sphere centres, a = {3:.4g}'\n"
        "plot $centres using 1:2 with steps lw 2 lc rgb 'black' title 'this bed'\n",
        x_max, radial_svg.string(), centres_svg.string(), aspect_ratio, a.band.z_low, a.band.z_high,
        curves);
    const auto script_path = out.path() / fmt::format(".plots.gp.tmp-{}", ::getpid());
    std::ofstream(script_path) << script;
    const int status =
        std::system(fmt::format("gnuplot '{}' >/dev/null 2>&1", script_path.string()).c_str());
    std::remove(script_path.c_str());
    if (status != 0)
        return "gnuplot failed: no plots";
    return {};
}

} // namespace packbed::cli
