#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/error.hpp"
#include "packbed/files.hpp"

namespace packbed {

/// A named choice users make (a solver, an update order, an engine, a lattice type, a size
/// distribution, a fraction basis, a contact treatment, an export format, a turbulence model):
/// its names and values in one table, which the library, the command line (its checks and
/// help) and the Python module all read, so that none of them knows a name the others do not
/// or words a refusal differently. Iterates as (name, value) pairs in the table's order.
template <class T> class Registry {
public:
    using Entry = std::pair<std::string, T>;

    /// \param option the option that picks one ("solver": `--solver`, `solver=`)
    Registry(std::string option, std::initializer_list<Entry> entries)
        : m_option(std::move(option))
        , m_entries(entries) {}

    auto begin() const { return m_entries.begin(); }
    auto end() const { return m_entries.end(); }
    std::size_t size() const { return m_entries.size(); }

    /// \return the value named `name`, or nothing.
    std::optional<T> find(std::string_view name) const {
        for (const auto& [n, value] : m_entries)
            if (n == name)
                return value;
        return std::nullopt;
    }

    /// \return the value named `name`; InvalidInput naming the option and every name if none.
    T at(std::string_view name) const {
        if (const auto value = find(name))
            return *value;
        throw InvalidInput("--" + m_option + ": '" + printable(name.substr(0, 80)) +
                           "' is not allowed; allowed: " + allowed());
    }

    /// \return the name of `value` ("unknown" for one the table does not hold).
    std::string name(T value) const {
        for (const auto& [n, v] : m_entries)
            if (v == value)
                return n;
        return "unknown";
    }

    /// \return every name, in the table's order.
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& entry : m_entries)
            out.push_back(entry.first);
        return out;
    }

    /// \return the names as a refusal lists them: "a, b, c".
    std::string allowed() const {
        std::string text;
        for (const auto& entry : m_entries)
            text += (text.empty() ? "" : ", ") + entry.first;
        return text;
    }

    const std::string& option() const { return m_option; }

private:
    std::string m_option;
    std::vector<Entry> m_entries;
};

} // namespace packbed
