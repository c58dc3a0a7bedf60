// Live progress on a terminal; silence in pipes, in CI and with --quiet.
#pragma once

#include <chrono>

#include "packbed/soft_sphere.hpp"

namespace packbed::cli {

/// \return true when progress should be drawn: stderr is a terminal, CI is not set, not quiet.
bool progress_wanted(bool quiet);

/// Redraws one status line on stderr at most ten times a second. Not thread-safe.
class TerminalProgress {
public:
    /// \param enabled when false, every call does nothing
    explicit TerminalProgress(bool enabled)
        : m_enabled(enabled) {}
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
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point m_last{};
};

} // namespace packbed::cli
