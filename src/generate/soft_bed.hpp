// Internal: what the soft-sphere solvers share (Salvat et al. 2005, section 3): the generation
// stage, the contact law, the Verlet list and the storage of the spheres in spatial order.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "generate/random.hpp"
#include "packbed/container.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/packing.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed::detail {

/// A uniform double in [0, 1) from 53 random bits: the same numbers on every platform
/// (std::uniform_real_distribution is implementation-defined); random.hpp holds it.
using portable_random::uniform01;

/// The parameters a solver runs with: the solver's schedule where none was given, and the
/// tolerance and the control band of eq. (7), given in units of the smallest diameter
/// (SoftSphereParameters::sizes), turned into Dp. The same values for a mono-sized bed (times 1).
inline SoftSphereParameters in_dp(const SoftSphereParameters& p) {
    SoftSphereParameters out = p;
    const double smallest = p.smallest_size();
    const SoftSphereParameters::Schedule schedule = p.schedule();
    out.tolerance *= smallest;
    out.overlap_low = schedule.overlap_low * smallest;
    out.overlap_high = schedule.overlap_high * smallest;
    out.mc_tolerance = schedule.mc_tolerance;
    return out;
}

/// The contact law of eq. (2b) multiplied by the step length, as it enters eq. (4): sphere i
/// moves by \f$-C_k R(\delta_{ij}) \hat r_{ij}\f$. Linear in the overlap, no friction. With
/// ck = 1 it gives the force of the energy \f$\frac12 \sum \delta_{ij}^2\f$ (unit stiffness).
struct LinearOverlapLaw {
    double ck;

    /// Add the displacement of sphere i caused by sphere j to `move`; track the overlap.
    void apply(const Vec3& xi, const Vec3& xj, double sum_radii, bool i_below, Vec3& move,
               double& max_overlap) const {
        apply(xj - xi, sum_radii, i_below, move, max_overlap);
    }
    /// The same from the separation rij = x_j - x_i (the minimum image in a periodic cell).
    void apply(const Vec3& rij, double sum_radii, bool i_below, Vec3& move,
               double& max_overlap) const {
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

struct SoftBed;

/// What the final stage of either solver does once gravity is negligible and the overlaps stay
/// above the tolerance: it records the largest overlap every mc_period iterations; when the
/// last `window` records agree within 1 %, spheres pressed flat on the floor are lifted
/// (SoftBed::lift_squeezed_floor_spheres, up to max_lifts times) and the run goes on; when
/// none is, or after budget_windows mass-centre windows of this, the bed is jammed.
class StallGuard {
public:
    enum class Verdict { wait, lifted, jammed };
    static constexpr int max_lifts = 20;
    static constexpr std::uint64_t budget_windows = 50;

    /// \param window, period the mass-centre rule's mc_window and mc_period
    StallGuard(std::uint32_t window, std::uint32_t period);

    /// One record at iteration `step` of a stalled stage, `overlap` its largest overlap.
    Verdict record(SoftBed& bed, double overlap, double tolerance, std::uint32_t first_free,
                   std::uint64_t step);

private:
    MassCentreWindow m_overlaps; // the same rule as the mass centre's, on the overlap
    std::uint64_t m_budget;
    std::uint64_t m_since = 0;
    bool m_started = false;
    int m_lifts = 0;
};

/// Spheres of one soft-sphere bed in units of Dp, in a container, stored in a spatial order
/// (renewed at each Verlet-list build) so that neighbours in space are neighbours in memory.
/// Sphere k of `packing` is sphere order[k] of the generation stage; slot[i] is where sphere
/// i is stored. Neighbours are summed in generation order, so the stored order never changes
/// a bit of a result.
struct SoftBed {
    Container container;
    /// The container's periods, where it has them: pairs by the minimum image.
    std::optional<Periods> cell;
    Packing packing;
    std::vector<std::uint32_t> order;
    std::vector<std::uint32_t> slot;
    std::vector<Vec3> next;     // scratch, one per sphere
    std::vector<Vec3> velocity; // per sphere, stored order; empty for the paper's solver
    std::vector<double> factor; // per listed pair, see pair_factors()
    static constexpr std::size_t pair_chunk = 512; // pairs per work item of pair_factors()
    NeighborList list;
    double drift2 = 0.0;          // largest squared move since the last list build
    double initial_height = 0.0;  // L0, Dp
    double ceiling = 0.0;         // a centre above this has been thrown out of the bed
    double smallest_radius = 0.5; // of the whole bed, Dp (sets each sphere's step length)

    explicit SoftBed(const Container& c)
        : container(c) {
        cell = c.periods();
        new_list();
    }

    /// \return the separation x_j - x_i of two stored spheres: the minimum image in a
    /// periodic cell (Wrap), the plain difference otherwise.
    template <bool Wrap> Vec3 separation(const Vec3& xi, const Vec3& xj) const {
        if constexpr (Wrap)
            return cell->separation(xi, xj);
        else
            return xj - xi;
    }

    /// Section 3.1: L0 from eq. (6), centres uniform over the accessible cross-section (the
    /// part of the container a centre of the sphere's radius may reach).
    void generate(const SoftSphereParameters& params);

    /// Take `spheres` (units of Dp) as the bed, in their order as the generation order, with
    /// L0 = `height` (sets the ceiling); no list, no velocities. `smallest` is the smallest
    /// radius of the whole bed the spheres belong to (the step lengths follow it).
    void assign(Packing spheres, double height, double smallest);

    /// Spheres of many sizes (docs/sizes.md, "Both solvers"): each sphere moves
    /// with its own step length U_i = U (r_min / r_i)^2, the step of the paper's eq. (4) for
    /// the smallest sphere and less for larger ones, whose contacts grow as their surface
    /// (r_i / r_min)^2: the sum of a sphere's contact steps stays within what keeps the
    /// mono-sized iteration stable. \return U_i / U; exactly 1 in a mono-sized bed.
    double mobility(double r) const {
        const double q = smallest_radius / r;
        return q * q;
    }
    /// The gravity step of a sphere of radius r in units of the reference sphere's Cg Dp:
    /// its weight (r / 0.5)^3 (eq. 2c, mass as volume) times its step length. Exactly 1 in a
    /// mono-sized bed.
    double weight(double r) const { return mobility(r) * (8.0 * r * r * r); }

    /// \return true when the Verlet list must be rebuilt before the next evaluation: none
    /// yet, or a sphere moved more than skin/2 (the caller keeps drift2 up to date).
    bool list_stale() const { return list.builds() == 0 || drift2 > list.drift_limit2(); }

    /// Store the spheres in the order of a cell grid, then build the Verlet list on them with
    /// rows in generation order. \return the new order: stored sphere k was stored at perm[k].
    std::vector<std::uint32_t> rebuild_list(double skin);

    /// Add the wall term of eq. (4) for a sphere at `xk` of radius `r` to `move`; track the
    /// largest wall overlap: each wall the sphere presses adds its own term
    /// (Container::wall_contacts).
    [[gnu::always_inline]] void add_wall_term(const Vec3& xk, double r, const LinearOverlapLaw& law,
                                              Vec3& move, double& wall) const {
        // Inlined, as Container::wall_contacts' fast path (docs/notes/iteration-kernels.md).
        container.wall_contacts(
            xk, r, [&](double overlap, const Vec3& push) __attribute__((always_inline)) {
                wall = std::max(wall, overlap);
                move += push * (law.ck * overlap);
            });
    }

    /// \return law-weighted sum of the pair and wall terms of sphere k (the move of eq. (4)
    /// without gravity and floor); `pair` and `wall` track the largest overlaps seen.
    Vec3 contact_move(std::size_t k, const LinearOverlapLaw& law, double& pair,
                      double& wall) const {
        return cell ? contact_move<true>(k, law, pair, wall)
                    : contact_move<false>(k, law, pair, wall);
    }
    template <bool Wrap>
    Vec3 contact_move(std::size_t k, const LinearOverlapLaw& law, double& pair,
                      double& wall) const {
        const Vec3* const x = packing.centers.data();
        const double* const radius = packing.radii.data();
        const Vec3 xk = x[k];
        Vec3 move{};
        for (const auto j : list.neighbors_of(k))
            law.apply(separation<Wrap>(xk, x[j]), radius[k] + radius[j], order[k] < order[j], move,
                      pair);
        add_wall_term(xk, radius[k], law, move, wall);
        return move;
    }

    /// First half of contact_move split in two passes (the simultaneous update, FIRE): the
    /// factor \f$C_k \delta_{ij} / |r_{ij}|\f$ of each listed pair p in [begin, end),
    /// computed once for both spheres and with no branch (+0 when they do not touch; +inf
    /// when their centres coincide). \f$\delta\f$, \f$|r|\f$ and so the factor are the same
    /// bits from either side (r_ji = -r_ij exactly). Two pairs share one SSE2 square root and
    /// division where there is SSE2 (IEEE-exact either way). \return the largest overlap.
    double pair_factors(std::size_t begin, std::size_t end, const LinearOverlapLaw& law) {
        return cell ? pair_factors<true>(begin, end, law) : pair_factors<false>(begin, end, law);
    }
    template <bool Wrap>
    double pair_factors(std::size_t begin, std::size_t end, const LinearOverlapLaw& law) {
        const Vec3* const x = packing.centers.data();
        const double* const radius = packing.radii.data();
        const std::uint32_t* const first = list.pair_first().data();
        const std::uint32_t* const second = list.pair_second().data();
        double* const f = factor.data();
        double largest = 0.0;
        std::size_t p = begin;
#if defined(__SSE2__)
        __m128d top = _mm_setzero_pd();
        const __m128d ck = _mm_set1_pd(law.ck);
        for (; p + 1 < end; p += 2) {
            const std::uint32_t i0 = first[p], j0 = second[p], i1 = first[p + 1],
                                j1 = second[p + 1];
            const __m128d dist2 = _mm_set_pd(norm2(separation<Wrap>(x[i1], x[j1])),
                                             norm2(separation<Wrap>(x[i0], x[j0])));
            const __m128d sum = _mm_set_pd(radius[i1] + radius[j1], radius[i0] + radius[j0]);
            const __m128d dist = _mm_sqrt_pd(dist2);
            const __m128d overlap = _mm_sub_pd(sum, dist);
            const __m128d value = _mm_div_pd(_mm_mul_pd(ck, overlap), dist);
            const __m128d touching = _mm_cmplt_pd(dist2, _mm_mul_pd(sum, sum));
            _mm_storeu_pd(f + p, _mm_and_pd(value, touching));
            top = _mm_max_pd(top, _mm_and_pd(overlap, touching));
        }
        alignas(16) double tops[2];
        _mm_store_pd(tops, top);
        largest = std::max(tops[0], tops[1]);
#endif
        for (; p < end; ++p) {
            const std::uint32_t i = first[p], j = second[p];
            const double sum = radius[i] + radius[j];
            const double dist2 = norm2(separation<Wrap>(x[i], x[j]));
            const double dist = std::sqrt(dist2);
            const double overlap = sum - dist;
            const double value = law.ck * overlap / dist; // +inf for coincident centres
            // Masks, not branches: whether a pair touches is not predictable.
            const std::uint64_t touching = 0 - static_cast<std::uint64_t>(dist2 < sum * sum);
            f[p] = std::bit_cast<double>(std::bit_cast<std::uint64_t>(value) & touching);
            largest = std::max(
                largest, std::bit_cast<double>(std::bit_cast<std::uint64_t>(overlap) & touching));
        }
        return largest;
    }

    /// Second half: contact_move of sphere k from the factors of pair_factors(), the same
    /// bits (a factor of 0 leaves the sum unchanged: it never holds -0). `wall` tracks the
    /// largest wall overlap.
    Vec3 contact_move_from_factors(std::size_t k, const LinearOverlapLaw& law, double& wall) const {
        return cell ? contact_move_from_factors<true>(k, law, wall)
                    : contact_move_from_factors<false>(k, law, wall);
    }
    template <bool Wrap>
    Vec3 contact_move_from_factors(std::size_t k, const LinearOverlapLaw& law, double& wall) const {
        const Vec3* const x = packing.centers.data();
        const double* const radius = packing.radii.data();
        const Vec3 xk = x[k];
        const std::span<const std::uint32_t> row = list.neighbors_of(k);
        const std::uint32_t* const pair_number = list.pair_numbers_of(k).data();
        Vec3 move{};
        for (std::size_t e = 0; e < row.size(); ++e) {
            const std::uint32_t j = row[e];
            const double f = factor[pair_number[e]];
            if (f == std::numeric_limits<double>::infinity()) [[unlikely]] {
                // Coincident centres, as LinearOverlapLaw.
                const double overlap = radius[k] + radius[j];
                move.z += order[k] < order[j] ? -law.ck * overlap : law.ck * overlap;
            } else {
                move -= separation<Wrap>(xk, x[j]) * f;
            }
        }
        add_wall_term(xk, radius[k], law, move, wall);
        return move;
    }

    /// Spheres pressed flat on the floor: the rigid floor
    /// holds the centres of the spheres resting on it at exactly z = r, so the contacts between
    /// them push only sideways. A floor layer that gravity squeezed tighter than the floor's
    /// area allows (12 spheres on the floor of an a = 4 tube: 12 circles need a container 4.03
    /// times their radius) then stays squeezed, its overlaps far above the tolerance, however
    /// small gravity gets: no force can lift any of them. This lifts each sphere resting on the
    /// floor that presses a neighbour or the wall beyond `tolerance` by its own amount, 0.1 to
    /// 0.2 of its largest overlap (by a hash of its generation index: the same for any number
    /// of threads), so that the squeezed layer buckles upwards as it would in any real bed.
    /// Spheres of generation index below `first_free` (held fixed) are not lifted. The list
    /// must be valid; it is rebuilt at the next step. \return the number of spheres lifted.
    std::size_t lift_squeezed_floor_spheres(double tolerance, std::uint32_t first_free = 0);

    /// \return the spheres in generation order (refreshed at each call), units of Dp.
    const Packing& packing_in_generation_order() const;

    /// Set the packing (generation order), container, L0, exact final overlaps and list
    /// builds of `result`, lengths scaled from Dp to `diameter`.
    void fill_result(SoftSphereResult& result, double diameter) const;

    /// Height of the mass centre of spheres `first` to the last (generation order),
    /// \f$\sum r_i^3 z_i / \sum r_i^3\f$, Dp, summed in generation order.
    double mass_centre_z(std::uint32_t first = 0) const;

private:
    void reset_order(); // order and slot the identity, scratch sized
    /// An empty Verlet list (built at the next step) that measures pairs by the minimum image
    /// in a periodic cell. (A layer's part once got a list without it: docs/notes/tall-beds.md.)
    void new_list() {
        list = NeighborList{};
        if (cell)
            list.wrap(*cell);
    }

    mutable Packing m_in_generation_order;
};

} // namespace packbed::detail
