#include "progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "interrupt.hpp"

namespace packbed::cli {

bool progress_wanted(bool quiet) {
    const char* ci = std::getenv("CI");
    return !quiet && ::isatty(STDERR_FILENO) && !(ci && *ci);
}

void TerminalProgress::operator()(const Progress& p) {
    if (!m_enabled)
        return;
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - m_start).count();
    const std::optional<double> stage_left = m_time_left.update(p, seconds); // every report
    const std::optional<double> run_left = m_layers_left.update(p, seconds);
    // In layers the time left in the run; in one piece, in the stage.
    const std::optional<double> left = p.layers > 1 ? run_left : stage_left;
    const std::string layer =
        p.layers > 1 ? fmt::format("layer {}/{}  ", p.layer + 1, p.layers) : std::string();
    if (m_drawn && now - m_last < std::chrono::milliseconds(100))
        return;
    const std::string left_text =
        left.has_value() ? fmt::format("~{:.0f} s left", left.value_or(0.0)) : "estimating";
    m_last = now;
    m_drawn = true;
    progress_line_drawn(true);
    std::string line = fmt::format(
        "{:>5.1f} s  {}{:<12} {:>14}  iteration {:>9}  Cg {:.3e}  overlap pair {:.2e} wall "
        "{:.2e} Dp  mass centre {:.6f} Dp",
        seconds, layer, p.stage, left_text, p.iteration, p.cg, p.max_overlap_pair,
        p.max_overlap_wall, p.mass_centre_z);
    // One line that fits the terminal (a wrapped line could not be redrawn in place).
    struct winsize size {};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 &&
        line.size() >= size.ws_col)
        line.resize(size.ws_col - 1u);
    fmt::print(stderr, "\r\033[K{}", line);
    std::fflush(stderr);
}

void TerminalProgress::finish() {
    if (m_enabled && m_drawn) {
        fmt::print(stderr, "\r\033[K");
        std::fflush(stderr);
        progress_line_drawn(false);
    }
    m_drawn = false;
}

} // namespace packbed::cli
