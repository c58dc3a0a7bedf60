#include "toml_config.hpp"

#include <algorithm>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "packbed/files.hpp"

namespace packbed::cli {

namespace {

std::string normalise(std::string key) {
    std::replace(key.begin(), key.end(), '_', '-');
    return key;
}

std::string line_of(const toml::node& node) {
    return fmt::format("line {}", node.source().begin.line);
}

/// One TOML scalar as the text CLI11 would have received on the command line.
std::string scalar_text(const toml::node& node, const std::string& key, const std::string& where) {
    if (const auto* v = node.as_integer())
        return std::to_string(v->get());
    if (const auto* v = node.as_floating_point())
        return fmt::format("{}", v->get());
    if (const auto* v = node.as_boolean())
        return v->get() ? "true" : "false";
    if (const auto* v = node.as_string())
        return v->get();
    throw CLI::ConfigError(fmt::format("{}: {}: key '{}' has a value of the wrong type; "
                                       "allowed: a number, a string or true/false",
                                       where, line_of(node), key));
}

} // namespace

std::vector<CLI::ConfigItem> TomlConfig::from_config(std::istream& input) const {
    const std::string where =
        m_file_name.empty() ? std::string("--config") : "--config " + printable(m_file_name);
    toml::table root;
    try {
        root = toml::parse(input);
    } catch (const toml::parse_error& e) {
        throw CLI::ConfigError(fmt::format("{}: line {}, column {}: {}", where,
                                           e.source().begin.line, e.source().begin.column,
                                           e.description()));
    }
    const auto selected = m_root->get_subcommands();
    if (selected.empty())
        throw CLI::ConfigError(where + ": a subcommand must be given with a config file");
    const CLI::App& command = *selected.front();
    const std::string section = command.get_name();
    const std::set<std::string> allowed = configurable_names(command);
    std::vector<CLI::ConfigItem> result;
    auto add = [&](const toml::key& raw_key, const toml::node& node) {
        const std::string key = normalise(std::string(raw_key.str()));
        if (node.is_table())
            throw CLI::ConfigError(
                fmt::format("{}: {}: unknown table '{}'; allowed: top-level keys or [{}]", where,
                            line_of(node), printable(raw_key.str()), section));
        if (!allowed.count(key)) {
            std::string names;
            for (const auto& n : allowed)
                names += (names.empty() ? "" : ", ") + n;
            throw CLI::ConfigError(fmt::format("{}: {}: unknown key '{}'; allowed: {}", where,
                                               line_of(node), printable(raw_key.str()), names));
        }
        CLI::ConfigItem item;
        item.parents = {section};
        item.name = key;
        if (const auto* array = node.as_array())
            for (const auto& element : *array)
                item.inputs.push_back(scalar_text(element, key, where));
        else
            item.inputs.push_back(scalar_text(node, key, where));
        result.push_back(std::move(item));
    };
    for (const auto& [key, node] : root) {
        if (const auto* table = node.as_table(); table && key.str() == section) {
            for (const auto& [inner_key, inner_node] : *table)
                add(inner_key, inner_node);
        } else {
            add(key, node);
        }
    }
    return result;
}

std::string TomlConfig::to_config(const CLI::App* app, bool default_also, bool, std::string) const {
    std::ostringstream out;
    for (const CLI::Option* opt : app->get_options()) {
        if (!opt->get_configurable() || opt->get_lnames().empty())
            continue;
        const auto results = opt->results();
        const std::string value = results.empty() ? opt->get_default_str() : results.front();
        if (value.empty() && !default_also)
            continue;
        out << opt->get_lnames().front() << " = \"" << value << "\"\n";
    }
    return out.str();
}

std::set<std::string> configurable_names(const CLI::App& app) {
    std::set<std::string> names;
    for (const CLI::Option* opt : app.get_options())
        if (opt->get_configurable() && !opt->get_lnames().empty())
            names.insert(opt->get_lnames().front());
    return names;
}

} // namespace packbed::cli
