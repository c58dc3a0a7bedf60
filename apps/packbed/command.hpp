// The pieces every subcommand shares: how it registers, validators with our error wording.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "packbed/container.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/read.hpp"

namespace packbed::cli {

/// A subcommand: its CLI11 app (filled at registration) and what to run once it is parsed.
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run; ///< returns the exit status
};

/// A real number within `range` (option_ranges.hpp: the table the Python module checks with too).
/// Rejects text that is not wholly a finite number. The message names the value and the allowed
/// range; CLI11 prefixes the option name.
CLI::Validator real_in(const NumberRange& range);
/// \copydoc real_in(const NumberRange&), for an option of one subcommand only
CLI::Validator real_in(double low, double high, bool low_open, bool high_open);

/// A path: not empty, no control characters (newline, tab, ...), at most 4095 bytes
/// (packbed::path_problem). Paths are checked as text only here; files are checked when opened.
CLI::Validator path_text();

/// The options of a subcommand that writes an output directory (OutputDirectory): -o,--out
/// (a path, see path_text) and --force. \param default_text what --out defaults to, when that
/// is not the option's own default value (shown in --help), or ""
void add_output_directory(CLI::App& app, std::string& out, bool& force,
                          const std::string& default_text = "");

/// One of `names` (exactly). The message quotes the value, so an empty one shows as ''.
CLI::Validator one_of(std::vector<std::string> names);

/// A whole number within `range` (option_ranges.hpp). The message quotes text that is not one.
CLI::Validator whole_in(const WholeRange& range);
/// \copydoc whole_in(const WholeRange&)
CLI::Validator whole_in(unsigned long long low, unsigned long long high);

/// Which frame of a bed file to read and where its container is: --frame, --axis and --floor,
/// the same for every subcommand that reads a bed (analyze, export).
struct InputPlacement {
    long long frame = -1; ///< 1 the first, -1 the last (ReadOptions::frame)
    std::string axis;     ///< "X,Y": the container's axis; "" for x = y = 0
    double floor = 0.0;   ///< the container's floor

    /// true when --axis or --floor moved the centres (messages say so)
    bool shifted() const { return !axis.empty() || floor != 0.0; }
    /// Set the frame, axis and floor of `read`.
    void apply(ReadOptions& read) const;
};

/// Add -j,--threads to `app`, bound to `threads` (its default: every core), the same words in
/// every subcommand that runs in parallel.
void add_threads_option(CLI::App& app, unsigned long long& threads);

/// Add --frame, --axis and --floor to `app`, bound to `placement`.
/// \return the --frame option (for excludes)
CLI::Option* add_input_placement(CLI::App& app, InputPlacement& placement);

/// `--container SPEC` (parse_container).
/// Add `--container SPEC` to `app`, bound to `text` ("" when not given), checked by
/// parse_container. \param meaning what lengths are measured in and what it replaces, for
/// --help \param shapes the shapes the subcommand takes
CLI::Option* add_container_option(CLI::App& app, std::string& text, const std::string& meaning,
                                  const std::vector<std::string_view>& shapes = all_shapes);

} // namespace packbed::cli
