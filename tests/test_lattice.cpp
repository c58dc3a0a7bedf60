// Regular packings (Tsayger 2013 and the cubic / close packings) against geometry.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/json_text.hpp"
#include "packbed/lattice.hpp"
#include "packbed/periodic.hpp"

namespace packbed {
namespace {

constexpr double pi = std::numbers::pi;

TEST(Lattice, DiamondCellIsTsaygersTable1) {
    const UnitCell c = unit_cell(LatticeType::diamond);
    const double s = std::sqrt(3.0);
    EXPECT_DOUBLE_EQ(c.edges.x, 4.0 / s); // note 2 of Table 1
    ASSERT_EQ(c.balls.size(), 8u);
    const double table1[8][3] = {{0, 0, 0}, {2, 2, 0}, {2, 0, 2}, {0, 2, 2},  // A B C D
                                 {1, 3, 3}, {3, 1, 3}, {1, 1, 1}, {3, 3, 1}}; // E F G H
    for (int b = 0; b < 8; ++b) {
        EXPECT_DOUBLE_EQ(c.balls[b].x, table1[b][0] / s) << "ball " << char('A' + b);
        EXPECT_DOUBLE_EQ(c.balls[b].y, table1[b][1] / s) << "ball " << char('A' + b);
        EXPECT_DOUBLE_EQ(c.balls[b].z, table1[b][2] / s) << "ball " << char('A' + b);
    }
    // Notes 3-5: E-D, F-C, G-A, G-B, G-C and B-H are one diameter apart.
    enum { A, B, C, D, E, F, G, H };
    for (const auto& [i, j] : {std::pair{E, D}, {F, C}, {G, A}, {G, B}, {G, C}, {B, H}})
        EXPECT_NEAR(norm(c.balls[i] - c.balls[j]), 1.0, 1e-15) << char('A' + i) << char('A' + j);
}

TEST(Lattice, TsaygersWorkedExampleBallE) {
    // Ball E of the cell at position 5, row 6, layer 3 lies at (21, 27, 15) / sqrt(3) d: fill
    // a box with ball A of cell (0,0,0) at the origin and find it, here with d = 2.
    LatticeParameters p;
    p.type = LatticeType::diamond;
    p.diameter = 2.0;
    p.region = LatticeRegion{Box(40.0, 40.0), 40.0};
    p.origin = Vec3{0.0, 0.0, 0.0};
    p.keep = LatticeKeep::centres;
    const Packing bed = fill_lattice(p);
    const double s = std::sqrt(3.0);
    const Vec3 expected{21.0 / s * 2.0, 27.0 / s * 2.0, 15.0 / s * 2.0};
    double nearest = 1e9;
    for (const Vec3& c : bed.centers)
        nearest = std::min(nearest, norm(c - expected));
    EXPECT_LT(nearest, 1e-12);
}

TEST(Lattice, PorositiesAreTheClosedForms) {
    EXPECT_NEAR(unit_cell(LatticeType::sc).porosity, 1.0 - pi / 6.0, 1e-15);
    EXPECT_NEAR(unit_cell(LatticeType::bcc).porosity, 1.0 - pi * std::sqrt(3.0) / 8.0, 1e-15);
    EXPECT_NEAR(unit_cell(LatticeType::fcc).porosity, 1.0 - pi / (3.0 * std::sqrt(2.0)), 1e-15);
    EXPECT_NEAR(unit_cell(LatticeType::hcp).porosity, 1.0 - pi / (3.0 * std::sqrt(2.0)), 1e-15);
    EXPECT_NEAR(unit_cell(LatticeType::diamond).porosity, 1.0 - pi * std::sqrt(3.0) / 16.0, 1e-15);
    EXPECT_NEAR(unit_cell(LatticeType::diamond).porosity, 0.65991, 5e-6); // Tsayger's value
}

class EveryLattice : public ::testing::TestWithParam<LatticeType> {};

TEST_P(EveryLattice, InteriorBallsHaveExactlyTheirCoordinationAndNoneIsCloser) {
    const UnitCell cell = unit_cell(GetParam());
    LatticeParameters p;
    p.type = GetParam();
    p.region = LatticeRegion{Box(8.0, 8.0), 8.0};
    const Packing bed = fill_lattice(p);
    ASSERT_GT(bed.size(), 200u);
    const LatticeContacts contacts = lattice_contacts(bed);
    EXPECT_NEAR(contacts.closest, 1.0, 1e-12) << "no two balls closer than d";
    std::size_t interior = 0;
    for (std::size_t i = 0; i < bed.size(); ++i) {
        const Vec3 c = bed.centers[i];
        // More than one diameter from every wall: all neighbours are in the box.
        if (std::min({c.x, c.y, c.z, 8.0 - c.x, 8.0 - c.y, 8.0 - c.z}) <= 1.5)
            continue;
        ++interior;
        EXPECT_EQ(contacts.contacts[i], static_cast<unsigned>(cell.coordination))
            << to_string(GetParam()) << " ball " << i;
    }
    EXPECT_GT(interior, 20u);
}

TEST_P(EveryLattice, LargeBoxPorosityTendsToTheLattices) {
    // Balls wholly inside a box of side L leave a wall layer of order d / L empty (sides
    // that are no whole number of cells, or the simple cubic lattice would fill them exactly).
    const UnitCell cell = unit_cell(GetParam());
    double previous_gap = 1.0;
    for (const double side : {10.3, 20.3, 40.3}) {
        LatticeParameters p;
        p.type = GetParam();
        p.region = LatticeRegion{Box(side, side), side};
        const Packing bed = fill_lattice(p);
        const double porosity =
            1.0 - static_cast<double>(bed.size()) * pi / 6.0 / (side * side * side);
        const double gap = porosity - cell.porosity;
        EXPECT_GT(gap, 0.0) << "a finite box is looser";
        EXPECT_LT(gap, 4.0 / side) << to_string(GetParam()) << " side " << side;
        EXPECT_LT(gap, previous_gap);
        previous_gap = gap;
    }
    EXPECT_LT(previous_gap, 0.1);
}

INSTANTIATE_TEST_SUITE_P(Types, EveryLattice,
                         ::testing::Values(LatticeType::diamond, LatticeType::sc, LatticeType::bcc,
                                           LatticeType::fcc, LatticeType::hcp),
                         [](const auto& test) { return to_string(test.param); });

TEST(Lattice, WholeBallsStayInsideTheCylinderAndTouchingOnesAreKept) {
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.region =
        LatticeRegion{Cylinder(0.5 * 5.0), 4.0}; // radius 2.5: centres up to 2.0 from the axis
    const Packing bed = fill_lattice(p);
    double widest = 0.0;
    for (const Vec3& c : bed.centers) {
        widest = std::max(widest, std::hypot(c.x, c.y));
        EXPECT_GE(c.z, 0.5 - 1e-12);
        EXPECT_LE(c.z, 3.5 + 1e-12);
    }
    EXPECT_NEAR(widest, 2.0, 1e-12); // (2, 0) and (0, 2) touch the wall exactly
    // Layers z = 0.5 .. 3.5 (4), each the integer points with x^2 + y^2 <= 4: 13 of them.
    EXPECT_EQ(bed.size(), 4u * 13u);
}

TEST(Lattice, CentresOptionKeepsBallsCutByTheWalls) {
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.region = LatticeRegion{Box(3.0, 3.0), 3.0};
    p.origin = Vec3{0.0, 0.0, 0.0};
    EXPECT_EQ(fill_lattice(p).size(), 8u); // 1 and 2 along each axis: whole balls
    p.keep = LatticeKeep::centres;
    EXPECT_EQ(fill_lattice(p).size(), 64u); // 0 to 3 along each axis
}

TEST(Lattice, ACellTwoBallsWideCountsBothCopiesOfANeighbour) {
    // Simple cubic in periodic:2,2,2 (2 x 2 x 2 balls): each ball touches its x neighbour on
    // both sides (d = 1 either way), its y neighbour likewise, and the one ball above or below
    // it: 5 contacts; in periodic:3,3,2 the same 5 through three distinct neighbours a side.
    for (const double width : {2.0, 3.0}) {
        LatticeParameters p;
        p.type = LatticeType::sc;
        p.region = LatticeRegion{Periodic(width, width), 2.0};
        p.origin = Vec3{0.5, 0.5, 0.5};
        const Packing bed = fill_lattice(p);
        ASSERT_EQ(bed.size(), static_cast<std::size_t>(width * width * 2.0));
        const LatticeContacts contacts = lattice_contacts(bed, Periodic(width, width));
        EXPECT_NEAR(contacts.closest, 1.0, 1e-12);
        for (std::size_t i = 0; i < bed.size(); ++i)
            EXPECT_EQ(contacts.contacts[i], 5u) << "width " << width << ", ball " << i;
    }
}

TEST(Lattice, RotatedLatticesKeepTheirContactsAndStayInside) {
    LatticeParameters p;
    p.type = LatticeType::diamond;
    p.region = LatticeRegion{Box(9.0, 9.0), 9.0};
    p.origin = Vec3{4.5, 4.5, 4.5};
    p.rotations = {{'z', 30.0}, {'x', 20.0}};
    const Packing bed = fill_lattice(p);
    ASSERT_GT(bed.size(), 200u);
    const LatticeContacts contacts = lattice_contacts(bed);
    EXPECT_NEAR(contacts.closest, 1.0, 1e-12);
    std::size_t interior = 0;
    for (std::size_t i = 0; i < bed.size(); ++i) {
        const Vec3 c = bed.centers[i];
        EXPECT_GE(std::min({c.x, c.y, c.z}), 0.5 - 1e-9);
        EXPECT_LE(std::max({c.x, c.y, c.z}), 8.5 + 1e-9);
        if (std::min({c.x, c.y, c.z, 9.0 - c.x, 9.0 - c.y, 9.0 - c.z}) > 1.5) {
            ++interior;
            EXPECT_EQ(contacts.contacts[i], 4u) << "ball " << i;
        }
    }
    EXPECT_GT(interior, 20u);
    // The ball at the origin stays there; a lattice vector turns: G - A = (1,1,1)/sqrt(3) d.
    const double s = 1.0 / std::sqrt(3.0);
    const double cz = std::cos(M_PI / 6), sz = std::sin(M_PI / 6);
    const Vec3 after_z{cz * s - sz * s, sz * s + cz * s, s};
    const double cx = std::cos(M_PI / 9), sx = std::sin(M_PI / 9);
    const Vec3 expected = Vec3{4.5, 4.5, 4.5} + Vec3{after_z.x, cx * after_z.y - sx * after_z.z,
                                                     sx * after_z.y + cx * after_z.z};
    double nearest = 1e9;
    for (const Vec3& c : bed.centers)
        nearest = std::min(nearest, norm(c - expected));
    EXPECT_LT(nearest, 1e-12);
}

TEST(Lattice, AQuarterTurnMapsTheCubicLatticesOntoThemselves) {
    for (const LatticeType type : {LatticeType::sc, LatticeType::bcc, LatticeType::fcc}) {
        LatticeParameters p;
        p.type = type;
        p.region = LatticeRegion{Box(7.3, 7.3), 7.3};
        p.origin = Vec3{3.65, 3.65, 3.65}; // the box centre: the turn maps the box onto itself
        const std::size_t plain = fill_lattice(p).size();
        for (const char axis : {'x', 'y', 'z'}) {
            p.rotations = {{axis, 90.0}};
            EXPECT_EQ(fill_lattice(p).size(), plain) << to_string(type) << " " << axis;
        }
    }
}

TEST(Lattice, BoxOfWholeCellsWithCutBallsHasTheLatticesPorosity) {
    // Centres kept from a lattice point at the corner of a box of whole cells: the pieces of
    // the balls cut by the walls add up to exactly the cells' share, so the porosity measured
    // in the box is the lattice's (exact volumes of balls cut by faces, edges and corners).
    for (const LatticeType type :
         {LatticeType::sc, LatticeType::bcc, LatticeType::fcc, LatticeType::diamond}) {
        const UnitCell cell = unit_cell(type);
        LatticeParameters p;
        p.type = type;
        p.diameter = 2.0;
        const Vec3 size = cell.edges * (3.0 * p.diameter);
        p.region = LatticeRegion{Box(size.x, size.y), size.z};
        p.origin = Vec3{0.0, 0.0, 0.0};
        p.keep = LatticeKeep::centres;
        const auto summary = lattice_summary(p, fill_lattice(p));
        EXPECT_NEAR(summary["porosity_region"].get<double>(), cell.porosity, 1e-10)
            << to_string(type);
    }
}

/// \return the message fill_lattice refuses `p` with, or "accepted".
std::string message_of(const LatticeParameters& p) {
    try {
        fill_lattice(p);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

TEST(Lattice, BadParametersNameTheValue) {
    LatticeParameters p;
    p.region = LatticeRegion{Box(10.0, -1.0), 10.0};
    try {
        fill_lattice(p);
        FAIL() << "a negative box side was accepted";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--region box:10,-1,10 is not allowed; allowed: three lengths > 0 "
                               "and at most 1e+15");
    }
    // The real limit, not "> 0" alone.
    p.region = LatticeRegion{Box(1e16, 10.0), 10.0};
    EXPECT_EQ(message_of(p), "--region box:1e+16,10,10 is not allowed; allowed: three lengths > 0 "
                             "and at most 1e+15");
    p.region = LatticeRegion{Cylinder(0.5 * 10.0), 2e15};
    EXPECT_EQ(message_of(p),
              "--region cylinder:10,2000000000000000 is not allowed; allowed: diameter and "
              "height > 0 and at most 1e+15");
    p.region = LatticeRegion{Box(1e4, 1e4), 1e4};
    p.diameter = 1.0;
    EXPECT_THROW(fill_lattice(p), InvalidInput); // about 3e11 balls
    p.region = LatticeRegion{Cylinder(0.5 * 10.0), 10.0};
    p.diameter = 0.0;
    EXPECT_THROW(fill_lattice(p), InvalidInput);
}

TEST(Lattice, FarOriginIsRefusedNotLoopedOver) {
    // At x = 1e18 a double loop counter stopped changing (i + 1 == i): the fill never ended.
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.origin = Vec3{1e18, 0.0, 0.0};
    EXPECT_EQ(message_of(p), "--origin 1e+18,0,0 is not allowed (1e+18 ball diameters from the "
                             "region: the positions would lose their precision); allowed: within "
                             "1e+06 ball diameters of the region");
    EXPECT_THROW(p.validate(), InvalidInput); // the command line refuses it before any output
    // Within the limit the lattice is the same, to the bit, as one through a nearer origin a
    // whole number of cells away.
    p.origin = Vec3{0.5 - 1e5, 0.5, 0.5 + 1e5};
    const Packing far = fill_lattice(p);
    p.origin.reset(); // (d/2, d/2, d/2)
    const Packing near = fill_lattice(p);
    ASSERT_EQ(far.size(), 1000u);
    ASSERT_EQ(far.size(), near.size());
    for (std::size_t i = 0; i < far.size(); ++i) {
        EXPECT_EQ(far.centers[i].x, near.centers[i].x);
        EXPECT_EQ(far.centers[i].y, near.centers[i].y);
        EXPECT_EQ(far.centers[i].z, near.centers[i].z);
    }
}

TEST(Lattice, LongThinRegionIsRefusedByTheCellsItSpans) {
    // 1e11 x 0.001 x 0.001 holds about 5e4 balls' volume, so the volume check let it through,
    // and the fill then visited about 1e12 cells.
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.keep = LatticeKeep::centres;
    p.region = LatticeRegion{Box(1e11, 0.001), 0.001};
    EXPECT_EQ(message_of(p),
              "--region box:100000000000,0.001,0.001 is not allowed with sc balls of diameter 1: "
              "filling it would try 1.6e+12 ball positions (1e+11 x 4 x 4 cells, 1 per cell); "
              "allowed: at most 1e+09 (a larger diameter or a smaller region)");
    // The same thin region at a length the limit allows: one row of balls, centres at x = k + 1/2.
    p.region = LatticeRegion{Box(1e5, 1.0), 1.0};
    const Packing row = fill_lattice(p);
    ASSERT_EQ(row.size(), 100000u);
    EXPECT_EQ(row.centers.back().x, 99999.5);
    EXPECT_EQ(row.centers.back().z, 0.5);
}

} // namespace
} // namespace packbed
