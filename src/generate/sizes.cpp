#include "packbed/sizes.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <optional>
#include <random>

#include <fmt/format.h>

#include "generate/random.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/text.hpp"

namespace packbed {

namespace {

// ---------------------------------------------------------------------------------------------
// Elementary functions from +, -, *, /, sqrt, frexp and ldexp only: IEEE 754 rounds these
// exactly, so the sizes drawn from them are the same bits on every platform, which std::exp,
// std::log and std::erfc (a few ulp, differing between C libraries) do not promise.

constexpr double ln2_hi = 0x1.62e42fee00000p-1;  // ln 2 in two parts (Cody & Waite): k ln2_hi
constexpr double ln2_lo = 0x1.a39ef35793c76p-33; // is exact for |k| < 2^11
constexpr double sqrt_pi = 0x1.c5bf891b4ef6bp0;
constexpr double sqrt_2pi = 0x1.40d931ff62705p1;
constexpr double sqrt_half = 0x1.6a09e667f3bcdp-1;

/// \f$e^x\f$: x = k ln 2 + r with |r| <= ln 2 / 2, \f$e^r\f$ by its Taylor series to r^13
/// (remainder below 4e-18), times 2^k. Within 3e-16 of std::exp.
double exp_portable(double x) {
    if (x < -746.0)
        return 0.0;
    if (x > 709.8)
        return std::numeric_limits<double>::infinity();
    const double k = std::floor(x * 0x1.71547652b82fep0 + 0.5); // x / ln 2, rounded
    const double r = (x - k * ln2_hi) - k * ln2_lo;
    static constexpr std::array<double, 14> inverse_factorial{1.0,
                                                              1.0,
                                                              1.0 / 2,
                                                              1.0 / 6,
                                                              1.0 / 24,
                                                              1.0 / 120,
                                                              1.0 / 720,
                                                              1.0 / 5040,
                                                              1.0 / 40320,
                                                              1.0 / 362880,
                                                              1.0 / 3628800,
                                                              1.0 / 39916800,
                                                              1.0 / 479001600,
                                                              1.0 / 6227020800.0};
    double p = inverse_factorial[13];
    for (int i = 12; i >= 0; --i)
        p = p * r + inverse_factorial[static_cast<std::size_t>(i)];
    const int e = static_cast<int>(k);
    if (e < -1021 || e > 1022)
        return std::ldexp(p, e);
    // 2^e from its bits: exact, and cheaper than ldexp.
    return p * std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52);
}

/// ln x for x > 0: x = m 2^e with m in [sqrt(1/2), sqrt 2), \f$\ln m = 2\,\mathrm{atanh}\,s\f$,
/// s = (m - 1) / (m + 1), |s| <= 0.172, by its series to s^25. Within 5e-16 of std::log.
double log_portable(double x) {
    int e = 0;
    double m = std::frexp(x, &e);
    if (m < sqrt_half) {
        m *= 2.0;
        --e;
    }
    const double s = (m - 1.0) / (m + 1.0), s2 = s * s;
    double sum = 1.0 / 25.0;
    for (int k = 11; k >= 0; --k)
        sum = sum * s2 + 1.0 / (2 * k + 1);
    return e * ln2_hi + (e * ln2_lo + 2.0 * s * sum);
}

/// \f$e^{-x^2}\f$ without the rounding of x^2 (which alone costs x^2 1.1e-16 relative):
/// x = h + l with h holding 26 significant bits, so that h^2 is exact.
double exp_minus_square(double x) {
    const double h = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) & ~((1ull << 27) - 1));
    return exp_portable(-h * h) * exp_portable((h - x) * (h + x));
}

/// erfc x for x >= 0. Below 1: 1 - erf x with Abramowitz & Stegun 7.1.6,
/// \f$\mathrm{erf}\,x = \frac{2}{\sqrt\pi} e^{-x^2} \sum_n \frac{2^n x^{2n+1}}{1 \cdot 3 \cdots
/// (2n+1)}\f$ (positive terms). From 1: the continued fraction A&S 7.1.14,
/// \f$\mathrm{erfc}\,x = \frac{e^{-x^2}}{\sqrt\pi}\,\cfrac{1}{x + \cfrac{1/2}{x + \cfrac{1}{x +
/// \cfrac{3/2}{x + \cdots}}}}\f$, evaluated from a fixed depth (200 terms at 1, 40 from 2.5).
/// Within 1e-15 relative of std::erfc up to x = 26.
double erfc_portable(double x) {
    if (x < 1.0) {
        double term = x, sum = x;
        const double two_x2 = 2.0 * x * x;
        for (int n = 1; n < 100 && term > 1e-17 * sum; ++n) {
            term *= two_x2 / (2 * n + 1);
            sum += term;
        }
        return 1.0 - 2.0 / sqrt_pi * exp_minus_square(x) * sum;
    }
    const int depth = x < 1.5 ? 200 : x < 2.5 ? 100 : 40;
    double t = x;
    for (int k = depth; k >= 1; --k)
        t = x + (0.5 * k) / t;
    return exp_minus_square(x) / (sqrt_pi * t);
}

/// \f$\Phi(z)\f$, the standard normal cumulative distribution, with its relative precision
/// kept in the lower tail.
double normal_lower(double z) {
    return z <= 0.0 ? 0.5 * erfc_portable(-z * sqrt_half)
                    : 1.0 - 0.5 * erfc_portable(z * sqrt_half);
}

/// \f$1 - \Phi(z) = \Phi(-z)\f$, precise in the upper tail.
double normal_upper(double z) {
    return normal_lower(-z);
}

/// \return z <= 0 with \f$\Phi(z) = p\f$ for p in [0, 1/2]: Acklam's rational approximation
/// (relative error below 1.2e-9; P. J. Acklam, "An algorithm for computing the inverse normal
/// cumulative distribution function", 2003), then one step of Halley's method on
/// \f$\Phi(z) - p\f$, which takes it to about 1e-16.
double normal_lower_quantile(double p) {
    if (!(p > 0.0))
        return -std::numeric_limits<double>::infinity();
    static constexpr std::array<double, 6> a{-3.969683028665376e+01, 2.209460984245205e+02,
                                             -2.759285104469687e+02, 1.383577518672690e+02,
                                             -3.066479806614716e+01, 2.506628277459239e+00};
    static constexpr std::array<double, 5> b{-5.447609879822406e+01, 1.615858368580409e+02,
                                             -1.556989798598866e+02, 6.680131188771972e+01,
                                             -1.328068155288572e+01};
    static constexpr std::array<double, 6> c{-7.784894002430293e-03, -3.223964580411365e-01,
                                             -2.400758277161838e+00, -2.549732539343734e+00,
                                             4.374664141464968e+00,  2.938163982698783e+00};
    static constexpr std::array<double, 4> d{7.784695709041462e-03, 3.224671290700398e-01,
                                             2.445134137142996e+00, 3.754408661907416e+00};
    double z = 0.0;
    if (p < 0.02425) {
        const double q = std::sqrt(-2.0 * log_portable(p));
        z = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    } else {
        const double q = p - 0.5, r = q * q;
        z = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
            (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
    }
    if (p < 1e-300) // the density below would overflow; Acklam alone is within 1.2e-9 there
        return z;
    const double u = (normal_lower(z) - p) * sqrt_2pi * exp_portable(0.5 * z * z);
    return z - u / (1.0 + 0.5 * z * u);
}

/// \return z with \f$\Phi(z) = p\f$, p in [0, 1].
double normal_quantile(double p) {
    return p <= 0.5 ? normal_lower_quantile(p) : -normal_lower_quantile(1.0 - p);
}

/// The standard normal truncated to [alpha, beta]. Where the interval lies mostly above 0 it
/// works with upper tails, so that an interval far out in either tail keeps its precision.
class TruncatedNormal {
public:
    TruncatedNormal() = default;
    TruncatedNormal(double alpha, double beta)
        : m_alpha(alpha)
        , m_beta(beta)
        , m_upper(alpha + beta > 0.0)
        , m_p_alpha(m_upper ? normal_upper(alpha) : normal_lower(alpha))
        , m_p_beta(m_upper ? normal_upper(beta) : normal_lower(beta)) {}

    /// \return the fraction of the truncated distribution at most z.
    double cumulative(double z) const {
        z = std::clamp(z, m_alpha, m_beta);
        const double f = m_upper ? (m_p_alpha - normal_upper(z)) / (m_p_alpha - m_p_beta)
                                 : (normal_lower(z) - m_p_alpha) / (m_p_beta - m_p_alpha);
        return std::clamp(f, 0.0, 1.0);
    }
    /// \return z with cumulative(z) = t.
    double quantile(double t) const {
        const double z = m_upper ? -normal_quantile(m_p_beta + (1.0 - t) * (m_p_alpha - m_p_beta))
                                 : normal_quantile(m_p_alpha + t * (m_p_beta - m_p_alpha));
        return std::clamp(z, m_alpha, m_beta);
    }

private:
    double m_alpha = 0.0, m_beta = 0.0;
    bool m_upper = false;
    double m_p_alpha = 0.0, m_p_beta = 1.0; ///< Phi (or 1 - Phi, upper) at alpha and beta
};

/// Neumaier's compensated sum: the result of a long sum to about one rounding, in the order
/// the terms are added.
class CompensatedSum {
public:
    void add(double x) {
        const double t = m_sum + x;
        m_correction += std::fabs(m_sum) >= std::fabs(x) ? (m_sum - t) + x : (x - t) + m_sum;
        m_sum = t;
    }
    double value() const { return m_sum + m_correction; }

private:
    double m_sum = 0.0, m_correction = 0.0;
};

/// Gauss-Legendre 8-point rule on [-1, 1]: nodes +-x_i, weights w_i.
constexpr std::array<double, 4> gl8_nodes{0.1834346424956498049394761, 0.5255324099163289858177390,
                                          0.7966664774136267395915539, 0.9602898564975362316835609};
constexpr std::array<double, 4> gl8_weights{
    0.3626837833783619829651504, 0.3137066458778872873379622, 0.2223810344533744705443560,
    0.1012285362903762591525314};

// ---------------------------------------------------------------------------------------------
// Messages.

/// The spec as messages show it: control characters escaped, cut after 100 bytes.
std::string shown(std::string_view spec) {
    return spec.size() > 100 ? printable(spec.substr(0, 100)) + "..." : printable(spec);
}

[[noreturn]] void refuse(std::string_view spec, std::string_view reason, std::string_view allowed) {
    throw InvalidInput(
        fmt::format("--sizes '{}' is not allowed: {}; allowed: {}", shown(spec), reason, allowed));
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
        return fmt::format("normal:MEAN,SD or normal:MEAN,SD,MIN,MAX with MEAN from {:g} to {:g}, "
                           "SD > 0, {:g} <= MIN < MAX <= {:g}, MAX <= {:g} MIN, MIN < MEAN + 8 SD "
                           "and MAX > MEAN - 8 SD (by default MIN = MEAN - 3 SD, at least MAX / "
                           "{:g}, and MAX = MEAN + 3 SD)",
                           lo, hi, lo, hi, ratio, ratio);
    case SizeKind::lognormal:
        return fmt::format("lognormal:MEDIAN,GSD or lognormal:MEDIAN,GSD,MIN,MAX with MEDIAN from "
                           "{:g} to {:g}, GSD > 1, {:g} <= MIN < MAX <= {:g}, MAX <= {:g} MIN, "
                           "MIN < MEDIAN GSD^8 and MAX > MEDIAN / GSD^8 (by default MEDIAN / GSD^3 "
                           "to MEDIAN GSD^3, narrowed to MAX = {:g} MIN)",
                           lo, hi, lo, hi, ratio, ratio);
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
        refuse(spec, fmt::format("unknown distribution '{}'", shown(name)), allowed_names());
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

// ---------------------------------------------------------------------------------------------
// The number distribution.

struct NumberDistribution::Impl {
    enum class Form {
        steps,          ///< mono, discrete: m_x the sizes, m_c cumulative number fractions
        linear,         ///< Q0 linear between the nodes (m_x, m_c)
        inverse_square, ///< Q3 linear between the nodes: Q0 linear in d^-2 on each interval;
                        ///< m_c the cumulative number (times low^3) at the nodes
        gaussian,       ///< normal by number: (d - location) / scale truncated standard normal
        log_gaussian,   ///< lognormal: (ln d - location) / scale truncated standard normal
        tabulated,      ///< normal by volume: m_c the integral of q0 at the nodes m_x
    };
    Form form = Form::steps;
    double low = 0.0, high = 0.0;
    std::vector<double> x, c;
    double location = 0.0, scale = 1.0;
    double size_scale = 1.0; ///< tabulated: the lower bound, scaling the density near 1
    TruncatedNormal standard;

    /// The unnormalised q0 of `tabulated`: \f$e^{-((d - \mu)/\sigma)^2/2} (s / d)^3\f$.
    double density(double d) const {
        const double z = (d - location) / scale, r = size_scale / d;
        return exp_portable(-0.5 * z * z) * (r * r * r);
    }
    /// \f$\int_a^b\f$ density: Gauss-Legendre with 8 points (b - a <= 0.1 sigma and 0.05 low).
    double integral(double a, double b) const {
        const double half = 0.5 * (b - a), middle = 0.5 * (a + b);
        double sum = 0.0;
        for (std::size_t i = 0; i < gl8_nodes.size(); ++i)
            sum += gl8_weights[i] *
                   (density(middle - half * gl8_nodes[i]) + density(middle + half * gl8_nodes[i]));
        return half * sum;
    }
    /// The interval k of the nodes with c[k] < target <= c[k + 1] (0 for target <= 0).
    std::size_t interval_of_mass(double target) const {
        const auto it = std::lower_bound(c.begin() + 1, c.end() - 1, target);
        return static_cast<std::size_t>(it - c.begin()) - 1;
    }
    /// The interval k of the nodes with x[k] <= d < x[k + 1] (the last for d = high).
    std::size_t interval_of_diameter(double d) const {
        const auto it = std::upper_bound(x.begin() + 1, x.end() - 1, d);
        return static_cast<std::size_t>(it - x.begin()) - 1;
    }
};

NumberDistribution::NumberDistribution(const SizeDistribution& sizes, FractionBasis basis) {
    auto impl = std::make_shared<Impl>();
    using Form = Impl::Form;
    impl->low = sizes.low;
    impl->high = sizes.high;
    switch (sizes.kind) {
    case SizeKind::mono:
    case SizeKind::discrete: {
        impl->form = Form::steps;
        impl->x = sizes.diameters;
        const auto x = number_fractions(sizes, basis);
        CompensatedSum sum;
        for (const double f : x) {
            sum.add(f);
            impl->c.push_back(std::min(sum.value(), 1.0));
        }
        // The last size with a fraction reaches 1 exactly.
        for (std::size_t k = x.size(); k-- > 0;) {
            impl->c[k] = 1.0;
            if (x[k] > 0.0)
                break;
        }
        break;
    }
    case SizeKind::uniform:
    case SizeKind::file:
        impl->x = sizes.diameters;
        if (basis == FractionBasis::number) {
            impl->form = Form::linear;
            impl->c = sizes.fractions;
        } else {
            // q3 = dF / dd constant on each interval, so q0 = q3 / d^3 integrates to
            // dF (d_i + d_{i+1}) / (2 d_i^2 d_{i+1}^2), here times low^3.
            impl->form = Form::inverse_square;
            CompensatedSum sum;
            impl->c.push_back(0.0);
            for (std::size_t i = 0; i + 1 < impl->x.size(); ++i) {
                const double a = impl->x[i], b = impl->x[i + 1];
                const double ra = sizes.low / a, rb = sizes.low / b;
                sum.add((sizes.fractions[i + 1] - sizes.fractions[i]) * 0.5 * (ra * ra) *
                        (rb * rb) * ((a + b) / sizes.low));
                impl->c.push_back(sum.value());
            }
        }
        break;
    case SizeKind::lognormal: {
        impl->form = Form::log_gaussian;
        impl->scale = log_portable(sizes.spread);
        // Hatch & Choate (1929): q3 lognormal with median M gives q0 lognormal with median
        // M exp(-3 sigma^2), the same sigma.
        impl->location = log_portable(sizes.location) -
                         (basis == FractionBasis::volume ? 3.0 * impl->scale * impl->scale : 0.0);
        impl->standard = TruncatedNormal((log_portable(sizes.low) - impl->location) / impl->scale,
                                         (log_portable(sizes.high) - impl->location) / impl->scale);
        break;
    }
    case SizeKind::normal:
        impl->location = sizes.location;
        impl->scale = sizes.spread;
        if (basis == FractionBasis::number) {
            impl->form = Form::gaussian;
            impl->standard = TruncatedNormal((sizes.low - sizes.location) / sizes.spread,
                                             (sizes.high - sizes.location) / sizes.spread);
        } else {
            // q0 proportional to the normal density over d^3 has no closed form: tabulated at
            // nodes 0.1 sigma and 0.05 low apart at most, from 40 sigma around the mean
            // (beyond, the density is below 1e-347 of its peak).
            impl->form = Form::tabulated;
            const double a = std::max(sizes.low, sizes.location - 40.0 * sizes.spread);
            const double b = std::min(sizes.high, sizes.location + 40.0 * sizes.spread);
            impl->low = a;
            impl->high = b;
            const double step = std::min(0.1 * sizes.spread, 0.05 * a);
            const auto intervals =
                static_cast<std::size_t>(std::clamp(std::ceil((b - a) / step), 1.0, 1e6));
            impl->x.resize(intervals + 1);
            for (std::size_t j = 0; j <= intervals; ++j)
                impl->x[j] =
                    j == intervals
                        ? b
                        : a + (b - a) * (static_cast<double>(j) / static_cast<double>(intervals));
            impl->size_scale = a;
            CompensatedSum sum;
            impl->c.push_back(0.0);
            for (std::size_t j = 0; j < intervals; ++j) {
                sum.add(impl->integral(impl->x[j], impl->x[j + 1]));
                impl->c.push_back(sum.value());
            }
        }
        break;
    }
    m_impl = std::move(impl);
}

double NumberDistribution::cumulative(double diameter) const {
    const Impl& d = *m_impl;
    using Form = Impl::Form;
    if (d.form == Form::steps) {
        const auto k = static_cast<std::size_t>(std::upper_bound(d.x.begin(), d.x.end(), diameter) -
                                                d.x.begin());
        return k == 0 ? 0.0 : d.c[k - 1];
    }
    if (!(diameter > d.low))
        return 0.0;
    if (!(diameter < d.high))
        return 1.0;
    switch (d.form) {
    case Form::linear: {
        const std::size_t i = d.interval_of_diameter(diameter);
        const double w = (diameter - d.x[i]) / (d.x[i + 1] - d.x[i]);
        return std::clamp(d.c[i] + w * (d.c[i + 1] - d.c[i]), 0.0, 1.0);
    }
    case Form::inverse_square: {
        // The part of interval i below d: (a^-2 - d^-2) / (a^-2 - b^-2).
        const std::size_t i = d.interval_of_diameter(diameter);
        const double a = d.x[i], b = d.x[i + 1];
        const double w = ((diameter - a) * (diameter + a) * (b * b)) /
                         ((b - a) * (b + a) * (diameter * diameter));
        return std::clamp((d.c[i] + w * (d.c[i + 1] - d.c[i])) / d.c.back(), 0.0, 1.0);
    }
    case Form::gaussian:
        return d.standard.cumulative((diameter - d.location) / d.scale);
    case Form::log_gaussian:
        return d.standard.cumulative((log_portable(diameter) - d.location) / d.scale);
    case Form::tabulated: {
        const std::size_t i = d.interval_of_diameter(diameter);
        return std::clamp((d.c[i] + d.integral(d.x[i], diameter)) / d.c.back(), 0.0, 1.0);
    }
    case Form::steps:
        break;
    }
    return 0.0;
}

double NumberDistribution::quantile(double fraction) const {
    const Impl& d = *m_impl;
    using Form = Impl::Form;
    const double t = std::clamp(fraction, 0.0, 1.0);
    if (d.form != Form::steps) { // the bounds themselves, not their rounded images
        if (!(t > 0.0))
            return d.low;
        if (!(t < 1.0))
            return d.high;
    }
    switch (d.form) {
    case Form::steps: {
        if (!(t > 0.0))
            return d.low;
        const auto k =
            static_cast<std::size_t>(std::lower_bound(d.c.begin(), d.c.end(), t) - d.c.begin());
        return d.x[std::min(k, d.x.size() - 1)];
    }
    case Form::linear: {
        const std::size_t i = d.interval_of_mass(t);
        const double w = (t - d.c[i]) / (d.c[i + 1] - d.c[i]);
        return std::clamp(d.x[i] + w * (d.x[i + 1] - d.x[i]), d.x[i], d.x[i + 1]);
    }
    case Form::inverse_square: {
        // d^-2 is linear in the mass within an interval.
        const double target = t * d.c.back();
        const std::size_t i = d.interval_of_mass(target);
        const double a = d.x[i], b = d.x[i + 1];
        const double w = std::clamp((target - d.c[i]) / (d.c[i + 1] - d.c[i]), 0.0, 1.0);
        const double r = a / b;
        return std::clamp(a / std::sqrt((1.0 - w) + w * (r * r)), a, b);
    }
    case Form::gaussian:
        return std::clamp(d.location + d.scale * d.standard.quantile(t), d.low, d.high);
    case Form::log_gaussian:
        return std::clamp(exp_portable(d.location + d.scale * d.standard.quantile(t)), d.low,
                          d.high);
    case Form::tabulated: {
        // Newton's method on the integral from the interval's node, kept inside the interval
        // (bisection where a step would leave it). It converges quadratically with an error
        // below (|q0'| / 2 q0) step^2 <= 2 step^2 / width: a step of 1e-9 of the interval's
        // width leaves an error below 2e-18 of it.
        const double target = t * d.c.back();
        const std::size_t i = d.interval_of_mass(target);
        double a = d.x[i], b = d.x[i + 1];
        const double node = a, base = d.c[i], width = b - a;
        double x = a + width * std::clamp((target - base) / (d.c[i + 1] - base), 0.0, 1.0);
        for (int iteration = 0; iteration < 100; ++iteration) {
            const double g = base + d.integral(node, x) - target;
            if (g == 0.0)
                break;
            (g > 0.0 ? b : a) = x;
            const double slope = d.density(x);
            const double step = slope > 0.0 ? g / slope : width;
            if (std::fabs(step) <= 1e-9 * width) { // converged (above): the last step
                x -= step;
                break;
            }
            x = x - step > a && x - step < b ? x - step : 0.5 * (a + b);
            if (!(a < b))
                break;
        }
        return std::clamp(x, d.x[i], d.x[i + 1]);
    }
    }
    return d.low;
}

// ---------------------------------------------------------------------------------------------
// Drawing.

std::vector<double> number_fractions(const SizeDistribution& sizes, FractionBasis basis) {
    if (sizes.kind != SizeKind::mono && sizes.kind != SizeKind::discrete)
        return {};
    std::vector<double> x(sizes.fractions.size());
    CompensatedSum sum;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double r = sizes.diameters[k] / sizes.low; // scaled: no overflow at any size
        x[k] =
            basis == FractionBasis::volume ? sizes.fractions[k] / (r * r * r) : sizes.fractions[k];
        sum.add(x[k]);
    }
    const double total = sum.value();
    for (auto& f : x)
        f /= total;
    return x;
}

std::vector<std::size_t> discrete_counts(const SizeDistribution& sizes, FractionBasis basis,
                                         std::size_t count) {
    const auto x = number_fractions(sizes, basis);
    std::vector<std::size_t> counts(x.size(), 0);
    std::vector<double> remainders(x.size(), 0.0);
    std::size_t given = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double exact = static_cast<double>(count) * x[k];
        counts[k] = std::min(static_cast<std::size_t>(std::floor(exact)), count);
        remainders[k] = exact - std::floor(exact);
        given += counts[k];
    }
    // Largest remainders first, ties to the smaller size (stable order).
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t i, std::size_t j) { return remainders[i] > remainders[j]; });
    for (std::size_t k = 0; given < count && !order.empty(); k = (k + 1) % order.size()) {
        if (x[order[k]] > 0.0) {
            ++counts[order[k]];
            ++given;
        }
    }
    while (given > count) // only if the floors summed above count through rounding
        for (std::size_t k = order.size(); k-- > 0 && given > count;)
            if (counts[order[k]] > 0) {
                --counts[order[k]];
                --given;
            }
    return counts;
}

std::vector<double> draw_diameters(const SizeDistribution& sizes, std::size_t count,
                                   FractionBasis basis, std::uint64_t seed) {
    if (sizes.kind == SizeKind::mono)
        return std::vector<double>(count, sizes.diameters.front());
    std::vector<double> out;
    out.reserve(count);
    std::mt19937_64 rng(seed);
    if (sizes.kind == SizeKind::discrete) {
        const auto counts = discrete_counts(sizes, basis, count);
        for (std::size_t k = 0; k < counts.size(); ++k)
            out.insert(out.end(), counts[k], sizes.diameters[k]);
    } else {
        const NumberDistribution law(sizes, basis);
        const double n = static_cast<double>(count);
        for (std::size_t i = 0; i < count; ++i)
            out.push_back(
                law.quantile((static_cast<double>(i) + portable_random::uniform01(rng)) / n));
    }
    portable_random::shuffle(std::span<double>(out), rng);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Statistics.

namespace {

void check_diameters(std::span<const double> diameters) {
    for (std::size_t i = 0; i < diameters.size(); ++i)
        if (!(std::isfinite(diameters[i]) && diameters[i] > 0.0))
            throw InvalidInput(fmt::format("size statistics: diameter {} of sphere {} is not "
                                           "allowed; allowed: a finite number > 0",
                                           diameters[i], i + 1));
}

/// size_classes of diameters already sorted and checked.
std::vector<SizeClass> classes_of_sorted(std::span<const double> sorted, std::size_t bins) {
    std::vector<SizeClass> classes;
    if (sorted.empty())
        return classes;
    std::vector<double> distinct;
    for (const double d : sorted) {
        if (distinct.empty() || d != distinct.back())
            distinct.push_back(d);
        if (distinct.size() > max_discrete_classes)
            break;
    }
    if (distinct.size() <= max_discrete_classes) {
        for (const double d : distinct)
            classes.push_back(SizeClass{d, d, 0, 0.0, 0.0});
        return classes;
    }
    bins = std::max<std::size_t>(bins, 1);
    const double smallest = sorted.front(), largest = sorted.back();
    const double log_ratio = log_portable(largest / smallest);
    std::vector<double> edges(bins + 1);
    for (std::size_t j = 0; j <= bins; ++j)
        edges[j] = j == 0      ? smallest
                   : j == bins ? largest
                               : smallest * exp_portable(log_ratio * static_cast<double>(j) /
                                                         static_cast<double>(bins));
    for (std::size_t j = 0; j < bins; ++j)
        classes.push_back(SizeClass{edges[j], edges[j + 1], 0, 0.0, 0.0});
    return classes;
}

} // namespace

std::vector<SizeClass> size_classes(std::span<const double> diameters, std::size_t bins) {
    check_diameters(diameters);
    std::vector<double> sorted(diameters.begin(), diameters.end());
    std::sort(sorted.begin(), sorted.end());
    return classes_of_sorted(sorted, bins);
}

std::size_t size_class_of(std::span<const SizeClass> classes, double diameter) {
    const auto it = std::upper_bound(classes.begin(), classes.end(), diameter,
                                     [](double d, const SizeClass& c) { return d < c.low; });
    return it == classes.begin() ? 0 : static_cast<std::size_t>(it - classes.begin()) - 1;
}

SizeStatistics size_statistics(std::span<const double> diameters, std::size_t bins) {
    check_diameters(diameters);
    SizeStatistics s;
    if (diameters.empty())
        return s;
    std::vector<double> sorted(diameters.begin(), diameters.end());
    std::sort(sorted.begin(), sorted.end());
    s.classes = classes_of_sorted(sorted, bins);
    s.count = sorted.size();
    s.smallest = sorted.front();
    s.largest = sorted.back();
    s.size_ratio = s.largest / s.smallest;

    // Moments, the volume of each class, and Q3 at each distinct diameter.
    CompensatedSum m1, m2, m3, m4;
    std::vector<CompensatedSum> class_volume(s.classes.size());
    std::vector<double> distinct, cumulative;
    std::size_t j = 0;
    for (const double d : sorted) {
        const double d2 = d * d, d3 = d2 * d;
        m1.add(d);
        m2.add(d2);
        m3.add(d3);
        m4.add(d3 * d);
        while (j + 1 < s.classes.size() && d >= s.classes[j + 1].low)
            ++j;
        ++s.classes[j].count;
        class_volume[j].add(d3);
        if (distinct.empty() || d != distinct.back()) {
            distinct.push_back(d);
            cumulative.push_back(0.0);
        }
        cumulative.back() = m3.value();
    }
    const double n = static_cast<double>(s.count), volume = m3.value();
    s.number_mean = m1.value() / n;
    s.sauter_mean = volume / m2.value();
    s.volume_mean = m4.value() / volume;
    CompensatedSum squares;
    for (const double d : sorted)
        squares.add((d - s.number_mean) * (d - s.number_mean));
    s.number_sd = std::sqrt(squares.value() / n);
    for (std::size_t k = 0; k < s.classes.size(); ++k) {
        s.classes[k].number_fraction = static_cast<double>(s.classes[k].count) / n;
        s.classes[k].volume_fraction = class_volume[k].value() / volume;
    }

    // d_p: Q3 is 0 at the smallest diameter, cumulative[i] / volume at distinct[i], linear in
    // between; the first diameter where it reaches p.
    auto at_fraction = [&](double p) {
        for (std::size_t i = 0; i < distinct.size(); ++i) {
            const double q = cumulative[i] / volume;
            if (q >= p) {
                if (i == 0)
                    return distinct[0];
                const double q0 = cumulative[i - 1] / volume;
                return distinct[i - 1] + (p - q0) / (q - q0) * (distinct[i] - distinct[i - 1]);
            }
        }
        return distinct.back();
    };
    s.d10 = at_fraction(0.1);
    s.d50 = at_fraction(0.5);
    s.d90 = at_fraction(0.9);
    return s;
}

} // namespace packbed
