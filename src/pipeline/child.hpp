// Internal: the programs the pipeline starts (gnuplot, LAMMPS), without a shell.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace packbed {

/// Run `words` (the program, looked up on PATH, then its arguments) in `folder`, without a
/// shell, its standard input /dev/null and its output (stdout and stderr) written to `output`
/// (created or truncated; /dev/null to drop it), in a process group of its own (the interrupt
/// handler stops it through set_child_watcher; a Ctrl-C reaches packbed only). No text of the
/// user's reaches a shell: each word is one argument.
/// \param keep_going when given, called about ten times a second while the program runs;
/// returning false stops the program's process group (SIGTERM) and waits for it
/// \return the exit status; 127 when the program cannot be started; -1 when it was stopped
/// (by keep_going) or killed by a signal
int run_program(const std::vector<std::string>& words, const std::filesystem::path& folder,
                const std::filesystem::path& output, const std::function<bool()>& keep_going = {});

/// Run several programs at once, as run_program runs one: all in one process group (the
/// first's), so that the interrupt handler and keep_going stop them together; their output
/// appended to the same `output`. Returns when every one has ended.
/// \return 0 when all exited with 0; else the first nonzero exit status in the order given;
/// 127 when one cannot be started (those started are stopped); -1 when stopped or when one was
/// killed by a signal
int run_programs(const std::vector<std::vector<std::string>>& commands,
                 const std::filesystem::path& folder, const std::filesystem::path& output,
                 const std::function<bool()>& keep_going = {});

} // namespace packbed
