// Elementary functions for the size distributions (sizes.cpp, size_spec.cpp). Internal.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace packbed::detail {

// Elementary functions from +, -, *, /, sqrt, frexp and ldexp only: IEEE 754 rounds these
// exactly, so the sizes drawn from them are the same bits on every platform, which std::exp,
// std::log and std::erfc (a few ulp, differing between C libraries) do not promise.

inline constexpr double ln2_hi = 0x1.62e42fee00000p-1; // ln 2 in two parts (Cody & Waite): k ln2_hi
inline constexpr double ln2_lo = 0x1.a39ef35793c76p-33; // is exact for |k| < 2^11
inline constexpr double sqrt_pi = 0x1.c5bf891b4ef6bp0;
inline constexpr double sqrt_2pi = 0x1.40d931ff62705p1;
inline constexpr double sqrt_half = 0x1.6a09e667f3bcdp-1;

/// \f$e^x\f$: x = k ln 2 + r with |r| <= ln 2 / 2, \f$e^r\f$ by its Taylor series to r^13
/// (remainder below 4e-18), times 2^k. Within 3e-16 of std::exp.
inline double exp_portable(double x) {
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
inline double log_portable(double x) {
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
inline double exp_minus_square(double x) {
    const double h = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) & ~((1ull << 27) - 1));
    return exp_portable(-h * h) * exp_portable((h - x) * (h + x));
}

/// erfc x for x >= 0. Below 1: 1 - erf x with Abramowitz & Stegun 7.1.6,
/// \f$\mathrm{erf}\,x = \frac{2}{\sqrt\pi} e^{-x^2} \sum_n \frac{2^n x^{2n+1}}{1 \cdot 3 \cdots
/// (2n+1)}\f$ (positive terms). From 1: the continued fraction A&S 7.1.14,
/// \f$\mathrm{erfc}\,x = \frac{e^{-x^2}}{\sqrt\pi}\,\cfrac{1}{x + \cfrac{1/2}{x + \cfrac{1}{x +
/// \cfrac{3/2}{x + \cdots}}}}\f$, evaluated from a fixed depth (200 terms at 1, 40 from 2.5).
/// Within 1e-15 relative of std::erfc up to x = 26.
inline double erfc_portable(double x) {
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
inline double normal_lower(double z) {
    return z <= 0.0 ? 0.5 * erfc_portable(-z * sqrt_half)
                    : 1.0 - 0.5 * erfc_portable(z * sqrt_half);
}

/// \f$1 - \Phi(z) = \Phi(-z)\f$, precise in the upper tail.
inline double normal_upper(double z) {
    return normal_lower(-z);
}

/// \return z <= 0 with \f$\Phi(z) = p\f$ for p in [0, 1/2]: Acklam's rational approximation
/// (relative error below 1.2e-9; P. J. Acklam, "An algorithm for computing the inverse normal
/// cumulative distribution function", 2003), then one step of Halley's method on
/// \f$\Phi(z) - p\f$, which takes it to about 1e-16.
inline double normal_lower_quantile(double p) {
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
inline double normal_quantile(double p) {
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
inline constexpr std::array<double, 4> gl8_nodes{
    0.1834346424956498049394761, 0.5255324099163289858177390, 0.7966664774136267395915539,
    0.9602898564975362316835609};
inline constexpr std::array<double, 4> gl8_weights{
    0.3626837833783619829651504, 0.3137066458778872873379622, 0.2223810344533744705443560,
    0.1012285362903762591525314};

} // namespace packbed::detail
