#include "progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "interrupt.hpp"
#include "packbed/memory.hpp"

namespace packbed::cli {

bool progress_wanted(bool quiet) {
    const char* ci = std::getenv("CI");
    return !quiet && ::isatty(STDERR_FILENO) && !(ci && *ci);
}

std::string fit_status_line(const std::vector<std::string>& fields, std::size_t columns) {
    const std::size_t width = columns > 1 ? columns - 1 : 0;
    std::vector<bool> kept(fields.size(), false);
    std::size_t used = 0;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::size_t need = fields[i].size() + (used > 0 ? 2 : 0);
        if (used + need <= width) {
            kept[i] = true;
            used += need;
        }
    }
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i)
        if (kept[i])
            line += (line.empty() ? "" : "  ") + fields[i];
    if (line.empty() && !fields.empty())
        line = fields.front().substr(0, width);
    return line;
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
    if (m_drawn && now - m_last < std::chrono::milliseconds(100))
        return;
    const std::string left_text = !m_engine.empty() ? m_engine
                                  : left.has_value()
                                      ? fmt::format("~{:.0f} s left", left.value_or(0.0))
                                      : "estimating";
    m_last = now;
    m_drawn = true;
    progress_line_drawn(true);
    // Most important first: on an 80-column terminal the line ends after the overlaps.
    std::vector<std::string> fields{fmt::format("{:>5.1f} s", seconds),
                                    fmt::format("{:<12}", p.stage)};
    if (p.layers > 1)
        fields.insert(fields.begin() + 1, fmt::format("layer {}/{}", p.layer + 1, p.layers));
    if (!p.run.empty()) // a run of a target's search
        fields.insert(fields.begin() + 1, std::string(p.run));
    fields.push_back(fmt::format("{:>12}", left_text));
    fields.push_back(
        fmt::format("overlaps {:.1e}/{:.1e} Dp", p.max_overlap_pair, p.max_overlap_wall));
    fields.push_back(fmt::format("it {:>9}", p.iteration));
    if (m_threads > 0)
        fields.push_back(fmt::format("{} thread{}", m_threads, m_threads > 1 ? "s" : ""));
    if (m_memory > 0)
        fields.push_back("memory ~" + memory_text(m_memory));
    fields.push_back(fmt::format("Cg {:.2e}", p.cg));
    fields.push_back(fmt::format("mass centre {:.6f} Dp", p.mass_centre_z));
    draw_status_line(fields);
}

void draw_status_line(const std::vector<std::string>& fields) {
    // One line that fits the terminal (a wrapped line could not be redrawn in place).
    struct winsize size {};
    std::size_t columns = 80;
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1)
        columns = size.ws_col;
    fmt::print(stderr, "\r\033[K{}", fit_status_line(fields, columns));
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
