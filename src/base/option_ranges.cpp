// The allowed values of the numeric options (option_ranges.hpp).
#include "packbed/option_ranges.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/text.hpp"

namespace packbed {

bool NumberRange::holds(double value) const {
    return std::isfinite(value) && (low_open ? value > low : value >= low) &&
           (high_open ? value < high : value <= high);
}

std::string NumberRange::allowed() const {
    if (std::isinf(high))
        return fmt::format("a number {} {:g}", low_open ? ">" : ">=", low);
    return fmt::format("a number in {}{:g}, {:g}{}", low_open ? "(" : "[", low, high,
                       high_open ? ")" : "]");
}

std::string WholeRange::allowed() const {
    return fmt::format("a whole number from {} to {}", low, high);
}

double check_option(std::string_view option, double value, const NumberRange& range) {
    if (!range.holds(value))
        throw InvalidInput(
            fmt::format("--{}: {} is not allowed; allowed: {}", option, value, range.allowed()));
    return value;
}

std::uint64_t check_option(std::string_view option, long long value, const WholeRange& range) {
    if (value < 0 || static_cast<std::uint64_t>(value) < range.low ||
        static_cast<std::uint64_t>(value) > range.high)
        throw InvalidInput(
            fmt::format("--{}: {} is not allowed; allowed: {}", option, value, range.allowed()));
    return static_cast<std::uint64_t>(value);
}

std::string whole_problem(std::string_view text, const WholeRange& range) {
    const auto value = parse_whole<std::uint64_t>(text);
    if (!value)
        return fmt::format("'{}' is not allowed; allowed: {}", printable(text.substr(0, 80)),
                           range.allowed());
    if (*value < range.low || *value > range.high)
        return fmt::format("{} is not allowed; allowed: {}", text, range.allowed());
    if (has_leading_zero(text))
        return fmt::format("'{}' is not allowed; allowed: {}, written without leading zeros",
                           printable(text.substr(0, 80)), range.allowed());
    return {};
}

std::uint64_t check_whole(std::string_view option, std::string_view text, const WholeRange& range) {
    if (const std::string problem = whole_problem(text, range); !problem.empty())
        throw InvalidInput(fmt::format("--{}: {}", option, problem));
    return *parse_whole<std::uint64_t>(text);
}

} // namespace packbed
