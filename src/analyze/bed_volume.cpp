#include "packbed/bed_volume.hpp"

#include <exception>
#include <vector>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/sphere_shape.hpp"

namespace packbed {

double detail::sum_in_order(std::size_t n, const std::function<double(std::size_t)>& volume) {
    std::vector<double> terms(n);
    std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 16) if (n > 1)
    for (std::size_t i = 0; i < n; ++i) {
        try {
            terms[i] = volume(i);
        } catch (...) {
#pragma omp critical(packbed_sum_in_order)
            if (!failure)
                failure = std::current_exception();
        }
    }
    if (failure)
        std::rethrow_exception(failure);
    double sum = 0.0;
    for (const double t : terms)
        sum += t;
    return sum;
}

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
