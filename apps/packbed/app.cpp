// packbed's command line: it parses, dispatches to one subcommand and maps errors to exit
// statuses.
#include "app.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "interrupt.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/version.hpp"
#include "toml_config.hpp"

namespace packbed::cli {
Command register_generate(CLI::App& parent);
Command register_analyze(CLI::App& parent);
Command register_correlations(CLI::App& parent);
Command register_lattice(CLI::App& parent);
Command register_random_array(CLI::App& parent);
Command register_hydraulics(CLI::App& parent);
Command register_export(CLI::App& parent);
Command register_voxelize(CLI::App& parent);
Command register_cfd_report(CLI::App& parent);
Command register_import_lammps(CLI::App& parent);

namespace {

/// An option whose default is a "not given" marker (0 for a radius that must be > 0, -1 for a
/// velocity that must be >= 0) would show `=0` in --help next to a range that excludes it: its
/// default is hidden, and its description says what happens when it is not given.
void hide_defaults_outside_their_range(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        std::string shown = option->get_default_str();
        if (shown.empty())
            continue;
        for (int i = 0;; ++i) {
            CLI::Validator* check = nullptr;
            try {
                check = option->get_validator(i);
            } catch (const CLI::OptionNotFound&) {
                break;
            }
            std::string value = shown;
            if (!(*check)(value).empty()) {
                option->default_str("");
                break;
            }
        }
    }
    for (CLI::App* sub : app.get_subcommands({}))
        hide_defaults_outside_their_range(*sub);
}

} // namespace

std::vector<Command> build_app(CLI::App& app) {
    app.set_version_flag("-V,--version", std::string("packbed ") + version);
    app.require_subcommand(1);
    app.set_config("--config", "",
                   "read a subcommand's options from this TOML file (keys are the option names, "
                   "e.g. aspect-ratio = 5); the command line wins");
    app.config_formatter(std::make_shared<TomlConfig>(&app));
    std::vector<Command> commands{register_generate(app),     register_lattice(app),
                                  register_random_array(app), register_hydraulics(app),
                                  register_export(app),       register_analyze(app),
                                  register_correlations(app), register_voxelize(app),
                                  register_cfd_report(app),   register_import_lammps(app)};
    hide_defaults_outside_their_range(app);
    return commands;
}

namespace {

/// Check the files `--config FILE` names before CLI11 opens them (it would wait for ever on a
/// FIFO and read a file of any size): regular files of at most limits::max_config_file bytes.
/// \return the last one named ("" for none). \throws InvalidInput naming the file otherwise
std::string check_config_files(int argc, char** argv) {
    std::string name;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--config" && i + 1 < argc)
            name = argv[i + 1];
        else if (arg.starts_with("--config="))
            name = arg.substr(9);
        else
            continue;
        read_small_file("--config", name, limits::max_config_file);
    }
    return name;
}

/// Edit distance (insertions, deletions, substitutions, swaps of neighbours) between a and b.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                                d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

/// "did you mean X?" for the candidate closest to `word` (at most 2 edits, or a third of its
/// length for long words), or "" when none is close.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
    if (word.size() > 100)
        return {};
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const auto& candidate : candidates) {
        const std::size_t distance = edit_distance(word, candidate);
        if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
        }
    }
    return best.empty() ? std::string() : fmt::format("did you mean {}?", best);
}

/// The long options of a subcommand as typed ("--aspect-ratio"), the inherited ones included.
std::vector<std::string> long_options(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* a = &app; a != nullptr; a = a->get_parent())
        for (const CLI::Option* option : a->get_options())
            for (const auto& name : option->get_lnames())
                names.push_back("--" + name);
    return names;
}

} // namespace

int run(int argc, char** argv) {
    block_interrupts(); // a signal from here on waits for handle_interrupts, below
    const JobScope job; // what the run reads and writes, so that no output replaces an input

    CLI::App app("packbed: packed beds of spheres for CFD and DEM", "packbed");
    const std::vector<Command> commands = build_app(app);

    // Every message is one line: what a user typed is shown with control characters escaped.
    try {
        const std::string config = check_config_files(argc, argv);
        if (const auto toml = std::dynamic_pointer_cast<TomlConfig>(app.get_config_formatter()))
            toml->set_file_name(config);
    } catch (const InvalidInput& e) {
        fmt::print(stderr, "packbed: {}\n", e.what());
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        const auto selected = app.get_subcommands();
        if (selected.empty()) { // no subcommand: say what was given instead, and what is allowed
            std::string names;
            for (const Command& command : commands)
                names += (names.empty() ? "" : ", ") + command.app->get_name();
            const auto remaining = app.remaining();
            const auto word = remaining.begin();
            if (word == remaining.end())
                fmt::print(stderr, "packbed: a subcommand is required; allowed: {}\n", names);
            else if (word->starts_with("-"))
                fmt::print(stderr,
                           "packbed: '{}' is not an option of packbed itself; allowed: a "
                           "subcommand first ({}), or --help, --version, --config FILE\n",
                           printable(word->substr(0, 80)), names);
            else {
                std::vector<std::string> candidates;
                for (const Command& command : commands)
                    candidates.push_back(command.app->get_name());
                const std::string hint = did_you_mean(*word, candidates);
                fmt::print(stderr, "packbed: '{}' is not a subcommand{}; allowed: {}\n",
                           printable(word->substr(0, 80)), hint.empty() ? "" : " (" + hint + ")",
                           names);
            }
            return 2;
        }
        if (const std::string text = e.what();
            dynamic_cast<const CLI::ExcludesError*>(&e) && text.find(" excludes ") != text.npos) {
            // Two options that say the same thing (--container and --aspect-ratio): both
            // named with the values given.
            const std::size_t at = text.find(" excludes ");
            auto given = [&](const std::string& name) {
                std::string shown = name;
                if (const CLI::Option* o = selected.front()->get_option_no_throw(name))
                    for (const std::string& v : o->results())
                        shown += " " + v.substr(0, 80);
                return printable(shown);
            };
            fmt::print(stderr, "packbed {}: {} and {} are both given; allowed: one of the two\n",
                       selected.front()->get_name(), given(text.substr(0, at)),
                       given(text.substr(at + 10)));
        } else if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
            // A mistyped option: the closest option of that subcommand.
            std::string suggestion;
            for (const auto& extra : app.remaining(true))
                if (extra.starts_with("--")) {
                    suggestion = did_you_mean(extra.substr(0, extra.find('=')),
                                              long_options(*selected.front()));
                    if (!suggestion.empty())
                        suggestion = " (" + suggestion + ")";
                    break;
                }
            // CLI11's own text lists the words backwards ("1 --threads"): in the given order.
            std::string words;
            for (const auto& extra : app.remaining(true))
                words += (words.empty() ? "" : " ") + extra;
            fmt::print(stderr,
                       "packbed {0}: '{1}' is not expected{2}; allowed: the options of "
                       "'packbed {0} --help'\n",
                       selected.front()->get_name(), printable(words.substr(0, 200)),
                       printable(suggestion));
        } else if (const std::string sub = selected.front()->get_name();
                   dynamic_cast<const CLI::ArgumentMismatch*>(&e) &&
                   text.find(": At Most 1 required but received ") != text.npos) {
            // An option given twice (-a 3 -a 4): CLI11 says "At Most 1 required".
            const std::size_t at = text.find(": At Most ");
            fmt::print(stderr, "packbed {}: {} is given {} times; allowed: once\n", sub,
                       printable(text.substr(0, at)), printable(text.substr(text.rfind(' ') + 1)));
        } else if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) && text.ends_with(" missing") &&
                   text.find(": 1 required ") != text.npos) {
            // An option at the end with no value (generate -n).
            constexpr std::string_view required = ": 1 required ", missing = " missing";
            const std::size_t at = text.find(required);
            const std::string type = text.substr(
                at + required.size(), text.size() - at - required.size() - missing.size());
            const std::size_t colon = type.find(':');
            fmt::print(stderr, "packbed {}: {} has no value; allowed: {}\n", sub,
                       printable(text.substr(0, at)),
                       printable(colon == type.npos ? type : type.substr(colon + 1)));
        } else if (dynamic_cast<const CLI::RequiredError*>(&e) && text.ends_with(" is required")) {
            // A required option or argument left out (voxelize without --voxel-size).
            const std::string name =
                printable(text.substr(0, text.size() - std::string_view(" is required").size()));
            if (name.starts_with("-"))
                fmt::print(stderr,
                           "packbed {0}: {1} is required and not given; allowed: {1} with its "
                           "value ('packbed {0} --help')\n",
                           sub, name);
            else {
                std::string upper = name;
                for (char& c : upper)
                    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
                fmt::print(stderr,
                           "packbed {0}: {1} is required and not given; allowed: packbed {0} "
                           "{1} ... ('packbed {0} --help')\n",
                           sub, upper);
            }
        } else
            fmt::print(stderr, "packbed: {}\n", printable(e.what()));
        return 2;
    }
    for (const auto& command : commands) {
        if (!command.app->parsed())
            continue;
        const std::string name = command.app->get_name();
        set_command_name(name);
        handle_interrupts(); // a signal sent while parsing is handled now, naming the command
        try {
            return command.run();
        } catch (const InvalidInput& e) {
            await_interrupt();
            fmt::print(stderr, "packbed {}: {}\n", name, printable(as_given(e.what())));
            return 2;
        } catch (const Cancelled&) {
            await_interrupt();
            fmt::print(stderr, "{}\n", interrupted_message());
            return 130;
        } catch (const std::bad_alloc&) {
            await_interrupt();
            fmt::print(stderr, "packbed {}: out of memory; nothing was written\n", name);
            return 1;
        } catch (const std::exception& e) {
            await_interrupt();
            fmt::print(stderr, "packbed {}: {}\n", name, printable(as_given(e.what())));
            return 1;
        }
    }
    return 2;
}

} // namespace packbed::cli
