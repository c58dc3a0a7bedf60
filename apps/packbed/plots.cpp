#include "plots.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>

#include <fmt/format.h>
#include <unistd.h>

#include "interrupt.hpp"
#include "packbed/correlations.hpp"
#include "packbed/io.hpp"
#include "packbed/summary.hpp"

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

/// Run `gnuplot SCRIPT` in `folder`, without a shell, its output to /dev/null, in a process
/// group of its own (the interrupt handler stops it; a Ctrl-C reaches packbed only).
/// `script` and the files it writes are named relative to `folder`, so no text of the user's
/// (an output path) ever reaches gnuplot.
/// \return the exit status; 127 when gnuplot cannot be started.
int run_gnuplot(const std::filesystem::path& folder, const std::string& script) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGHUP);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setpgroup(&attributes, 0);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF |
                                              POSIX_SPAWN_SETPGROUP);
    std::string program = "gnuplot", argument = script;
    char* argv[] = {program.data(), argument.data(), nullptr};
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, "gnuplot", &actions, &attributes, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (spawned != 0)
        return 127;
    watch_child(pid);
    int status = 0;
    const bool waited = waitpid(pid, &status, 0) == pid;
    watch_child(0);
    if (!waited || !WIFEXITED(status))
        return 1;
    return WEXITSTATUS(status);
}

} // namespace

std::string stage_plots(OutputDirectory& out, const BedAnalysis& a, double rt) {
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
        // The legend names the correlation as people cite it; in gnuplot's single-quoted
        // strings a quote is written twice.
        std::string title;
        for (char ch : c.label)
            title += ch == '\'' ? std::string("''") : std::string(1, ch);
        curves += fmt::format(", ${} using 1:2 with lines title '{}{}'",
                              c.name.substr(0, c.name.find('-')), title,
                              c(0.0, aspect_ratio).warning.empty() ? "" : " (outside range)");
    }
    // Every name gnuplot sees is one of ours, relative to the staging folder it runs in.
    const auto radial_svg = out.reserve("radial_void_fraction.svg");
    const auto centres_svg = out.reserve("radial_centre_distribution.svg");
    const auto script_path = out.reserve("plots.gp");
    const std::filesystem::path folder = script_path.parent_path();
    script += fmt::format(
        "set terminal svg size 800,450 background '#ffffff'\n"
        "set xlabel 'distance from the wall (Rt - r)/Dp'\nset xrange [0:{0}]\nset key top right\n"
        "set output '{1}'\nset ylabel 'radial void fraction'\n"
        "set title 'Radial void fraction, a = {3:.4g}, band z = {4:.4g} to {5:.4g}'\n"
        "plot $bed using 1:2 with lines lw 2 lc rgb 'black' title 'this bed'{6}\n"
        "set output '{2}'\nset ylabel 'centre density / mean'\n"
        "set title 'Radial distribution of sphere centres, a = {3:.4g}'\n"
        "plot $centres using 1:2 with steps lw 2 lc rgb 'black' title 'this bed'\n",
        x_max, radial_svg.filename().string(), centres_svg.filename().string(), aspect_ratio,
        a.band.z_low, a.band.z_high, curves);
    std::ofstream(script_path) << script;
    const int status = run_gnuplot(folder, script_path.filename().string());
    out.discard("plots.gp");
    if (status == 0 && std::filesystem::exists(radial_svg) && std::filesystem::exists(centres_svg))
        return {};
    // No plots, but the rest of the output stands.
    out.discard("radial_void_fraction.svg");
    out.discard("radial_centre_distribution.svg");
    return status == 127 ? "gnuplot not found (Debian package gnuplot-nox): no plots"
                         : fmt::format("gnuplot failed (exit status {}): no plots", status);
}

void stage_analysis(OutputDirectory& out, const Packing& packing, const Cylinder& container,
                    double band_clearance, nlohmann::json& summary) {
    AnalysisOptions options;
    options.band_clearance = band_clearance;
    const BedAnalysis analysis = analyze_bed(packing, container, options);
    summary["analysis"] = analysis_summary(analysis, options);
    for (const auto& [name, text] : analysis_tables(analysis, container.radius()))
        out.stage(name, text);
    if (const std::string why = stage_plots(out, analysis, container.radius()); !why.empty())
        summary["analysis"]["plots"] = why;
}

} // namespace packbed::cli
