// Live progress on a terminal; silence in pipes, in CI and with --quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "packbed/soft_sphere.hpp"
#include "packbed/time_left.hpp"

namespace packbed::cli {

/// \return true when progress should be drawn: stderr is a terminal, CI is not set, not quiet.
bool progress_wanted(bool quiet);

/// The fields of a status line joined by two spaces, in order, keeping only those that fit in
/// `columns` - 1 characters (a line as wide as the terminal wraps on some terminals): the
/// fields come most important first, so a narrow terminal drops the last ones. A first field
/// wider than the line is cut.
std::string fit_status_line(const std::vector<std::string>& fields_by_priority,
                            std::size_t columns);

/// Draw `fields` on stderr's status line in place of the last one (fit_status_line to the
/// terminal's width). The caller decides when (progress_wanted, at most ten times a second).
void draw_status_line(const std::vector<std::string>& fields);

/// Redraws one status line on stderr at most ten times a second. Not thread-safe.
class TerminalProgress {
public:
    /// \param enabled when false, every call does nothing
    /// \param parameters the run's, for the estimate of the time left in each stage
    /// \param memory the run's estimated memory (generation_memory), shown; 0: not shown
    /// \param threads the threads the run uses, shown; 0: not shown (another engine's)
    /// \param engine "" for packbed's solvers, whose time left is estimated; else the engine's
    /// name, shown instead (LAMMPS's settling rule is not the mass-centre rule the estimate
    /// follows)
    TerminalProgress(bool enabled, const SoftSphereParameters& parameters, std::uint64_t memory = 0,
                     int threads = 0, std::string engine = {})
        : m_enabled(enabled)
        , m_time_left(parameters)
        , m_engine(std::move(engine))
        , m_memory(memory)
        , m_threads(threads)
        , m_layers_left(parameters) {}
    ~TerminalProgress() { finish(); }
    TerminalProgress(const TerminalProgress&) = delete;
    TerminalProgress& operator=(const TerminalProgress&) = delete;

    /// Show the state of a soft-sphere run.
    void operator()(const Progress& progress);
    /// Erase the status line.
    void finish();

private:
    bool m_enabled;
    bool m_drawn = false;
    StageTimeLeft m_time_left;
    std::string m_engine;
    std::uint64_t m_memory;
    int m_threads;
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point m_last{};
    LayerTimeLeft m_layers_left;
};

} // namespace packbed::cli
