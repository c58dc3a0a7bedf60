#pragma once

#include <charconv>
#include <concepts>
#include <optional>
#include <string_view>
#include <vector>

namespace packbed {

/// Text from users and files, read one way everywhere: white space is std::isspace's, numbers
/// are std::from_chars' (no locale, no leading '+' or space, the whole text or nothing), specs
/// are "KIND" or "KIND:PARAMETERS" ("lognormal:1,1.5", "box:10,10", "caps:0.01").

/// `s` without its leading and trailing white space.
std::string_view trim(std::string_view s);

/// The parts of `text` between `separator`s, empty parts kept ("a,,b": 3 parts; "": 1).
std::vector<std::string_view> split(std::string_view text, char separator);

/// The words of `line` between runs of white space (no empty words).
std::vector<std::string_view> split_spaces(std::string_view line);

/// The number that is the whole of `text` (infinities and NaN included), or nothing.
std::optional<double> parse_number(std::string_view text);

/// The finite number that is the whole of `text`, or nothing.
std::optional<double> parse_finite(std::string_view text);

/// The whole number of type T that is all of `text` and fits T, or nothing.
template <std::integral T> std::optional<T> parse_whole(std::string_view text) {
    T value{};
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end)
        return std::nullopt;
    return value;
}

/// Whether a whole number's text has a leading zero ("010", "-07"), which the command line's
/// parser reads as octal (010 as 8): such options are refused rather than misread.
constexpr bool has_leading_zero(std::string_view text) {
    const std::string_view digits = text.substr(text.starts_with('-') ? 1 : 0);
    return digits.size() > 1 && digits.front() == '0';
}

/// The finite numbers of `text` between `separator`s ("1,2.5,-3"), or nothing when it is not
/// exactly that (an empty item, a non-number, NaN or infinity).
std::optional<std::vector<double>> parse_finite_list(std::string_view text, char separator = ',');

/// "KIND" or "KIND:PARAMETERS" split at the first colon.
struct KindSpec {
    std::string_view kind;
    std::optional<std::string_view> parameters; ///< nothing when there is no colon
};
KindSpec split_kind(std::string_view text);

} // namespace packbed
