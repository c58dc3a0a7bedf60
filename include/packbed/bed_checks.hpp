// What a measurement of a bed may hide, said to the person reading it (without these checks,
// `analyze` on a half-poured bed reported e = 0.74 without a word).
#pragma once

#include <string>
#include <vector>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"
#include "packbed/packing.hpp"

namespace packbed {

/// The thresholds of analysis_warnings.
struct BedCheckLimits {
    std::size_t min_centres = 100; ///< fewer sphere centres in the band: e is uncertain
    /// the void fractions of the band's lower and upper halves differ by more than this: the
    /// bed is not uniform along the band (a ragged top, a bed still being poured, layers)
    double max_half_difference = 0.05;
    /// e more than this above Dixon's (1988) correlation at the bed's aspect ratio: looser
    /// than a settled random packing
    double max_above_dixon = 0.1;
};

/// Warnings about a measured bed, each one line naming the numbers and what to do; empty when
/// nothing looks wrong. The halves' void fractions are exact (void_fraction).
std::vector<std::string> analysis_warnings(const Packing& packing, const Container& container,
                                           const BedAnalysis& analysis,
                                           const BedCheckLimits& limits = {});

} // namespace packbed
