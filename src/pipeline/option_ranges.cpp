// The allowed values of the numeric options (option_ranges.hpp).
#include "packbed/option_ranges.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "packbed/container.hpp"
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
    return {};
}

std::uint64_t check_whole(std::string_view option, std::string_view text, const WholeRange& range) {
    if (const std::string problem = whole_problem(text, range); !problem.empty())
        throw InvalidInput(fmt::format("--{}: {}", option, problem));
    return *parse_whole<std::uint64_t>(text);
}

std::string allowed_containers(std::span<const std::string_view> shapes) {
    const auto takes = [&](std::string_view s) {
        return std::find(shapes.begin(), shapes.end(), s) != shapes.end();
    };
    std::vector<std::string> forms;
    const double round = 2.0 * limits::max_length, flat = limits::max_length;
    if (takes("cylinder"))
        forms.push_back(
            fmt::format("cylinder:D, a tube of inner diameter D, a number in (0, {:g}]", round));
    if (takes("box"))
        forms.push_back(
            fmt::format("box:LX,LY, walls at x = 0, LX and y = 0, LY, each in (0, {:g}]", flat));
    if (takes("annulus"))
        forms.push_back(fmt::format("annulus:D,DI, between a tube of diameter D and a coaxial "
                                    "rod of diameter DI, 0 < DI < D <= {:g}",
                                    round));
    if (takes("periodic"))
        forms.push_back(
            fmt::format("periodic:LX,LY, a cell periodic in x and y, each in (0, {:g}]", flat));
    return fmt::format("{}", fmt::join(forms, "; or "));
}

std::string container_not_allowed(std::string_view option, std::string_view spec) {
    return fmt::format("{}: '{}' is not allowed; allowed: {}", option,
                       printable(spec.substr(0, 80)), allowed_containers(all_shapes));
}

} // namespace packbed
