#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

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
    double left = stage_left.value_or(0.0);
    bool known = stage_left.has_value();
    std::string layer;
    if (p.layers > 1) {
        // In layers: the mean time of the layers finished in this process, for those to come.
        if (p.layer != m_layer) {
            if (m_layer_start >= 0.0 && p.layer == m_layer + 1)
                ++m_layers_timed, m_layer_seconds += seconds - m_layer_start;
            m_layer = p.layer;
            m_layer_start = seconds;
        }
        known = m_layers_timed > 0;
        if (known) {
            const double mean = m_layer_seconds / m_layers_timed;
            left =
                mean * (p.layers - p.layer - 1) + std::max(0.0, mean - (seconds - m_layer_start));
        }
        layer = fmt::format("layer {}/{}  ", p.layer + 1, p.layers);
    }
    if (m_drawn && now - m_last < std::chrono::milliseconds(100))
        return;
    const std::string left_text = known ? fmt::format("~{:.0f} s left", left) : "estimating";
    m_last = now;
    m_drawn = true;
    fmt::print(stderr,
               "\r\033[K{:>5.1f} s  {}{:<12} {:>14}  iteration {:>9}  Cg {:.3e}  overlap pair "
               "{:.2e} wall {:.2e} Dp  mass centre {:.6f} Dp",
               seconds, layer, p.stage, left_text, p.iteration, p.cg, p.max_overlap_pair,
               p.max_overlap_wall, p.mass_centre_z);
    std::fflush(stderr);
}

void TerminalProgress::finish() {
    if (m_enabled && m_drawn) {
        fmt::print(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    m_drawn = false;
}

} // namespace packbed::cli
