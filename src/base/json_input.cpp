#include "base/json_input.hpp"

#include <cmath>

#include <fmt/format.h>

#include "packbed/files.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"

namespace packbed {

namespace {

/// Thrown by the parser's callback past the nesting limit.
struct TooDeep {};

/// `value` as JSON text, a UTF-8 sequence cut by a substring shown as U+FFFD (dump() throws on
/// it).
std::string dumped(const nlohmann::json& value) {
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

/// Append `value` to `out` until `out` holds `bytes` bytes (a value nested at most
/// limits::max_json_nesting deep: the recursion is bounded).
void excerpt(const nlohmann::json& value, std::size_t bytes, std::string& out) {
    if (out.size() >= bytes)
        return;
    if (value.is_array() || value.is_object()) {
        out += value.is_array() ? '[' : '{';
        bool first = true;
        for (auto it = value.begin(); it != value.end() && out.size() < bytes; ++it) {
            out += first ? "" : ",";
            first = false;
            if (value.is_object())
                out += dumped(nlohmann::json(it.key().substr(0, bytes))) + ":";
            excerpt(*it, bytes, out);
        }
        if (out.size() < bytes)
            out += value.is_array() ? ']' : '}';
        return;
    }
    if (value.is_string()) {
        const std::string& s = value.get_ref<const std::string&>();
        out += dumped(nlohmann::json(s.substr(0, bytes)));
        return;
    }
    out += dumped(value);
}

template <class Json> std::string non_finite(const Json& value, const std::string& at) {
    if (value.is_number_float())
        return std::isfinite(value.template get<double>()) ? std::string() : at.empty() ? "/" : at;
    if (value.is_object()) {
        for (auto it = value.begin(); it != value.end(); ++it)
            if (std::string found = non_finite(*it, at + "/" + it.key()); !found.empty())
                return found;
    } else if (value.is_array()) {
        for (std::size_t k = 0; k < value.size(); ++k)
            if (std::string found = non_finite(value[k], at + "/" + std::to_string(k));
                !found.empty())
                return found;
    }
    return {};
}

template <class Json> std::string file_text(const Json& value, std::string_view name) {
    if (const std::string at = non_finite(value, ""); !at.empty())
        throw std::runtime_error(fmt::format("{} would hold a number that is not finite at {}; "
                                             "nothing was written",
                                             name, at));
    return value.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

} // namespace

std::string json_file_text(const nlohmann::json& value, std::string_view name) {
    return file_text(value, name);
}

std::string json_file_text(const nlohmann::ordered_json& value, std::string_view name) {
    return file_text(value, name);
}

std::string non_finite_at(const nlohmann::json& value) {
    return non_finite(value, "");
}

std::string non_finite_at(const nlohmann::ordered_json& value) {
    return non_finite(value, "");
}

ParsedJson parse_json(std::string_view text) {
    ParsedJson parsed;
    try {
        parsed.value =
            nlohmann::json::parse(text.begin(), text.end(),
                                  [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
                                      if (depth > static_cast<int>(limits::max_json_nesting))
                                          throw TooDeep{};
                                      return true;
                                  });
    } catch (const TooDeep&) {
        parsed.value = nlohmann::json(nlohmann::json::value_t::discarded);
        parsed.error = fmt::format("nested deeper than {} levels", limits::max_json_nesting);
    } catch (const nlohmann::json::exception& e) {
        parsed.value = nlohmann::json(nlohmann::json::value_t::discarded);
        parsed.error = printable(std::string_view(e.what()).substr(0, 200));
    }
    return parsed;
}

std::string json_excerpt(const nlohmann::json& value, std::size_t bytes) {
    std::string out;
    excerpt(value, bytes + 1, out);
    if (out.size() > bytes) {
        out.resize(bytes);
        out += "...";
    }
    return printable(out);
}

} // namespace packbed
