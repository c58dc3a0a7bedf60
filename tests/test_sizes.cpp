// Particle-size distributions: parsing, exact discrete counts, sampled moments against
// the formulas, the sieve-file inverse, determinism, statistics and every refusal word for word.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/sizes.hpp"

using namespace packbed;
namespace fs = std::filesystem;

namespace {

constexpr double pi = 3.14159265358979323846;

fs::path scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path d = fs::temp_directory_path() / "packbed-test-sizes" /
                       (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

fs::path write_file(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

template <class F> std::string refusal(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

std::string refusal_of(const std::string& spec) {
    return refusal([&] { parse_sizes(spec, 1.0); });
}

/// FNV-1a over the bits of the doubles: the same value on every platform.
std::uint64_t fingerprint(const std::vector<double>& values) {
    std::uint64_t h = 1469598103934665603ull;
    for (const double v : values) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        for (int i = 0; i < 8; ++i) {
            h ^= (bits >> (8 * i)) & 0xff;
            h *= 1099511628211ull;
        }
    }
    return h;
}

double phi(double z) {
    return std::exp(-0.5 * z * z) / std::sqrt(2.0 * pi);
}
double Phi(double z) {
    return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

/// Composite Simpson's rule with `intervals` (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int intervals) {
    const double h = (b - a) / intervals;
    double sum = f(a) + f(b);
    for (int i = 1; i < intervals; ++i)
        sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
    return sum * h / 3.0;
}

/// Moments of a density on [a, b] by converged quadrature: E[d], Var[d] under f and under
/// d^3 f (by volume) or f / d^3 (a volume density turned into a number density).
struct Expected {
    double mean, variance;
};
Expected expected(const std::function<double(double)>& f, double a, double b) {
    const int n = 200000;
    const double z = simpson(f, a, b, n);
    const double m = simpson([&](double x) { return x * f(x); }, a, b, n) / z;
    const double v = simpson([&](double x) { return (x - m) * (x - m) * f(x); }, a, b, n) / z;
    return {m, v};
}

constexpr std::size_t n_moments = 200000;

/// Draw n_moments diameters and compare their mean and variance by number, and by volume (each
/// diameter weighted by d^3), with those of the number density q0 (`number`) and the volume
/// density q3 (`volume`). The tolerance is 5 standard errors of the stratified draws: sphere i
/// comes from the stratum [Q0^-1(i/n), Q0^-1((i+1)/n)], so a sum of d^k over the spheres has
/// a variance below sum_i (range of d^k over stratum i)^2 / 4 (Popoviciu); the strata at the
/// bounds of a distribution truncated far out in its tail dominate it.
void expect_moments(const std::string& spec, FractionBasis basis, Expected number,
                    Expected volume) {
    SCOPED_TRACE(spec + " by " + to_string(basis));
    const auto sizes = parse_sizes(spec, 1.0);
    const auto d = draw_diameters(sizes, n_moments, basis, 7);
    const NumberDistribution law(sizes, basis);
    const double n = static_cast<double>(n_moments);
    std::array<double, 6> sum{}, se{};
    for (const double x : d)
        for (int k = 1; k <= 5; ++k)
            sum[k] += std::pow(x, k) / n;
    double previous = law.quantile(0.0);
    for (std::size_t i = 1; i <= n_moments; ++i) {
        const double q = law.quantile(static_cast<double>(i) / n);
        for (int k = 1; k <= 5; ++k)
            se[k] += std::pow(std::pow(q, k) - std::pow(previous, k), 2) / 4.0;
        previous = q;
    }
    for (int k = 1; k <= 5; ++k)
        se[k] = 5.0 * std::sqrt(se[k]) / n;
    const double mean = sum[1], variance = sum[2] - sum[1] * sum[1];
    const double volume_mean = sum[4] / sum[3];
    const double volume_variance = sum[5] / sum[3] - volume_mean * volume_mean;
    const double mean_tolerance = se[1] + 1e-12;
    const double variance_tolerance = se[2] + 2.0 * mean * se[1] + 1e-12;
    const double volume_mean_tolerance = (se[4] + volume_mean * se[3]) / sum[3] + 1e-12;
    const double volume_variance_tolerance =
        (se[5] + sum[5] / sum[3] * se[3]) / sum[3] + 2.0 * volume_mean * volume_mean_tolerance;
    EXPECT_NEAR(mean, number.mean, mean_tolerance);
    EXPECT_NEAR(variance, number.variance, variance_tolerance);
    EXPECT_NEAR(volume_mean, volume.mean, volume_mean_tolerance);
    EXPECT_NEAR(volume_variance, volume.variance, volume_variance_tolerance);
    // Sharp enough to fail: a mean off by 1e-5 of itself would (the volume variance of a
    // distribution truncated far out in its tail is known to a few per cent only).
    EXPECT_LT(mean_tolerance, 1e-5 * mean);
    EXPECT_LT(variance_tolerance, 2e-2 * variance);
    EXPECT_LT(volume_mean_tolerance, 1e-3 * volume_mean);
}

/// Moments of the standard normal truncated to [alpha, beta] (Johnson, Kotz & Balakrishnan,
/// Continuous Univariate Distributions 1, 2nd ed., section on the truncated normal), scaled to mean
/// mu and standard deviation sigma.
Expected truncated_normal(double mu, double sigma, double a, double b) {
    const double alpha = (a - mu) / sigma, beta = (b - mu) / sigma;
    const double z = Phi(beta) - Phi(alpha);
    const double r = (phi(alpha) - phi(beta)) / z;
    return {mu + sigma * r,
            sigma * sigma * (1.0 + (alpha * phi(alpha) - beta * phi(beta)) / z - r * r)};
}

/// E[d^k] of ln d ~ N(mu, s^2) truncated to [a, b]: \f$e^{k\mu + k^2 s^2/2}
/// \frac{\Phi(\beta - ks) - \Phi(\alpha - ks)}{\Phi(\beta) - \Phi(\alpha)}\f$.
double lognormal_moment(double mu, double s, double a, double b, double k) {
    const double alpha = (std::log(a) - mu) / s, beta = (std::log(b) - mu) / s;
    return std::exp(k * mu + 0.5 * k * k * s * s) * (Phi(beta - k * s) - Phi(alpha - k * s)) /
           (Phi(beta) - Phi(alpha));
}

Expected from_raw(double m1, double m2) {
    return {m1, m2 - m1 * m1};
}

const std::vector<std::string> continuous_specs{
    "uniform:1,2",         "uniform:0.3,3",        "normal:1,0.1",    "normal:1,0.2,0.6,1.8",
    "normal:1,0.4",        "normal:2,0.3,2.9,3.5", "lognormal:1,1.3", "lognormal:1,1.5",
    "lognormal:2,1.2,1,5", "lognormal:1,1.1,1.5,2"};

} // namespace

// ---------------------------------------------------------------------------------------------
// Registries and parsing.

TEST(SizeRegistry, NamesRoundTrip) {
    std::vector<std::string> names;
    for (const auto& [name, kind] : size_kinds()) {
        names.push_back(name);
        EXPECT_EQ(to_string(kind), name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"mono", "discrete", "uniform", "normal", "lognormal",
                                               "file"}));
    EXPECT_EQ(size_syntax(SizeKind::lognormal), "lognormal:MEDIAN,GSD[,MIN,MAX]");
    ASSERT_EQ(fraction_bases().size(), 2u);
    EXPECT_EQ(fraction_bases().names().front(), "volume"); // the default first
    EXPECT_EQ(to_string(FractionBasis::number), "number");
}

TEST(ParseSizes, EachKindWithItsBounds) {
    const auto mono = parse_sizes("mono", 0.25);
    EXPECT_EQ(mono.kind, SizeKind::mono);
    EXPECT_EQ(mono.diameters, std::vector<double>{0.25});
    EXPECT_EQ(mono.low, 0.25);
    EXPECT_EQ(mono.high, 0.25);

    // Sorted by diameter; fractions within the tolerance rescaled to add up to 1.
    const auto mix = parse_sizes("discrete:2:0.5000001,1:0.5,3:0", 1.0);
    EXPECT_EQ(mix.diameters, (std::vector<double>{1, 2, 3}));
    EXPECT_NEAR(mix.fractions[0], 0.5 / 1.0000001, 1e-15);
    EXPECT_EQ(mix.fractions[2], 0.0);
    EXPECT_EQ(mix.low, 1.0);
    EXPECT_EQ(mix.high, 2.0); // a size with fraction 0 is never drawn

    const auto uniform = parse_sizes("uniform:1e-3,2e-3", 1.0);
    EXPECT_EQ(uniform.low, 1e-3);
    EXPECT_EQ(uniform.high, 2e-3);

    const auto normal = parse_sizes("normal:1,0.1", 1.0);
    EXPECT_DOUBLE_EQ(normal.low, 0.7);
    EXPECT_DOUBLE_EQ(normal.high, 1.3);
    // MEAN - 3 SD below MAX / 10: raised to MAX / 10.
    const auto wide = parse_sizes("normal:1,0.5", 1.0);
    EXPECT_DOUBLE_EQ(wide.high, 2.5);
    EXPECT_DOUBLE_EQ(wide.low, 0.25);
    const auto given = parse_sizes("normal:1,0.2,0.6,1.8", 1.0);
    EXPECT_EQ(given.low, 0.6);
    EXPECT_EQ(given.high, 1.8);

    const auto log = parse_sizes("lognormal:2,1.2", 1.0);
    EXPECT_DOUBLE_EQ(log.low, 2.0 / (1.2 * 1.2 * 1.2));
    EXPECT_DOUBLE_EQ(log.high, 2.0 * 1.2 * 1.2 * 1.2);
    // GSD^6 = 11.4 > 10: narrowed about the median to a ratio of 10.
    const auto broad = parse_sizes("lognormal:1,1.5", 1.0);
    EXPECT_DOUBLE_EQ(broad.low, 1.0 / std::sqrt(10.0));
    EXPECT_DOUBLE_EQ(broad.high, std::sqrt(10.0));
    EXPECT_NEAR(broad.size_ratio(), max_size_ratio, 1e-12);
}

TEST(ParseSizes, SieveFileWithHeaderCommentsAndCrlf) {
    const fs::path d = scratch();
    const auto path = write_file(d / "sieve.csv", "# mass passing\r\ndiameter_mm, passing\r\n"
                                                  "0.5,0\r\n1, 0\r\n 1.5 ,0.4\r\n\r\n2,1\r\n"
                                                  "4,1\r\n");
    const auto s = parse_sizes("file:" + path.string(), 1.0);
    EXPECT_EQ(s.kind, SizeKind::file);
    // The support: from the last row at 0 to the first at 1.
    EXPECT_EQ(s.diameters, (std::vector<double>{1, 1.5, 2}));
    EXPECT_EQ(s.fractions, (std::vector<double>{0, 0.4, 1}));
    EXPECT_EQ(s.low, 1.0);
    EXPECT_EQ(s.high, 2.0);
}

// ---------------------------------------------------------------------------------------------
// mono and discrete: exact.

TEST(DrawDiameters, MonoIsExactCopiesWithoutRandomNumbers) {
    const auto mono = parse_sizes("mono", 0.1);
    for (const std::uint64_t seed : {0ull, 1ull, 12345ull}) {
        const auto d = draw_diameters(mono, 1000, FractionBasis::volume, seed);
        ASSERT_EQ(d.size(), 1000u);
        for (const double x : d)
            ASSERT_EQ(std::memcmp(&x, &mono.diameters[0], sizeof x), 0);
        EXPECT_EQ(d, draw_diameters(mono, 1000, FractionBasis::number, seed + 1));
    }
    EXPECT_TRUE(draw_diameters(mono, 0, FractionBasis::volume, 1).empty());
}

TEST(DrawDiameters, DiscreteCountsAreTheLargestRemainderRoundingOfTheNumberFractions) {
    // By volume: x_1 = (0.5 / 1) / (0.5 / 1 + 0.5 / 8) = 8/9, so 800 x = 711.1 and 88.9.
    const auto binary = parse_sizes("discrete:1:0.5,2:0.5", 1.0);
    const auto x = number_fractions(binary, FractionBasis::volume);
    EXPECT_NEAR(x[0], 8.0 / 9.0, 1e-15);
    EXPECT_EQ(discrete_counts(binary, FractionBasis::volume, 800),
              (std::vector<std::size_t>{711, 89}));
    EXPECT_EQ(discrete_counts(binary, FractionBasis::number, 800),
              (std::vector<std::size_t>{400, 400}));
    // 7 x (0.25, 0.25, 0.5) = 1.75, 1.75, 3.5: floors 1, 1, 3 and the two spheres left go to the
    // two largest remainders.
    const auto three = parse_sizes("discrete:1:0.25,2:0.25,3:0.5", 1.0);
    EXPECT_EQ(discrete_counts(three, FractionBasis::number, 7),
              (std::vector<std::size_t>{2, 2, 3}));
    // Ties go to the smaller size: 2 x (0.25, 0.25, 0.5) = 0.5, 0.5, 1.
    EXPECT_EQ(discrete_counts(three, FractionBasis::number, 2),
              (std::vector<std::size_t>{1, 0, 1}));
    EXPECT_EQ(discrete_counts(three, FractionBasis::number, 0),
              (std::vector<std::size_t>{0, 0, 0}));

    const auto d = draw_diameters(binary, 800, FractionBasis::volume, 3);
    EXPECT_EQ(std::count(d.begin(), d.end(), 1.0), 711);
    EXPECT_EQ(std::count(d.begin(), d.end(), 2.0), 89);
    // Shuffled: the large spheres are not all at the end.
    EXPECT_LT(std::find(d.begin(), d.end(), 2.0) - d.begin(), 400);
}

TEST(DrawDiameters, DiscreteVolumeFractionsAsAskedWithinOneLargestSphere) {
    // Each count is within 1 of n x_k, so each volume fraction is within
    // (1 + K F_k) D_max^3 / V of the asked F_k (docs/sizes.md).
    for (const auto& [spec, n] : std::vector<std::pair<std::string, std::size_t>>{
             {"discrete:1:0.5,2:0.5", 800},
             {"discrete:1:0.2,1.5:0.3,3:0.5", 1000},
             {"discrete:0.4:0.7,4:0.3", 5000},
             {"discrete:1:0.1,1.2:0.2,1.4:0.3,1.9:0.4", 37}}) {
        SCOPED_TRACE(spec);
        const auto sizes = parse_sizes(spec, 1.0);
        const auto d = draw_diameters(sizes, n, FractionBasis::volume, 11);
        double total = 0;
        for (const double v : d)
            total += v * v * v;
        const std::size_t classes = sizes.diameters.size();
        const double dmax = sizes.high;
        for (std::size_t k = 0; k < classes; ++k) {
            double part = 0;
            for (const double v : d)
                if (v == sizes.diameters[k])
                    part += v * v * v;
            const double bound = (1.0 + classes * sizes.fractions[k]) * dmax * dmax * dmax / total;
            EXPECT_LE(std::fabs(part / total - sizes.fractions[k]), bound);
        }
        // For two sizes the bound is one sphere of the larger size.
        if (classes == 2) {
            double part = 0;
            for (const double v : d)
                if (v == sizes.diameters[0])
                    part += v * v * v;
            EXPECT_LE(std::fabs(part / total - sizes.fractions[0]), dmax * dmax * dmax / total);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Continuous: sampled moments against the formulas.

TEST(DrawDiameters, UniformMomentsByNumberAndByVolume) {
    // By number: q0 = 1 on [1, 2]; by volume, q3 = 1 and q0 proportional to d^-3.
    auto cubed = [](double x) { return x * x * x; };
    auto inverse_cubed = [](double x) { return 1.0 / (x * x * x); };
    expect_moments("uniform:1,2", FractionBasis::number, {1.5, 1.0 / 12.0},
                   expected(cubed, 1.0, 2.0));
    // Closed forms by volume: E0[d] = (1 - 1/2) / ((1 - 1/4) / 2) = 4/3, E0[d^2] = ln 2 / 0.375.
    expect_moments("uniform:1,2", FractionBasis::volume, from_raw(4.0 / 3.0, std::log(2.0) / 0.375),
                   {1.5, 1.0 / 12.0});
    expect_moments("uniform:0.3,3", FractionBasis::volume, expected(inverse_cubed, 0.3, 3.0),
                   {1.65, 2.7 * 2.7 / 12.0});
}

/// A continuous spec with its centre, spread and bounds written out.
struct Bell {
    std::string spec;
    double centre, spread, low, high;
};

TEST(DrawDiameters, TruncatedNormalMomentsByNumberAndByVolume) {
    for (const Bell& c : std::vector<Bell>{{"normal:1,0.1", 1.0, 0.1, 0.7, 1.3},
                                           {"normal:1,0.2,0.6,1.8", 1.0, 0.2, 0.6, 1.8},
                                           {"normal:1,0.4", 1.0, 0.4, 0.22, 2.2},
                                           {"normal:2,0.3,2.9,3.5", 2.0, 0.3, 2.9, 3.5}}) {
        const std::string& spec = c.spec;
        const double mu = c.centre, sigma = c.spread, a = c.low, b = c.high;
        auto q = [&](double x) { return phi((x - mu) / sigma); };
        // By number: the formulas; by volume of the number density the formulas hold for q3, and
        // the number moments come from q0 = q3 / d^3 by quadrature.
        expect_moments(spec, FractionBasis::number, truncated_normal(mu, sigma, a, b),
                       expected([&](double x) { return x * x * x * q(x); }, a, b));
        expect_moments(spec, FractionBasis::volume,
                       expected([&](double x) { return q(x) / (x * x * x); }, a, b),
                       truncated_normal(mu, sigma, a, b));
    }
}

TEST(DrawDiameters, TruncatedLognormalMomentsByNumberAndByVolume) {
    for (const Bell& c :
         std::vector<Bell>{{"lognormal:1,1.3", 1.0, 1.3, 1.0 / (1.3 * 1.3 * 1.3), 1.3 * 1.3 * 1.3},
                           {"lognormal:1,1.5", 1.0, 1.5, 1.0 / std::sqrt(10.0), std::sqrt(10.0)},
                           {"lognormal:2,1.2,1,5", 2.0, 1.2, 1.0, 5.0},
                           {"lognormal:1,1.1,1.5,2", 1.0, 1.1, 1.5, 2.0}}) {
        const std::string& spec = c.spec;
        const double mu = std::log(c.centre), s = std::log(c.spread), a = c.low, b = c.high;
        // E[d^k] of the truncated lognormal with median MEDIAN, in closed form.
        auto e = [&](double k) { return lognormal_moment(mu, s, a, b, k); };
        // By number it is q0; the volume moments are E[d^(k+3)] / E[d^3].
        expect_moments(spec, FractionBasis::number, from_raw(e(1), e(2)),
                       from_raw(e(4) / e(3), e(5) / e(3)));
        // By volume it is q3; the number moments are E[d^(k-3)] / E[d^-3] (no use of the
        // median shift the code applies).
        expect_moments(spec, FractionBasis::volume, from_raw(e(-2) / e(-3), e(-1) / e(-3)),
                       from_raw(e(1), e(2)));
    }
}

TEST(NumberDistribution, CumulativeAgainstClosedForms) {
    // Normal by number, lognormal by volume (Hatch & Choate), uniform by volume, against libm.
    const NumberDistribution normal(parse_sizes("normal:1,0.2,0.6,1.8", 1.0),
                                    FractionBasis::number);
    const double z = Phi(4.0) - Phi(-2.0);
    for (double d = 0.6; d <= 1.8; d += 0.05)
        EXPECT_NEAR(normal.cumulative(d), (Phi((d - 1.0) / 0.2) - Phi(-2.0)) / z, 2e-15) << d;

    const double s = std::log(1.5), mu0 = std::log(2.0) - 3.0 * s * s, a = 1.0, b = 5.0;
    const NumberDistribution log(parse_sizes("lognormal:2,1.5,1,5", 1.0), FractionBasis::volume);
    const double alpha = (std::log(a) - mu0) / s, beta = (std::log(b) - mu0) / s;
    for (double d = 1.0; d <= 5.0; d += 0.125)
        EXPECT_NEAR(log.cumulative(d),
                    (Phi((std::log(d) - mu0) / s) - Phi(alpha)) / (Phi(beta) - Phi(alpha)), 1e-14)
            << d;

    const NumberDistribution uniform(parse_sizes("uniform:1,2", 1.0), FractionBasis::volume);
    for (double d = 1.0; d <= 2.0; d += 0.0625)
        EXPECT_NEAR(uniform.cumulative(d), (1.0 - 1.0 / (d * d)) / 0.75, 1e-15) << d;

    // Normal by volume against Simpson's rule on q3 / d^3.
    const NumberDistribution tab(parse_sizes("normal:1,0.4", 1.0), FractionBasis::volume);
    auto q0 = [](double x) { return phi((x - 1.0) / 0.4) / (x * x * x); };
    const double total = simpson(q0, 0.22, 2.2, 200000);
    for (double d = 0.22; d <= 2.2; d += 0.11)
        EXPECT_NEAR(tab.cumulative(d), simpson(q0, 0.22, d, 200000) / total, 1e-12) << d;
}

TEST(NumberDistribution, QuantileInvertsCumulative) {
    for (const auto& spec : continuous_specs)
        for (const auto basis : {FractionBasis::volume, FractionBasis::number}) {
            SCOPED_TRACE(spec + " by " + to_string(basis));
            const auto sizes = parse_sizes(spec, 1.0);
            const NumberDistribution law(sizes, basis);
            EXPECT_EQ(law.quantile(0.0), sizes.low);
            EXPECT_DOUBLE_EQ(law.quantile(1.0), sizes.high);
            EXPECT_EQ(law.cumulative(sizes.low), 0.0);
            EXPECT_EQ(law.cumulative(sizes.high), 1.0);
            for (int i = 1; i < 1000; ++i) {
                const double t = i / 1000.0;
                const double d = law.quantile(t);
                ASSERT_GE(d, sizes.low);
                ASSERT_LE(d, sizes.high);
                ASSERT_NEAR(law.cumulative(d), t, 1e-13) << t;
            }
        }
}

TEST(DrawDiameters, StratifiedCountsWithinOneOfTheAskedFractions) {
    // The i-th smallest diameter of n comes from the stratum [i/n, (i+1)/n) of Q0.
    const std::size_t n = 3000;
    for (const auto& spec : continuous_specs)
        for (const auto basis : {FractionBasis::volume, FractionBasis::number}) {
            SCOPED_TRACE(spec + " by " + to_string(basis));
            const auto sizes = parse_sizes(spec, 1.0);
            const NumberDistribution law(sizes, basis);
            auto d = draw_diameters(sizes, n, basis, 5);
            ASSERT_EQ(d.size(), n);
            EXPECT_FALSE(std::is_sorted(d.begin(), d.end())); // shuffled
            std::sort(d.begin(), d.end());
            for (std::size_t i = 0; i < n; ++i) {
                const double q = law.cumulative(d[i]);
                ASSERT_GE(q, static_cast<double>(i) / n - 1e-13) << i;
                ASSERT_LE(q, static_cast<double>(i + 1) / n + 1e-13) << i;
            }
        }
}

TEST(DrawDiameters, VolumeFractionsOfAContinuousDistributionPerClass) {
    // The volume in [a, b) of the drawn spheres against the asked Q3(b) - Q3(a): by the stratified
    // counts, within 2 spheres of the largest size over the total volume.
    const auto sizes = parse_sizes("uniform:1,3", 1.0);
    const auto d = draw_diameters(sizes, 20000, FractionBasis::volume, 9);
    double total = 0;
    for (const double x : d)
        total += x * x * x;
    for (double a = 1.0; a < 3.0; a += 0.25) {
        double part = 0;
        for (const double x : d)
            if (x >= a && x < a + 0.25)
                part += x * x * x;
        EXPECT_NEAR(part / total, 0.125, 2.0 * 27.0 / total) << a;
    }
}

// ---------------------------------------------------------------------------------------------
// Sieve files.

TEST(SieveFile, QuantilesOfAKnownCumulativeComeBack) {
    // Q(d) = ((d - 1) / 2)^2 on [1, 3], tabulated every 0.02: by number, the rows come back
    // exactly and Q0 is linear between them.
    const fs::path dir = scratch();
    std::string text = "diameter,cumulative_fraction\n";
    auto known = [](double d) { return ((d - 1.0) / 2.0) * ((d - 1.0) / 2.0); };
    std::vector<double> rows;
    for (int i = 0; i <= 100; ++i) {
        const double d = 1.0 + 0.02 * i;
        rows.push_back(d);
        char row[64];
        std::snprintf(row, sizeof row, "%.17g,%.17g\n", d, known(d));
        text += row;
    }
    const auto path = write_file(dir / "known.csv", text);
    const auto sizes = parse_sizes("file:" + path.string(), 1.0);
    ASSERT_EQ(sizes.diameters.size(), 101u);
    const NumberDistribution law(sizes, FractionBasis::number);
    for (int i = 0; i <= 100; ++i)
        EXPECT_NEAR(law.quantile(known(sizes.diameters[i])), sizes.diameters[i], 1e-14);
    // Between rows: linear in the cumulative fraction against diameter.
    for (int i = 0; i < 100; ++i) {
        const double a = sizes.diameters[i], b = sizes.diameters[i + 1];
        const double p = 0.25 * known(a) + 0.75 * known(b);
        EXPECT_NEAR(law.quantile(p), 0.25 * a + 0.75 * b, 1e-14);
    }
    // Drawn: the d50 by number of the drawn spheres is the known median, 1 + 2 sqrt(0.5).
    auto d = draw_diameters(sizes, 10001, FractionBasis::number, 2);
    std::sort(d.begin(), d.end());
    EXPECT_NEAR(d[5000], 1.0 + 2.0 * std::sqrt(0.5), 2e-3);
}

TEST(SieveFile, ByVolumeIsTheMassPassing) {
    // A straight sieve curve from 1 to 2 (rows every 0.25) is uniform:1,2 by volume: the same Q0,
    // and the drawn spheres' d10, d50, d90 by volume are 1.1, 1.5 and 1.9.
    const fs::path dir = scratch();
    const auto path = write_file(dir / "line.csv", "1,0\n1.25,0.25\n1.5,0.5\n1.75,0.75\n2,1\n");
    const auto sieve = parse_sizes("file:" + path.string(), 1.0);
    const NumberDistribution from_file(sieve, FractionBasis::volume);
    const NumberDistribution uniform(parse_sizes("uniform:1,2", 1.0), FractionBasis::volume);
    for (double d = 1.0; d <= 2.0; d += 0.01)
        EXPECT_NEAR(from_file.cumulative(d), uniform.cumulative(d), 1e-14) << d;
    const auto stats = size_statistics(draw_diameters(sieve, 100000, FractionBasis::volume, 4));
    EXPECT_NEAR(stats.d10, 1.1, 1e-4);
    EXPECT_NEAR(stats.d50, 1.5, 1e-4);
    EXPECT_NEAR(stats.d90, 1.9, 1e-4);
}

// ---------------------------------------------------------------------------------------------
// Determinism.

TEST(DrawDiameters, SameSeedSameBitsOtherSeedOtherSizes) {
    const std::vector<std::string> specs{"discrete:1:0.5,2:0.5", "uniform:1,2", "normal:1,0.2",
                                         "lognormal:1,1.5"};
    for (const auto& spec : specs)
        for (const auto basis : {FractionBasis::volume, FractionBasis::number}) {
            SCOPED_TRACE(spec);
            const auto sizes = parse_sizes(spec, 1.0);
            const auto a = draw_diameters(sizes, 5000, basis, 17);
            const auto b = draw_diameters(sizes, 5000, basis, 17);
            ASSERT_EQ(a.size(), b.size());
            EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
            EXPECT_NE(a, draw_diameters(sizes, 5000, basis, 18));
        }
}

TEST(DrawDiameters, FingerprintsHoldOnEveryPlatform) {
    // The bits of 1000 draws: mt19937_64, bit-arithmetic uniforms and our own exp, log and erfc
    // give these with any compiler and C library (the same with GCC 12 -O3 -march=native and
    // clang 14 -O1; the library is built with -ffp-contract=off).
    struct Case {
        const char* spec;
        FractionBasis basis;
        std::uint64_t bits;
    };
    for (const Case& c : std::vector<Case>{
             {"discrete:1:0.5,2:0.3,3:0.2", FractionBasis::volume, 0x44867fed811656caull},
             {"discrete:1:0.5,2:0.3,3:0.2", FractionBasis::number, 0x061e5b74d31e2a43ull},
             {"uniform:1,2", FractionBasis::volume, 0x6f5bd889a1a94023ull},
             {"uniform:1,2", FractionBasis::number, 0x6238813d96c8fb0full},
             {"normal:1,0.2", FractionBasis::volume, 0x1de575cbd4a02c40ull},
             {"normal:1,0.2", FractionBasis::number, 0x6ca143e5a9bbcc7eull},
             {"lognormal:1,1.5", FractionBasis::volume, 0xbe2de73cffe681e8ull},
             {"lognormal:1,1.5", FractionBasis::number, 0x272ce9626e9af206ull}}) {
        const std::uint64_t bits =
            fingerprint(draw_diameters(parse_sizes(c.spec, 1.0), 1000, c.basis, 42));
        EXPECT_EQ(bits, c.bits) << c.spec << " by " << to_string(c.basis) << ": 0x" << std::hex
                                << bits;
    }
}

// ---------------------------------------------------------------------------------------------
// Statistics.

TEST(SizeStatistics, HandComputedThreeSpheres) {
    // d = 1, 2, 3: volumes 1, 8, 27 (36); Q3 = 1/36, 9/36, 1 at 1, 2, 3.
    const std::vector<double> d{3.0, 1.0, 2.0};
    const auto s = size_statistics(d);
    EXPECT_EQ(s.count, 3u);
    ASSERT_EQ(s.classes.size(), 3u);
    EXPECT_EQ(s.classes[1].low, 2.0);
    EXPECT_EQ(s.classes[1].count, 1u);
    EXPECT_DOUBLE_EQ(s.classes[2].volume_fraction, 27.0 / 36.0);
    EXPECT_DOUBLE_EQ(s.d10, 1.0 + (0.1 - 1.0 / 36.0) / (8.0 / 36.0));
    EXPECT_DOUBLE_EQ(s.d50, 2.0 + (0.5 - 9.0 / 36.0) / (27.0 / 36.0));
    EXPECT_DOUBLE_EQ(s.d90, 2.0 + (0.9 - 9.0 / 36.0) / (27.0 / 36.0));
    EXPECT_DOUBLE_EQ(s.sauter_mean, 36.0 / 14.0);
    EXPECT_DOUBLE_EQ(s.volume_mean, 98.0 / 36.0);
    EXPECT_DOUBLE_EQ(s.number_mean, 2.0);
    EXPECT_DOUBLE_EQ(s.number_sd, std::sqrt(2.0 / 3.0));
    EXPECT_EQ(s.smallest, 1.0);
    EXPECT_EQ(s.largest, 3.0);
    EXPECT_EQ(s.size_ratio, 3.0);
}

TEST(SizeStatistics, BinaryMixtureClassesAreTheSizes) {
    const auto d =
        draw_diameters(parse_sizes("discrete:1:0.5,2:0.5", 1.0), 800, FractionBasis::volume, 1);
    const auto s = size_statistics(d);
    ASSERT_EQ(s.classes.size(), 2u);
    EXPECT_EQ(s.classes[0].count, 711u);
    EXPECT_EQ(s.classes[1].count, 89u);
    EXPECT_DOUBLE_EQ(s.classes[0].number_fraction, 711.0 / 800.0);
    EXPECT_DOUBLE_EQ(s.classes[0].volume_fraction, 711.0 / 1423.0);
    EXPECT_DOUBLE_EQ(s.classes[1].volume_fraction, 712.0 / 1423.0);
    EXPECT_EQ(s.d10, 1.0);
    EXPECT_DOUBLE_EQ(s.d50, 1.0 + (0.5 - 711.0 / 1423.0) / (712.0 / 1423.0));
    EXPECT_DOUBLE_EQ(s.sauter_mean, 1423.0 / (711.0 + 4.0 * 89.0));
    EXPECT_DOUBLE_EQ(s.number_mean, (711.0 + 2.0 * 89.0) / 800.0);
    EXPECT_EQ(s.size_ratio, 2.0);
}

TEST(SizeStatistics, ContinuousSetsAreBinnedGeometricallyAndOrderDoesNotMatter) {
    const auto d =
        draw_diameters(parse_sizes("lognormal:1,1.5", 1.0), 5000, FractionBasis::volume, 8);
    const auto s = size_statistics(d);
    ASSERT_EQ(s.classes.size(), default_size_bins);
    EXPECT_EQ(s.classes.front().low, s.smallest);
    EXPECT_EQ(s.classes.back().high, s.largest);
    const double step = std::pow(s.size_ratio, 1.0 / default_size_bins);
    std::uint64_t count = 0;
    double number = 0, volume = 0;
    for (std::size_t k = 0; k < s.classes.size(); ++k) {
        EXPECT_NEAR(s.classes[k].high / s.classes[k].low, step, 1e-12);
        if (k > 0) {
            EXPECT_EQ(s.classes[k].low, s.classes[k - 1].high);
        }
        count += s.classes[k].count;
        number += s.classes[k].number_fraction;
        volume += s.classes[k].volume_fraction;
    }
    EXPECT_EQ(count, 5000u);
    EXPECT_NEAR(number, 1.0, 1e-12);
    EXPECT_NEAR(volume, 1.0, 1e-12);
    // Every diameter is in the class size_class_of names.
    std::vector<std::uint64_t> counted(s.classes.size(), 0);
    for (const double x : d) {
        const std::size_t k = size_class_of(s.classes, x);
        EXPECT_GE(x, s.classes[k].low);
        EXPECT_LE(x, s.classes[k].high);
        ++counted[k];
    }
    for (std::size_t k = 0; k < s.classes.size(); ++k)
        EXPECT_EQ(counted[k], s.classes[k].count);
    // The mass median of a lognormal by volume is its MEDIAN.
    const auto big = size_statistics(
        draw_diameters(parse_sizes("lognormal:1,1.5", 1.0), 100000, FractionBasis::volume, 8));
    EXPECT_NEAR(big.d50, 1.0, 1e-3);
    // Any order, the same bits.
    auto reversed = d;
    std::reverse(reversed.begin(), reversed.end());
    const auto r = size_statistics(reversed);
    EXPECT_EQ(std::memcmp(&r.sauter_mean, &s.sauter_mean, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&r.d50, &s.d50, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&r.number_sd, &s.number_sd, sizeof(double)), 0);
}

TEST(SizeStatistics, EmptyAndBadDiameters) {
    const auto s = size_statistics(std::vector<double>{});
    EXPECT_EQ(s.count, 0u);
    EXPECT_TRUE(s.classes.empty());
    EXPECT_EQ(refusal([] {
                  size_statistics(std::vector<double>{1.0, -2.0});
              }),
              "size statistics: diameter -2 of sphere 2 is not allowed; allowed: a finite "
              "number > 0");
    EXPECT_EQ(refusal([] { size_statistics(std::vector<double>{NAN}); }),
              "size statistics: diameter nan of sphere 1 is not allowed; allowed: a finite "
              "number > 0");
}

// ---------------------------------------------------------------------------------------------
// Bad input, word for word.

TEST(ParseSizes, RefusesBadInputWithOneLineNamingTheOption) {
    const std::string discrete =
        "allowed: discrete:D1:F1,D2:F2,... with each diameter once, from 1e-12 to 1e+12, the "
        "largest at most 10 times the smallest, at most 100000 sizes, and fractions >= 0 adding "
        "up to 1 (within 1e-06)";
    const std::string uniform =
        "allowed: uniform:MIN,MAX with 1e-12 <= MIN < MAX <= 1e+12 and MAX <= 10 MIN";
    const std::string normal =
        "allowed: normal:MEAN,SD or normal:MEAN,SD,MIN,MAX with MEAN from 1e-12 to 1e+12, SD > 0, "
        "1e-12 <= MIN < MAX <= 1e+12, MAX <= 10 MIN, MIN < MEAN + 8 SD and MAX > MEAN - 8 SD (by "
        "default MIN = MEAN - 3 SD, at least MAX / 10, and MAX = MEAN + 3 SD)";
    const std::string lognormal =
        "allowed: lognormal:MEDIAN,GSD or lognormal:MEDIAN,GSD,MIN,MAX with MEDIAN from 1e-12 to "
        "1e+12, GSD > 1, 1e-12 <= MIN < MAX <= 1e+12, MAX <= 10 MIN, MIN < MEDIAN GSD^8 and MAX > "
        "MEDIAN / GSD^8 (by default MEDIAN / GSD^3 to MEDIAN GSD^3, narrowed to MAX = 10 MIN)";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"gamma:1,2",
         "--sizes 'gamma:1,2' is not allowed: unknown distribution 'gamma'; allowed: mono, "
         "discrete:D1:F1,D2:F2,..., uniform:MIN,MAX, normal:MEAN,SD[,MIN,MAX], "
         "lognormal:MEDIAN,GSD[,MIN,MAX] or file:PATH"},
        {"", "--sizes '' is not allowed: unknown distribution ''; allowed: mono, "
             "discrete:D1:F1,D2:F2,..., uniform:MIN,MAX, normal:MEAN,SD[,MIN,MAX], "
             "lognormal:MEDIAN,GSD[,MIN,MAX] or file:PATH"},
        {"Mono", "--sizes 'Mono' is not allowed: unknown distribution 'Mono'; allowed: mono, "
                 "discrete:D1:F1,D2:F2,..., uniform:MIN,MAX, normal:MEAN,SD[,MIN,MAX], "
                 "lognormal:MEDIAN,GSD[,MIN,MAX] or file:PATH"},
        {"mono:1", "--sizes 'mono:1' is not allowed: mono takes no parameters (its diameter is "
                   "--diameter); allowed: mono, every sphere --diameter, without parameters"},
        {"uniform", "--sizes 'uniform' is not allowed: uniform needs its parameters; " + uniform},
        // Sizes.
        {"discrete:-1:0.5,2:0.5", "--sizes 'discrete:-1:0.5,2:0.5' is not allowed: diameter = -1 "
                                  "is not from 1e-12 to 1e+12; " +
                                      discrete},
        {"discrete:0:0.5,2:0.5", "--sizes 'discrete:0:0.5,2:0.5' is not allowed: diameter = 0 is "
                                 "not from 1e-12 to 1e+12; " +
                                     discrete},
        {"uniform:0,1", "--sizes 'uniform:0,1' is not allowed: MIN = 0 is not from 1e-12 to "
                        "1e+12; " +
                            uniform},
        {"normal:-1,0.1", "--sizes 'normal:-1,0.1' is not allowed: MEAN = -1 is not from 1e-12 to "
                          "1e+12; " +
                              normal},
        // Fractions.
        {"discrete:1:0.5,2:0.4", "--sizes 'discrete:1:0.5,2:0.4' is not allowed: the fractions "
                                 "add up to 0.9; " +
                                     discrete},
        {"discrete:1:0.5,2:0.75", "--sizes 'discrete:1:0.5,2:0.75' is not allowed: the fractions "
                                  "add up to 1.25; " +
                                      discrete},
        {"discrete:1:0.5,2:0.500002", "--sizes 'discrete:1:0.5,2:0.500002' is not allowed: the "
                                      "fractions add up to 1.0000019999999998; " +
                                          discrete},
        {"discrete:1:1.5,2:-0.5", "--sizes 'discrete:1:1.5,2:-0.5' is not allowed: the fraction "
                                  "-0.5 of diameter 2 is negative; " +
                                      discrete},
        {"discrete:1:0.5,1:0.5", "--sizes 'discrete:1:0.5,1:0.5' is not allowed: diameter 1 is "
                                 "given twice; " +
                                     discrete},
        {"discrete:1:x", "--sizes 'discrete:1:x' is not allowed: 'x' is not a number; " + discrete},
        {"discrete:1-1", "--sizes 'discrete:1-1' is not allowed: '1-1' is not D:F; " + discrete},
        {"discrete:", "--sizes 'discrete:' is not allowed: '' is not D:F; " + discrete},
        {"discrete:1:nan",
         "--sizes 'discrete:1:nan' is not allowed: 'nan' is not a number; " + discrete},
        // Size ratio.
        {"discrete:1:0.5,20:0.5", "--sizes 'discrete:1:0.5,20:0.5' is not allowed: the largest "
                                  "diameter over the smallest (of those with a fraction > 0) is "
                                  "20 (the solvers support up to 10); " +
                                      discrete},
        {"uniform:1,11", "--sizes 'uniform:1,11' is not allowed: MAX / MIN is 11 (the solvers "
                         "support up to 10); " +
                             uniform},
        {"lognormal:1,1.5,0.1,2", "--sizes 'lognormal:1,1.5,0.1,2' is not allowed: MAX / MIN is "
                                  "20 (the solvers support up to 10); " +
                                      lognormal},
        // Parameters.
        {"uniform:2,1",
         "--sizes 'uniform:2,1' is not allowed: MIN = 2 is not below MAX = 1; " + uniform},
        {"uniform:1,1",
         "--sizes 'uniform:1,1' is not allowed: MIN = 1 is not below MAX = 1; " + uniform},
        {"uniform:1,2,3", "--sizes 'uniform:1,2,3' is not allowed: uniform takes 2 numbers, not "
                          "3; " +
                              uniform},
        {"uniform:1,inf",
         "--sizes 'uniform:1,inf' is not allowed: 'inf' is not a number; " + uniform},
        {"normal:1,-0.1", "--sizes 'normal:1,-0.1' is not allowed: SD = -0.1 is not above 0 (one "
                          "size: discrete:D:1); " +
                              normal},
        {"normal:1,0", "--sizes 'normal:1,0' is not allowed: SD = 0 is not above 0 (one size: "
                       "discrete:D:1); " +
                           normal},
        {"normal:1,0.1,1.2", "--sizes 'normal:1,0.1,1.2' is not allowed: normal takes 2 or 4 "
                             "numbers, not 3; " +
                                 normal},
        {"normal:1,0.1,1.2,0.9", "--sizes 'normal:1,0.1,1.2,0.9' is not allowed: MIN = 1.2 is not "
                                 "below MAX = 0.9; " +
                                     normal},
        {"normal:1,0.1,1.9,2", "--sizes 'normal:1,0.1,1.9,2' is not allowed: MIN = 1.9 is not "
                               "below MEAN + 8 SD = 1.8; " +
                                   normal},
        {"normal:1,1e12", "--sizes 'normal:1,1e12' is not allowed: the default MAX (MEAN + 3 SD) "
                          "= 3000000000001 is not from 1e-12 to 1e+12; " +
                              normal},
        {"lognormal:1,1", "--sizes 'lognormal:1,1' is not allowed: GSD = 1 is not above 1 (one "
                          "size: discrete:D:1); " +
                              lognormal},
        {"lognormal:1,0.5", "--sizes 'lognormal:1,0.5' is not allowed: GSD = 0.5 is not above 1 "
                            "(one size: discrete:D:1); " +
                                lognormal},
        {"lognormal:1,1.1,3,4", "--sizes 'lognormal:1,1.1,3,4' is not allowed: MIN = 3 is not "
                                "below MEDIAN GSD^8 = 2.143588810000001; " +
                                    lognormal},
        // Control characters are escaped: one line.
        {"gamma\n:1", "--sizes 'gamma\\n:1' is not allowed: unknown distribution 'gamma\\n'; "
                      "allowed: mono, discrete:D1:F1,D2:F2,..., uniform:MIN,MAX, "
                      "normal:MEAN,SD[,MIN,MAX], lognormal:MEDIAN,GSD[,MIN,MAX] or file:PATH"},
    };
    for (const auto& [spec, message] : cases) {
        SCOPED_TRACE(spec);
        EXPECT_EQ(refusal_of(spec), message);
        EXPECT_EQ(refusal_of(spec).find('\n'), std::string::npos);
    }
    EXPECT_EQ(refusal([] { parse_sizes("mono", 0.0); }),
              "--diameter = 0 is not allowed; allowed: 1e-12 to 1e+12");
    // A long spec is cut in the message.
    std::string long_spec = "discrete:";
    for (int i = 0; i < 100; ++i)
        long_spec += "1:0.01,";
    long_spec += "x";
    const std::string cut =
        "--sizes '" + long_spec.substr(0, 100) + "...' is not allowed: 'x' is not D:F; " + discrete;
    EXPECT_EQ(refusal_of(long_spec), cut);
}

TEST(ParseSizes, RefusesBadSieveFiles) {
    const fs::path d = scratch();
    const std::string allowed =
        "allowed: file:PATH, a CSV of diameter,cumulative_fraction rows (fraction passing; a "
        "header line may come first, # starts a comment): 2 to 100000 rows, diameters from 1e-12 "
        "to 1e+12 ascending, cumulative fractions from 0 to 1 (within 1e-06) not decreasing, "
        "rising over at most a ratio of 10 in diameter";
    const std::vector<std::tuple<std::string, std::string, std::string>> cases{
        {"descending.csv", "1,0\n2,0.5\n1.5,1\n",
         "descending.csv:3: diameter 1.5 is not above the 2 of line 2"},
        {"equal.csv", "1,0\n1,1\n", "equal.csv:2: diameter 1 is not above the 1 of line 1"},
        {"falling.csv", "1,0\n2,0.6\n3,0.5\n4,1\n",
         "falling.csv:3: cumulative fraction 0.5 is below the 0.6 of line 2"},
        {"one.csv", "diameter,passing\n1,0\n", "one.csv has 1 row of numbers"},
        {"none.csv", "", "none.csv has 0 rows of numbers"},
        {"text.csv", "1,0\n2,half\n3,1\n", "text.csv:2: 'half' is not a number"},
        {"late_header.csv", "1,0\nd,q\n3,1\n", "late_header.csv:2: 'd' is not a number"},
        {"fields.csv", "1,0\n2,0.5,7\n3,1\n",
         "fields.csv:2: 3 fields, not 2 (diameter,cumulative_fraction)"},
        {"above.csv", "1,0\n2,1.2\n", "above.csv:2: cumulative fraction 1.2 is not from 0 to 1"},
        {"below.csv", "1,-0.1\n2,1\n", "below.csv:1: cumulative fraction -0.1 is not from 0 to 1"},
        {"start.csv", "1,0.1\n2,1\n", "start.csv:1: the first cumulative fraction is 0.1, not 0"},
        {"end.csv", "1,0\n2,0.9\n", "end.csv:2: the last cumulative fraction is 0.9, not 1"},
        {"size.csv", "0,0\n2,1\n", "size.csv:1: diameter = 0 is not from 1e-12 to 1e+12"},
        {"ratio.csv", "0.1,0\n0.5,0\n6,1\n9,1\n",
         "ratio.csv: the fraction passing rises from diameter 0.5 (line 2) to 6 (line 3), a ratio "
         "of 12 (the solvers support up to 10)"},
    };
    for (const auto& [name, text, reason] : cases) {
        SCOPED_TRACE(name);
        write_file(d / name, text);
        const std::string spec = "file:" + (d / name).string();
        std::string expected = "--sizes '" + spec + "' is not allowed: " + reason + "; " + allowed;
        // The path in the reason is the one given.
        const auto at = expected.find(": " + name);
        if (at != std::string::npos)
            expected.replace(at, name.size() + 2, ": " + (d / name).string());
        EXPECT_EQ(refusal_of(spec), expected);
    }
    // Missing files, directories and paths with control characters: the file functions' words.
    const std::string missing = (d / "missing.csv").string();
    EXPECT_EQ(refusal_of("file:" + missing),
              "--sizes " + missing +
                  ": cannot open the file (No such file or directory); allowed: a readable "
                  "regular file");
    EXPECT_EQ(refusal_of("file:" + d.string()),
              "--sizes " + d.string() + ": a directory; allowed: a readable regular file");
    EXPECT_EQ(refusal_of("file:a\nb"),
              "--sizes 'a\\nb' is not allowed (a control character in the path); allowed: a path "
              "of at most 4095 bytes without control characters (newline, tab, ...)");
    EXPECT_EQ(refusal_of("file:"),
              "--sizes '' is not allowed (an empty path); allowed: a path of at most 4095 bytes "
              "without control characters (newline, tab, ...)");
}
