// Options from a TOML file, through toml++, fed to CLI11 so that the command line wins.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace packbed::cli {

/// CLI11 config reader backed by toml++. Keys are option long names; `aspect_ratio` and
/// `aspect-ratio` are the same key. Top-level keys, or keys under a table named after the
/// subcommand (e.g. `[generate]`), are accepted. An unknown key, a syntax error or a value of
/// the wrong shape is an error naming the line.
class TomlConfig : public CLI::Config {
public:
    /// \param section the subcommand name whose table is accepted
    /// \param allowed the option long names (without dashes) a file may set
    TomlConfig(std::string section, std::set<std::string> allowed)
        : m_section(std::move(section))
        , m_allowed(std::move(allowed)) {}

    std::vector<CLI::ConfigItem> from_config(std::istream& input) const override;
    std::string to_config(const CLI::App*, bool, bool, std::string) const override;

private:
    std::string m_section;
    std::set<std::string> m_allowed;
};

/// \return the long names (without dashes) of the options of `app` that a config may set.
std::set<std::string> configurable_names(const CLI::App& app);

} // namespace packbed::cli
