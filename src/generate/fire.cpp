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
// The gravity schedule has the paper's stages (section 3): none until the overlaps of the
// random start are gone; then g under the control rule of eq. (7) until the mass centre
// settles; then g halved, each value held until the mass centre settles, until both overlaps
// are below the tolerance (the first cut goes straight to the g that should leave half the
// tolerance, the overlaps of a settled bed being proportional to g). Its numbers are fire's
// own unless given (SoftSphereParameters::fire_schedule): a band of eq. (7) three times
// the paper's and a mass-centre rule 500 times looser. FIRE's inertia keeps compacting a settled
// bed in a slow creep that the paper's rule waits for (95-98 % of the steps, ending 0.002-0.003
// denser than the paper's beds at a = 10-20); a heavier gravity compacts as far in fewer steps
// and the looser rule stops where the paper's beds are (docs/validation.md). Every global sum
// runs over fixed blocks added in order: the same bits for any number of threads.
// A bed taller than twice layer_height is relaxed in layers (relax_with_fire): a tall column
// under eq. (7) gets a gravity that shrinks as its height grows (the bottom layer carries the
// whole column), so it falls and settles ever more slowly; a layer gets the gravity of a
// short bed, and a step costs only the spheres of the layer and the one under it, which is
// relaxed again so that no part of the bed keeps the loose state of a free surface.
// With friction (SoftSphereParameters::friction, wall_friction) the contacts carry tangential
// springs and the spheres turn (detail::FrictionalContacts): FIRE then runs on translations and
// rotations together, from the intermediate stage on (frictional_step).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "base/parallel.hpp"
#include "generate/friction.hpp"
#include "generate/layers.hpp"
#include "generate/soft_bed.hpp"
#include "packbed/error.hpp"
#include "packbed/soft_sphere.hpp"

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
// Largest step, in units of 1/sqrt(k/m). Stable: the contact network's stiffest mode has
// omega <= sqrt(2 z) = sqrt(24) for 12 contacts (Gershgorin), and semi-implicit Euler is stable
// for omega dt < 2 (here 1.47). 0.3 rather than Bitzek et al.'s 10 dt0 = 0.5: against 0.2 it
// takes 27, 8 and 11 % fewer steps at a = 5, 10 and 20 (10 seeds each; 25 % on 60 000 spheres
// in layers) with the same beds, while 0.38 made a = 20 beds denser by 0.002-0.003
// (docs/notes/fire-schedule.md; docs/validation.md).
constexpr double fire_dt_max = 0.3;
constexpr double fire_dt0 = 0.05;
// FIRE 2.0 (Guenole et al. 2020) keeps dt >= 0.02 dt_max, so that a run of uphill steps
// cannot freeze the bed (which the mass-centre rule would take for a settled one).
constexpr double fire_dt_min = 0.02 * fire_dt_max;
// Largest move of one sphere in one step, Dp: keeps impacts of a falling bed gentle and the
// Verlet list (skin/2 = 0.1 Dp by default) valid for several steps. (0.02 took as many steps.)
constexpr double fire_max_step = 0.01;

// With friction, a cut of gravity in the final stage after which the largest overlap is still
// above this share of what it was before the cut finds it held by friction (Fire::relax). A
// borne overlap falls with g: to at most 0.5 of it at a halving (linear springs).
constexpr double held_by_friction = 0.75;

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

/// The three stages of the fire solver on one bed. Spheres 0 to fixed - 1 (generation order)
/// do not move (the settled layers under a layer, see relax_with_fire); the mass-centre rule
/// measures the other spheres' mass centre from the height `datum`.
class Fire {
public:
    Fire(const SoftSphereParameters& p, detail::SoftBed& bed, std::uint32_t fixed, double datum,
         std::uint64_t steps, std::uint32_t layer = 0, std::uint32_t layers = 1)
        : m_params(detail::in_dp(p))
        , m_schedule(m_params.schedule())
        , m_bed(bed)
        , m_window(p.mc_window, m_schedule.mc_tolerance)
        , m_fixed(fixed)
        , m_datum(datum)
        , m_steps(steps)
        , m_layer(layer)
        , m_layers(layers) {
        m_bed.velocity.assign(m_bed.packing.size(), Vec3{});
        m_force.resize(m_bed.packing.size());
        if (p.frictional()) {
            m_friction.emplace(p.friction, p.wall_friction);
            m_torque.resize(m_bed.packing.size());
        }
    }

    /// \return the number of steps taken so far (counted from the `steps` given)
    std::uint64_t steps() const { return m_steps; }

    /// Run the initial, intermediate and final stages. \return their records.
    std::vector<StageRecord> relax(const RunControl& control) {
        const SoftSphereParameters& p = m_params;
        std::vector<StageRecord> stages;

        // "initial": overlaps of the random start removed, no gravity. Without friction: the
        // random start's overlaps are no contacts, and friction could wedge a sphere between
        // the wall and the floor (mu >= 1) with its overlap held for good.
        std::uint64_t start = m_steps;
        m_g = 0.0;
        for (;;) {
            const PassTotals s = step("initial", control);
            if (s.pair < p.tolerance && s.wall < p.tolerance && converged_overlaps())
                break;
        }
        stages.push_back(record("initial", start, 1));
        if (m_friction)
            start_friction();

        // "intermediate": gravity under eq. (7), in force units g = Cg / Ck; until the mass
        // centre settles.
        start = m_steps;
        const double g_step = p.cg_step / p.ck;
        reset_dynamics();
        m_window.clear();
        for (;;) {
            const PassTotals s = step("intermediate", control);
            if (s.pair < m_schedule.overlap_low)
                m_g += g_step;
            else if (s.pair > m_schedule.overlap_high)
                m_g = std::max(m_g - g_step, 0.0);
            if (m_steps % p.mc_period == 0 && m_window.settled())
                break;
        }
        stages.push_back(record("intermediate", start, 1));

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
        // Gravity negligible and the overlaps still there: spheres pressed flat on the floor
        // are lifted and the run goes on, or the bed is jammed (detail::StallGuard).
        detail::StallGuard guard(p.mc_window, p.mc_period);
        double held = largest; // with friction: the largest overlap before the last cut
        for (bool done = false; !done; factor = 0.5) {
            m_g *= factor;
            if (m_friction) // the springs with the forces they bear
                m_friction->scale_springs(factor);
            ++steps;
            reset_dynamics();
            m_window.clear();
            for (;;) {
                const PassTotals s = step("final", control);
                if (s.pair < p.tolerance && s.wall < p.tolerance && converged_overlaps()) {
                    done = true;
                    break;
                }
                const bool record = m_steps % p.mc_period == 0;
                if (m_g < stalled_g && record && m_friction && !m_released) {
                    // Gravity negligible and an overlap held: friction can wedge spheres
                    // (against each other and the wall) so that they keep their overlaps with
                    // no load. The bed's structure is set; the rest of the final stage runs
                    // without friction, the spheres moving by about their overlaps.
                    m_friction->release();
                    m_released = true;
                    reset_dynamics();
                    m_window.clear();
                    continue;
                }
                if (m_g < stalled_g && record) {
                    const auto verdict = guard.record(m_bed, std::max(s.pair, s.wall), p.tolerance,
                                                      m_fixed, m_steps);
                    if (verdict == detail::StallGuard::Verdict::lifted) {
                        reset_dynamics();
                        m_window.clear();
                        continue;
                    }
                    if (verdict == detail::StallGuard::Verdict::jammed)
                        throw ConvergenceError(fmt::format(
                            "the fire solver did not reach the tolerance in the final stage at "
                            "iteration {}: the largest overlaps stay at {:.3g} (pair) and {:.3g} "
                            "(wall) Dp while gravity fell to {:.3g}: the bed is jammed; another "
                            "--seed gives another bed",
                            m_steps, s.pair, s.wall, m_g));
                }
                if (record && m_window.settled()) {
                    const double now = std::max(s.pair, s.wall);
                    if (m_friction && !m_released && now > held_by_friction * held) {
                        // The cut left the largest overlap where it was: friction holds it,
                        // not gravity, and further cuts would not free it (a = 5, mu = 0.5:
                        // 0.0127 Dp after 21 halvings of g was still 0.0030). Gravity made
                        // negligible at once; the branch above lets friction go.
                        m_g = std::min(m_g, 0.5 * stalled_g);
                        continue;
                    }
                    held = now;
                    break;
                }
            }
        }
        stages.push_back(record("final", start, steps));
        return stages;
    }

private:
    /// One FIRE step at the current gravity. \return the force pass's totals (overlaps of
    /// the configuration before the move, as the paper's iteration reports them).
    PassTotals step(std::string_view stage, const RunControl& control) {
        if (m_frictional)
            return frictional_step(stage, control);
        const SoftSphereParameters& p = m_params;
        detail::SoftBed& bed = m_bed;
        if (bed.list_stale())
            bed.rebuild_list(p.list_skin());
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
        const std::uint32_t* const order = bed.order.data();
        const std::uint32_t fixed = m_fixed;
        PassTotals forces = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            if (order[k] < fixed) {
                f[k] = Vec3{};
                return;
            }
            // Each sphere's step length and weight (SoftBed::mobility, weight; 1 when mono-sized).
            Vec3 force = bed.contact_move_from_factors(k, law, t.wall) * bed.mobility(radius[k]);
            force.z -= g * bed.weight(radius[k]);
            if (x[k].z <= radius[k] && force.z < 0.0)
                force.z = 0.0; // resting on the rigid floor
            f[k] = force;
            t.a += dot(force, v[k]);
            t.b += norm2(force);
            t.speed2 += norm2(v[k]);
        });
        forces.pair = largest_pair;
        check(forces, stage);

        const Mixing m = mixing(forces); // plain names: lambdas below capture them
        const bool uphill = m.uphill;
        const double dt = m.dt, back = m.back, mix = m.mix, keep = m.keep;
        const Vec3* const reference = bed.list.reference().data();
        // One pass: half step back and stop after an uphill step, v <- v + dt F, mixing,
        // x <- x + dt v with no step longer than fire_max_step, the rigid floor.
        const PassTotals moves = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            if (order[k] < fixed)
                return;
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
        end_step(forces, moves, stage, control);
        return forces;
    }

    /// What one FIRE step does with the velocities: whether it is uphill, dt, the half step
    /// back after an uphill step, and the mixing v <- keep v + mix F.
    struct Mixing {
        bool uphill;
        double dt, back, mix, keep;
    };
    /// control_step, then the mixing's numbers: |v + dt F|^2 from the force pass's sums (v = 0
    /// after an uphill step) for v <- (1 - alpha) v + alpha |v| F^.
    Mixing mixing(const PassTotals& forces) {
        const bool uphill = control_step(forces);
        const double dt = m_dt;
        const double speed2 =
            uphill ? dt * dt * forces.b
                   : std::max(0.0, forces.speed2 + 2.0 * dt * forces.a + dt * dt * forces.b);
        return {uphill, dt, uphill ? 0.5 * dt : 0.0,
                forces.b > 0.0 ? m_alpha * std::sqrt(speed2 / forces.b) : 0.0, 1.0 - m_alpha};
    }

    /// FIRE's control of dt and alpha from the power F.v of the force pass `forces`.
    /// \return true when the step is uphill (F.v <= 0).
    bool control_step(const PassTotals& forces) {
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
        return uphill;
    }

    /// After the move pass: the list's drift, the checks, the step count and the mass-centre
    /// record.
    void end_step(const PassTotals& forces, const PassTotals& moves, std::string_view stage,
                  const RunControl& control) {
        detail::SoftBed& bed = m_bed;
        bed.drift2 = std::max(bed.drift2, moves.drift);
        if (!moves.finite || moves.top > bed.ceiling)
            check(moves, stage);
        ++m_steps;
        if (m_steps % m_params.mc_period == 0) {
            const double mc = bed.mass_centre_z(m_fixed) - m_datum;
            m_window.push(mc);
            report(control, stage, forces, mc);
        }
    }

    /// One step with friction (detail::FrictionalContacts): FIRE on the translations and the
    /// rotations together, their velocities as one vector (the rotation as the surface speed
    /// u = r omega, so that both are speeds), F.v the power of forces and torques. Each sphere's
    /// displacement and rotation of the step move its contacts' springs in the next force pass.
    PassTotals frictional_step(std::string_view stage, const RunControl& control) {
        const SoftSphereParameters& p = m_params;
        detail::SoftBed& bed = m_bed;
        detail::FrictionalContacts& friction = *m_friction;
        if (bed.list_stale())
            friction.rebuild_list(bed, p.list_skin());
        const std::size_t n = bed.packing.size();
        Vec3* const x = bed.packing.centers.data();
        Vec3* const v = bed.velocity.data();
        Vec3* const u = friction.spin.data();
        Vec3* const f = m_force.data();
        Vec3* const tau = m_torque.data();
        const double* const radius = bed.packing.radii.data();
        const detail::LinearOverlapLaw law{1.0};
        const double g = m_g;

        const std::size_t pairs = bed.list.pairs();
        const std::size_t chunk = detail::SoftBed::pair_chunk;
        const std::size_t chunks = (pairs + chunk - 1) / chunk;
        double largest_pair = 0.0;
#pragma omp parallel for schedule(static)                                                          \
    reduction(max                                                                                  \
              : largest_pair) if (n >= detail::parallel_min_spheres)
        for (std::size_t c = 0; c < chunks; ++c)
            largest_pair =
                std::max(largest_pair, friction.pair_terms(bed, c * chunk,
                                                           std::min(pairs, (c + 1) * chunk), law));
        const std::uint32_t* const order = bed.order.data();
        const std::uint32_t fixed = m_fixed;
        PassTotals forces = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            if (order[k] < fixed) {
                f[k] = tau[k] = Vec3{};
                return;
            }
            const double r = radius[k];
            const Vec3 weight{0.0, 0.0, -g * 8.0 * r * r * r}; // SoftBed::weight over mobility
            friction.sphere_terms(bed, k, law, weight, f[k], tau[k], t.wall);
            t.a += dot(f[k], v[k]) + dot(tau[k], u[k]);
            t.b += norm2(f[k]) + norm2(tau[k]);
            t.speed2 += norm2(v[k]) + norm2(u[k]);
        });
        forces.pair = largest_pair;
        check(forces, stage);

        const Mixing m = mixing(forces); // plain names: lambdas below capture them
        const bool uphill = m.uphill;
        const double dt = m.dt, back = m.back, mix = m.mix, keep = m.keep;
        const Vec3* const reference = bed.list.reference().data();
        Vec3* const moved_by = friction.moved.data();
        Vec3* const turned_by = friction.turned.data();
        const auto limit = [dt](Vec3& speed) { // no step longer than fire_max_step
            const double step2 = norm2(speed) * dt * dt;
            if (step2 > fire_max_step * fire_max_step)
                speed *= fire_max_step / std::sqrt(step2);
        };
        const PassTotals moves = for_each_block(n, m_blocks, [&](std::size_t k, PassTotals& t) {
            if (order[k] < fixed)
                return;
            const Vec3 before = x[k];
            Vec3 xk = before;
            Vec3 vk = v[k], uk = u[k], turn{};
            if (uphill) {
                xk -= vk * back;
                xk.z = std::max(xk.z, radius[k]);
                turn -= uk * back;
                vk = uk = Vec3{};
            }
            vk += f[k] * dt;
            uk += tau[k] * dt;
            vk = vk * keep + f[k] * mix;
            uk = uk * keep + tau[k] * mix;
            limit(vk);
            limit(uk);
            Vec3 moved = xk + vk * dt;
            if (moved.z < radius[k]) {
                moved.z = radius[k];
                vk.z = std::max(vk.z, 0.0);
            }
            v[k] = vk;
            u[k] = uk;
            x[k] = moved;
            moved_by[k] = moved - before;
            turned_by[k] = turn + uk * dt;
            t.top = std::max(t.top, moved.z);
            t.drift = std::max(t.drift, norm2(moved - reference[k]));
            t.finite = t.finite && is_finite(moved);
        });
        end_step(forces, moves, stage, control);
        return forces;
    }

public:
    /// With friction, after relax(): the largest force and torque left on a free sphere by its
    /// contacts, the floor and the final gravity (one force pass on the final bed; the last
    /// step's slip moves the springs first). Force in units of k Dp (k the contact stiffness),
    /// torque in k Dp^2.
    std::pair<double, double> residuals() {
        detail::SoftBed& bed = m_bed;
        detail::FrictionalContacts& friction = *m_friction;
        if (bed.list_stale())
            friction.rebuild_list(bed, m_params.list_skin());
        const detail::LinearOverlapLaw law{1.0};
        friction.pair_terms(bed, 0, bed.list.pairs(), law);
        double force = 0.0, torque = 0.0, wall = 0.0;
        for (std::size_t k = 0; k < bed.packing.size(); ++k) {
            if (bed.order[k] < m_fixed)
                continue;
            const double r = bed.packing.radii[k];
            Vec3 accel, spin;
            friction.sphere_terms(bed, k, law, {0.0, 0.0, -m_g * 8.0 * r * r * r}, accel, spin,
                                  wall);
            const double mass = 1.0 / bed.mobility(r);
            force = std::max(force, norm(accel) * mass);
            torque = std::max(torque, norm(spin) * mass * r / 2.5);
        }
        return {force, torque};
    }

private:
    /// From the intermediate stage on: every sphere at rest, no spring held, the pairs of the
    /// list the frictionless steps built.
    void start_friction() {
        m_friction->reset(m_bed.packing.size());
        m_friction->rebuild_list(m_bed, m_params.list_skin());
        m_frictional = true;
    }

    void reset_dynamics() {
        std::fill(m_bed.velocity.begin(), m_bed.velocity.end(), Vec3{});
        if (m_friction)
            std::fill(m_friction->spin.begin(), m_friction->spin.end(), Vec3{});
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
            control.on_progress({stage, m_steps, m_g * m_params.ck, t.pair, t.wall, mass_centre,
                                 m_layer, m_layers});
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
        r.mass_centre_z = m_bed.mass_centre_z(m_fixed);
        r.mass_centre_window = m_window.values();
        return r;
    }

    SoftSphereParameters m_params;
    SoftSphereParameters::Schedule m_schedule; // in Dp (m_params is)
    detail::SoftBed& m_bed;
    std::vector<Vec3> m_force;
    std::vector<PassTotals> m_blocks;
    std::optional<detail::FrictionalContacts> m_friction; // with friction only
    bool m_frictional = false;  // steps with friction (from the intermediate stage on)
    bool m_released = false;    // friction let go in a stalled final stage
    std::vector<Vec3> m_torque; // rate of each sphere's u (FrictionalContacts::sphere_terms)
    detail::MassCentreWindow m_window;
    std::uint32_t m_fixed;
    double m_datum;
    std::uint64_t m_steps;
    std::uint32_t m_layer, m_layers;
    double m_g = 0.0;
    double m_dt = fire_dt0;
    double m_alpha = fire_alpha0;
    int m_positive = 0;
};

} // namespace

std::uint32_t fire_layers(const SoftSphereParameters& p) {
    const double height = initial_bed_height(p);
    if (p.layer_height <= 0.0 || height <= 2.0 * p.layer_height)
        return 1;
    return static_cast<std::uint32_t>(std::min(height / p.layer_height, 1e6));
}

namespace {

// A layer is relaxed with the whole layer below it free to move, and the top layer_band Dp of
// the bed under that layer, above a shell of fixed spheres. Every sphere but the top layer's
// thus ends its relaxation under a layer's weight, as the bulk of a bed in one piece does: a
// bed relaxed with a free surface is looser down to 10-20 Dp below it (docs/validation.md,
// "A tall bed's axial profile"), and a band of 4 Dp left that gradient in every layer.
constexpr double layer_band = 4.0;
constexpr double layer_shell = 1.5; // > 1 Dp: no free sphere reaches past the shell

} // namespace

SoftSphereResult relax_with_fire(const SoftSphereParameters& parameters,
                                 const RunControl& control) {
    parameters.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const SoftSphereParameters& p = parameters;
    detail::SoftBed bed(p.container);
    bed.generate(p);
    SoftSphereResult result;
    const std::uint32_t layers = fire_layers(p);
    std::uint64_t steps = 0, builds = 0;
    if (layers == 1) {
        if (control.resume)
            throw InvalidInput("a checkpoint can only resume a fire run in layers (L0 > 2 "
                               "layer-height); this run is relaxed in one piece");
        Fire fire(p, bed, 0, 0.0, 0);
        result.stages = fire.relax(control);
        if (p.frictional())
            result.residuals = fire.residuals();
        steps = fire.steps();
        builds = bed.list.builds();
    } else {
        // Layers: the generation stage's bed cut into `layers` slices of equal height; each
        // slice, moved down to just above the bed below, relaxed by the three stages with the
        // top layer_band of that bed free and the rest fixed.
        const Packing start = bed.packing_in_generation_order();
        const std::size_t n = start.size();
        const double slice = bed.initial_height / layers;
        std::vector<std::vector<std::uint32_t>> members(layers);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double z = start.centers[i].z - start.radii[i];
            const auto l = static_cast<std::uint32_t>(std::clamp(z / slice, 0.0, layers - 1.0));
            members[l].push_back(i);
        }
        std::vector<Vec3> position = start.centers;
        double top = 0.0; // highest settled centre
        std::uint32_t first = 0;
        if (const LayerCheckpoint* from = control.resume) {
            if (from->packing.size() != n || from->layers_done > layers)
                throw InvalidInput(fmt::format(
                    "the checkpoint holds {} spheres after {} layers; this run has {} spheres "
                    "in {} layers",
                    from->packing.size(), from->layers_done, n, layers));
            position = from->packing.centers;
            top = from->top;
            steps = from->iterations;
            builds = from->neighbor_builds;
            result.stages = from->stages;
            first = from->layers_done;
        }
        // Slices holding no sphere (a loose start, e0 near 1, cut into more slices than it has
        // spheres) are skipped: there is nothing to relax, and the next slice is laid on the
        // highest settled layer, on the floor while none has settled.
        bool on_floor =
            std::all_of(members.begin(), members.begin() + first,
                        [](const auto& slice_members) { return slice_members.empty(); });
        // Lengths of a Dp above, for spheres of many sizes the largest diameter's (1 when
        // mono-sized): the shell must hold every sphere a free one can touch.
        const double largest =
            p.sizes.empty() ? 1.0
                            : std::max(1.0, *std::max_element(p.sizes.begin(), p.sizes.end()));
        const double shell = layer_shell * largest;
        detail::SoftBed part(p.container);
        for (std::uint32_t l = first; l < layers; ++l) {
            if (members[l].empty())
                continue;
            // the part's spheres: fixed shell, free band, new slice (each in a fixed order).
            detail::LayerPart layer = detail::layer_part(
                members, l, [&](std::uint32_t i) { return position[i].z; }, layer_band, shell);
            std::vector<std::uint32_t>& ids = layer.ids;
            const auto fixed = static_cast<std::uint32_t>(layer.fixed);
            const double datum = layer.datum;
            const double base = on_floor ? 0.0 : top + largest; // where the slice's bottom goes
            const double lift = base - l * slice;
            for (const std::uint32_t i : members[l]) {
                position[i].z += lift;
                ids.push_back(i);
            }
            Packing spheres;
            spheres.centers.reserve(ids.size());
            spheres.radii.reserve(ids.size());
            for (const std::uint32_t i : ids)
                spheres.add(position[i], start.radii[i]);
            part.assign(std::move(spheres), base + slice, bed.smallest_radius);
            Fire fire(p, part, fixed, datum, steps, l, layers);
            std::vector<StageRecord> stages = fire.relax(control);
            if (p.frictional()) {
                const auto [force, torque] = fire.residuals();
                result.residuals = {
                    std::max(force, result.residuals ? result.residuals->first : 0.0),
                    std::max(torque, result.residuals ? result.residuals->second : 0.0)};
            }
            steps = fire.steps();
            builds += part.list.builds();
            if (result.stages.empty()) {
                result.stages = std::move(stages);
            } else {
                for (std::size_t s = 0; s < stages.size(); ++s) {
                    stages[s].iterations += result.stages[s].iterations;
                    stages[s].steps += result.stages[s].steps;
                }
                result.stages = std::move(stages);
            }
            const Packing& moved = part.packing_in_generation_order();
            for (std::size_t k = fixed; k < ids.size(); ++k) {
                position[ids[k]] = moved.centers[k];
                top = std::max(top, moved.centers[k].z);
            }
            on_floor = false;
            if (control.on_layer) {
                LayerCheckpoint state{l + 1, steps, builds, top, {}, result.stages};
                state.packing.centers = position;
                state.packing.radii = start.radii;
                control.on_layer(state);
            }
        }
        Packing all;
        all.centers = std::move(position);
        all.radii = start.radii;
        bed.assign(std::move(all), bed.initial_height, bed.smallest_radius);
        if (!result.stages.empty())
            result.stages.back().mass_centre_z = bed.mass_centre_z();
    }
    bed.fill_result(result, p.diameter);
    result.neighbor_builds = builds;
    result.layers = layers;
    result.iterations = steps;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

} // namespace packbed
