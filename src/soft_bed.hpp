// Internal: what the soft-sphere solvers share (Salvat et al. 2005, section 3): the generation
// stage, the contact law, the Verlet list and the storage of the spheres in spatial order.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/packing.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed::detail {

/// A uniform double in [0, 1) from 53 random bits: the same numbers on every platform
/// (std::uniform_real_distribution is implementation-defined).
inline double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// The contact law of eq. (2b) multiplied by the step length, as it enters eq. (4): sphere i
/// moves by \f$-C_k R(\delta_{ij}) \hat r_{ij}\f$. Linear in the overlap, no friction. With
/// ck = 1 it gives the force of the energy \f$\frac12 \sum \delta_{ij}^2\f$ (unit stiffness).
struct LinearOverlapLaw {
    double ck;

    /// Add the displacement of sphere i caused by sphere j to `move`; track the overlap.
    void apply(const Vec3& xi, const Vec3& xj, double sum_radii, bool i_below, Vec3& move,
               double& max_overlap) const {
        const Vec3 rij = xj - xi;
        const double dist2 = norm2(rij);
        if (dist2 >= sum_radii * sum_radii)
            return;
        const double dist = std::sqrt(dist2);
        const double overlap = sum_radii - dist;
        max_overlap = std::max(max_overlap, overlap);
        if (dist > 0.0)
            move -= rij * (ck * overlap / dist);
        else // coincident centres: separate them vertically, lower index downwards
            move.z += i_below ? -ck * overlap : ck * overlap;
    }
};

/// The last `window` mass-centre records and the paper's settling rule (section 3.3).
class MassCentreWindow {
public:
    MassCentreWindow(std::uint32_t window, double tolerance_percent)
        : m_window(window)
        , m_fraction(tolerance_percent / 100.0) {}
    void push(double value) {
        m_values.push_back(value);
        if (m_values.size() > m_window)
            m_values.pop_front();
    }
    /// \return true when `window` successive values lie within the tolerance:
    /// (max - min) <= tolerance/100 * |mean|.
    bool settled() const {
        if (m_values.size() < m_window)
            return false;
        const auto [lo, hi] = std::minmax_element(m_values.begin(), m_values.end());
        double mean = 0.0;
        for (double v : m_values)
            mean += v;
        mean /= static_cast<double>(m_values.size());
        return *hi - *lo <= m_fraction * std::abs(mean);
    }
    std::vector<double> values() const { return {m_values.begin(), m_values.end()}; }
    void clear() { m_values.clear(); }

private:
    std::uint32_t m_window;
    double m_fraction;
    std::deque<double> m_values;
};

/// Spheres of one soft-sphere bed in units of Dp, in a cylinder, stored in a spatial order
/// (renewed at each Verlet-list build) so that neighbours in space are neighbours in memory.
/// Sphere k of `packing` is sphere order[k] of the generation stage; slot[i] is where sphere
/// i is stored. Neighbours are summed in generation order, so the stored order never changes
/// a bit of a result.
struct SoftBed {
    Cylinder container;
    Packing packing;
    std::vector<std::uint32_t> order;
    std::vector<std::uint32_t> slot;
    std::vector<Vec3> next;     // scratch, one per sphere
    std::vector<Vec3> velocity; // per sphere, stored order; empty for the paper's solver
    NeighborList list;
    double drift2 = 0.0;         // largest squared move since the last list build
    double initial_height = 0.0; // L0, Dp
    double ceiling = 0.0;        // a centre above this has been thrown out of the bed

    explicit SoftBed(double aspect_ratio)
        : container(0.5 * aspect_ratio) {}

    /// Section 3.1: L0 from eq. (6), centres uniform over the accessible cross-section.
    void generate(const SoftSphereParameters& params);

    /// \return true when the Verlet list must be rebuilt before the next evaluation: none
    /// yet, or a sphere moved more than skin/2 (the caller keeps drift2 up to date).
    bool list_stale() const { return list.builds() == 0 || drift2 > list.drift_limit2(); }

    /// Store the spheres in the order of a cell grid, then build the Verlet list on them with
    /// rows in generation order.
    void rebuild_list(double skin);

    /// \return law-weighted sum of the pair and wall terms of sphere k (the move of eq. (4)
    /// without gravity and floor); `pair` and `wall` track the largest overlaps seen.
    Vec3 contact_move(std::size_t k, const LinearOverlapLaw& law, double& pair,
                      double& wall) const {
        const Vec3* const x = packing.centers.data();
        const double* const radius = packing.radii.data();
        const Vec3 xk = x[k];
        Vec3 move{};
        for (const auto j : list.neighbors_of(k))
            law.apply(xk, x[j], radius[k] + radius[j], order[k] < order[j], move, pair);
        const WallContact w = container.wall_contact(xk, radius[k]);
        if (w.overlap > 0.0) {
            wall = std::max(wall, w.overlap);
            move += w.push * (law.ck * w.overlap);
        }
        return move;
    }

    /// \return the spheres in generation order (refreshed at each call), units of Dp.
    const Packing& packing_in_generation_order() const;

    /// Set the packing (generation order), container, L0, exact final overlaps and list
    /// builds of `result`, lengths scaled from Dp to `diameter`.
    void fill_result(SoftSphereResult& result, double diameter) const;

    /// Height of the mass centre, \f$\sum r_i^3 z_i / \sum r_i^3\f$, Dp, summed in generation
    /// order.
    double mass_centre_z() const;

private:
    mutable Packing m_in_generation_order;
};

} // namespace packbed::detail
