// JSON from users (summary.json, checkpoint headers, job.json, an OpenFOAM case's
// packbed.json), parsed with its nesting bounded and shown in messages within a bound.
// nlohmann's parser does not recurse, but dumping, comparing, copying and destroying a value
// do: 1e5 nested brackets overflow the stack there, so they are refused where they are read.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace packbed {

/// What parse_json found: the value, or why there is none.
struct ParsedJson {
    nlohmann::json value; ///< discarded when `error` is set
    std::string error;    ///< "" for a value; else a short reason, printable, at most ~200 bytes
};

/// Parse `text` as one JSON value nested at most limits::max_json_nesting levels deep.
ParsedJson parse_json(std::string_view text);

/// \return where `value` holds a number that is not finite (NaN or an infinity, which JSON
/// cannot hold: nlohmann writes them as null), as a JSON pointer ("/fluxes_m3_s/imbalance"),
/// or "" when every number is finite. For packbed's own values (the recursion follows their
/// nesting).
std::string non_finite_at(const nlohmann::json& value);
std::string non_finite_at(const nlohmann::ordered_json& value);

/// `value` as JSON text of at most about `bytes` bytes ("..." where it is cut), with control
/// characters escaped: what a message quotes of a user's value, whatever its size.
std::string json_excerpt(const nlohmann::json& value, std::size_t bytes = 40);

} // namespace packbed
