// `packbed --config FILE.toml SUBCOMMAND`: the input is FILE, read by TomlConfig::from_config
// and fed through CLI11 into the subcommand's options and validators, as the command line does,
// for every subcommand (a required positional argument gets an existing file). The parse must
// succeed or throw CLI::ParseError (ConfigError, ValidationError, ...: exit 2) or
// InvalidInput; nothing else may come out. The subcommand is not run.
//
// The app is built once (build_app costs about 4 ms under ASan, six times the parse) and
// parsed again for each input and subcommand: CLI11 clears every option's results before a
// parse, so an input sees the options of no earlier one; the variables the options are bound
// to keep earlier values, which nothing here reads.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "app.hpp"
#include "fuzz_support.hpp"

namespace {

/// The file the input is written to: `--config` takes a path, and CLI11 opens it itself.
std::string config_path;

/// The command line, built once; the commands own the variables its options are bound to.
CLI::App* app = nullptr;
std::vector<packbed::cli::Command>* commands = nullptr;

/// The names of the subcommands, and whether each has a required positional argument.
struct Subcommand {
    std::string name;
    bool positional = false;
};
std::vector<Subcommand> subcommands;

void parse_with_config(const Subcommand& sub) {
    std::vector<std::string> args{"packbed", "--config", config_path, sub.name};
    if (sub.positional)
        args.push_back(config_path); // an existing file (analyze checks it exists)
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    try {
        app->parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError&) {
    } catch (const packbed::InvalidInput&) {
    } catch (...) {
        packbed::fuzz::unexpected_exception();
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/packbed-fuzz-XXXXXX.toml";
    const int fd = mkstemps(pattern.data(), 5);
    if (fd < 0) {
        std::perror("fuzz_toml: mkstemps");
        std::abort();
    }
    close(fd);
    config_path = pattern;
    std::atexit([] { std::remove(config_path.c_str()); });

    // Never freed: they live as long as the process, like the command line's.
    app = new CLI::App("packbed: packed beds of spheres for CFD and DEM", "packbed");
    commands = new std::vector<packbed::cli::Command>(packbed::cli::build_app(*app));
    for (const auto& command : *commands) {
        Subcommand sub{command.app->get_name()};
        for (const CLI::Option* opt : command.app->get_options())
            if (opt->get_positional() && opt->get_required())
                sub.positional = true;
        subcommands.push_back(sub);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    {
        std::ofstream file(config_path, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!file.flush())
            packbed::fuzz::finding("cannot write " + config_path);
    }
    for (const auto& sub : subcommands)
        parse_with_config(sub);
    return 0;
}
