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
#include "packbed/read.hpp"

namespace packbed::cli {

/// A subcommand: its CLI11 app (filled at registration) and what to run once it is parsed.
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run; ///< returns the exit status
};

/// A real number within [low, high] (each end open or closed). Rejects text that is not
/// wholly a finite number. The message names the value and the allowed range; CLI11 prefixes
/// the option name.
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

/// A whole number within [low, high].
CLI::Validator whole_in(unsigned long long low, unsigned long long high);

/// \return the comma-separated finite numbers of `text` ("1,2.5,-3"), or nothing when it is
/// not exactly that (an empty item, a non-number, NaN or infinity).
std::optional<std::vector<double>> comma_numbers(std::string_view text);

/// Run the library's parallel loops on at most `threads` OpenMP threads, fewer while the
/// machine is busy (OpenMP's dynamic adjustment, which in GCC's libgomp subtracts the load
/// average from the cores): a thread that waits for a core at every barrier turns seconds
/// into minutes, and the results do not depend on the number of threads anyway. Setting
/// OMP_DYNAMIC (e.g. false, for benchmarks) leaves the choice to OpenMP.
void use_threads(unsigned long long threads);

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

/// Add --frame, --axis and --floor to `app`, bound to `placement`.
/// \return the --frame option (for excludes)
CLI::Option* add_input_placement(CLI::App& app, InputPlacement& placement);

/// `--container SPEC`, the container in length units, the one form every subcommand takes:
/// `cylinder:D`, a tube of inner diameter D (the axis is the z axis, the floor z = 0);
/// `box:LX,LY`, four flat walls at x = 0, LX and y = 0, LY; `annulus:D,DI`, the space between
/// the tube of diameter D and a coaxial rod of diameter DI < D; `periodic:LX,LY`, a cell
/// periodic in x and y, [0, LX) x [0, LY), with no side walls.
struct ContainerSpec {
    std::string shape;     ///< "cylinder", "box", "annulus" or "periodic"
    double diameter = 0.0; ///< a cylinder's or annulus's D, > 0
    double inner = 0.0;    ///< an annulus's DI, 0 < DI < D
    double lx = 0.0;       ///< a box's or cell's widths, > 0
    double ly = 0.0;
    /// \return the library's container.
    Container container() const;
};

/// \return the container of `text` ("cylinder:D", "box:LX,LY", "annulus:D,DI",
/// "periodic:LX,LY"), or nothing when it is not one.
std::optional<ContainerSpec> parse_container(std::string_view text);

/// The shapes every subcommand takes.
inline const std::vector<std::string_view> all_shapes{"cylinder", "box", "annulus", "periodic"};

/// Add `--container SPEC` to `app`, bound to `text` ("" when not given), checked by
/// parse_container. \param meaning what lengths are measured in and what it replaces, for
/// --help \param shapes the shapes the subcommand takes
CLI::Option* add_container_option(CLI::App& app, std::string& text, const std::string& meaning,
                                  const std::vector<std::string_view>& shapes = all_shapes);

/// The container recorded in `summary.json` beside a particle file (written by
/// `packbed generate`, `lattice`, `analyze`): any of the four shapes (read_bed_summary).
/// \return nothing when there is no such file or it names no container.
/// \throws InvalidInput naming the file when it exists but is not a regular file, not a
/// summary, or has a container outside the limits
std::optional<Container> container_beside(const std::filesystem::path& particles);

/// "radius R" for a cylinder, "box:LX,LY" for a box: the container in messages.
std::string describe(const Container& container);

} // namespace packbed::cli
