// What the shapes' files share: the limits of a fit, the words of a prism's answers, the
// LAMMPS numbers. Internal to src/geometry/.
#pragma once

#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "packbed/shape.hpp"

namespace packbed::detail {

/// Widest allowed container, in Dp: as the cylinder's largest aspect ratio.
inline constexpr double widest = 1e4;

/// \return true when every length of a SPEC is in (0, largest] (false for NaN).
inline bool lengths_in(std::span<const double> v, double largest) {
    for (const double x : v)
        if (!(x > 0.0 && x <= largest))
            return false;
    return true;
}

/// The height of `solid` (diameters cubed, Dp^3) over a cross-section of `area` at void
/// fraction e0: (pi / 6) solid / (A (1 - e0)).
inline double prism_fill_height(double area, double solid, double e0) {
    return std::numbers::pi / 6.0 * solid / (area * (1.0 - e0));
}

/// A box's or a periodic cell's fit: widths from `least` to `widest` Dp.
inline std::string widths_problem(const Rectangle& b, double least, std::string_view why) {
    const double lx = b.x_high - b.x_low, ly = b.y_high - b.y_low;
    if (!(lx >= least && ly >= least && lx <= widest && ly <= widest))
        return fmt::format("widths from {:.6g} Dp ({}) to {:g} Dp", least, why, widest);
    return {};
}

/// The search lines at irrational fractions of the half widths of `b` from its middle, so
/// that no line lies on a cell face of a background mesh.
inline std::vector<std::pair<double, double>> lines_in(const Rectangle& b) {
    const double x_mid = 0.5 * (b.x_low + b.x_high), y_mid = 0.5 * (b.y_low + b.y_high);
    const double x_half = 0.5 * (b.x_high - b.x_low), y_half = 0.5 * (b.y_high - b.y_low);
    constexpr double fractions[8][2] = {{0.0123, 0.0371},  {0.3137, 0.1291},   {-0.2719, 0.2213},
                                        {0.1409, -0.4129}, {-0.5231, -0.0917}, {0.6143, 0.2753},
                                        {-0.1733, 0.6571}, {0.4421, -0.5309}};
    std::vector<std::pair<double, double>> lines;
    for (const auto& f : fractions)
        lines.emplace_back(x_mid + f[0] * x_half, y_mid + f[1] * y_half);
    return lines;
}

/// A point at distance sqrt(a^2 + (b^2 - a^2) u) from the axis and angle 2 pi v: uniform
/// over the ring between the radii a and b (section 3.1 of the paper for a = 0).
inline Vec3 ring_point(double a, double b, double u, double v) {
    const double r = std::sqrt(a * a + (b * b - a * a) * u);
    const double theta = 2.0 * std::numbers::pi * v;
    return {r * std::cos(theta), r * std::sin(theta), 0.0};
}

/// A prism's summary: {shape, size [LX, LY], spec}.
inline nlohmann::json prism_json(std::string_view shape, const Rectangle& b,
                                 const std::string& spec) {
    return {{"shape", shape}, {"size", {b.x_high - b.x_low, b.y_high - b.y_low}}, {"spec", spec}};
}

inline nlohmann::ordered_json prism_export_json(std::string_view shape, const Rectangle& b,
                                                double height) {
    return {{"shape", shape},
            {"size", {b.x_high - b.x_low, b.y_high - b.y_low}},
            {"corner", {b.x_low, b.y_low}},
            {"height", height}};
}

/// Shortest round-trip text of a number, as the LAMMPS data file's.
inline std::string num(double value) {
    return fmt::format("{}", value);
}

/// line(t + 1, d / 2 + setback) for each size t: a wall fix per type.
template <class F>
std::string per_type(std::span<const double> diameters, double setback, F&& line) {
    std::string out;
    for (std::size_t t = 0; t < diameters.size(); ++t)
        out += line(t + 1, 0.5 * diameters[t] + setback);
    return out;
}

} // namespace packbed::detail
