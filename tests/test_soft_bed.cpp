// The solvers' internal kernels (src/generate/soft_bed.hpp): the two-pass pair sum against the
// one-pass reference, bit for bit, on hand-placed spheres with every special case.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "generate/soft_bed.hpp"

namespace packbed::detail {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) {
    return std::memcmp(&a, &b, sizeof(Vec3)) == 0;
}

TEST(SoftBedKernels, PairFactorsGiveContactMovesBitForBit) {
    SoftBed bed(Cylinder(2.0)); // Rt = 2 Dp
    const std::vector<Vec3> centres = {
        {0.0, 0.0, 1.0},   {0.0, 0.0, 1.0},    // coincident centres
        {0.9, 0.0, 1.0},                       // overlaps both of them by 0.1 Dp
        {0.9, 1.0, 1.0},                       // touching sphere 2 exactly: no force
        {1.6, 0.3, 1.2},   {-1.55, -0.4, 0.5}, // pressing into the wall
        {0.2, -0.85, 1.3}, {-0.3, 0.45, 1.6},  // generic overlaps, in no symmetric place
        {0.0, 0.0, 5.0},                       // alone
    };
    for (const Vec3& c : centres)
        bed.packing.add(c, 0.5);
    const std::size_t n = bed.packing.size();
    bed.order.resize(n);
    bed.slot.resize(n);
    for (std::uint32_t i = 0; i < n; ++i)
        bed.order[i] = bed.slot[i] = i;
    bed.next.resize(n);
    bed.rebuild_list(0.1);
    ASSERT_GT(bed.list.pairs(), 5u);

    for (const double ck : {0.3, 1.0}) {
        const LinearOverlapLaw law{ck};
        const double largest = bed.pair_factors(0, bed.list.pairs(), law);
        double reference_largest = 0.0, reference_wall = 0.0, wall = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
            const Vec3 reference = bed.contact_move(k, law, reference_largest, reference_wall);
            const Vec3 two_pass = bed.contact_move_from_factors(k, law, wall);
            EXPECT_TRUE(same_bits(reference, two_pass))
                << "sphere " << bed.order[k] << " ck " << ck << ": (" << reference.x << ", "
                << reference.y << ", " << reference.z << ") vs (" << two_pass.x << ", "
                << two_pass.y << ", " << two_pass.z << ")";
        }
        EXPECT_EQ(largest, reference_largest);
        EXPECT_EQ(largest, 1.0); // the coincident pair overlaps by a whole diameter
        EXPECT_EQ(wall, reference_wall);
        EXPECT_NEAR(wall, std::hypot(1.6, 0.3) + 0.5 - 2.0, 1e-15);
    }
    // The coincident pair moves apart vertically, the lower generation index downwards.
    const LinearOverlapLaw law{0.3};
    bed.pair_factors(0, bed.list.pairs(), law);
    double wall = 0.0;
    EXPECT_LT(bed.contact_move_from_factors(bed.slot[0], law, wall).z, 0.0);
    EXPECT_GT(bed.contact_move_from_factors(bed.slot[1], law, wall).z, 0.0);
}

TEST(StallGuard, LiftsSpheresSqueezedOnTheFloorOnceThenCallsTheBedJammed) {
    // Two spheres on the floor of a tube of Rt = 1 Dp, 0.98 Dp apart: overlapping by 0.02 Dp,
    // held at z = r, so their contact pushes only sideways. Records every 100 iterations; a
    // window of 3 that agrees within 1 % is a stall.
    SoftBed bed(Cylinder(1.0));
    bed.packing.add({-0.49, 0.0, 0.5}, 0.5);
    bed.packing.add({0.49, 0.0, 0.5}, 0.5);
    bed.packing.add({0.0, 0.0, 1.4}, 0.5); // above them, not on the floor
    bed.order = bed.slot = {0, 1, 2};
    bed.next.resize(3);
    bed.rebuild_list(0.1);
    const auto k0 = bed.slot[0], k1 = bed.slot[1], k2 = bed.slot[2];
    StallGuard guard(3, 100); // budget 50 windows: 15 000 iterations
    using V = StallGuard::Verdict;
    EXPECT_EQ(guard.record(bed, 0.02, 1e-4, 0, 100), V::wait);
    EXPECT_EQ(guard.record(bed, 0.02, 1e-4, 0, 200), V::wait);
    EXPECT_EQ(guard.record(bed, 0.0201, 1e-4, 0, 300), V::lifted);
    // each lifted by 0.1 to 0.2 of its overlap (about 0.02 Dp), by its own amount
    for (const auto k : {k0, k1}) {
        EXPECT_GE(bed.packing.centers[k].z - 0.5, 0.1 * 0.0199) << k;
        EXPECT_LE(bed.packing.centers[k].z - 0.5, 0.2 * 0.0201) << k;
    }
    EXPECT_NE(bed.packing.centers[k0].z, bed.packing.centers[k1].z);
    EXPECT_EQ(bed.packing.centers[k2].z, 1.4);
    EXPECT_TRUE(bed.list_stale()); // moved outside a step: the list is rebuilt
    bed.rebuild_list(0.1);
    // stalled again with nothing on the floor: jammed
    EXPECT_EQ(guard.record(bed, 0.02, 1e-4, 0, 400), V::wait);
    EXPECT_EQ(guard.record(bed, 0.02, 1e-4, 0, 500), V::wait);
    EXPECT_EQ(guard.record(bed, 0.02, 1e-4, 0, 600), V::jammed);

    // Spheres held fixed (generation index below first_free) are never lifted.
    SoftBed fixed_bed(Cylinder(1.0));
    fixed_bed.packing.add({-0.49, 0.0, 0.5}, 0.5);
    fixed_bed.packing.add({0.49, 0.0, 0.5}, 0.5);
    fixed_bed.order = fixed_bed.slot = {0, 1};
    fixed_bed.next.resize(2);
    fixed_bed.rebuild_list(0.1);
    EXPECT_EQ(fixed_bed.lift_squeezed_floor_spheres(1e-4, 1), 1u);
    EXPECT_EQ(fixed_bed.packing.centers[fixed_bed.slot[0]].z, 0.5);
    EXPECT_GT(fixed_bed.packing.centers[fixed_bed.slot[1]].z, 0.5);
    // Overlaps within the tolerance are not a squeeze: nothing lifted.
    EXPECT_EQ(fixed_bed.lift_squeezed_floor_spheres(0.05, 0), 0u);

    // The budget: after `budget` iterations of stall, jammed whatever the records say.
    StallGuard short_guard(3, 1); // budget 50 x 3 x 1 = 150 iterations
    EXPECT_EQ(short_guard.record(bed, 0.5, 1e-4, 0, 1000), V::wait);
    EXPECT_EQ(short_guard.record(bed, 0.3, 1e-4, 0, 1100), V::wait);
    EXPECT_EQ(short_guard.record(bed, 0.1, 1e-4, 0, 1200), V::jammed);
}

} // namespace
} // namespace packbed::detail

namespace packbed::detail {
namespace {

TEST(SoftBedKernels, UnequalSpheresPressEachOtherAndTheWallByTheirOwnRadii) {
    // Eq. (2b) with r_i + r_j: spheres of radius 0.25 and 1 (Dp units) 1.15 apart overlap by
    // 0.1; with Ck = 0.3 each moves 0.03 along the line of centres. Eq. (2a) with r_i: the
    // large one, 2.1 from the axis in a tube of radius 3, presses the wall by 0.1.
    const LinearOverlapLaw law{0.3};
    Vec3 move{};
    double largest = 0.0;
    law.apply({0.0, 0.0, 1.0}, {1.15, 0.0, 1.0}, 0.25 + 1.0, true, move, largest);
    EXPECT_NEAR(largest, 0.1, 1e-15);
    EXPECT_NEAR(move.x, -0.03, 1e-15);
    EXPECT_EQ(move.y, 0.0);
    SoftBed bed(Cylinder(3.0)); // Rt = 3
    Vec3 wall_move{};
    double wall = 0.0;
    bed.add_wall_term({0.0, 2.1, 1.0}, 1.0, law, wall_move, wall);
    EXPECT_NEAR(wall, 0.1, 1e-15);
    EXPECT_NEAR(wall_move.y, -0.03, 1e-15);
    // Step lengths (r_min / r)^2 and gravity steps (r_min / r)^2 (r / 0.5)^3 with r_min = 0.25:
    // the smallest sphere moves by the paper's step and weighs 1/8 of a Dp sphere; a sphere of
    // radius 1 moves 1/16 as far per unit force and falls 8 x 1/16 = 1/2 as far per Cg.
    bed.smallest_radius = 0.25;
    EXPECT_EQ(bed.mobility(0.25), 1.0);
    EXPECT_EQ(bed.weight(0.25), 0.125);
    EXPECT_EQ(bed.mobility(1.0), 0.0625);
    EXPECT_EQ(bed.weight(1.0), 0.5);
    // A mono-sized bed: exactly 1, so its bits are those of the paper's eq. (4).
    bed.smallest_radius = 0.5;
    EXPECT_EQ(bed.mobility(0.5), 1.0);
    EXPECT_EQ(bed.weight(0.5), 1.0);
}

} // namespace
} // namespace packbed::detail
