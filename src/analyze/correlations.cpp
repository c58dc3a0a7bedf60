#include "packbed/correlations.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

namespace packbed {

namespace {

constexpr double unbounded = std::numeric_limits<double>::infinity();

/// The warning for a value at aspect ratio a: outside the validity range, or not a void
/// fraction at all. Zou & Yu's dense formula gives 54.39 at a = 1.5 (exp(15.306 / 1.5)): no
/// source we have states its range, so only the value tells that it does not hold there.
std::string range_warning(std::string_view label, double a, double low, double high) {
    if (a >= low && a <= high)
        return {};
    return fmt::format("{}: a = {} is outside its validity range ({})", label, a,
                       validity_range(low, high));
}

std::string value_warning(std::string_view label, double value, double a, double low, double high) {
    if (!(value > 0.0 && value < 1.0))
        return fmt::format("{} gives {:.4g} at a = {}, which is not a void fraction (it must lie "
                           "in (0, 1)): the formula does not hold at this aspect ratio",
                           label, value, a);
    return range_warning(label, a, low, high);
}

/// Dixon (1988), x = 1/a: x <= 0.5: 0.4 + 0.05 x + 0.412 x^2; 0.5 < x <= 0.536:
/// 0.528 + 2.464 (x - 0.5); x > 0.536: 1 - 0.667 x^3 (2x - 1)^(-1/2).
double dixon(double a) {
    const double x = 1.0 / a;
    if (x <= 0.5)
        return 0.4 + 0.05 * x + 0.412 * x * x;
    if (x <= 0.536)
        return 0.528 + 2.464 * (x - 0.5);
    return 1.0 - 0.667 * x * x * x / std::sqrt(2.0 * x - 1.0);
}

/// Benyahia & O'Neill (2005), spheres: 0.390 + 1.740 / (a + 1.140)^2.
double benyahia_oneill(double a) {
    return 0.390 + 1.740 / ((a + 1.140) * (a + 1.140));
}

/// Jeschar (1975): 0.375 + 0.34 / a.
double jeschar(double a) {
    return 0.375 + 0.34 / a;
}

/// Zou & Yu (1995), dense random packing: 0.372 + 0.002 (exp(15.306 / a) - 1).
double zou_yu_dense(double a) {
    return 0.372 + 0.002 * (std::exp(15.306 / a) - 1.0);
}

/// Zou & Yu (1995), loose random packing: 0.400 + 0.010 (exp(10.686 / a) - 1).
double zou_yu_loose(double a) {
    return 0.400 + 0.010 * (std::exp(10.686 / a) - 1.0);
}

/// Bulk void fraction of Mueller (1992), used by both profiles: e_b = 0.365 + 0.220 / a.
double bulk_void_fraction(double a) {
    return 0.365 + 0.220 / a;
}

/// de Klerk (2003): z <= 0.637: 2.14 z^2 - 2.53 z + 1; z > 0.637:
/// e_b + 0.29 exp(-0.6 z) cos(2.3 pi (z - 0.16)) + 0.15 exp(-0.9 z), with e_b of Mueller.
double de_klerk(double z, double a) {
    if (z <= 0.637)
        return 2.14 * z * z - 2.53 * z + 1.0;
    return bulk_void_fraction(a) +
           0.29 * std::exp(-0.6 * z) * std::cos(2.3 * std::numbers::pi * (z - 0.16)) +
           0.15 * std::exp(-0.9 * z);
}

/// Mueller (1992): e_b + (1 - e_b) J0(a* z) exp(-b* z), a* = 7.45 - 3.15/a (a <= 13) or
/// 7.45 - 11.25/a (a > 13), b* = 0.315 - 0.725/a, e_b = 0.365 + 0.220/a.
double mueller(double z, double a) {
    const double eb = bulk_void_fraction(a);
    const double a_star = a <= 13.0 ? 7.45 - 3.15 / a : 7.45 - 11.25 / a;
    const double b_star = 0.315 - 0.725 / a;
    return eb + (1.0 - eb) * std::cyl_bessel_j(0.0, a_star * z) * std::exp(-b_star * z);
}

} // namespace

std::string validity_range(double a_low, double a_high) {
    if (a_low <= 1.0 && a_high == unbounded)
        return "no range stated by the source";
    if (a_high == unbounded)
        return fmt::format("a >= {}", a_low);
    return fmt::format("{} <= a <= {}", a_low, a_high);
}

CorrelationValue MeanVoidFractionCorrelation::operator()(double aspect_ratio) const {
    const double v = function(aspect_ratio);
    return {v, value_warning(label, v, aspect_ratio, a_low, a_high)};
}

CorrelationValue RadialVoidFractionCorrelation::operator()(double z, double aspect_ratio) const {
    return {function(z, aspect_ratio), range_warning(label, aspect_ratio, a_low, a_high)};
}

const std::vector<MeanVoidFractionCorrelation>& mean_void_fraction_correlations() {
    // How each was checked (for us): Dixon, Benyahia & O'Neill and Jeschar against two
    // independent sources; Zou & Yu against one, which states no range.
    static const std::vector<MeanVoidFractionCorrelation> registry{
        {"dixon-1988", "Dixon (1988)", "A. G. Dixon, Can. J. Chem. Eng. 66 (1988) 705",
         "x = 1/a; x <= 0.5: 0.4 + 0.05 x + 0.412 x^2; x <= 0.536: 0.528 + 2.464 (x - 0.5); "
         "else 1 - 0.667 x^3 (2x - 1)^-0.5",
         1.0, unbounded, dixon},
        {"benyahia-oneill-2005", "Benyahia & O'Neill (2005)",
         "F. Benyahia, K. E. O'Neill, Part. Sci. Technol. 23 (2005) 169",
         "0.390 + 1.740 / (a + 1.140)^2", 1.5, 50.0, benyahia_oneill},
        {"jeschar-1975", "Jeschar (1975)", "R. Jeschar, Arch. Eisenhuettenwes. 46 (1975) 99",
         "0.375 + 0.34 / a", 1.0, unbounded, jeschar},
        {"zou-yu-1995-dense", "Zou & Yu (1995), dense",
         "R. P. Zou, A. B. Yu, Chem. Eng. Sci. 50 (1995) 1504",
         "0.372 + 0.002 (exp(15.306 / a) - 1)", 1.0, unbounded, zou_yu_dense},
        {"zou-yu-1995-loose", "Zou & Yu (1995), loose",
         "R. P. Zou, A. B. Yu, Chem. Eng. Sci. 50 (1995) 1504",
         "0.400 + 0.010 (exp(10.686 / a) - 1)", 1.0, unbounded, zou_yu_loose},
    };
    return registry;
}

const std::vector<RadialVoidFractionCorrelation>& radial_void_fraction_correlations() {
    // Both checked against one source each; de Klerk states no range, and his e_b is taken
    // from Mueller.
    static const std::vector<RadialVoidFractionCorrelation> registry{
        {"de-klerk-2003", "de Klerk (2003)", "A. de Klerk, AIChE J. 49 (2003) 2022",
         "z <= 0.637: 2.14 z^2 - 2.53 z + 1; else e_b + 0.29 exp(-0.6 z) cos(2.3 pi (z - 0.16)) "
         "+ 0.15 exp(-0.9 z), e_b = 0.365 + 0.220 / a (Mueller 1992)",
         1.0, unbounded, de_klerk},
        {"mueller-1992", "Mueller (1992)", "G. E. Mueller, Powder Technol. 72 (1992) 269",
         "e_b + (1 - e_b) J0(a* z) exp(-b* z), a* = 7.45 - 3.15/a (a <= 13), 7.45 - 11.25/a "
         "(a > 13), b* = 0.315 - 0.725/a, e_b = 0.365 + 0.220/a",
         2.02, unbounded, mueller},
    };
    return registry;
}

} // namespace packbed
