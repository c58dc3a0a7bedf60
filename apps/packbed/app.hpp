// The command line as a library (packbed_cli_core): the app with its subcommands, and one run.
#pragma once

#include <vector>

#include "command.hpp"

namespace packbed::cli {

/// Configure `app` as the packbed command line (version flag, --config through TomlConfig) and
/// register every subcommand. \return the subcommands, in the order of `packbed --help`.
std::vector<Command> build_app(CLI::App& app);

/// Parse `argv`, run the subcommand and map its errors to exit statuses: 0 success, 1 the run
/// failed (no convergence, I/O), 2 bad input, 130 interrupted.
int run(int argc, char** argv);

} // namespace packbed::cli
