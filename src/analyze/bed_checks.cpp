#include "packbed/bed_checks.hpp"

#include <cmath>

#include <fmt/format.h>

#include "packbed/bed_volume.hpp"
#include "packbed/correlations.hpp"
#include "packbed/volume.hpp"

namespace packbed {

std::vector<std::string> analysis_warnings(const Packing& packing, const Container& container,
                                           const BedAnalysis& a, const BedCheckLimits& limits) {
    std::vector<std::string> out;
    const Band band = a.band;
    // The void fraction sums the spheres' volumes, overlaps counted once for each sphere: where
    // they overlap heavily the sum exceeds the band's volume.
    if (a.void_fraction < 0.0)
        out.push_back(fmt::format(
            "the void fraction {:.4f} is below 0: the spheres overlap each other by more than the "
            "band's volume (a pellet's clump read as separate spheres, or a radius column that "
            "holds diameters?); no bed has it",
            a.void_fraction));
    std::size_t centres = 0;
    for (const Vec3& c : packing.centers)
        centres += c.z >= band.z_low && c.z <= band.z_high ? 1 : 0;
    if (centres < limits.min_centres)
        out.push_back(fmt::format(
            "the band z = {:.6g} to {:.6g} holds {} sphere centres (fewer than {}): its void "
            "fraction {:.4f} is uncertain; a taller bed, or a wider band (--band, "
            "--band-clearance), measures more",
            band.z_low, band.z_high, centres, limits.min_centres, a.void_fraction));
    const double middle = 0.5 * (band.z_low + band.z_high);
    const double lower = void_fraction(packing, container, band.z_low, middle);
    const double upper = void_fraction(packing, container, middle, band.z_high);
    if (std::abs(upper - lower) > limits.max_half_difference)
        out.push_back(fmt::format(
            "the void fraction changes along the band: {:.4f} in its lower half (z = {:.6g} to "
            "{:.6g}), {:.4f} in its upper half (to {:.6g}); a ragged top or a bed still being "
            "poured? See axial_void_fraction.csv, and set the band with --band ZLOW,ZHIGH",
            lower, band.z_low, middle, upper, band.z_high));
    // Dixon's correlation is for cylinders: a box or a lattice has no such reference.
    const std::optional<double> tube = container.tube_diameter();
    const double aspect_ratio = tube ? *tube / a.diameter : 0.0;
    for (const auto& c : mean_void_fraction_correlations())
        if (tube && c.name == "dixon-1988") {
            const double dixon = c(aspect_ratio).value;
            if (a.void_fraction > dixon + limits.max_above_dixon)
                out.push_back(fmt::format(
                    "the void fraction {:.4f} is more than {} above that of a settled random "
                    "packing at a = {:.4g} (Dixon 1988: {:.4f}): a bed still being poured, a "
                    "fluidised bed, a lattice, or the wrong container radius?",
                    a.void_fraction, limits.max_above_dixon, aspect_ratio, dixon));
        }
    return out;
}

} // namespace packbed
