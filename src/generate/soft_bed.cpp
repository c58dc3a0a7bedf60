#include "generate/soft_bed.hpp"

#include <limits>
#include <numbers>
#include <type_traits>

namespace packbed::detail {

namespace {

/// The widest extent of the container's cross-section (a cylinder's: 2 Rt = a).
double width(const Container& container) {
    const Rectangle b = container.bounds();
    return std::max(b.x_high - b.x_low, b.y_high - b.y_low);
}

} // namespace

void SoftBed::generate(const SoftSphereParameters& params) {
    initial_height = initial_bed_height(params);
    ceiling = 4.0 * initial_height + 10.0 * width(container) + 10.0;
    smallest_radius = 0.5 * params.smallest_size();
    std::mt19937_64 rng(params.seed);
    packing.centers.reserve(params.particles);
    packing.radii.reserve(params.particles);
    // Section 3.1 with each sphere's own radius r_i: r = (Rt - r_i) Rnd^(1/2), theta = 2 pi
    // Rnd, z = L0 Rnd + r_i (the paper's Dp/2 is the radius), and the same over the other
    // containers' cross-sections at that height (uniform_point). The same random numbers
    // whatever the sizes.
    for (std::uint64_t i = 0; i < params.particles; ++i) {
        const double radius = params.sizes.empty() ? 0.5 : 0.5 * params.sizes[i];
        const double u = uniform01(rng);
        const double v = uniform01(rng);
        const double z = initial_height * uniform01(rng) + radius;
        packing.add(container.uniform_point(radius, u, v, z), radius);
    }
    reset_order();
}

void SoftBed::assign(Packing spheres, double height, double smallest) {
    smallest_radius = smallest;
    packing = std::move(spheres);
    initial_height = height;
    ceiling = 4.0 * height + 10.0 * width(container) + 10.0;
    new_list();
    velocity.clear();
    drift2 = 0.0;
    reset_order();
}

void SoftBed::reset_order() {
    order.resize(packing.size());
    slot.resize(packing.size());
    for (std::uint32_t i = 0; i < order.size(); ++i)
        order[i] = slot[i] = i;
    next.resize(packing.size());
}

std::vector<std::uint32_t> SoftBed::rebuild_list(double skin) {
    if (cell) // the centres back into the cell: the list's reference, and the spatial order
        for (Vec3& c : packing.centers)
            c = cell->wrapped(c);
    const double max_radius = *std::max_element(packing.radii.begin(), packing.radii.end());
    const std::vector<std::uint32_t> perm = spatial_order(packing.centers, 2.0 * max_radius + skin);
    for (std::size_t k = 0; k < perm.size(); ++k) {
        next[k] = packing.centers[perm[k]];
        slot[order[perm[k]]] = static_cast<std::uint32_t>(k);
    }
    packing.centers.swap(next);
    for (std::size_t i = 0; i < slot.size(); ++i)
        order[slot[i]] = static_cast<std::uint32_t>(i);
    if (!velocity.empty()) {
        for (std::size_t k = 0; k < perm.size(); ++k)
            next[k] = velocity[perm[k]];
        velocity.swap(next);
    }
    std::vector<double> radii(perm.size());
    for (std::size_t k = 0; k < perm.size(); ++k)
        radii[k] = packing.radii[perm[k]];
    packing.radii.swap(radii);
    list.build(packing.centers, packing.radii, skin, order);
    factor.resize(list.pairs());
    drift2 = 0.0;
    return perm;
}

const Packing& SoftBed::packing_in_generation_order() const {
    m_in_generation_order.centers.resize(packing.size());
    m_in_generation_order.radii.resize(packing.size());
    for (std::size_t i = 0; i < slot.size(); ++i) {
        m_in_generation_order.centers[i] = packing.centers[slot[i]];
        m_in_generation_order.radii[i] = packing.radii[slot[i]];
    }
    return m_in_generation_order;
}

void SoftBed::fill_result(SoftSphereResult& result, double diameter) const {
    const Overlaps final_overlaps = measure_overlaps(packing, container);
    result.max_overlap_pair = final_overlaps.pair;
    result.max_overlap_wall = final_overlaps.wall;
    result.packing = packing_in_generation_order();
    if (cell)
        for (Vec3& c : result.packing.centers)
            c = cell->wrapped(c);
    result.packing.scale(diameter);
    result.container = container.scaled(diameter);
    result.initial_height = initial_height * diameter;
    result.neighbor_builds = list.builds();
}

std::size_t SoftBed::lift_squeezed_floor_spheres(double tolerance, std::uint32_t first_free) {
    const LinearOverlapLaw law{1.0};
    std::vector<std::pair<std::size_t, double>> squeezed; // sphere, its largest overlap
    for (std::size_t k = 0; k < packing.size(); ++k) {
        if (order[k] < first_free || packing.centers[k].z > packing.radii[k])
            continue;
        double pair = 0.0, wall = 0.0;
        contact_move(k, law, pair, wall);
        if (std::max(pair, wall) > tolerance)
            squeezed.emplace_back(k, std::max(pair, wall));
    }
    for (const auto& [k, overlap] : squeezed)
        packing.centers[k].z += overlap * (0.1 + 0.1 * portable_random::hash01(order[k]));
    if (!squeezed.empty())
        drift2 = std::numeric_limits<double>::infinity(); // the list rebuilt at the next step
    return squeezed.size();
}

StallGuard::StallGuard(std::uint32_t window, std::uint32_t period)
    : m_overlaps(window, 1.0)
    , m_budget(budget_windows * std::uint64_t{window} * period) {}

StallGuard::Verdict StallGuard::record(SoftBed& bed, double overlap, double tolerance,
                                       std::uint32_t first_free, std::uint64_t step) {
    if (!m_started) {
        m_started = true;
        m_since = step;
    }
    if (step - m_since > m_budget)
        return Verdict::jammed;
    m_overlaps.push(overlap);
    if (!m_overlaps.settled())
        return Verdict::wait;
    m_overlaps.clear();
    if (m_lifts < max_lifts && bed.lift_squeezed_floor_spheres(tolerance, first_free) > 0) {
        ++m_lifts;
        return Verdict::lifted;
    }
    return Verdict::jammed;
}

double SoftBed::mass_centre_z(std::uint32_t first) const {
    double weighted = 0.0, total = 0.0;
    for (std::size_t i = first; i < slot.size(); ++i) {
        const std::uint32_t k = slot[i];
        const double m = packing.radii[k] * packing.radii[k] * packing.radii[k];
        weighted += m * packing.centers[k].z;
        total += m;
    }
    return weighted / total;
}

} // namespace packbed::detail
