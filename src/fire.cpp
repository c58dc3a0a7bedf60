// The second solver: the energy the paper's iteration descends, minimised with FIRE.
//
// Eq. (4) of Salvat et al. (2005) is a steepest-descent step of length Ck on
//   E = 1/2 sum_pairs delta_ij^2 + 1/2 sum_walls delta_iw^2 + g sum_i z_i,   z_i >= r_i,
// with g = Cg / Ck: unit contact stiffness, unit mass, gravity force g per sphere. FIRE (Bitzek,
// Koskinen, Gaehler, Moseler & Gumbsch, "Structural relaxation made simple", Phys. Rev. Lett. 97
// (2006) 170201) minimises the same E with inertia and a velocity mixing, in the variant of
// Guenole et al., "Assessment and optimization of the fast inertial relaxation engine (FIRE)
// for energy minimization in atomistic simulations", Comput. Mater. Sci. 175 (2020) 109584:
// semi-implicit Euler, half step back on an uphill move. Per step:
//   F = -grad E (floor: no downward force on a sphere resting on it),
//   P = F.v; P > 0 for more than N_min steps: dt <- min(f_inc dt, dt_max), alpha <- f_alpha
//   alpha; P <= 0: dt <- f_dec dt, alpha <- alpha_0, x <- x - dt v / 2, v <- 0;
//   v <- v + dt F;  v <- (1 - alpha) v + alpha |v| F / |F|;  x <- x + dt v.
// The gravity schedule is the paper's (section 3): none until the overlaps of the random start
// are gone; then g under the control rule of eq. (7) until the mass centre settles; then g
// halved, each value held until the mass centre settles, until both overlaps are below the
// tolerance (the first cut goes straight to the g that should leave half the tolerance, the
// overlaps of a settled bed being proportional to g). Every global sum runs over fixed blocks
// added in order: the same bits for any number of threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/soft_sphere.hpp"
#include "parallel.hpp"
#include "soft_bed.hpp"

namespace packbed {

namespace {

// FIRE's parameters: Bitzek et al. (2006) except alpha_0; dt in units of 1/sqrt(k/m).
constexpr int fire_n_min = 5;
constexpr double fire_f_inc = 1.1;
constexpr double fire_f_dec = 0.5;
// Bitzek et al. use alpha_0 = 0.1. At a = 5 (10 seeds) 0.1 and 0.9 gave beds more ordered near
// the wall than the paper's (mean e 0.003-0.004 lower, radial-profile RMS 0.016-0.018), 0.5
// and 0.7 matched (0.001; 0.007-0.008): stronger mixing damps the rattling that lets spheres
// order. docs/validation.md, "The fire solver against the paper's".
constexpr double fire_alpha0 = 0.5;
constexpr double fire_f_alpha = 0.99;
constexpr double fire_dt_max = 0.2; // stable: a sphere with 12 contacts has omega <= sqrt(24)
constexpr double fire_dt0 = 0.05;
// FIRE 2.0 (Guenole et al. 2020) keeps dt >= 0.02 dt_max, so that a run of uphill steps
// cannot freeze the bed (which the mass-centre rule would take for a settled one).
constexpr double fire_dt_min = 0.02 * fire_dt_max;
// Largest move of one sphere in one step, Dp: keeps impacts of a falling bed gentle and the
// Verlet list (skin/2 = 0.05 Dp by default) valid for several steps.
constexpr double fire_max_step = 0.01;

constexpr std::size_t sum_block = 1024;

/// Global sums and maxima of one pass over the spheres.
struct PassTotals {
    double a = 0.0, b = 0.0;                  // two sums (meaning set by the pass)
    double pair = 0.0, wall = 0.0, top = 0.0; // largest overlaps, highest centre
    double drift = 0.0, speed2 = 0.0;         // largest squared move, sum of squared speeds
    bool finite = true;
};

/// Sum per-block partials in block order; maxima need no order.
PassTotals combine(const std::vector<PassTotals>& blocks) {
    PassTotals t;
    for (const PassTotals& p : blocks) {
        t.a += p.a;
        t.b += p.b;
        t.pair = std::max(t.pair, p.pair);
        t.wall = std::max(t.wall, p.wall);
        t.top = std::max(t.top, p.top);
        t.drift = std::max(t.drift, p.drift);
        t.speed2 += p.speed2;
        t.finite = t.finite && p.finite;
    }
    return t;
}

/// Run `body(k, totals)` for every sphere, in fixed blocks of sum_block spheres, in parallel
/// from detail::parallel_min_spheres on. \return the block totals combined in order.
template <class Body>
PassTotals for_each_block(std::size_t n, std::vector<PassTotals>& blocks, Body&& body) {
    const std::size_t nblocks = (n + sum_block - 1) / sum_block;
    blocks.assign(nblocks, PassTotals{});
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t c = 0; c < nblocks; ++c) {
        PassTotals t; // on the stack, so that the sums can live in registers
        for (std::size_t k = c * sum_block; k < std::min(n, (c + 1) * sum_block); ++k)
            body(k, t);
        blocks[c] = t;
    }
    return combine(blocks);
}

/// detail::SoftBed::pair_factors over all pairs, in parallel from
/// detail::parallel_min_spheres on. \return the largest pair overlap.
double pair_factors(detail::SoftBed& bed, const detail::LinearOverlapLaw& law) {
    const std::size_t pairs = bed.list.pairs();
    const std::size_t chunk = detail::SoftBed::pair_chunk;
    const std::size_t chunks = (pairs + chunk - 1) / chunk;
    double largest = 0.0;
#pragma omp parallel for schedule(static)                                                          \
    reduction(max                                                                                  \
              : largest) if (bed.packing.size() >= detail::parallel_min_spheres)
    for (std::size_t c = 0; c < chunks; ++c)
        largest =
            std::max(largest, bed.pair_factors(c * chunk, std::min(pairs, (c + 1) * chunk), law));
    return largest;
}

class Fire {
public:
    explicit Fire(const SoftSphereParameters& p)
        : m_params(p)
        , m_bed(p.aspect_ratio)
        , m_window(p.mc_window, p.mc_tolerance) {
        m_bed.generate(p);
        m_bed.velocity.assign(m_bed.packing.size(), Vec3{});
        m_force.resize(m_bed.packing.size());
    }

    SoftSphereResult run(const RunControl& control) {
        const auto t0 = std::chrono::steady_clock::now();
        const SoftSphereParameters& p = m_params;
        SoftSphereResult result;

        // "initial": overlaps of the random start removed, no gravity.
        std::uint64_t start = m_steps;
        m_g = 0.0;
        for (;;) {
            const PassTotals s = step("initial", control);
            if (s.pair < p.tolerance && s.wall < p.tolerance && converged_overlaps())
                break;
        }
        result.stages.push_back(record("initial", start, 1));

        // "intermediate": gravity under eq. (7), in force units g = Cg / Ck; until the mass
        // centre settles.
        start = m_steps;
        const double g_step = p.cg_step / p.ck;
        reset_dynamics();
        m_window.clear();
        for (;;) {
            const PassTotals s = step("intermediate", control);
            if (s.pair < p.overlap_low)
                m_g += g_step;
            else if (s.pair > p.overlap_high)
                m_g = std::max(m_g - g_step, 0.0);
            if (m_steps % p.mc_period == 0 && m_window.settled())
                break;
        }
        result.stages.push_back(record("intermediate", start, 1));

        // "final": g halved, each value held until the mass centre settles, until both
        // overlaps are below the tolerance.
        start = m_steps;
        std::uint32_t steps = 0;
        const double stalled_g = 1e-8 * p.tolerance;
        // The overlaps of a settled bed are proportional to g (linear springs, a contact
        // network that no longer changes), so the first step goes straight to the g that
        // should leave half the tolerance; later steps halve as the paper does.
        const Overlaps settled_overlaps = measure_overlaps(m_bed.packing, m_bed.container);
        const double largest = std::max(settled_overlaps.pair, settled_overlaps.wall);
        double factor = largest > 0.0 ? std::min(0.5, 0.5 * p.tolerance / largest) : 0.5;
        for (bool done = false; !done; factor = 0.5) {
            m_g *= factor;
            ++steps;
            reset_dynamics();
            m_window.clear();
            for (;;) {
                const PassTotals s = step("final", control);
                if (s.pair < p.tolerance && s.wall < p.tolerance && converged_overlaps()) {
                    done = true;
                    break;
                }
                if (m_g < stalled_g)
                    throw ConvergenceError(fmt::format(
                        "the fire solver did not reach the tolerance in the final stage at "
                        "iteration {}: the largest overlaps stay at {:.3g} (pair) and {:.3g} "
                        "(wall) Dp while gravity fell to {:.3g}",
                        m_steps, s.pair, s.wall, m_g));
                if (m_steps % p.mc_period == 0 && m_window.settled())
                    break;
            }
        }
        result.stages.push_back(record("final", start, steps));

        m_bed.fill_result(result, p.diameter);
        result.iterations = m_steps;
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return result;
    }

private:
    /// One FIRE step at the current gravity. \return the force pass's totals (overlaps of
    /// the configuration before the move, as the paper's iteration reports them).
    PassTotals step(std::string_view stage, const RunControl& control) {
        const SoftSphereParameters& p = m_params;
        detail::SoftBed& bed = m_bed;
        if (bed.list_stale())
            bed.rebuild_list(p.skin);
        const std::size_t n = bed.packing.size();
        Vec3* const x = bed.packing.centers.data();
        Vec3* const v = bed.velocity.data();
        Vec3* const f = m_force.data();
        const double* const radius = bed.packing.radii.data();
        const detail::LinearOverlapLaw law{1.0};
        const double g = m_g;

        // Forces (the pair factors once per pair, then each sphere's sum); a = F.v,
        // b = |F|^2, speed2 = |v|^2 (a sum here).
        const double largest_pair = pair_factors(bed, law);
        PassTotals forces = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            Vec3 force = bed.contact_move_from_factors(k, law, t.wall);
            force.z -= g;
            if (x[k].z <= radius[k] && force.z < 0.0)
                force.z = 0.0; // resting on the rigid floor
            f[k] = force;
            t.a += dot(force, v[k]);
            t.b += norm2(force);
            t.speed2 += norm2(v[k]);
        });
        forces.pair = largest_pair;
        check(forces, stage);

        // FIRE's control of dt and alpha.
        const bool uphill = !(forces.a > 0.0);
        if (!uphill) {
            m_positive = std::min(m_positive + 1, fire_n_min + 1); // no overflow on long runs
            if (m_positive > fire_n_min) {
                m_dt = std::min(m_dt * fire_f_inc, fire_dt_max);
                m_alpha *= fire_f_alpha;
            }
        } else {
            m_positive = 0;
            m_dt = std::max(m_dt * fire_f_dec, fire_dt_min);
            m_alpha = fire_alpha0;
        }
        const double dt = m_dt;
        const double back = uphill ? 0.5 * dt : 0.0;
        // |v + dt F|^2 from the sums above (v = 0 after an uphill step), then the mixing
        // v <- (1 - alpha) v + alpha |v| F^.
        const double speed2 =
            uphill ? dt * dt * forces.b
                   : std::max(0.0, forces.speed2 + 2.0 * dt * forces.a + dt * dt * forces.b);
        const double mix = forces.b > 0.0 ? m_alpha * std::sqrt(speed2 / forces.b) : 0.0;
        const double keep = 1.0 - m_alpha;
        const Vec3* const reference = bed.list.reference().data();
        // One pass: half step back and stop after an uphill step, v <- v + dt F, mixing,
        // x <- x + dt v with no step longer than fire_max_step, the rigid floor.
        const PassTotals moves = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            Vec3 xk = x[k];
            Vec3 vk = v[k];
            if (uphill) {
                xk -= vk * back;
                xk.z = std::max(xk.z, radius[k]);
                vk = Vec3{};
            }
            vk += f[k] * dt;
            vk = vk * keep + f[k] * mix;
            const double step2 = norm2(vk) * dt * dt;
            if (step2 > fire_max_step * fire_max_step)
                vk *= fire_max_step / std::sqrt(step2);
            Vec3 moved = xk + vk * dt;
            if (moved.z < radius[k]) {
                moved.z = radius[k];
                vk.z = std::max(vk.z, 0.0);
            }
            v[k] = vk;
            x[k] = moved;
            t.top = std::max(t.top, moved.z);
            t.drift = std::max(t.drift, norm2(moved - reference[k]));
            t.finite = t.finite && is_finite(moved);
        });
        bed.drift2 = std::max(bed.drift2, moves.drift);
        if (!moves.finite || moves.top > bed.ceiling)
            check(moves, stage);
        ++m_steps;
        if (m_steps % p.mc_period == 0) {
            const double mc = bed.mass_centre_z();
            m_window.push(mc);
            report(control, stage, forces, mc);
        }
        return forces;
    }

    void reset_dynamics() {
        std::fill(m_bed.velocity.begin(), m_bed.velocity.end(), Vec3{});
        m_dt = fire_dt0;
        m_alpha = fire_alpha0;
        m_positive = 0;
    }

    /// The overlaps seen by the force pass were below the tolerance; confirm them on the
    /// configuration the step left (exact, O(N)).
    bool converged_overlaps() const {
        const Overlaps now = measure_overlaps(m_bed.packing, m_bed.container);
        return now.pair < m_params.tolerance && now.wall < m_params.tolerance;
    }

    void check(const PassTotals& t, std::string_view stage) const {
        std::string what;
        if (!t.finite)
            what = "a position became NaN or infinite";
        else if (t.top > m_bed.ceiling)
            what = fmt::format("a sphere was thrown to z = {:.3g} Dp", t.top);
        else if (t.wall >= (m_g > 0.0 ? 0.5 : 2.5))
            what = fmt::format("a sphere left the container through the wall (overlap {:.3g} Dp)",
                               t.wall);
        else if (m_g > 0.0 && t.pair > 0.5)
            what = fmt::format("the largest overlap grew to {:.3g} Dp", t.pair);
        if (!what.empty())
            throw ConvergenceError(fmt::format(
                "the fire solver diverged in the {} stage at iteration {}: {}{}", stage, m_steps,
                what,
                m_g > 0.0 ? fmt::format("; lower --cg-step (now {}) or raise --ck (now {}): "
                                        "gravity grows by cg-step / ck per step",
                                        m_params.cg_step, m_params.ck)
                          : ""));
    }

    void report(const RunControl& control, std::string_view stage, const PassTotals& t,
                double mass_centre) const {
        if (m_steps >= m_params.max_iterations)
            throw ConvergenceError(fmt::format(
                "the {} stage of the fire solver did not finish within --max-iterations {} "
                "(largest overlap now {:.3g} Dp); raise --max-iterations or lower --cg-step "
                "(now {})",
                stage, m_params.max_iterations, t.pair, m_params.cg_step));
        if (control.should_stop && control.should_stop())
            throw Cancelled();
        if (control.on_progress)
            control.on_progress({stage, m_steps, m_g * m_params.ck, t.pair, t.wall, mass_centre});
    }

    StageRecord record(std::string name, std::uint64_t start, std::uint32_t steps) const {
        StageRecord r;
        r.name = std::move(name);
        r.iterations = m_steps - start;
        r.steps = steps;
        r.cg = m_g * m_params.ck; // the paper's Cg = Ck g, comparable between the solvers
        const Overlaps now = measure_overlaps(m_bed.packing, m_bed.container);
        r.max_overlap_pair = now.pair;
        r.max_overlap_wall = now.wall;
        r.mass_centre_z = m_bed.mass_centre_z();
        r.mass_centre_window = m_window.values();
        return r;
    }

    SoftSphereParameters m_params;
    detail::SoftBed m_bed;
    std::vector<Vec3> m_force;
    std::vector<PassTotals> m_blocks;
    detail::MassCentreWindow m_window;
    std::uint64_t m_steps = 0;
    double m_g = 0.0;
    double m_dt = fire_dt0;
    double m_alpha = fire_alpha0;
    int m_positive = 0;
};

} // namespace

SoftSphereResult relax_with_fire(const SoftSphereParameters& parameters,
                                 const RunControl& control) {
    parameters.validate();
    return Fire(parameters).run(control);
}

} // namespace packbed
