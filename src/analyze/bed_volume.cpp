#include "packbed/bed_volume.hpp"

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/sphere_shape.hpp"

namespace packbed {

void check_band(double z_low, double z_high) {
    if (!(z_high > z_low))
        throw InvalidInput(fmt::format(
            "void fraction: band [{}, {}] is empty; the upper height must exceed the lower", z_low,
            z_high));
}

double void_fraction(const Packing& packing, const Container& container, double z_low,
                     double z_high) {
    return void_fraction(spheres(packing), container, z_low, z_high);
}

double bed_top(const Packing& packing) {
    return bed_top(spheres(packing));
}

std::optional<Band> band_clear_of_ends(const Packing& packing, double clearance) {
    const Band band{clearance, bed_top(packing) - clearance};
    if (!(band.z_high > band.z_low))
        return std::nullopt;
    return band;
}

} // namespace packbed
