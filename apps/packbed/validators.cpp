#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "command.hpp"
#include "packbed/error.hpp"

namespace packbed::cli {

CLI::Validator real_in(double low, double high, bool low_open, bool high_open) {
    const std::string allowed =
        std::isinf(high) ? fmt::format("a number {} {:g}", low_open ? ">" : ">=", low)
                         : fmt::format("a number in {}{:g}, {:g}{}", low_open ? "(" : "[", low,
                                       high, high_open ? ")" : "]");
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            double value = 0.0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (ec != std::errc() || ptr != end || !std::isfinite(value))
                return fmt::format("'{}' is not allowed; allowed: {}", text, allowed);
            const bool above = low_open ? value > low : value >= low;
            const bool below = high_open ? value < high : value <= high;
            if (!above || !below)
                return fmt::format("{} is not allowed; allowed: {}", text, allowed);
            return {};
        },
        allowed);
}

CLI::Validator whole_in(unsigned long long low, unsigned long long high) {
    const std::string allowed = fmt::format("a whole number from {} to {}", low, high);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            unsigned long long value = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (ec != std::errc() || ptr != end || value < low || value > high)
                return fmt::format("'{}' is not allowed; allowed: {}", text, allowed);
            return {};
        },
        allowed);
}

std::optional<std::vector<double>> comma_numbers(std::string_view text) {
    std::vector<double> values;
    while (true) {
        const std::size_t comma = text.find(',');
        const std::string_view item = text.substr(0, comma);
        double value = 0.0;
        const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || ec != std::errc() || ptr != item.data() + item.size() ||
            !std::isfinite(value))
            return std::nullopt;
        values.push_back(value);
        if (comma == std::string_view::npos)
            return values;
        text.remove_prefix(comma + 1);
    }
}

void use_threads(unsigned long long threads) {
    omp_set_num_threads(static_cast<int>(threads));
    if (std::getenv("OMP_DYNAMIC") == nullptr) // OMP_DYNAMIC=false keeps the count fixed
        omp_set_dynamic(1);
}

} // namespace packbed::cli

namespace packbed::cli {

std::optional<double> container_radius_beside(const std::filesystem::path& particles) {
    const std::filesystem::path summary = particles.parent_path() / "summary.json";
    std::ifstream in(summary);
    if (!in)
        return std::nullopt;
    try {
        const auto json = nlohmann::json::parse(in);
        const double r = json.at("container").at("radius").get<double>();
        if (r > 0.0)
            return r;
    } catch (const nlohmann::json::exception&) {
    }
    throw InvalidInput(
        fmt::format("{}: no positive container.radius; give --container-radius", summary.string()));
}

} // namespace packbed::cli
