// Friction of the contacts (src/generate/friction.hpp; docs/generate.md, "Friction"): the
// tangential spring and Coulomb's cap of one contact, a sphere on a tilted plane (rolling and
// sliding, and a body that cannot roll: sticking below tan(theta) = mu), the torque and force
// balance of a sphere at rest on two others, and the frictional beds of the fire solver.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "generate/friction.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/box.hpp"
#include "packbed/error.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed::detail {
namespace {

constexpr double kt = tangential_stiffness;

TEST(Friction, CoulombCapOfOneContact) {
    // A contact of normal z pressed with F_n = 0.1 (mu = 0.5: cap 0.05), sheared along x by
    // 0.01 per step: the force grows as k_t s until it reaches mu F_n = 0.05 (s = 0.175), then
    // stays there while the contact slides. Sheared back, it unloads elastically (slope k_t)
    // from +cap to -cap over a reversal of 2 cap / k_t = 0.35, then slides again.
    const Vec3 n{0.0, 0.0, 1.0};
    const double cap = 0.5 * 0.1;
    Vec3 spring{};
    for (int s = 1; s <= 40; ++s) {
        const Vec3 f = tangential_spring(spring, n, {0.01, 0.0, 0.0}, cap);
        EXPECT_NEAR(f.x, std::min(kt * 0.01 * s, cap), 1e-15) << "step " << s;
        EXPECT_EQ(f.y, 0.0);
        EXPECT_EQ(f.z, 0.0);
        EXPECT_LE(std::abs(f.x), cap * (1.0 + 1e-15));
    }
    for (int s = 1; s <= 60; ++s) {
        const Vec3 f = tangential_spring(spring, n, {-0.01, 0.0, 0.0}, cap);
        EXPECT_NEAR(f.x, std::max(cap - kt * 0.01 * s, -cap), 1e-15) << "back, step " << s;
    }
    // A normal slip moves nothing; a spring is kept in the tangent plane of a turned normal.
    Vec3 held{0.1, 0.0, 0.0};
    EXPECT_NEAR(tangential_spring(held, n, {0.0, 0.0, 0.3}, 1.0).x, kt * 0.1, 1e-15);
    const Vec3 turned{std::sin(0.01), 0.0, std::cos(0.01)};
    const Vec3 f = tangential_spring(held, turned, {}, 1.0);
    EXPECT_NEAR(dot(f, turned), 0.0, 1e-15);
    EXPECT_NEAR(norm(f), kt * 0.1 * std::cos(0.01), 1e-15);
    // Nothing held: no force, whatever the cap.
    Vec3 none{};
    EXPECT_EQ(norm(tangential_spring(none, n, {}, 0.0)), 0.0);
}

TEST(Friction, CoulombCapOfAContactOfItsOwnStiffness) {
    // A pellet's contact takes its own k_t (2/7 of its secant normal stiffness): k_t = 3, the
    // same contact as above, reaches its cap 0.05 after 0.05 / (3 * 0.01) = 1.67 steps.
    const Vec3 n{0.0, 0.0, 1.0};
    const double cap = 0.05, k = 3.0;
    Vec3 spring{};
    EXPECT_NEAR(tangential_spring(spring, n, {0.01, 0.0, 0.0}, cap, k).x, 0.03, 1e-15);
    EXPECT_NEAR(spring.x, 0.01, 1e-15);
    EXPECT_NEAR(tangential_spring(spring, n, {0.01, 0.0, 0.0}, cap, k).x, cap, 1e-15);
    EXPECT_NEAR(spring.x, cap / k, 1e-15); // held at the cap's length: it slid
    EXPECT_NEAR(tangential_spring(spring, n, {-0.01, 0.0, 0.0}, cap, k).x, cap - 0.03, 1e-15);
}

/// Plain Newtonian dynamics (semi-implicit Euler, optional viscous damping) of spheres of
/// radius 0.5 and unit mass through the solver's contact terms (FrictionalContacts): spheres
/// of generation index below `fixed` stay put. Gravity is an acceleration vector here, so that
/// the floor can be a tilted plane.
struct Dynamics {
    SoftBed bed;
    FrictionalContacts friction;
    std::uint32_t fixed;
    bool rotations = true;
    double damping = 0.0;
    static constexpr double skin = 0.2;

    Dynamics(const Container& c, Packing spheres, std::uint32_t fixed_spheres, double mu,
             double wall_mu)
        : bed(c)
        , friction(mu, wall_mu)
        , fixed(fixed_spheres) {
        bed.assign(std::move(spheres), 10.0, 0.5);
        bed.velocity.assign(bed.packing.size(), Vec3{});
        friction.reset(bed.packing.size());
    }

    void step(double dt, const Vec3& gravity) {
        if (bed.list_stale())
            friction.rebuild_list(bed, skin);
        const LinearOverlapLaw law{1.0};
        friction.pair_terms(bed, 0, bed.list.pairs(), law);
        const std::size_t n = bed.packing.size();
        std::vector<Vec3> accel(n), spin_accel(n);
        double wall = 0.0;
        for (std::size_t k = 0; k < n; ++k)
            if (bed.order[k] >= fixed)
                friction.sphere_terms(bed, k, law, gravity, accel[k], spin_accel[k], wall);
        for (std::size_t k = 0; k < n; ++k) {
            if (bed.order[k] < fixed)
                continue;
            Vec3& v = bed.velocity[k];
            Vec3& u = friction.spin[k];
            v += accel[k] * dt;
            if (rotations)
                u += spin_accel[k] * dt;
            v *= 1.0 - damping * dt;
            u *= 1.0 - damping * dt;
            Vec3& x = bed.packing.centers[k];
            Vec3 next = x + v * dt;
            if (next.z < bed.packing.radii[k]) { // the solver's rigid floor
                next.z = bed.packing.radii[k];
                v.z = std::max(v.z, 0.0);
            }
            friction.moved[k] = next - x;
            friction.turned[k] = u * dt;
            x = next;
            bed.drift2 = std::max(bed.drift2, norm2(x - bed.list.reference()[k]));
        }
    }
    const Vec3& centre(std::uint32_t generation) const {
        return bed.packing.centers[bed.slot[generation]];
    }
    const Vec3& spin(std::uint32_t generation) const { return friction.spin[bed.slot[generation]]; }
};

/// The displacement of a body whose acceleration grows linearly from 0 to A over `ramp`, then
/// stays A, after time T >= ramp, over A.
double ramp_distance(double ramp, double T) {
    return ramp * ramp / 6.0 + ramp * (T - ramp) / 2.0 + (T - ramp) * (T - ramp) / 2.0;
}

/// A sphere on the floor of a wide box under gravity g tilted by theta, the floor's friction
/// mu, gravity raised linearly over `ramp` (no impact, as the solver's stages raise it).
/// \return its acceleration along the slope and its final u = r omega and speed.
struct Slope {
    double accel, spin, speed;
};
Slope slope(double theta, double mu, bool rotations) {
    Packing one;
    one.add({10.0, 50.0, 0.5}, 0.5);
    Dynamics d(Box(100.0, 100.0), std::move(one), 0, 0.0, mu);
    d.rotations = rotations;
    const double g = 1e-4, dt = 0.05, ramp = 200.0, T = 600.0;
    const auto steps = static_cast<int>(T / dt), ramp_steps = static_cast<int>(ramp / dt);
    for (int s = 0; s < steps; ++s) {
        const double on = std::min(1.0, (s + 1.0) / ramp_steps);
        d.step(dt, Vec3{std::sin(theta), 0.0, -std::cos(theta)} * (g * on));
    }
    EXPECT_EQ(d.centre(0).z, 0.5); // it stays on the floor
    return {(d.centre(0).x - 10.0) / ramp_distance(ramp, T), d.spin(0).y,
            d.bed.velocity[d.bed.slot[0]].x};
}

TEST(Friction, SphereOnTiltedPlaneRollsOrSlides) {
    // A solid sphere rolls without slipping while tan(theta) < (7/2) mu, with acceleration
    // (5/7) g sin(theta) and u = r omega equal to its speed (the contact point at rest); above,
    // it slides with acceleration g (sin - mu cos) while the friction spins it up at
    // du/dt = (5/2) mu g cos (I = 2/5 m r^2). With mu = 0.2 the threshold is theta = 35 deg.
    const double g = 1e-4, mu = 0.2;
    const double rolling = 15.0 * std::numbers::pi / 180.0;
    const Slope roll = slope(rolling, mu, true);
    EXPECT_NEAR(roll.accel / (5.0 / 7.0 * g * std::sin(rolling)), 1.0, 5e-3);
    EXPECT_NEAR(roll.spin / roll.speed, 1.0, 5e-3); // rolling: omega along +y for +x motion
    const double sliding = 50.0 * std::numbers::pi / 180.0;
    const Slope slide = slope(sliding, mu, true);
    EXPECT_NEAR(slide.accel / (g * (std::sin(sliding) - mu * std::cos(sliding))), 1.0, 5e-3);
    EXPECT_GT(slide.speed, slide.spin * 1.5); // the contact point slips
    // Frictionless, it slides at g sin(theta) and does not turn.
    const Slope free = slope(rolling, 0.0, true);
    EXPECT_NEAR(free.accel / (g * std::sin(rolling)), 1.0, 5e-3);
    EXPECT_EQ(free.spin, 0.0);
}

TEST(Friction, BodyThatCannotRollSticksBelowTanThetaEqualsMu) {
    // Rotations held (a block's contact): it sticks while tan(theta) < mu, its only motion the
    // spring's stretch g sin / k_t, and slides above at g (sin - mu cos).
    const double g = 1e-4, mu = 0.5; // tan(theta) = mu at 26.6 deg
    for (const double degrees : {10.0, 20.0, 25.0}) {
        const double theta = degrees * std::numbers::pi / 180.0;
        const Slope s = slope(theta, mu, false);
        EXPECT_LT(std::abs(s.accel * ramp_distance(200.0, 600.0)), 2.0 * g * std::sin(theta) / kt)
            << degrees << " deg";
    }
    for (const double degrees : {28.0, 40.0}) {
        const double theta = degrees * std::numbers::pi / 180.0;
        const Slope s = slope(theta, mu, false);
        EXPECT_NEAR(s.accel / (g * (std::sin(theta) - mu * std::cos(theta))), 1.0, 2e-2)
            << degrees << " deg";
    }
}

TEST(Friction, SphereAtRestOnTwoOthersBalancesForcesAndTorques) {
    // Two fixed spheres at different heights and a third dropped on them (mu = 0.5, damped):
    // at rest, the contact forces, computed here from each pair's overlap and tangential force
    // (not from the solver's sums), balance its weight, and their torques about its centre
    // cancel: the two tangential forces are equal in size. Each stays within mu F_n, and
    // friction holds (the tangential forces are not 0).
    Packing spheres;
    spheres.add({4.45, 5.0, 0.5}, 0.5);
    spheres.add({5.5, 5.0, 0.8}, 0.5);
    spheres.add({5.1, 5.0, 1.75}, 0.5);
    const double mu = 0.5, g = 1e-3;
    Dynamics d(Box(10.0, 10.0), std::move(spheres), 2, mu, 0.0);
    d.damping = 0.05;
    for (int s = 0; s < 40000; ++s)
        d.step(0.1, {0.0, 0.0, -g});
    const std::size_t k = d.bed.slot[2];
    EXPECT_LT(norm(d.bed.velocity[k]), 1e-12);
    EXPECT_LT(norm(d.friction.spin[k]), 1e-12);
    Vec3 force{0.0, 0.0, -g}, torque{};
    std::vector<double> tangential;
    for (std::size_t p = 0; p < d.bed.list.pairs(); ++p) {
        const std::uint32_t i = d.bed.list.pair_first()[p], j = d.bed.list.pair_second()[p];
        if (i != k && j != k)
            continue;
        const std::uint32_t other = i == k ? j : i;
        const Vec3 towards = d.bed.packing.centers[other] - d.bed.packing.centers[k];
        const double overlap = 1.0 - norm(towards);
        if (overlap <= 0.0)
            continue;
        const Vec3 n = towards * (1.0 / norm(towards));
        const Vec3 ft = d.friction.pair_force(p) * (i == k ? 1.0 : -1.0);
        force += -n * overlap + ft;
        torque += cross(n * 0.5, ft);
        EXPECT_LE(norm(ft), mu * overlap * (1.0 + 1e-12));
        EXPECT_NEAR(dot(ft, n), 0.0, 1e-15);
        tangential.push_back(norm(ft));
    }
    ASSERT_EQ(tangential.size(), 2u);
    EXPECT_LT(norm(force), 1e-9 * g);
    EXPECT_LT(norm(torque), 1e-9 * g);
    EXPECT_NEAR(tangential[0], tangential[1], 1e-9 * g);
    EXPECT_GT(tangential[0], 1e-3 * g);
}

SoftSphereParameters frictional_bed(double mu, double wall_mu) {
    SoftSphereParameters p;
    p.container = Container::tube(8.0);
    p.particles = 1500;
    p.seed = 3;
    p.friction = mu;
    p.wall_friction = wall_mu;
    return p;
}

double band_void_fraction(const SoftSphereResult& r) {
    const auto band = band_clear_of_ends(r.packing, 1.0);
    return void_fraction(r.packing, r.container, band->z_low, band->z_high);
}

TEST(FrictionalBeds, LooserAsFrictionGrowsWithinTheTolerance) {
    // a = 8, 1500 spheres: the frictionless bed is the dense limit; friction holds the spheres
    // where they first touch, and the bed gets looser as mu grows (docs/validation.md,
    // "Friction"), every overlap still below the tolerance.
    double previous = 0.0;
    for (const double mu : {0.0, 0.05, 0.3, 1.0}) {
        const SoftSphereResult r = relax_with_fire(frictional_bed(mu, mu));
        const double e = band_void_fraction(r);
        EXPECT_GT(e, previous + 0.005) << "mu " << mu;
        previous = e;
        EXPECT_LT(r.max_overlap_pair, 1e-4);
        EXPECT_LT(r.max_overlap_wall, 1e-4);
    }
    // From the dense frictionless bed (e about 0.40 at a = 8) to a loose one (above 0.45).
    EXPECT_GT(previous, 0.45);
}

TEST(FrictionalBeds, OverlapsHeldByFrictionInANarrowTubeLetGoAfterOneCut) {
    // a = 5, 750 spheres, mu = 0.5 at spheres and walls (seed 1): friction wedges spheres
    // against the wall and holds overlaps of about 0.01 Dp that cuts of gravity do not free
    // (21 halvings, 22 915 steps in the final stage, when gravity was halved until negligible).
    // The first cut that leaves the largest overlap above 3/4 of itself lets friction go
    // (docs/generate.md, "Friction: poured beds"): two cuts, every overlap below the tolerance.
    SoftSphereParameters p = frictional_bed(0.5, 0.5);
    p.container = Container::tube(5.0);
    p.particles = 750;
    p.seed = 1;
    const SoftSphereResult r = relax_with_fire(p);
    ASSERT_EQ(r.stages.size(), 3u);
    EXPECT_LE(r.stages[2].steps, 2u);
    EXPECT_LT(r.stages[2].iterations, 5000u);
    EXPECT_LT(r.max_overlap_pair, 1e-4);
    EXPECT_LT(r.max_overlap_wall, 1e-4);
    EXPECT_GT(band_void_fraction(r), 0.46); // still a loose bed (0.4767; frictionless 0.43)
}

TEST(FrictionalBeds, SameBitsWhateverTheThreads) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const SoftSphereResult one = relax_with_fire(frictional_bed(0.3, 0.3));
    omp_set_num_threads(2);
    const SoftSphereResult two = relax_with_fire(frictional_bed(0.3, 0.3));
    omp_set_num_threads(saved);
    ASSERT_EQ(one.packing.size(), two.packing.size());
    EXPECT_EQ(one.iterations, two.iterations);
    for (std::size_t i = 0; i < one.packing.size(); ++i)
        ASSERT_EQ(one.packing.centers[i], two.packing.centers[i]) << "sphere " << i;
}

TEST(FrictionalBeds, PaperSolverRefusesFriction) {
    SoftSphereParameters p = frictional_bed(0.3, 0.0);
    p.solver = Solver::paper;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.friction = 0.0;
    p.wall_friction = 0.1;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.solver = Solver::fire;
    p.wall_friction = -0.1;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.wall_friction = 101.0;
    EXPECT_THROW(p.validate(), InvalidInput);
}

} // namespace
} // namespace packbed::detail
