// Published correlations for beds of mono-sized spheres in tubes, to validate against.
// One registry per kind; each entry carries its source, its formula, how sure we are of it
// (checked in two independent sources, or one) and its validity range.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace packbed {

/// A correlation value, and a warning when it was evaluated outside its validity range.
struct CorrelationValue {
    double value = 0.0;
    std::string warning; ///< empty inside the range
};

/// Mean (overall) void fraction of a packed bed against the aspect ratio a = D/d.
struct MeanVoidFractionCorrelation {
    std::string_view name;    ///< registry key, e.g. "dixon-1988"
    std::string_view source;  ///< the publication
    std::string_view formula; ///< the formula as plain text
    std::string_view status;  ///< "checked" (two sources) or "one source"
    double a_low, a_high;     ///< validity range of a
    double (*function)(double aspect_ratio);

    /// \return the void fraction at aspect ratio a, with a warning outside [a_low, a_high].
    CorrelationValue operator()(double aspect_ratio) const;
};

/// Radial void-fraction profile against z = (R - r)/d, the distance from the wall in diameters.
struct RadialVoidFractionCorrelation {
    std::string_view name;
    std::string_view source;
    std::string_view formula;
    std::string_view status;
    double a_low, a_high; ///< validity range of a
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

} // namespace packbed
