#include "packbed/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/neighbor_list.hpp"
#include "parallel.hpp"

namespace packbed {

namespace {

constexpr double pi = std::numbers::pi;

/// Spheres are summed in fixed chunks, each into its own partial histogram, and the partials
/// are added in chunk order: the same bits whatever the number of threads.
constexpr std::size_t chunk_size = 1024;

/// Add per-chunk partial sums in order. `partials` holds nchunks rows of `bins` values.
std::vector<double> reduce_chunks(const std::vector<double>& partials, std::size_t bins) {
    std::vector<double> total(bins, 0.0);
    for (std::size_t at = 0; at < partials.size(); at += bins)
        for (std::size_t k = 0; k < bins; ++k)
            total[k] += partials[at + k];
    return total;
}

/// Run `per_sphere(i, row)` for every sphere, `row` being its chunk's partial histogram.
template <class F>
std::vector<double> histogram_over_spheres(std::size_t n, std::size_t bins, F&& per_sphere) {
    const std::size_t chunks = (n + chunk_size - 1) / chunk_size;
    std::vector<double> partials(chunks * bins, 0.0);
#pragma omp parallel for schedule(dynamic, 1) if (n >= detail::parallel_min_spheres)
    for (std::size_t c = 0; c < chunks; ++c) {
        double* row = partials.data() + c * bins;
        for (std::size_t i = c * chunk_size; i < std::min(n, (c + 1) * chunk_size); ++i)
            per_sphere(i, row);
    }
    return reduce_chunks(partials, bins);
}

/// e(r) over shells [b_{k+1}, b_k], b_k = Rt - k w (wall first); exact volumes.
std::vector<ProfileBin> radial_void_fraction(const Packing& packing, double rt, double width,
                                             const Band& band) {
    const auto shells = static_cast<std::size_t>(std::ceil(rt / width - 1e-9));
    auto boundary = [&](std::size_t k) {
        return std::max(rt - static_cast<double>(k) * width, 0.0);
    };
    const auto solid =
        histogram_over_spheres(packing.size(), shells, [&](std::size_t i, double* row) {
            const Vec3& c = packing.centers[i];
            const double radius = packing.radii[i];
            const double rho = std::hypot(c.x, c.y);
            // Shells that can hold part of the sphere: boundaries between rho - R and rho + R.
            const double outer = rho + radius, inner = rho - radius;
            const auto k_first =
                static_cast<std::size_t>(std::max(std::floor((rt - outer) / width), 0.0));
            if (k_first >= shells)
                return;
            const auto k_last =
                std::min(shells - 1,
                         static_cast<std::size_t>(std::max(std::ceil((rt - inner) / width), 0.0)));
            auto inside = [&](double cylinder) {
                return cylinder <= 0.0 ? 0.0
                                       : sphere_volume_in_cylinder_slab(c, radius, cylinder,
                                                                        band.z_low, band.z_high);
            };
            double outer_volume = inside(boundary(k_first));
            for (std::size_t k = k_first; k <= k_last; ++k) {
                const double inner_volume = inside(boundary(k + 1));
                row[k] += outer_volume - inner_volume;
                outer_volume = inner_volume;
            }
        });
    const double height = band.z_high - band.z_low;
    std::vector<ProfileBin> out(shells);
    for (std::size_t k = 0; k < shells; ++k) {
        const double hi = boundary(k), lo = boundary(k + 1);
        out[k] = {lo, hi, 1.0 - solid[k] / (pi * (hi * hi - lo * lo) * height)};
    }
    return out;
}

/// e(z) over slabs [k h, (k+1) h] from the floor to the top of the bed; exact volumes.
/// The spheres are taken in order of height, so each chunk touches a short run of slabs and
/// keeps a partial row for that run only: memory O(N) however tall the bed.
std::vector<ProfileBin> axial_void_fraction(const Packing& packing, double rt, double height,
                                            double top) {
    const auto slabs = static_cast<std::size_t>(std::ceil(top / height - 1e-9));
    const std::size_t n = packing.size();
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i)
        order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return packing.centers[a].z < packing.centers[b].z ||
               (packing.centers[a].z == packing.centers[b].z && a < b);
    });
    auto slab_range = [&](std::size_t i) {
        const Vec3& c = packing.centers[i];
        const double r = packing.radii[i];
        const auto first = static_cast<std::size_t>(std::max(std::floor((c.z - r) / height), 0.0));
        const auto last = std::min(
            slabs - 1, static_cast<std::size_t>(std::max(std::floor((c.z + r) / height), 0.0)));
        return std::pair{std::min(first, last), last};
    };
    const std::size_t chunks = (n + chunk_size - 1) / chunk_size;
    std::vector<std::size_t> row_start(chunks);
    std::vector<std::vector<double>> rows(chunks);
#pragma omp parallel for schedule(dynamic, 1) if (n >= detail::parallel_min_spheres)
    for (std::size_t c = 0; c < chunks; ++c) {
        const std::size_t begin = c * chunk_size, end = std::min(n, begin + chunk_size);
        std::size_t lo = slabs, hi = 0;
        for (std::size_t s = begin; s < end; ++s) {
            const auto [first, last] = slab_range(order[s]);
            lo = std::min(lo, first);
            hi = std::max(hi, last);
        }
        row_start[c] = lo;
        rows[c].assign(hi - lo + 1, 0.0);
        for (std::size_t s = begin; s < end; ++s) {
            const std::size_t i = order[s];
            const auto [first, last] = slab_range(i);
            for (std::size_t k = first; k <= last; ++k)
                rows[c][k - lo] += sphere_volume_in_cylinder_slab(
                    packing.centers[i], packing.radii[i], rt, static_cast<double>(k) * height,
                    static_cast<double>(k + 1) * height);
        }
    }
    std::vector<double> solid(slabs, 0.0);
    for (std::size_t c = 0; c < chunks; ++c) // in chunk order: the same bits for any threads
        for (std::size_t j = 0; j < rows[c].size(); ++j)
            solid[row_start[c] + j] += rows[c][j];
    std::vector<ProfileBin> out(slabs);
    for (std::size_t k = 0; k < slabs; ++k) {
        const double lo = static_cast<double>(k) * height, hi = lo + height;
        out[k] = {lo, hi, 1.0 - solid[k] / (pi * rt * rt * height)};
    }
    return out;
}

bool in_band(const Vec3& c, const Band& band) {
    return c.z >= band.z_low && c.z <= band.z_high;
}

/// Relative number density of centres in annuli [b_{k+1}, b_k], b_k = Rt - k w.
std::vector<ProfileBin> centre_distribution(const Packing& packing, double rt, double width,
                                            const Band& band) {
    const auto bins = static_cast<std::size_t>(std::ceil(rt / width - 1e-9));
    std::vector<double> count(bins, 0.0);
    double total = 0.0;
    for (const Vec3& c : packing.centers) {
        if (!in_band(c, band))
            continue;
        const double from_wall = rt - std::hypot(c.x, c.y);
        const auto k = static_cast<std::size_t>(
            std::clamp(std::floor(from_wall / width), 0.0, static_cast<double>(bins - 1)));
        count[k] += 1.0;
        total += 1.0;
    }
    const double mean_density = total / (pi * rt * rt);
    std::vector<ProfileBin> out(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        const double hi = std::max(rt - static_cast<double>(k) * width, 0.0);
        const double lo = std::max(rt - static_cast<double>(k + 1) * width, 0.0);
        const double density = count[k] / (pi * (hi * hi - lo * lo));
        out[k] = {lo, hi, total > 0.0 ? density / mean_density : 0.0};
    }
    return out;
}

Coordination coordination(const Packing& packing, const Cylinder& container, double tolerance,
                          const Band& band) {
    // The list keeps d < r_i + r_j + skin (strict); a contact is gap <= tolerance, so the skin
    // is a hair larger than the tolerance (exactly touching spheres at tolerance 0).
    NeighborList list;
    list.build(packing.centers, packing.radii, tolerance + 1e-9 * (1.0 + tolerance), {}, false);
    Coordination out;
    std::size_t contacts_total = 0, contacts_stable = 0;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double gap_wall = container.radius() - (std::hypot(c.x, c.y) + packing.radii[i]);
        const bool wall = gap_wall <= tolerance;
        out.wall_contacts += wall ? 1 : 0;
        if (!in_band(c, band))
            continue;
        out.wall_contacts_in_band += wall ? 1 : 0;
        std::size_t contacts = 0;
        for (const auto j : list.neighbors_of(i)) {
            const double gap = norm(packing.centers[j] - c) - packing.radii[i] - packing.radii[j];
            contacts += gap <= tolerance ? 1 : 0;
        }
        if (out.histogram.size() <= contacts)
            out.histogram.resize(contacts + 1, 0);
        ++out.histogram[contacts];
        ++out.spheres;
        contacts_total += contacts;
        if (contacts + (wall ? 1 : 0) < 4) {
            ++out.rattlers;
        } else {
            contacts_stable += contacts;
        }
    }
    if (out.spheres > 0)
        out.mean = static_cast<double>(contacts_total) / static_cast<double>(out.spheres);
    if (out.spheres > out.rattlers)
        out.mean_without_rattlers =
            static_cast<double>(contacts_stable) / static_cast<double>(out.spheres - out.rattlers);
    return out;
}

std::vector<ProfileBin> pair_correlation(const Packing& packing, double rt, double range,
                                         double width, const Band& band) {
    const double min_radius = *std::min_element(packing.radii.begin(), packing.radii.end());
    NeighborList list;
    // rows only: at a range of 3 Dp a bed has about 110 listed neighbours per sphere
    list.build(packing.centers, packing.radii, std::max(range - 2.0 * min_radius, 0.0), {}, false);
    const auto bins = static_cast<std::size_t>(std::ceil(range / width - 1e-9));
    std::vector<double> count(bins, 0.0);
    double in = 0.0;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        if (!in_band(packing.centers[i], band))
            continue;
        in += 1.0;
        for (const auto j : list.neighbors_of(i)) {
            const double d = norm(packing.centers[j] - packing.centers[i]);
            // d/width may round up to `bins` when d is just below the range: last bin.
            if (d < range)
                count[std::min(static_cast<std::size_t>(d / width), bins - 1)] += 1.0;
        }
    }
    const double density = in / (pi * rt * rt * (band.z_high - band.z_low));
    std::vector<ProfileBin> out(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        const double lo = static_cast<double>(k) * width, hi = lo + width;
        const double shell = 4.0 / 3.0 * pi * (hi * hi * hi - lo * lo * lo);
        out[k] = {lo, hi, in > 0.0 ? count[k] / (in * density * shell) : 0.0};
    }
    return out;
}

} // namespace

BedAnalysis analyze_bed(const Packing& packing, const Cylinder& container,
                        const AnalysisOptions& options) {
    if (packing.size() == 0)
        throw InvalidInput("analyze: the bed has no spheres");
    BedAnalysis out;
    out.diameter = options.diameter.value_or(packing.mean_diameter());
    const double dp = out.diameter;
    const auto band = band_clear_of_ends(packing, options.band_clearance * dp);
    if (!band)
        throw InvalidInput(fmt::format(
            "analyze: the bed (top at {:.6g}) is not taller than twice the band clearance ({} Dp); "
            "lower the band clearance",
            bed_top(packing), options.band_clearance));
    out.band = *band;
    const double rt = container.radius();
    out.void_fraction = void_fraction(packing, container, band->z_low, band->z_high);
    out.radial_void_fraction = radial_void_fraction(packing, rt, options.shell_width * dp, *band);
    out.axial_void_fraction =
        axial_void_fraction(packing, rt, options.slab_height * dp, bed_top(packing));
    out.centre_distribution = centre_distribution(packing, rt, options.centre_bin * dp, *band);
    out.coordination = coordination(packing, container, options.contact_tolerance * dp, *band);
    out.pair_correlation =
        pair_correlation(packing, rt, options.rdf_range * dp, options.rdf_bin * dp, *band);
    return out;
}

} // namespace packbed
