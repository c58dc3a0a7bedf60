#include "packbed/sizes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "generate/portable_math.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/text.hpp"

namespace packbed {

using namespace detail; // the portable elementary functions (generate/portable_math.hpp)

std::string shown_sizes(std::string_view spec) {
    return spec.size() > 100 ? printable(spec.substr(0, 100)) + "..." : printable(spec);
}

namespace {

// ---------------------------------------------------------------------------------------------
// Messages.

[[noreturn]] void refuse(std::string_view spec, std::string_view reason, std::string_view allowed) {
    throw InvalidInput(fmt::format("--sizes '{}' is not allowed: {}; allowed: {}",
                                   shown_sizes(spec), reason, allowed));
}

std::string allowed_for(SizeKind kind) {
    const double lo = limits::min_diameter, hi = limits::max_diameter, ratio = max_size_ratio;
    switch (kind) {
    case SizeKind::mono:
        return "mono, every sphere --diameter, without parameters";
    case SizeKind::discrete:
        return fmt::format("discrete:D1:F1,D2:F2,... with each diameter once, from {:g} to {:g}, "
                           "the largest at most {:g} times the smallest, at most {} sizes, and "
                           "fractions >= 0 adding up to 1 (within {:g})",
                           lo, hi, ratio, max_size_rows, fraction_tolerance);
    case SizeKind::uniform:
        return fmt::format("uniform:MIN,MAX with {:g} <= MIN < MAX <= {:g} and MAX <= {:g} MIN", lo,
                           hi, ratio);
    case SizeKind::normal:
    case SizeKind::lognormal: {
        // A two-parameter law cut to [MIN, MAX]: its spec, its centre's range, its spread, the
        // cut's bounds, and where the cut may lie against the law's tails.
        const bool normal = kind == SizeKind::normal;
        const std::string_view name = normal ? "normal" : "lognormal";
        const std::string_view centre = normal ? "MEAN" : "MEDIAN";
        const std::string_view spread = normal ? "SD" : "GSD";
        const std::string tails =
            normal ? fmt::format("MIN < MEAN + 8 SD and MAX > MEAN - 8 SD (by default MIN = "
                                 "MEAN - 3 SD, at least MAX / {:g}, and MAX = MEAN + 3 SD)",
                                 ratio)
                   : fmt::format("MIN < MEDIAN GSD^8 and MAX > MEDIAN / GSD^8 (by default "
                                 "MEDIAN / GSD^3 to MEDIAN GSD^3, narrowed to MAX = {:g} MIN)",
                                 ratio);
        return fmt::format("{0}:{1},{2} or {0}:{1},{2},MIN,MAX with {1} from {3:g} to {4:g}, {2} "
                           "{5}, {3:g} <= MIN < MAX <= {4:g}, MAX <= {6:g} MIN, {7}",
                           name, centre, spread, lo, hi, normal ? "> 0" : "> 1", ratio, tails);
    }
    case SizeKind::file:
        return fmt::format("file:PATH, a CSV of diameter,cumulative_fraction rows (fraction "
                           "passing; a header line may come first, # starts a comment): 2 to {} "
                           "rows, diameters from {:g} to {:g} ascending, cumulative fractions from "
                           "0 to 1 (within {:g}) not decreasing, rising over at most a ratio of "
                           "{:g} in diameter",
                           max_size_rows, lo, hi, fraction_tolerance, ratio);
    }
    return {};
}

std::string allowed_names() {
    std::string text;
    const std::size_t count = size_kinds().size();
    std::size_t i = 0;
    for (const auto& [name, kind] : size_kinds()) {
        text += std::string(i == 0           ? ""
                            : i + 1 == count ? " or "
                                             : ", ") +
                std::string(size_syntax(kind));
        ++i;
    }
    return text;
}

// ---------------------------------------------------------------------------------------------
// Parsing.

bool in_diameter_range(double d) {
    return d >= limits::min_diameter && d <= limits::max_diameter;
}

std::string range_reason(std::string_view what, double value) {
    return fmt::format("{} = {} is not from {:g} to {:g}", what, value, limits::min_diameter,
                       limits::max_diameter);
}

/// The numbers of "A,B,..." for a continuous kind, `counts` the counts allowed.
std::vector<double> parameters(std::string_view spec, std::string_view text, SizeKind kind,
                               std::initializer_list<std::size_t> counts) {
    std::vector<double> values;
    for (const auto item : split(text, ',')) {
        const auto v = parse_finite(item);
        if (!v)
            refuse(spec, fmt::format("'{}' is not a number", printable(item.substr(0, 40))),
                   allowed_for(kind));
        values.push_back(*v);
    }
    if (std::find(counts.begin(), counts.end(), values.size()) == counts.end())
        refuse(spec,
               fmt::format("{} takes {} numbers, not {}", to_string(kind),
                           counts.size() == 1
                               ? fmt::format("{}", *counts.begin())
                               : fmt::format("{} or {}", *counts.begin(), *(counts.end() - 1)),
                           values.size()),
               allowed_for(kind));
    return values;
}

void check_ratio(std::string_view spec, SizeKind kind, double low, double high,
                 std::string_view what) {
    // A relative 1e-12 lets the default bounds, computed to a ratio of exactly 10, through.
    if (high / low > max_size_ratio * (1.0 + 1e-12))
        refuse(spec,
               fmt::format("{} is {:.6g} (the solvers support up to {:g})", what, high / low,
                           max_size_ratio),
               allowed_for(kind));
}

SizeDistribution parse_discrete(std::string_view spec, std::string_view text) {
    const SizeKind kind = SizeKind::discrete;
    std::vector<std::pair<double, double>> sizes;
    for (const auto item : split(text, ',')) {
        const auto parts = split(item, ':');
        if (parts.size() != 2)
            refuse(spec, fmt::format("'{}' is not D:F", printable(item.substr(0, 40))),
                   allowed_for(kind));
        const auto d = parse_finite(parts[0]), f = parse_finite(parts[1]);
        if (!d || !f)
            refuse(spec,
                   fmt::format("'{}' is not a number",
                               printable((!d ? parts[0] : parts[1]).substr(0, 40))),
                   allowed_for(kind));
        if (!in_diameter_range(*d))
            refuse(spec, range_reason("diameter", *d), allowed_for(kind));
        if (*f < 0.0)
            refuse(spec, fmt::format("the fraction {} of diameter {} is negative", *f, *d),
                   allowed_for(kind));
        if (sizes.size() == max_size_rows)
            refuse(spec, fmt::format("more than {} sizes", max_size_rows), allowed_for(kind));
        sizes.emplace_back(*d, *f);
    }
    CompensatedSum sum;
    for (const auto& s : sizes)
        sum.add(s.second);
    const double total = sum.value();
    if (!(std::fabs(total - 1.0) <= fraction_tolerance))
        refuse(spec, fmt::format("the fractions add up to {}", total), allowed_for(kind));
    std::sort(sizes.begin(), sizes.end());
    for (std::size_t i = 1; i < sizes.size(); ++i)
        if (sizes[i].first == sizes[i - 1].first)
            refuse(spec, fmt::format("diameter {} is given twice", sizes[i].first),
                   allowed_for(kind));
    SizeDistribution out;
    out.kind = kind;
    out.spec = std::string(spec);
    out.low = std::numeric_limits<double>::infinity();
    for (const auto& [d, f] : sizes) {
        out.diameters.push_back(d);
        out.fractions.push_back(f / total);
        if (f > 0.0) {
            out.low = std::min(out.low, d);
            out.high = std::max(out.high, d);
        }
    }
    check_ratio(spec, kind, out.low, out.high,
                "the largest diameter over the smallest (of those with a fraction > 0)");
    return out;
}

SizeDistribution parse_uniform(std::string_view spec, std::string_view text) {
    const SizeKind kind = SizeKind::uniform;
    const auto v = parameters(spec, text, kind, {2});
    if (!in_diameter_range(v[0]))
        refuse(spec, range_reason("MIN", v[0]), allowed_for(kind));
    if (!in_diameter_range(v[1]))
        refuse(spec, range_reason("MAX", v[1]), allowed_for(kind));
    if (!(v[0] < v[1]))
        refuse(spec, fmt::format("MIN = {} is not below MAX = {}", v[0], v[1]), allowed_for(kind));
    check_ratio(spec, kind, v[0], v[1], "MAX / MIN");
    SizeDistribution out;
    out.kind = kind;
    out.spec = std::string(spec);
    out.diameters = {v[0], v[1]};
    out.fractions = {0.0, 1.0};
    out.low = v[0];
    out.high = v[1];
    return out;
}

/// normal and lognormal: location, spread and the bounds (given or the defaults).
SizeDistribution parse_bell(std::string_view spec, std::string_view text, SizeKind kind) {
    const bool log = kind == SizeKind::lognormal;
    const auto v = parameters(spec, text, kind, {2, 4});
    const double location = v[0], spread = v[1];
    if (!in_diameter_range(location))
        refuse(spec, range_reason(log ? "MEDIAN" : "MEAN", location), allowed_for(kind));
    if (log && !(spread > 1.0))
        refuse(spec, fmt::format("GSD = {} is not above 1 (one size: discrete:D:1)", spread),
               allowed_for(kind));
    if (!log && !(spread > 0.0))
        refuse(spec, fmt::format("SD = {} is not above 0 (one size: discrete:D:1)", spread),
               allowed_for(kind));
    double low = 0.0, high = 0.0;
    std::string low_name = "MIN", high_name = "MAX";
    if (v.size() == 4) {
        low = v[2];
        high = v[3];
    } else if (log) {
        // MEDIAN / GSD^3 to MEDIAN GSD^3, narrowed about MEDIAN to the largest ratio supported.
        const double r = std::min(spread * spread * spread, std::sqrt(max_size_ratio));
        low = location / r;
        high = location * r;
        low_name = "the default MIN (MEDIAN / GSD^3)";
        high_name = "the default MAX (MEDIAN GSD^3)";
    } else {
        high = location + 3.0 * spread;
        low = std::max(location - 3.0 * spread, high / max_size_ratio);
        low_name = "the default MIN (MEAN - 3 SD, at least MAX / 10)";
        high_name = "the default MAX (MEAN + 3 SD)";
    }
    if (!in_diameter_range(low))
        refuse(spec, range_reason(low_name, low), allowed_for(kind));
    if (!in_diameter_range(high))
        refuse(spec, range_reason(high_name, high), allowed_for(kind));
    if (!(low < high))
        refuse(spec, fmt::format("MIN = {} is not below MAX = {}", low, high), allowed_for(kind));
    check_ratio(spec, kind, low, high, "MAX / MIN");
    // The bounds must keep some of the distribution: within 8 standard deviations of its centre.
    if (log) {
        const double g2 = spread * spread, g8 = (g2 * g2) * (g2 * g2);
        if (!(low < location * g8))
            refuse(spec, fmt::format("MIN = {} is not below MEDIAN GSD^8 = {}", low, location * g8),
                   allowed_for(kind));
        if (!(high > location / g8))
            refuse(spec,
                   fmt::format("MAX = {} is not above MEDIAN / GSD^8 = {}", high, location / g8),
                   allowed_for(kind));
    } else {
        if (!(low < location + 8.0 * spread))
            refuse(
                spec,
                fmt::format("MIN = {} is not below MEAN + 8 SD = {}", low, location + 8.0 * spread),
                allowed_for(kind));
        if (!(high > location - 8.0 * spread))
            refuse(spec,
                   fmt::format("MAX = {} is not above MEAN - 8 SD = {}", high,
                               location - 8.0 * spread),
                   allowed_for(kind));
    }
    SizeDistribution out;
    out.kind = kind;
    out.spec = std::string(spec);
    out.location = location;
    out.spread = spread;
    out.low = low;
    out.high = high;
    return out;
}

SizeDistribution parse_file(std::string_view spec, std::string_view path_text) {
    const SizeKind kind = SizeKind::file;
    const std::filesystem::path path{std::string(path_text)};
    check_path("--sizes", path);
    std::ifstream input = open_regular_file("--sizes", path);
    const std::string name = printable(path_text);
    auto at = [&](std::size_t line, std::string_view reason) {
        return fmt::format("{}:{}: {}", name, line, reason);
    };
    std::vector<double> diameters, fractions;
    std::vector<std::size_t> lines;
    std::string line;
    bool first = true;
    for (std::size_t number_of_line = 1;; ++number_of_line) {
        const LineRead read = read_line(input, line, limits::max_line_length);
        if (read == LineRead::end)
            break;
        if (read == LineRead::error)
            refuse(spec, at(number_of_line, "the file could not be read"), allowed_for(kind));
        if (read == LineRead::too_long)
            refuse(spec,
                   at(number_of_line,
                      fmt::format("a line longer than {} bytes", limits::max_line_length)),
                   allowed_for(kind));
        const std::string_view text = trim(line);
        if (text.empty() || text.front() == '#')
            continue;
        const bool header = first && ((text.front() >= 'a' && text.front() <= 'z') ||
                                      (text.front() >= 'A' && text.front() <= 'Z'));
        first = false;
        if (header)
            continue;
        const auto fields = split(text, ',');
        if (fields.size() != 2)
            refuse(spec,
                   at(number_of_line, fmt::format("{} fields, not 2 (diameter,cumulative_fraction)",
                                                  fields.size())),
                   allowed_for(kind));
        std::array<double, 2> values{};
        for (std::size_t i = 0; i < 2; ++i) {
            const auto v = parse_finite(trim(fields[i]));
            if (!v)
                refuse(spec,
                       at(number_of_line, fmt::format("'{}' is not a number",
                                                      printable(trim(fields[i]).substr(0, 40)))),
                       allowed_for(kind));
            values[i] = *v;
        }
        const double d = values[0], f = values[1];
        if (!in_diameter_range(d))
            refuse(spec, at(number_of_line, range_reason("diameter", d)), allowed_for(kind));
        if (!(f >= 0.0 && f <= 1.0))
            refuse(spec,
                   at(number_of_line, fmt::format("cumulative fraction {} is not from 0 to 1", f)),
                   allowed_for(kind));
        if (!diameters.empty() && !(d > diameters.back()))
            refuse(spec,
                   at(number_of_line, fmt::format("diameter {} is not above the {} of line {}", d,
                                                  diameters.back(), lines.back())),
                   allowed_for(kind));
        if (!fractions.empty() && f < fractions.back())
            refuse(
                spec,
                at(number_of_line, fmt::format("cumulative fraction {} is below the {} of line {}",
                                               f, fractions.back(), lines.back())),
                allowed_for(kind));
        if (diameters.size() == max_size_rows)
            refuse(spec, fmt::format("{}: more than {} rows", name, max_size_rows),
                   allowed_for(kind));
        diameters.push_back(d);
        fractions.push_back(f);
        lines.push_back(number_of_line);
    }
    if (diameters.size() < 2)
        refuse(spec,
               fmt::format("{} has {} row{} of numbers", name, diameters.size(),
                           diameters.size() == 1 ? "" : "s"),
               allowed_for(kind));
    const double first_f = fractions.front(), last_f = fractions.back();
    if (!(first_f <= fraction_tolerance))
        refuse(
            spec,
            at(lines.front(), fmt::format("the first cumulative fraction is {}, not 0", first_f)),
            allowed_for(kind));
    if (!(last_f >= 1.0 - fraction_tolerance))
        refuse(spec,
               at(lines.back(), fmt::format("the last cumulative fraction is {}, not 1", last_f)),
               allowed_for(kind));
    for (auto& f : fractions)
        f = std::clamp((f - first_f) / (last_f - first_f), 0.0, 1.0);
    // The support: from the last row at 0 to the first at 1.
    std::size_t begin = 0, end = fractions.size() - 1;
    while (fractions[begin + 1] == 0.0)
        ++begin;
    while (fractions[end - 1] == 1.0)
        --end;
    if (diameters[end] / diameters[begin] > max_size_ratio * (1.0 + 1e-12))
        refuse(spec,
               fmt::format("{}: the fraction passing rises from diameter {} (line {}) to {} (line "
                           "{}), a ratio of {:.6g} (the solvers support up to {:g})",
                           name, diameters[begin], lines[begin], diameters[end], lines[end],
                           diameters[end] / diameters[begin], max_size_ratio),
               allowed_for(kind));
    SizeDistribution out;
    out.kind = kind;
    out.spec = std::string(spec);
    out.diameters.assign(diameters.begin() + static_cast<std::ptrdiff_t>(begin),
                         diameters.begin() + static_cast<std::ptrdiff_t>(end) + 1);
    out.fractions.assign(fractions.begin() + static_cast<std::ptrdiff_t>(begin),
                         fractions.begin() + static_cast<std::ptrdiff_t>(end) + 1);
    out.low = out.diameters.front();
    out.high = out.diameters.back();
    return out;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Registries.

const Registry<SizeKind>& size_kinds() {
    static const Registry<SizeKind> names("sizes", {{"mono", SizeKind::mono},
                                                    {"discrete", SizeKind::discrete},
                                                    {"uniform", SizeKind::uniform},
                                                    {"normal", SizeKind::normal},
                                                    {"lognormal", SizeKind::lognormal},
                                                    {"file", SizeKind::file}});
    return names;
}

std::string to_string(SizeKind kind) {
    return size_kinds().name(kind);
}

std::string_view size_syntax(SizeKind kind) {
    switch (kind) {
    case SizeKind::mono:
        return "mono";
    case SizeKind::discrete:
        return "discrete:D1:F1,D2:F2,...";
    case SizeKind::uniform:
        return "uniform:MIN,MAX";
    case SizeKind::normal:
        return "normal:MEAN,SD[,MIN,MAX]";
    case SizeKind::lognormal:
        return "lognormal:MEDIAN,GSD[,MIN,MAX]";
    case SizeKind::file:
        return "file:PATH";
    }
    return "unknown";
}

const Registry<FractionBasis>& fraction_bases() {
    static const Registry<FractionBasis> names(
        "fractions", {{"volume", FractionBasis::volume}, {"number", FractionBasis::number}});
    return names;
}

std::string to_string(FractionBasis basis) {
    return fraction_bases().name(basis);
}

// ---------------------------------------------------------------------------------------------
// Parsing.

SizeDistribution parse_sizes(std::string_view spec, double mono_diameter) {
    const KindSpec parts = split_kind(spec);
    const std::string_view name = parts.kind;
    const std::optional<std::string_view> parameters = parts.parameters;
    const std::string_view rest = parameters.value_or(std::string_view{});
    const std::optional<SizeKind> found = size_kinds().find(name);
    if (!found)
        refuse(spec, fmt::format("unknown distribution '{}'", shown_sizes(name)), allowed_names());
    const SizeKind kind = *found;
    if (kind != SizeKind::mono && !parameters)
        refuse(spec, fmt::format("{} needs its parameters", name), allowed_for(kind));
    switch (kind) {
    case SizeKind::mono: {
        if (parameters)
            refuse(spec, "mono takes no parameters (its diameter is --diameter)",
                   allowed_for(kind));
        if (!in_diameter_range(mono_diameter))
            throw InvalidInput(fmt::format("--diameter = {} is not allowed; allowed: {:g} to {:g}",
                                           mono_diameter, limits::min_diameter,
                                           limits::max_diameter));
        SizeDistribution out;
        out.spec = std::string(spec);
        out.diameters = {mono_diameter};
        out.fractions = {1.0};
        out.low = out.high = mono_diameter;
        return out;
    }
    case SizeKind::discrete:
        return parse_discrete(spec, rest);
    case SizeKind::uniform:
        return parse_uniform(spec, rest);
    case SizeKind::normal:
    case SizeKind::lognormal:
        return parse_bell(spec, rest, kind);
    case SizeKind::file:
        return parse_file(spec, rest);
    }
    refuse(spec, "unknown distribution", allowed_names());
}

} // namespace packbed
