// Published correlations for beds of mono-sized spheres in tubes, to validate against.
// One registry per kind; each entry carries its source, its formula and its validity range.
// How each formula was checked (against two independent sources, or one) is written beside
// its entry in src/analyze/correlations.cpp and in docs/sources.md: that is for us, not for users.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace packbed {

/// A correlation value, and a warning when it was evaluated outside its validity range or
/// when the value is not a void fraction at all (outside (0, 1): the formula does not hold).
struct CorrelationValue {
    double value = 0.0;
    std::string warning; ///< empty inside the range and for a value in (0, 1)
};

/// Mean (overall) void fraction of a packed bed against the aspect ratio a = D/d.
struct MeanVoidFractionCorrelation {
    std::string_view name;    ///< registry key, e.g. "dixon-1988"
    std::string_view label;   ///< what people call it, e.g. "Dixon (1988)"
    std::string_view source;  ///< the publication
    std::string_view formula; ///< the formula as plain text
    double a_low, a_high;     ///< validity range of a; [1, inf) where the source states none
    double (*function)(double aspect_ratio);

    /// \return the void fraction at aspect ratio a, with a warning outside [a_low, a_high].
    CorrelationValue operator()(double aspect_ratio) const;
};

/// Radial void-fraction profile against z = (R - r)/d, the distance from the wall in diameters.
struct RadialVoidFractionCorrelation {
    std::string_view name;
    std::string_view label;
    std::string_view source;
    std::string_view formula;
    double a_low, a_high; ///< validity range of a; [1, inf) where the source states none
    double (*function)(double z, double aspect_ratio);

    /// \return the void fraction at distance z (diameters) from the wall in a tube of aspect
    /// ratio a, with a warning outside the range of a.
    CorrelationValue operator()(double z, double aspect_ratio) const;
};

/// The mean void-fraction correlations (Dixon 1988, Benyahia & O'Neill 2005, Jeschar 1975,
/// Zou & Yu 1995 dense and loose), filled in one place.
const std::vector<MeanVoidFractionCorrelation>& mean_void_fraction_correlations();

/// The radial profile correlations (de Klerk 2003, Mueller 1992), filled in one place.
const std::vector<RadialVoidFractionCorrelation>& radial_void_fraction_correlations();

/// "a >= 1.5 and a <= 50", "a >= 2.02", or "no range stated by the source" (a range of
/// [1, inf), which every tube has), for users.
std::string validity_range(double a_low, double a_high);

} // namespace packbed
