#include "toml_config.hpp"

#include <algorithm>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "packbed/files.hpp"
#include "packbed/limits.hpp"

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

/// Skip the string that starts at text[i] (a quote): basic or literal, on one line or on many
/// (triple quotes). \return the index of its last character; `line` counts its newlines.
std::size_t skip_string(std::string_view text, std::size_t i, std::size_t& line) {
    const char quote = text[i];
    const bool multi = text.substr(i, 3) == std::string(3, quote);
    const std::string close = multi ? std::string(3, quote) : std::string(1, quote);
    for (std::size_t k = i + close.size(); k < text.size(); ++k) {
        if (text[k] == '\n') {
            ++line;
            if (!multi)
                return k - 1; // an unterminated string: toml++ says so
        } else if (text[k] == '\\' && quote == '"')
            ++k;
        else if (text.substr(k, close.size()) == close)
            return k + close.size() - 1;
    }
    return text.size();
}

} // namespace

std::string toml_nesting_problem(std::string_view text) {
    // The depth of a value: the parts of its table header, of its dotted key, and of the arrays
    // and inline tables it lies in (each inline table adds the parts of the keys in it).
    const std::size_t most = limits::max_toml_nesting;
    std::size_t line = 1, header = 0, parts = 1, base = 0;
    bool key = true, in_header = false, started = false;
    std::vector<std::pair<char, std::size_t>> open; // '[' or '{' and its depth
    auto too_deep = [&] {
        return fmt::format("line {}: nested deeper than {} levels (tables, dotted keys, arrays); "
                           "allowed: at most that deep",
                           line, most);
    };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            if (open.empty() && !in_header) { // a new statement
                key = true;
                started = false;
                parts = 1;
                base = header;
            }
        } else if (c == '#') {
            while (i + 1 < text.size() && text[i + 1] != '\n')
                ++i;
        } else if (c == '"' || c == '\'') {
            i = skip_string(text, i, line);
            started = true;
        } else if (c == '}' || (c == ']' && !in_header)) {
            if (!open.empty())
                open.pop_back();
            key = false;
        } else if (key || in_header) {
            if (c == '.' && base + ++parts > most)
                return too_deep();
            if (c == '=' && !in_header)
                key = false;
            else if (c == '[' && key && open.empty() && !started) {
                in_header = true;
                parts = 1;
                base = 0;
                if (i + 1 < text.size() && text[i + 1] == '[')
                    ++i;
            } else if (c == ']' && in_header) {
                in_header = false;
                key = false;
                header = parts;
            }
            if (c != ' ' && c != '\t' && c != '\r')
                started = true;
        } else if (c == '[' || c == '{') {
            const std::size_t depth = (open.empty() ? base + parts : open.back().second) + 1;
            if (depth > most)
                return too_deep();
            open.emplace_back(c, depth);
            if (c == '{') {
                key = true;
                parts = 1;
                base = depth;
            }
        } else if (c == ',' && !open.empty() && open.back().first == '{') {
            key = true;
            parts = 1;
            base = open.back().second;
        }
    }
    return {};
}

std::vector<CLI::ConfigItem> TomlConfig::from_config(std::istream& input) const {
    const std::string where =
        m_file_name.empty() ? std::string("--config") : "--config " + printable(m_file_name);
    // Bounded before toml++ reads it: its size (a parser keeps ~60 bytes per value) and its
    // nesting (toml++ recurses over both).
    std::string text;
    char buffer[1 << 14];
    while (input.read(buffer, sizeof buffer) || input.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(input.gcount()));
        if (text.size() > limits::max_config_file)
            throw CLI::ConfigError(fmt::format("{}: larger than {} bytes; allowed: a config file "
                                               "up to that size",
                                               where, limits::max_config_file));
    }
    if (const std::string problem = toml_nesting_problem(text); !problem.empty())
        throw CLI::ConfigError(where + ": " + problem);
    toml::table root;
    try {
        root = toml::parse(text);
    } catch (const toml::parse_error& e) {
        throw CLI::ConfigError(fmt::format("{}: line {}, column {}: {}", where,
                                           e.source().begin.line, e.source().begin.column,
                                           printable(e.description().substr(0, 200))));
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
                            line_of(node), printable(raw_key.str().substr(0, 80)), section));
        if (!allowed.count(key)) {
            std::string names;
            for (const auto& n : allowed)
                names += (names.empty() ? "" : ", ") + n;
            throw CLI::ConfigError(fmt::format("{}: {}: unknown key '{}'; allowed: {}", where,
                                               line_of(node),
                                               printable(raw_key.str().substr(0, 80)), names));
        }
        // The command line wins, also over a key whose option excludes one it gives
        // (`aspect_ratio` in the file, --container on the command line).
        if (const CLI::Option* option = command.get_option_no_throw("--" + key))
            for (const CLI::Option* other : option->get_excludes())
                if (other->count() > 0)
                    return;
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
        } else if (const std::string_view name = key.str();
                   table && !m_root
                                 ->get_subcommands(
                                     [name](const CLI::App* c) { return c->get_name() == name; })
                                 .empty()) {
            continue; // another subcommand's section: one file serves several
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
