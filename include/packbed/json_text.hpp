// JSON written to files: one text for every JSON output.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace packbed {

/// `value` as the text of the JSON file `name` (indented by 2, a newline at the end). JSON has
/// no NaN or infinity (nlohmann writes null): no output may hold one.
/// \throws std::runtime_error naming the file and the field when a number is not finite
std::string json_file_text(const nlohmann::json& value, std::string_view name);
std::string json_file_text(const nlohmann::ordered_json& value, std::string_view name);

} // namespace packbed
