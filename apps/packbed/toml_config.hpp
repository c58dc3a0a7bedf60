// Options from a TOML file, through toml++, fed to CLI11 so that the command line wins.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace packbed::cli {

/// CLI11 config reader backed by toml++, set on the top-level app (CLI11 reads config files
/// only there). The keys are the options of the subcommand being run, by long name;
/// `aspect_ratio` and `aspect-ratio` are the same key. Top-level keys, or keys under a table
/// named after that subcommand (e.g. `[generate]`), are accepted. An unknown key, a syntax
/// error or a value of the wrong shape is an error naming the line. Options given on the
/// command line win over the file.
class TomlConfig : public CLI::Config {
public:
    /// \param root the top-level app (not owned; must outlive this object)
    explicit TomlConfig(const CLI::App* root)
        : m_root(root) {}

    std::vector<CLI::ConfigItem> from_config(std::istream& input) const override;
    /// Name the file being read in messages ("--config FILE: line 3: ...").
    void set_file_name(std::string name) { m_file_name = std::move(name); }
    std::string to_config(const CLI::App*, bool, bool, std::string) const override;

private:
    const CLI::App* m_root;
    std::string m_file_name;
};

/// \return "" when `text`, read as TOML, nests at most limits::max_toml_nesting levels deep
/// (the parts of a table header and of a dotted key, arrays, inline tables); else "line N:
/// ..." saying where it goes deeper. Strings and comments are skipped; what is not TOML is
/// left to the parser.
std::string toml_nesting_problem(std::string_view text);

/// \return the long names (without dashes) of the options of `app` that a config may set.
std::set<std::string> configurable_names(const CLI::App& app);

} // namespace packbed::cli
