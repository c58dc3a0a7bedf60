#include "soft_bed.hpp"

#include <numbers>

namespace packbed::detail {

void SoftBed::generate(const SoftSphereParameters& params) {
    initial_height = initial_bed_height(params);
    ceiling = 4.0 * initial_height + 10.0 * params.aspect_ratio + 10.0;
    smallest_radius = 0.5 * params.smallest_size();
    std::mt19937_64 rng(params.seed);
    packing.centers.reserve(params.particles);
    packing.radii.reserve(params.particles);
    // Section 3.1 with each sphere's own radius r_i: r = (Rt - r_i) Rnd^(1/2), theta = 2 pi
    // Rnd, z = L0 Rnd + r_i (the paper's Dp/2 is the radius). The same random numbers whatever
    // the sizes.
    for (std::uint64_t i = 0; i < params.particles; ++i) {
        const double radius = params.sizes.empty() ? 0.5 : 0.5 * params.sizes[i];
        const double reach = container.radius() - radius;
        const double r = reach * std::sqrt(uniform01(rng));
        const double theta = 2.0 * std::numbers::pi * uniform01(rng);
        const double z = initial_height * uniform01(rng) + radius;
        packing.add({r * std::cos(theta), r * std::sin(theta), z}, radius);
    }
    reset_order();
}

void SoftBed::assign(Packing spheres, double height, double smallest) {
    smallest_radius = smallest;
    packing = std::move(spheres);
    initial_height = height;
    ceiling = 4.0 * height + 10.0 * 2.0 * container.radius() + 10.0;
    list = NeighborList{};
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

void SoftBed::rebuild_list(double skin) {
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
    result.packing.scale(diameter);
    result.container = Cylinder(container.radius() * diameter);
    result.initial_height = initial_height * diameter;
    result.neighbor_builds = list.builds();
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
