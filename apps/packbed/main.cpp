// packbed: the command line. It parses, dispatches to one subcommand and maps errors to exit
// statuses: 0 success, 1 the run failed (no convergence, I/O), 2 bad input, 130 interrupted.
#include <cstdio>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "packbed/error.hpp"
#include "packbed/version.hpp"
#include "toml_config.hpp"

namespace packbed::cli {
Command register_generate(CLI::App& parent);
Command register_analyze(CLI::App& parent);
Command register_correlations(CLI::App& parent);
Command register_lattice(CLI::App& parent);
Command register_hydraulics(CLI::App& parent);
Command register_export(CLI::App& parent);
} // namespace packbed::cli

int main(int argc, char** argv) {
    using namespace packbed;
    CLI::App app("packbed: packed beds of spheres for CFD and DEM", "packbed");
    app.set_version_flag("-V,--version", std::string("packbed ") + version);
    app.require_subcommand(1);
    app.set_config("--config", "",
                   "read a subcommand's options from this TOML file (keys are the option names, "
                   "e.g. aspect-ratio = 5); the command line wins");
    app.config_formatter(std::make_shared<cli::TomlConfig>(&app));
    const std::vector<cli::Command> commands{
        cli::register_generate(app), cli::register_lattice(app), cli::register_hydraulics(app),
        cli::register_export(app),   cli::register_analyze(app), cli::register_correlations(app)};

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ExtrasError& e) {
        const auto selected = app.get_subcommands();
        fmt::print(stderr, "packbed: {}; run 'packbed {}--help' for the options\n", e.what(),
                   selected.empty() ? "" : selected.front()->get_name() + " ");
        return 2;
    } catch (const CLI::ParseError& e) {
        fmt::print(stderr, "packbed: {}\n", e.what());
        return 2;
    }
    for (const auto& command : commands) {
        if (!command.app->parsed())
            continue;
        const std::string name = command.app->get_name();
        try {
            return command.run();
        } catch (const InvalidInput& e) {
            fmt::print(stderr, "packbed {}: {}\n", name, e.what());
            return 2;
        } catch (const Cancelled&) {
            fmt::print(stderr, "packbed {}: interrupted; nothing was written\n", name);
            return 130;
        } catch (const std::exception& e) {
            fmt::print(stderr, "packbed {}: {}\n", name, e.what());
            return 1;
        }
    }
    return 2;
}
