#include "packbed/analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include <boost/math/quadrature/gauss.hpp>
#include <fmt/format.h>
#include <omp.h>

#include "base/parallel.hpp"
#include "geometry/cell_grid.hpp"
#include "packbed/error.hpp"
#include "packbed/limits.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/sizes.hpp"
#include "packbed/sphere_shape.hpp"

namespace packbed {

namespace {

/// Spheres are summed in fixed chunks, each into its own partial histogram, and the partials
/// are added in chunk order: the same bits whatever the number of threads. A chunk holds at
/// most 1 024 spheres, and a bed of fewer than 16 384 is cut into 16 chunks of at least 32: a
/// sphere's exact volumes cost tens of microseconds, so even a bed of a few hundred spheres is
/// worth sharing among threads (unlike a relaxation step, detail::parallel_min_spheres). The
/// size depends on the bed alone, never on the threads.
std::size_t chunk_size_for(std::size_t n) {
    return std::clamp<std::size_t>((n + 15) / 16, 32, 1024);
}

/// The partial histograms held at once, values (2^24: 128 MB): chunks are processed in
/// batches that fit, so the memory does not grow with bins x spheres.
constexpr std::size_t partial_values = std::size_t{1} << 24;

/// The first exception thrown by the bodies of a parallel loop, rethrown after it: one that
/// escapes an OpenMP region terminates the process. (The loops allocate nothing; this holds
/// for whatever a volume routine might throw.)
class ParallelErrors {
public:
    template <class F> void run(F&& body) noexcept {
        try {
            body();
        } catch (...) {
#pragma omp critical(packbed_analysis_errors)
            if (!m_first)
                m_first = std::current_exception();
        }
    }
    void rethrow() const {
        if (m_first)
            std::rethrow_exception(m_first);
    }

private:
    std::exception_ptr m_first;
};

/// Chunks fewer than this (a bed of fewer than about 500 particles) leave threads idle; each
/// particle is then computed alone into its own row, in parallel, and the rows are added in
/// the chunks' order (histogram_over_spheres, axial_void_fraction).
constexpr std::size_t few_chunks = 16;

/// Run `per_sphere(i, row)` for every sphere, `row` being its chunk's partial histogram of
/// `bins` values, and add the rows in chunk order (batches of chunks at a time: the same
/// additions in the same order as all at once). `per_sphere` adds to each value of the row at
/// most once: a bed of few chunks then runs each particle into a zeroed row of its own, in
/// parallel, and adds those rows to their chunk's in order, the same additions (x + 0 = x).
template <class F>
std::vector<double> histogram_over_spheres(std::size_t n, std::size_t bins, F&& per_sphere) {
    const std::size_t chunk_size = chunk_size_for(n);
    const std::size_t chunks = (n + chunk_size - 1) / chunk_size;
    std::vector<double> total(bins, 0.0);
    if (chunks < few_chunks && n * bins <= partial_values) {
        std::vector<double> rows(n * bins, 0.0);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
        for (std::size_t i = 0; i < n; ++i)
            errors.run([&] { per_sphere(i, rows.data() + i * bins); });
        errors.rethrow();
        std::vector<double> row(bins);
        for (std::size_t c = 0; c < chunks; ++c) {
            std::fill(row.begin(), row.end(), 0.0);
            for (std::size_t i = c * chunk_size; i < std::min(n, (c + 1) * chunk_size); ++i)
                for (std::size_t k = 0; k < bins; ++k)
                    row[k] += rows[i * bins + k];
            for (std::size_t k = 0; k < bins; ++k)
                total[k] += row[k];
        }
        return total;
    }
    const std::size_t batch = std::clamp<std::size_t>(partial_values / bins, 1, chunks);
    std::vector<double> partials(batch * bins);
    for (std::size_t first = 0; first < chunks; first += batch) {
        const std::size_t count = std::min(batch, chunks - first);
        std::fill(partials.begin(), partials.begin() + static_cast<std::ptrdiff_t>(count * bins),
                  0.0);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) if (count > 1)
        for (std::size_t b = 0; b < count; ++b)
            errors.run([&] {
                const std::size_t c = first + b;
                double* row = partials.data() + b * bins;
                for (std::size_t i = c * chunk_size; i < std::min(n, (c + 1) * chunk_size); ++i)
                    per_sphere(i, row);
            });
        errors.rethrow();
        for (std::size_t b = 0; b < count; ++b)
            for (std::size_t k = 0; k < bins; ++k)
                total[k] += partials[b * bins + k];
    }
    return total;
}

/// e(d) over `shells` shells of the distance d from wall `wall` (Container::profile_walls),
/// [k w, (k+1) w] (wall first; the last ends at the container's depth); exact volumes: each
/// sphere's part in a shell is the difference of its volumes inside the container shrunk from
/// that wall by the shell's two distances (Container::shrunk_from).
template <ParticleShape S>
std::vector<ProfileBin> wall_void_fraction(const ShapedBed<S>& bed, const Container& container,
                                           std::size_t wall, double width, const Band& band,
                                           std::size_t shells) {
    auto distance = [&](std::size_t k) { return static_cast<double>(k) * width; };
    const double last_shell = static_cast<double>(shells - 1);
    const auto solid = histogram_over_spheres(bed.size(), shells, [&](std::size_t i, double* row) {
        const S& shape = bed.shape(i);
        const Placement p = bed.placement(i);
        // Shells that can hold part of the particle: from its nearest to its farthest
        // distance from the wall (clamped in double, before the casts).
        const auto [nearest, farthest] = shape.wall_extent(container, wall, p);
        const double first = std::max(std::floor(nearest / width), 0.0);
        if (first > last_shell)
            return;
        const auto k_first = static_cast<std::size_t>(first);
        const auto k_last = static_cast<std::size_t>(
            std::min(last_shell, std::max(std::ceil(farthest / width), 0.0)));
        auto inside = [&](std::size_t k) {
            return shape.volume_from_wall(container, wall, distance(k), p, band.z_low, band.z_high);
        };
        double outer_volume = inside(k_first);
        for (std::size_t k = k_first; k <= k_last; ++k) {
            const double inner_volume = inside(k + 1);
            row[k] += outer_volume - inner_volume;
            outer_volume = inner_volume;
        }
    });
    const double height = band.z_high - band.z_low;
    const double depth = container.depth(band.z_low, band.z_high);
    std::vector<ProfileBin> out(shells);
    for (std::size_t k = 0; k < shells; ++k) {
        const double lo = distance(k), hi = distance(k + 1);
        const double area = container.shell_area_from(wall, lo, hi, band.z_low, band.z_high);
        out[k] = {lo, std::min(hi, depth), 1.0 - solid[k] / (area * height)};
    }
    return out;
}

/// e(z) over `slabs` slabs [k h, (k+1) h] from the floor to the top of the bed; exact volumes.
/// The spheres are taken in order of height, so each chunk touches a short run of slabs and
/// keeps a partial row for that run only: memory O(N) however tall the bed.
template <ParticleShape S>
std::vector<ProfileBin> axial_void_fraction(const ShapedBed<S>& bed, const Container& container,
                                            double height, std::size_t slabs) {
    const Packing& packing = bed.particles();
    const std::size_t n = packing.size();
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i)
        order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return packing.centers[a].z < packing.centers[b].z ||
               (packing.centers[a].z == packing.centers[b].z && a < b);
    });
    const double last_slab = static_cast<double>(slabs - 1);
    auto slab_range = [&](std::size_t i) {
        const Placement p = bed.placement(i);
        const double low = bed.shape(i).support(p, Vec3{0.0, 0.0, -1.0}).z;
        const double high = bed.shape(i).support(p, Vec3{0.0, 0.0, 1.0}).z;
        const auto first =
            static_cast<std::size_t>(std::clamp(std::floor(low / height), 0.0, last_slab));
        const auto last =
            static_cast<std::size_t>(std::clamp(std::floor(high / height), 0.0, last_slab));
        return std::pair{std::min(first, last), last};
    };
    // The run of slabs of each chunk first (no allocation in the parallel loops), then the
    // chunks' rows in batches of bounded size, added in chunk order.
    const std::size_t chunk_size = chunk_size_for(n);
    const std::size_t chunks = (n + chunk_size - 1) / chunk_size;
    std::vector<std::size_t> row_start(chunks), row_end(chunks);
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t c = 0; c < chunks; ++c) {
        std::size_t lo = slabs, hi = 0;
        for (std::size_t s = c * chunk_size; s < std::min(n, (c + 1) * chunk_size); ++s) {
            const auto [first, last] = slab_range(order[s]);
            lo = std::min(lo, first);
            hi = std::max(hi, last);
        }
        row_start[c] = lo;
        row_end[c] = hi + 1;
    }
    auto volume = [&](std::size_t i, std::size_t k) {
        return bed.shape(i).volume_in(container, bed.placement(i), static_cast<double>(k) * height,
                                      static_cast<double>(k + 1) * height);
    };
    // Few chunks (few_chunks): each particle's slabs first, in parallel over the particles,
    // stored from at[s]; the chunks below then add the stored values in the same order.
    std::vector<double> stored;
    std::vector<std::size_t> at;
    if (chunks < few_chunks) {
        at.assign(n + 1, 0);
        for (std::size_t s = 0; s < n; ++s) {
            const auto [k_first, k_last] = slab_range(order[s]);
            at[s + 1] = at[s] + (k_last - k_first + 1);
        }
        stored.assign(at[n], 0.0);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
        for (std::size_t s = 0; s < n; ++s)
            errors.run([&] {
                const std::size_t i = order[s];
                const auto [k_first, k_last] = slab_range(i);
                for (std::size_t k = k_first; k <= k_last; ++k)
                    stored[at[s] + (k - k_first)] = volume(i, k);
            });
        errors.rethrow();
    }
    std::vector<double> solid(slabs, 0.0);
    std::vector<double> rows;
    std::vector<std::size_t> row_at(chunks);
    for (std::size_t first = 0; first < chunks;) {
        std::size_t end = first, values = 0;
        while (end < chunks &&
               (end == first || values + (row_end[end] - row_start[end]) <= partial_values)) {
            row_at[end] = values;
            values += row_end[end] - row_start[end];
            ++end;
        }
        rows.assign(values, 0.0);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) if (end - first > 1)
        for (std::size_t c = first; c < end; ++c)
            errors.run([&] {
                double* row = rows.data() + row_at[c];
                for (std::size_t s = c * chunk_size; s < std::min(n, (c + 1) * chunk_size); ++s) {
                    const std::size_t i = order[s];
                    const auto [k_first, k_last] = slab_range(i);
                    for (std::size_t k = k_first; k <= k_last; ++k)
                        row[k - row_start[c]] +=
                            stored.empty() ? volume(i, k) : stored[at[s] + (k - k_first)];
                }
            });
        errors.rethrow();
        for (std::size_t c = first; c < end; ++c) // in chunk order: the same bits for any threads
            for (std::size_t j = 0; j < row_end[c] - row_start[c]; ++j)
                solid[row_start[c] + j] += rows[row_at[c] + j];
        first = end;
    }
    std::vector<ProfileBin> out(slabs);
    for (std::size_t k = 0; k < slabs; ++k) {
        const double lo = static_cast<double>(k) * height, hi = lo + height;
        out[k] = {lo, hi, 1.0 - solid[k] / (container.cross_section_area(lo, hi) * height)};
    }
    return out;
}

bool in_band(const Vec3& c, const Band& band) {
    return c.z >= band.z_low && c.z <= band.z_high;
}

/// Relative number density of centres in `bins` shells of the distance from wall `wall`,
/// [k w, (k+1) w], over the mean density across the whole cross-section; a shell counts the
/// centres of that wall's part of the cross-section (Container::nearest_wall); only the
/// spheres i with member(i) (a size class), each over the class's own mean density.
template <class Member>
std::vector<ProfileBin> centre_distribution(const Packing& packing, const Container& container,
                                            std::size_t wall, double width, const Band& band,
                                            std::size_t bins, Member member) {
    std::vector<double> count(bins, 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        if (!in_band(c, band) || !member(i))
            continue;
        total += 1.0;
        if (container.nearest_wall(c) != wall)
            continue;
        const double from_wall = container.wall_distance_from(wall, c);
        const auto k = static_cast<std::size_t>(
            std::clamp(std::floor(from_wall / width), 0.0, static_cast<double>(bins - 1)));
        count[k] += 1.0;
    }
    const double mean_density = total / container.cross_section_area(band.z_low, band.z_high);
    const double depth = container.depth(band.z_low, band.z_high);
    std::vector<ProfileBin> out(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        const double lo = static_cast<double>(k) * width, hi = static_cast<double>(k + 1) * width;
        const double density =
            count[k] / container.shell_area_from(wall, lo, hi, band.z_low, band.z_high);
        out[k] = {lo, std::min(hi, depth), total > 0.0 ? density / mean_density : 0.0};
    }
    return out;
}

/// The pair searches of the contacts and g(r) visit pairs in a CellGrid without storing them,
/// so their memory is O(N) whatever the distance searched (the rows of a NeighborList for g(r)
/// to 20 Dp would take 130 GB for 1e6 spheres).
using detail::CellGrid;

/// Cells a hair larger than the distance searched: a pair that distance apart lies in
/// neighbouring cells despite the rounding of the cell indices (< 1e-7 of a cell, the grid
/// having at most 8 N + 64 cells along an axis).
constexpr double cell_margin = 1.0 + 1e-6;

/// The points a pair search runs on: the centres themselves, or in a periodic cell the
/// centres moved into the cell and their copies within `cut` of its sides
/// (detail::periodic_images), each copy standing for its sphere. Points 0 to n - 1 are the
/// spheres. Not copyable (it may point at its own copies).
struct SearchPoints {
    std::size_t n = 0;
    std::vector<Vec3> images;         // periodic: the spheres in the cell, then the copies
    std::vector<std::uint32_t> owner; // periodic: the sphere of copy n + k
    const Vec3* points = nullptr;     // the points searched

    SearchPoints(const Packing& packing, const Container& container, double cut)
        : n(packing.size())
        , points(packing.centers.data()) {
        if (const std::optional<Periods> cell = container.periods()) {
            detail::periodic_images(*cell, packing.centers, cut, images, owner);
            points = images.data();
        }
    }
    SearchPoints(const SearchPoints&) = delete;
    SearchPoints& operator=(const SearchPoints&) = delete;

    std::span<const Vec3> all() const { return {points, n + owner.size()}; }
    /// \return the sphere point j stands for.
    std::uint32_t sphere(std::uint32_t j) const { return j < n ? j : owner[j - n]; }
};

/// The contact search. Spheres up to `small_radius` (the largest radius, or the mean diameter
/// if some sphere is larger) find their contacts among themselves in the 27 cells around their
/// own, of edge 2 small_radius + tolerance; a larger sphere searches as many cells as its own
/// reach needs and counts its contacts for both spheres. One huge sphere among small ones
/// then costs about N checks, not N per sphere.
struct ContactSearch {
    double tolerance = 0.0;
    double small_radius = 0.0;
    double largest_radius = 0.0;
    SearchPoints points; // the centres, or their copies in a periodic cell
    CellGrid grid;
    std::vector<std::uint32_t> large; // spheres above small_radius
    std::uint64_t work = 0;           // distance checks (and cells) the search takes

    ContactSearch(const Packing& packing, const Container& container, double tol, const Band& band,
                  double mean_diameter)
        : tolerance(tol)
        , small_radius(std::min(*std::max_element(packing.radii.begin(), packing.radii.end()),
                                mean_diameter))
        , largest_radius(*std::max_element(packing.radii.begin(), packing.radii.end()))
        , points(packing, container, 2.0 * largest_radius + tol)
        , grid(points.all(), (2.0 * small_radius + tol) * cell_margin) {
        for (std::size_t i = 0; i < packing.size(); ++i) {
            if (packing.radii[i] > small_radius) {
                large.push_back(static_cast<std::uint32_t>(i));
                work += grid.work(i, reach_of(packing.radii[i]));
            } else if (in_band(packing.centers[i], band)) {
                work += grid.work(i, 1);
            }
        }
    }

    /// Cells out a sphere of radius r searches to find every sphere it may touch.
    int reach_of(double r) const {
        return grid.cells_within((r + largest_radius + tolerance) * cell_margin);
    }
};

/// The contact counts of the particles in the band added up into a Coordination: the histogram,
/// the rattlers and the two means.
struct CoordinationTally {
    Coordination& out;
    std::size_t total = 0, held = 0;

    /// One particle: k contacts with others, `walls` walls touched (each one contact for the
    /// rattler rule).
    void add(std::size_t k, std::size_t walls) {
        if (out.histogram.size() <= k)
            out.histogram.resize(k + 1, 0);
        ++out.histogram[k];
        ++out.spheres;
        total += k;
        if (k + walls < out.rattler_contacts)
            ++out.rattlers;
        else
            held += k;
    }
    void finish() {
        if (out.spheres > 0)
            out.mean = static_cast<double>(total) / static_cast<double>(out.spheres);
        if (out.spheres > out.rattlers)
            out.mean_without_rattlers =
                static_cast<double>(held) / static_cast<double>(out.spheres - out.rattlers);
    }
};

/// The contacts of the spheres in the band; `per_sphere` gets each sphere's count of
/// sphere-sphere contacts (0 outside the band), `walls` one entry per profile wall with its
/// name and wall contacts; `frictional` takes the rattler rule of frictional contacts.
Coordination coordination(const Packing& packing, const Container& container,
                          const ContactSearch& search, const Band& band, bool frictional,
                          std::vector<std::uint32_t>& per_sphere,
                          std::vector<WallAnalysis>& walls) {
    const std::size_t n = packing.size();
    const double tolerance = search.tolerance, small = search.small_radius;
    const Vec3* const x = search.points.points;
    const double* const radius = packing.radii.data();
    auto sphere = [&](std::uint32_t j) { return search.points.sphere(j); };
    // A contact is gap <= tolerance, gap = |x_j - x_i| - r_i - r_j, subtracted in this order
    // for sphere i (whichever sphere finds the pair); i and j are points (a copy in a periodic
    // cell: every copy within the distance is a contact).
    auto touching = [&](std::uint32_t i, std::uint32_t j) {
        return norm(x[j] - x[i]) - radius[sphere(i)] - radius[sphere(j)] <= tolerance;
    };
    std::vector<std::uint32_t> contacts(n, 0);
#pragma omp parallel for schedule(dynamic, 256) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i) {
        if (radius[i] > small || !in_band(x[i], band))
            continue;
        std::uint32_t count = 0;
        search.grid.for_each_near(i, 1, [&](std::uint32_t j) {
            count +=
                j != i && radius[sphere(j)] <= small && touching(static_cast<std::uint32_t>(i), j)
                    ? 1
                    : 0;
        });
        contacts[i] = count;
    }
    for (const std::uint32_t i : search.large) // few: serially, as they add to others' counts
        search.grid.for_each_near(i, search.reach_of(radius[i]), [&](std::uint32_t j) {
            if (j == i)
                return;
            contacts[i] += touching(i, j) ? 1 : 0;
            if (radius[sphere(j)] <= small)
                contacts[sphere(j)] += touching(j, i) ? 1 : 0;
        });

    Coordination out;
    out.rattler_contacts = frictional ? 2 : 4;
    const std::size_t wall_count = container.profile_walls().size();
    walls.assign(wall_count, WallAnalysis{});
    for (std::size_t w = 0; w < wall_count; ++w)
        walls[w].name = container.profile_walls()[w];
    CoordinationTally tally{out};
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& c = packing.centers[i];
        // Each wall the sphere touches is one contact for the rattler rule; `wall` says it
        // touches one.
        std::size_t touched = 0;
        for (std::size_t w = 0; w < wall_count; ++w)
            if (container.wall_distances_from(w, c, radius[i]).first <= tolerance) {
                ++touched;
                ++walls[w].wall_contacts;
                walls[w].wall_contacts_in_band += in_band(c, band) ? 1 : 0;
            }
        const bool wall = touched > 0;
        out.wall_contacts += wall ? 1 : 0;
        if (!in_band(c, band))
            continue;
        out.wall_contacts_in_band += wall ? 1 : 0;
        tally.add(contacts[i], touched);
    }
    tally.finish();
    per_sphere = std::move(contacts);
    return out;
}

/// The size classes of a bed of more than one size (size_classes: one per distinct diameter
/// up to max_discrete_classes, else bins even in ln d), each with its spheres' share, their
/// mean coordination in the band and their centre distribution; empty for one size.
std::vector<SizeClassAnalysis> by_size(const Packing& packing, const Container& container,
                                       double width, const Band& band, std::size_t bins,
                                       const std::vector<std::uint32_t>& contacts,
                                       SizeStatistics& statistics) {
    statistics = {};
    const auto [smallest, largest] =
        std::minmax_element(packing.radii.begin(), packing.radii.end());
    if (*smallest == *largest) // one size: nothing to sort or classify
        return {};
    std::vector<double> diameters(packing.size());
    for (std::size_t i = 0; i < packing.size(); ++i)
        diameters[i] = 2.0 * packing.radii[i];
    statistics = size_statistics(diameters);
    if (statistics.classes.size() < 2) {
        statistics = {};
        return {};
    }
    std::vector<std::size_t> class_of(packing.size());
    for (std::size_t i = 0; i < packing.size(); ++i)
        class_of[i] = size_class_of(statistics.classes, diameters[i]);
    std::vector<SizeClassAnalysis> out;
    for (std::size_t c = 0; c < statistics.classes.size(); ++c) {
        const SizeClass& k = statistics.classes[c];
        SizeClassAnalysis a;
        a.low = k.low;
        a.high = k.high;
        a.spheres = k.count;
        a.number_fraction = k.number_fraction;
        a.volume_fraction = k.volume_fraction;
        std::uint64_t touching = 0;
        for (std::size_t i = 0; i < packing.size(); ++i)
            if (class_of[i] == c && in_band(packing.centers[i], band)) {
                ++a.in_band;
                touching += contacts[i];
            }
        a.mean_coordination =
            a.in_band > 0 ? static_cast<double>(touching) / static_cast<double>(a.in_band) : 0.0;
        if (container.profile_walls().size() == 1)
            a.centre_distribution =
                centre_distribution(packing, container, 0, width, band, bins,
                                    [&](std::size_t i) { return class_of[i] == c; });
        out.push_back(std::move(a));
    }
    return out;
}

/// g(r) over `bins` bins of `width` up to `range`, from the pairs `grid` (cells of edge >=
/// range, over `points`) finds with both centres in `band`, normalised in `region`
/// (analysis.hpp). In a periodic cell every copy within the range counts, and the region's
/// volume is the whole ball's (Periodic::ball_volume).
std::vector<ProfileBin> pair_correlation(const Packing& packing, const Band& band,
                                         const PairRegion& region, double range, double width,
                                         std::size_t bins, const SearchPoints& points,
                                         const CellGrid& grid) {
    const std::size_t n = packing.size();
    const Vec3* const x = points.points; // the centres, or their copies in a periodic cell
    // Whole-number counts, so their sum is the same in any order: one histogram per thread,
    // as many threads as 128 MB of histograms allow.
    const bool parallel = n >= detail::parallel_min_spheres;
    const int copies =
        parallel ? static_cast<int>(std::clamp<std::size_t>(
                       partial_values / bins, 1, static_cast<std::size_t>(omp_get_max_threads())))
                 : 1;
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(copies) * bins, 0);
#pragma omp parallel num_threads(copies) if (parallel && copies > 1)
    {
        std::uint64_t* const count = counts.data() + omp_get_thread_num() * bins;
#pragma omp for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            if (!in_band(x[i], band))
                continue;
            grid.for_each_near(i, 1, [&](std::uint32_t j) {
                const double d = norm(x[j] - x[i]);
                // d/width may round up to `bins` when d is just below the range: last bin.
                if (j != i && d < range && in_band(x[j], band))
                    ++count[std::min(static_cast<std::size_t>(d / width), bins - 1)];
            });
        }
    }
    std::vector<double> count(bins, 0.0);
    for (int t = 0; t < copies; ++t)
        for (std::size_t k = 0; k < bins; ++k)
            count[k] += static_cast<double>(counts[static_cast<std::size_t>(t) * bins + k]);
    double in = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        in += in_band(x[i], band) ? 1.0 : 0.0;

    // sum_i V_i of each bin, V_i the shell's volume inside the region around centre i: the
    // differences of the ball volumes at successive bin edges (the last edge is the range,
    // where the counting stops), summed in fixed chunks (the same bits for any threads).
    auto edge = [&](std::size_t k) { return k < bins ? static_cast<double>(k) * width : range; };
    const std::vector<double> volume =
        histogram_over_spheres(n, bins, [&](std::size_t i, double* row) {
            if (!in_band(x[i], band))
                return;
            double inner = 0.0;
            for (std::size_t k = 0; k < bins; ++k) {
                const double outer = ball_volume_in_pair_region(x[i], edge(k + 1), region);
                row[k] += outer - inner;
                inner = outer;
            }
        });
    // The density of the other centres in the region: an ideal gas of `in` points in it puts
    // (in - 1) V_i / |region| of them in the shell around each.
    const double height = region.band.z_high - region.band.z_low;
    const double area = region.container.cross_section_area(region.band.z_low, region.band.z_high);
    const double density = area > 0.0 && height > 0.0 ? (in - 1.0) / (area * height) : 0.0;
    std::vector<ProfileBin> out(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        const double lo = static_cast<double>(k) * width, hi = lo + width;
        const double expected = density * volume[k];
        out[k] = {lo, hi, expected > 0.0 ? count[k] / expected : 0.0};
    }
    return out;
}

/// Refuse a sphere or an option that no measurement can use.
void check_input(const Packing& packing, const Container& container, const AnalysisOptions& o) {
    if (packing.size() > limits::max_spheres)
        throw InvalidInput(fmt::format("the bed has {} spheres; allowed: at most {}",
                                       packing.size(), limits::max_spheres));
    const double far = limits::max_length;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double r = packing.radii[i];
        if (!(std::abs(c.x) <= far && std::abs(c.y) <= far && std::abs(c.z) <= far && r > 0.0 &&
              r <= far))
            throw InvalidInput(
                fmt::format("sphere {} at ({}, {}, {}) of radius {} is not allowed; allowed: "
                            "coordinates within {:g} of the origin and a radius > 0 up to {:g}",
                            i + 1, c.x, c.y, c.z, r, far, far));
    }
    if (const std::optional<double> tube = container.tube_diameter()) {
        const double rt = 0.5 * *tube;
        if (!(rt > 0.0 && rt <= far))
            throw InvalidInput(fmt::format("--container-radius = {} is not allowed; "
                                           "allowed: > 0 and at most {:g}",
                                           rt, far));
    } else {
        const Rectangle b = container.bounds();
        if (!(container.cross_section_area(0.0, 0.0) > 0.0 && std::abs(b.x_low) <= far &&
              std::abs(b.x_high) <= far && std::abs(b.y_low) <= far && std::abs(b.y_high) <= far))
            throw InvalidInput(fmt::format("--container {} is not allowed; allowed: widths > 0, "
                                           "sides within {:g} of the origin",
                                           container.spec(), far));
    }
    auto positive = [](double v, std::string_view name) {
        if (!(std::isfinite(v) && v > 0.0))
            throw InvalidInput(fmt::format("{} = {} is not allowed; allowed: > 0 (Dp)", name, v));
    };
    positive(o.shell_width, "--shell-width");
    positive(o.slab_height, "--slab-height");
    positive(o.centre_bin, "--centre-bin");
    positive(o.rdf_range, "--rdf-range");
    positive(o.rdf_bin, "--rdf-bin");
    for (const auto& [v, name] : {std::pair{o.band_clearance, "--band-clearance"},
                                  std::pair{o.contact_tolerance, "--contact-tolerance"}})
        if (!(std::isfinite(v) && v >= 0.0))
            throw InvalidInput(fmt::format("{} = {} is not allowed; allowed: >= 0 (Dp)", name, v));
}

/// The most bins a profile of n spheres may have (limits.hpp).
double bin_budget(std::size_t n) {
    return std::max(limits::min_profile_bins,
                    limits::profile_bins_per_sphere * static_cast<double>(n));
}

/// ceil(extent / width - 1e-9) and at least 1, in double: compared with the budget before any
/// cast.
double bins_over(double extent, double width) {
    return std::max(1.0, std::ceil(extent / width - 1e-9));
}

/// " (N spheres: the larger of 1e6 and 100 per sphere)", for the messages.
std::string budget_reason(std::size_t n) {
    return fmt::format("{} spheres: the larger of {:g} and {:g} per sphere", n,
                       limits::min_profile_bins, limits::profile_bins_per_sphere);
}

/// The number of axial slabs, checked: a bed made tall by a sphere far above the rest is
/// refused saying so.
std::size_t axial_slabs(const Packing& packing, double height, double slab, double dp) {
    const double slabs = bins_over(height, slab * dp);
    const double budget = bin_budget(packing.size());
    if (slabs <= budget)
        return static_cast<std::size_t>(slabs);
    // The top of the highest sphere and of the next highest.
    double first = -std::numeric_limits<double>::infinity(), second = first;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const double top = packing.centers[i].z + packing.radii[i];
        if (top > first) {
            second = first;
            first = top;
        } else if (top > second) {
            second = top;
        }
    }
    const std::string outlier =
        packing.size() > 1 && first - second > 0.5 * height
            ? fmt::format("; its highest sphere (top at z = {:.6g}) is {:.3g} Dp above the next "
                          "highest (top at z = {:.6g}): remove it, or raise --slab-height",
                          first, (first - second) / dp, second)
            : "; raise --slab-height";
    throw InvalidInput(fmt::format(
        "the bed is {:.6g} tall (the top of its highest sphere), which needs {:.3g} "
        "slabs of --slab-height {} Dp (Dp = {:.6g}) for the axial profile; allowed: at most "
        "{:.3g} ({}){}",
        height, slabs, slab, dp, budget, budget_reason(packing.size()), outlier));
}

/// The number of bins of `width` Dp from the wall to the container's depth, checked.
std::size_t radial_bins(const Packing& packing, const Container& container, const Band& band,
                        double width, double dp, std::string_view option, std::string_view noun,
                        std::string_view profile) {
    const double depth = container.depth(band.z_low, band.z_high);
    const double bins = bins_over(depth, width * dp);
    const double budget = bin_budget(packing.size());
    if (bins <= budget)
        return static_cast<std::size_t>(bins);
    if (!container.tube_diameter())
        throw InvalidInput(fmt::format(
            "--container {} needs {:.3g} {} of {} {} Dp (Dp = {:.6g}) from the wall to the "
            "middle for the {}; allowed: at most {:.3g} ({}); a smaller container or a larger {}",
            container.spec(), bins, noun, option, width, dp, profile, budget,
            budget_reason(packing.size()), option));
    const double rt = depth;
    double reach = 0.0; // how far the spheres reach from the axis
    for (std::size_t i = 0; i < packing.size(); ++i)
        reach = std::max(reach,
                         std::hypot(packing.centers[i].x, packing.centers[i].y) + packing.radii[i]);
    throw InvalidInput(fmt::format(
        "--container-radius {} needs {:.3g} {} of {} {} Dp (Dp = {:.6g}) for the {}; "
        "allowed: at most {:.3g} ({}){}",
        rt, bins, noun, option, width, dp, profile, budget, budget_reason(packing.size()),
        reach < 0.5 * rt ? fmt::format("; the spheres reach only {:.6g} from the axis", reach)
                         : fmt::format("; lower --container-radius or raise {}", option)));
}

/// The most distance checks a pair search to `distance` may take (limits.hpp).
double pair_budget(std::size_t n, double distance, double mean_diameter) {
    const double scale = std::max(1.0, std::pow(distance / mean_diameter, 3));
    return std::max(limits::min_pair_checks,
                    limits::pair_checks_per_sphere * static_cast<double>(n) * scale);
}

} // namespace

PairRegion pair_region(const Packing& packing, const Container& container, const Band& band) {
    double radii = 0.0, counted = 0.0;
    for (std::size_t i = 0; i < packing.size(); ++i)
        if (in_band(packing.centers[i], band)) {
            radii += packing.radii[i];
            counted += 1.0;
        }
    const double mean_radius = counted > 0.0 ? radii / counted : 0.0;
    // A band given by the user may reach the floor or the top, where no centre can be.
    const Band heights{std::max(band.z_low, mean_radius),
                       std::min(band.z_high, bed_top(packing) - mean_radius)};
    return {container.shrunk(mean_radius), heights};
}

double ball_volume_in_pair_region(const Vec3& centre, double radius, const PairRegion& region) {
    if (!(region.band.z_high > region.band.z_low))
        return 0.0;
    return region.container.ball_volume(centre, radius, region.band.z_low, region.band.z_high);
}

BedAnalysis analyze_bed(const Packing& packing, const Container& container,
                        const AnalysisOptions& options) {
    if (packing.size() == 0)
        throw InvalidInput("the bed has no spheres");
    check_input(packing, container, options);
    BedAnalysis out;
    const double mean_diameter = packing.mean_diameter();
    out.diameter = options.diameter.value_or(mean_diameter);
    const double dp = out.diameter;
    // Bins and search distances are set in Dp: a Dp far from the spheres' size measures
    // nothing (a bin per sphere, or every sphere in one bin) and multiplies the work.
    const double ratio = limits::max_reference_diameter_ratio;
    if (!(dp >= mean_diameter / ratio && dp <= mean_diameter * ratio))
        throw InvalidInput(fmt::format(
            "--diameter = {} is not allowed; allowed: {:.6g} to {:.6g} ({:g} to {:g} "
            "times the spheres' mean diameter, {:.6g})",
            dp, mean_diameter / ratio, mean_diameter * ratio, 1.0 / ratio, ratio, mean_diameter));
    if (options.band) {
        const Band b = *options.band;
        const double top = bed_top(packing);
        if (!(b.z_low >= 0.0 && b.z_low < b.z_high && b.z_high <= top))
            throw InvalidInput(fmt::format(
                "--band {},{} is not allowed; allowed: ZLOW,ZHIGH with 0 <= ZLOW < ZHIGH <= {:.6g} "
                "(the bed's top)",
                b.z_low, b.z_high, top));
    }
    const auto band =
        options.band ? options.band : band_clear_of_ends(packing, options.band_clearance * dp);
    if (!band)
        throw InvalidInput(fmt::format(
            "--band-clearance {} Dp is not allowed for this bed (top at {:.6g}, {:.6g} Dp); "
            "allowed: less than half its height",
            options.band_clearance, bed_top(packing), bed_top(packing) / dp));
    out.band = *band;

    // Every bin count and the work of the pair searches, checked before any of it is done.
    // A periodic cell has no wall to measure profiles from.
    const bool walled = !container.profile_walls().empty();
    const std::size_t shells = walled ? radial_bins(packing, container, *band, options.shell_width,
                                                    dp, "--shell-width", "shells", "radial profile")
                                      : 0;
    const std::size_t centre_bins =
        walled ? radial_bins(packing, container, *band, options.centre_bin, dp, "--centre-bin",
                             "bins", "centre distribution")
               : 0;
    const std::size_t slabs = axial_slabs(packing, bed_top(packing), options.slab_height, dp);
    const double rdf_range = options.rdf_range * dp, rdf_bin = options.rdf_bin * dp;
    const double rdf_bins = bins_over(rdf_range, rdf_bin);
    const double budget = bin_budget(packing.size());
    if (!(rdf_bins <= budget))
        throw InvalidInput(fmt::format("--rdf-range {} Dp needs {:.3g} bins of --rdf-bin "
                                       "{} Dp for g(r); allowed: at most {:.3g} ({})",
                                       options.rdf_range, rdf_bins, options.rdf_bin, budget,
                                       budget_reason(packing.size())));
    if (const std::optional<Periods> cell = container.periods()) {
        // The searches find every copy within their distance among the copies one period
        // away (detail::periodic_images): the distance must not exceed a period.
        const double period = std::min(cell->lx(), cell->ly());
        const double largest = *std::max_element(packing.radii.begin(), packing.radii.end());
        const double contact = 2.0 * largest + options.contact_tolerance * dp;
        if (!(contact <= period))
            throw InvalidInput(fmt::format(
                "--container {} is not allowed for this bed: its largest spheres (diameter "
                "{:.6g}) touch across more than a period; allowed: periods of at least {:.6g} "
                "(the largest diameter plus --contact-tolerance)",
                container.spec(), 2.0 * largest, contact));
        if (!(rdf_range <= period))
            throw InvalidInput(fmt::format(
                "--rdf-range {} Dp ({:.6g}) is not allowed in --container {}; allowed: at most "
                "the smaller period, {:.6g} ({:.6g} Dp)",
                options.rdf_range, rdf_range, container.spec(), period, period / dp));
    }
    const ContactSearch contacts(packing, container, options.contact_tolerance * dp, *band,
                                 mean_diameter);
    const double contact_budget = pair_budget(packing.size(), contacts.grid.edge, mean_diameter);
    if (!(static_cast<double>(contacts.work) <= contact_budget))
        throw InvalidInput(fmt::format(
            "finding the contacts would take {:.3g} distance checks; allowed: at most "
            "{:.3g} for {} spheres ({:g} per sphere, times the cube of the search distance {:.3g} "
            "over the mean diameter {:.3g}): the spheres are piled on each other (up to {} "
            "centres within {:.3g}) or far larger than the mean (the largest diameter is {:.3g})",
            static_cast<double>(contacts.work), contact_budget, packing.size(),
            limits::pair_checks_per_sphere, contacts.grid.edge, mean_diameter,
            contacts.grid.largest_cell, contacts.grid.edge, 2.0 * contacts.largest_radius));
    const SearchPoints rdf_points(packing, container, rdf_range);
    const CellGrid rdf_grid(rdf_points.all(), rdf_range * cell_margin);
    std::uint64_t rdf_work = 0;
    for (std::size_t i = 0; i < packing.size(); ++i)
        rdf_work += in_band(packing.centers[i], *band) ? rdf_grid.work(i, 1) : 0;
    const double rdf_budget = pair_budget(packing.size(), rdf_grid.edge, mean_diameter);
    if (!(static_cast<double>(rdf_work) <= rdf_budget))
        throw InvalidInput(fmt::format(
            "g(r) up to --rdf-range {} Dp would take {:.3g} distance checks; allowed: "
            "at most {:.3g} for {} spheres ({:g} per sphere, times the cube of the search "
            "distance {:.3g} over the mean diameter {:.3g}): the spheres are piled on each other "
            "(up to {} centres within {:.3g}); lower --rdf-range",
            options.rdf_range, static_cast<double>(rdf_work), rdf_budget, packing.size(),
            limits::pair_checks_per_sphere, rdf_grid.edge, mean_diameter, rdf_grid.largest_cell,
            rdf_grid.edge));

    // The volumes through the particles' shape (particle_shape.hpp): spheres.
    const ShapedBed<SphereShape> bed = spheres(packing);
    out.void_fraction = void_fraction(bed, container, band->z_low, band->z_high);
    out.axial_void_fraction = axial_void_fraction(bed, container, options.slab_height * dp, slabs);
    std::vector<std::uint32_t> per_sphere;
    out.coordination = coordination(packing, container, contacts, *band, options.frictional,
                                    per_sphere, out.walls);
    for (std::size_t w = 0; w < out.walls.size(); ++w) {
        out.walls[w].void_fraction =
            wall_void_fraction(bed, container, w, options.shell_width * dp, *band, shells);
        out.walls[w].centre_distribution =
            centre_distribution(packing, container, w, options.centre_bin * dp, *band, centre_bins,
                                [](std::size_t) { return true; });
    }
    if (out.walls.size() == 1) { // the profiles against the one wall, where they always were
        out.radial_void_fraction = out.walls.front().void_fraction;
        out.centre_distribution = out.walls.front().centre_distribution;
    }
    out.by_size = by_size(packing, container, options.centre_bin * dp, *band, centre_bins,
                          per_sphere, out.sizes);
    out.pair_region = pair_region(packing, container, *band);
    out.pair_correlation =
        pair_correlation(packing, *band, out.pair_region, rdf_range, rdf_bin,
                         static_cast<std::size_t>(rdf_bins), rdf_points, rdf_grid);
    return out;
}

namespace {

/// The contacts of a bed of pellets (PelletAnalysis::coordination): the pairs whose bounding
/// spheres come within `tolerance` (a NeighborList, by the minimum image in a periodic cell)
/// measured by their exact gap, and the pellets whose support function grown by `tolerance`
/// reaches a side wall.
template <class S>
Coordination pellet_coordination(const ShapedBed<S>& bed, const Container& container,
                                 double tolerance, const Band& band) {
    const Packing& packing = bed.particles();
    const std::size_t n = bed.size();
    const std::vector<double> reach = bed.bounding_radii();
    std::vector<Vec3> centres = packing.centers;
    const std::optional<Periods> cell = container.periods();
    NeighborList list;
    if (cell) {
        const double widest = 2.0 * *std::max_element(reach.begin(), reach.end()) + tolerance;
        if (!(cell->lx() >= 2.0 * widest && cell->ly() >= 2.0 * widest))
            throw InvalidInput(fmt::format(
                "the periodic cell {} is not allowed for the contacts of these pellets; allowed: "
                "periods at least {:.6g}, twice the reach of two touching pellets",
                container.spec(), 2.0 * widest));
        for (Vec3& c : centres)
            c = cell->wrapped(c);
        list.wrap(*cell);
    }
    list.build(centres, reach, tolerance);
    const auto first = list.pair_first();
    const auto second = list.pair_second();
    const std::size_t pairs = list.pairs();
    std::vector<char> touching(pairs, 0);
#pragma omp parallel for schedule(dynamic, 16) if (pairs >= 64)
    for (std::size_t k = 0; k < pairs; ++k) {
        const std::size_t a = first[k], b = second[k];
        const Vec3 u = cell ? cell->separation(centres[a], centres[b]) : centres[b] - centres[a];
        if (norm(u) > reach[a] + reach[b] + tolerance)
            continue;
        const Placement pa = bed.placement(a);
        Placement pb = bed.placement(b);
        pb.position = pa.position + u;
        touching[k] = bed.shape(a).pair_gap(pa, bed.shape(b), pb, u) <= tolerance ? 1 : 0;
    }
    std::vector<std::size_t> contacts(n, 0);
    for (std::size_t k = 0; k < pairs; ++k)
        if (touching[k]) {
            ++contacts[first[k]];
            ++contacts[second[k]];
        }
    Coordination out;
    out.rattler_contacts = 1;
    CoordinationTally tally{out};
    for (std::size_t i = 0; i < n; ++i) {
        const Placement p = bed.placement(i);
        const S& shape = bed.shape(i);
        const bool wall = shape.wall_overlap(container, p, tolerance) > 0.0;
        out.wall_contacts += wall ? 1 : 0;
        if (!in_band(p.position, band))
            continue;
        out.wall_contacts_in_band += wall ? 1 : 0;
        tally.add(contacts[i], wall ? 1 : 0);
    }
    tally.finish();
    return out;
}

/// The unit normal of the container's one wall at p: the gradient of the distance from it (by
/// central differences `h` apart), which points away from the wall; the zero vector where the
/// gradient vanishes (the axis of a tube).
Vec3 wall_normal(const Container& container, const Vec3& p, double h) {
    const auto d = [&](const Vec3& q) { return container.wall_distances_from(0, q, 0.0).first; };
    const Vec3 g{d(p + Vec3{h, 0.0, 0.0}) - d(p - Vec3{h, 0.0, 0.0}),
                 d(p + Vec3{0.0, h, 0.0}) - d(p - Vec3{0.0, h, 0.0}),
                 d(p + Vec3{0.0, 0.0, h}) - d(p - Vec3{0.0, 0.0, h})};
    const double length = norm(g);
    return length > 0.0 ? g * (1.0 / length) : Vec3{};
}

/// analyze_pellet_bed for pellets of shape class S.
template <class S>
PelletAnalysis analyze_pellets(const Packing& packing, const S& shape, const Container& container,
                               const AnalysisOptions& options) {
    if (packing.size() == 0)
        throw InvalidInput("no pellets to analyse; allowed: a bed with at least one pellet");
    if (packing.orientations.size() != packing.size())
        throw InvalidInput("a bed of pellets needs each one's orientation; allowed: a table with "
                           "the columns qw, qx, qy, qz");
    const ShapedBed<S> bed(packing, {shape});
    PelletAnalysis out;
    // The unit: the pellets' d_v, or with sizes their Sauter mean sum d_v^3 / sum d_v^2 (the
    // reference pellet's, as generate --sizes makes it).
    double dv = packing.mean_diameter();
    if (std::adjacent_find(packing.radii.begin(), packing.radii.end(), std::not_equal_to<>()) !=
        packing.radii.end()) {
        double cubes = 0.0, squares = 0.0;
        for (const double r : packing.radii) {
            cubes += r * r * r;
            squares += r * r;
        }
        dv = 2.0 * cubes / squares;
    }
    out.diameter = dv;
    const double top = bed_top(bed);
    out.band = options.band ? *options.band
                            : Band{options.band_clearance * dv, top - options.band_clearance * dv};
    if (!(out.band.z_low >= 0.0 && out.band.z_high > out.band.z_low))
        throw InvalidInput(fmt::format(
            "--band-clearance {} d_v is not allowed for this bed (top at {:.6g}, {:.6g} d_v); "
            "allowed: less than half the bed's height, or --band",
            options.band_clearance, top, top / dv));
    out.void_fraction = void_fraction(bed, container, out.band.z_low, out.band.z_high);
    const auto slabs = static_cast<std::size_t>(std::ceil(top / (options.slab_height * dv)));
    out.axial_void_fraction = axial_void_fraction(bed, container, options.slab_height * dv,
                                                  std::max<std::size_t>(slabs, 1));
    // Sums of cos^2 theta and cos^2 psi over the pellets of a bin.
    struct Sums {
        double cos2 = 0.0, cos2_wall = 0.0;
        std::uint64_t pellets = 0;
    };
    const auto orientation = [](const Sums& s, double low, double high) {
        const double n = static_cast<double>(s.pellets);
        const double mean = s.pellets > 0 ? s.cos2 / n : 0.0;
        return OrientationBin{low,
                              high,
                              s.pellets,
                              mean,
                              s.pellets > 0 ? 1.5 * mean - 0.5 : 0.0,
                              s.pellets > 0 ? s.cos2_wall / n : 0.0};
    };
    Sums all;
    const bool one_wall = container.profile_walls().size() == 1;
    const double depth = container.depth(out.band.z_low, out.band.z_high);
    const double bin = 0.1 * dv;
    const auto bins = static_cast<std::size_t>(std::ceil(depth / bin));
    std::vector<Sums> sums(one_wall ? bins : 0);
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        if (c.z < out.band.z_low || c.z >= out.band.z_high)
            continue;
        const Vec3 axis = rotate(packing.orientations[i], Vec3{0.0, 0.0, 1.0});
        all.cos2 += axis.z * axis.z;
        ++all.pellets;
        if (one_wall) {
            const double d = container.wall_distances_from(0, c, 0.0).first;
            const double towards = dot(axis, wall_normal(container, c, 1e-6 * dv));
            const auto k = static_cast<std::size_t>(
                std::clamp(std::floor(d / bin), 0.0, static_cast<double>(bins - 1)));
            sums[k].cos2 += axis.z * axis.z;
            sums[k].cos2_wall += towards * towards;
            ++sums[k].pellets;
            all.cos2_wall += towards * towards;
        }
    }
    out.overall = orientation(all, 0.0, depth);
    for (std::size_t k = 0; k < sums.size(); ++k)
        out.orientation.push_back(orientation(sums[k], k * bin, std::min(depth, (k + 1) * bin)));
    if (one_wall) {
        const auto shells = static_cast<std::size_t>(std::ceil(depth / (options.shell_width * dv)));
        out.radial_void_fraction =
            wall_void_fraction(bed, container, 0, options.shell_width * dv, out.band, shells);
    }
    out.coordination =
        pellet_coordination(bed, container, options.contact_tolerance * dv, out.band);
    return out;
}

} // namespace

PelletAnalysis analyze_pellet_bed(const Packing& packing, const PelletShape& shape,
                                  const Container& container, const AnalysisOptions& options) {
    return std::visit(
        [&](const auto& s) { return analyze_pellets(packing, s, container, options); }, shape);
}

} // namespace packbed
