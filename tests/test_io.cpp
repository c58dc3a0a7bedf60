// Output files: round-trip CSV, a VTU that is well-formed.
#include <cmath>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/io.hpp"

using namespace packbed;

namespace {
Packing three_spheres() {
    Packing p;
    p.add({0.1, 0.2, 0.30000000000000004}, 0.5);
    p.add({-1.0 / 3.0, 2e-17, 1.5}, 0.5);
    p.add({1e10, -7.25, 123.456}, 0.25);
    return p;
}

} // namespace

TEST(ParticlesCsv, HeaderAndRoundTripPrecision) {
    const Packing p = three_spheres();
    std::istringstream in(particles_csv(p));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "x,y,z,r");
    for (std::size_t i = 0; i < p.size(); ++i) {
        ASSERT_TRUE(std::getline(in, line));
        std::istringstream row(line);
        double v[4];
        char comma;
        row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
        EXPECT_EQ(v[0], p.centers[i].x); // exact: round trip
        EXPECT_EQ(v[1], p.centers[i].y);
        EXPECT_EQ(v[2], p.centers[i].z);
        EXPECT_EQ(v[3], p.radii[i]);
    }
    EXPECT_FALSE(std::getline(in, line));
}

TEST(ParticlesVtu, CountsAndArrays) {
    const std::string vtu = particles_vtu(three_spheres());
    EXPECT_NE(vtu.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
    EXPECT_NE(vtu.find("NumberOfPoints=\"3\" NumberOfCells=\"3\""), std::string::npos);
    EXPECT_NE(vtu.find("Name=\"radius\""), std::string::npos);
    EXPECT_NE(vtu.find("\n0.25\n"), std::string::npos);
    EXPECT_NE(vtu.find("10000000000 -7.25 123.456\n"), std::string::npos);
    // Balanced tags: as many closing DataArray tags as opening ones (6 arrays).
    std::size_t open = 0, close = 0;
    for (std::size_t at = 0; (at = vtu.find("<DataArray", at)) != std::string::npos; ++at)
        ++open;
    for (std::size_t at = 0; (at = vtu.find("</DataArray>", at)) != std::string::npos; ++at)
        ++close;
    EXPECT_EQ(open, 6u);
    EXPECT_EQ(close, 6u);
}

TEST(ContainerBox, HoldsTheContainerWithTheStatedMargin) {
    // m = max(Dp / 2, Rt / 100): Dp / 2 for a narrow tube, Rt / 100 for a wide one.
    EXPECT_EQ(container_box_margin(0.003, 0.006), 0.0015);
    EXPECT_EQ(container_box_margin(1.0, 200.0), 2.0);
    const AxisBox b = container_box(0.006, 0.02, 0.003);
    EXPECT_EQ(b.lo.x, -0.0075);
    EXPECT_EQ(b.hi.x, 0.0075);
    EXPECT_EQ(b.lo.y, -0.0075);
    EXPECT_EQ(b.hi.y, 0.0075);
    EXPECT_EQ(b.lo.z, -0.0015);
    EXPECT_EQ(b.hi.z, 0.02 + 0.0015); // H + m, as summed
    // The prism about the cylinder (at least 48 sides) reaches Rt / cos(pi / 48) < Rt + Rt / 100.
    EXPECT_LT(1.0 / std::cos(std::numbers::pi / 48), 1.01);
    EXPECT_THROW(container_box(0.0, 1.0, 1.0), InvalidInput);
    EXPECT_THROW(container_box(1.0, std::nan(""), 1.0), InvalidInput);
}

TEST(RayleighTime, MatchesTheFormulaByHand) {
    // R = 1.5 mm, rho = 2500, E = 1e7, nu = 0.25: G = 4e6, sqrt(rho / G) = 0.025,
    // t_R = pi 1.5e-3 0.025 / (0.1631 0.25 + 0.8766) = 1.1780972e-4 / 0.917375.
    EXPECT_NEAR(rayleigh_time(0.0015, 2500, 1e7, 0.25), 1.2842046e-4, 1e-11);
    // t_R grows with R and sqrt(rho / E).
    EXPECT_DOUBLE_EQ(rayleigh_time(0.003, 2500, 1e7, 0.25),
                     2 * rayleigh_time(0.0015, 2500, 1e7, 0.25));
    EXPECT_DOUBLE_EQ(rayleigh_time(0.0015, 10000, 1e7, 0.25),
                     2 * rayleigh_time(0.0015, 2500, 1e7, 0.25));
    EXPECT_THROW(rayleigh_time(0.0015, 2500, 1e7, 0.5), InvalidInput);
    EXPECT_THROW(rayleigh_time(0.0, 2500, 1e7, 0.25), InvalidInput);
    EXPECT_THROW(rayleigh_time(0.0015, -1, 1e7, 0.25), InvalidInput);
}

namespace {
DemSettle settle() {
    DemSettle s;
    s.data_file = "bed.data";
    s.wall_stl = "bed.data.wall.stl";
    s.bottom_stl = "bed.data.bottom.stl";
    s.dump = "bed.data.liggghts.dump";
    s.container = Cylinder(0.006);
    s.container_height = 0.0186;
    s.smallest_radius = 0.0015;
    s.diameter = 0.003;
    s.density = 2500;
    return s;
}
} // namespace

TEST(SettleInput, NamesTheFilesAndTheTimeStep) {
    const std::string lig = liggghts_settle_input(settle());
    EXPECT_NE(lig.find("read_data       bed.data\n"), std::string::npos) << lig;
    EXPECT_NE(lig.find("fix             side all mesh/surface file bed.data.wall.stl type 1\n"),
              std::string::npos);
    EXPECT_NE(lig.find("fix             floor all mesh/surface file bed.data.bottom.stl type 1\n"),
              std::string::npos);
    EXPECT_NE(lig.find("meshes side floor"), std::string::npos);
    EXPECT_NE(lig.find("t_R = 0.00012842 s,\n#   dt = 2.56841e-05 s; 2000 steps = 0.0513682 s"),
              std::string::npos)
        << lig;
    EXPECT_NE(lig.find("variable        dt equal 0.2*v_rayleigh\n"), std::string::npos);
    EXPECT_NE(
        lig.find("dump            settle all custom 2000 bed.data.liggghts.dump id type x y z "
                 "radius\n"),
        std::string::npos);
    EXPECT_NE(lig.find("run             2000\n"), std::string::npos);
    const std::string lmp = lammps_settle_input(settle());
    EXPECT_NE(lmp.find("region          container cylinder z 0 0 0.006 0 0.0186 side in open 1 "
                       "open 2 units box\n"),
              std::string::npos)
        << lmp;
    EXPECT_NE(lmp.find("zplane 0.0 NULL\n"), std::string::npos);
    EXPECT_EQ(lmp.find("mesh/surface"), std::string::npos);
    EXPECT_NE(lmp.find("neighbor        0.00030000000000000003 bin\n"), std::string::npos);
}

TEST(SettleInput, RefusesWhatTheProgramsCannotRead) {
    DemSettle s = settle();
    s.data_file = "my bed.data"; // a blank splits the word
    EXPECT_THROW(lammps_settle_input(s), InvalidInput);
    s = settle();
    s.wall_stl = "${x}.stl";
    EXPECT_THROW(liggghts_settle_input(s), InvalidInput);
    s = settle();
    s.material.restitution = 0.0;
    EXPECT_THROW(lammps_settle_input(s), InvalidInput);
    s = settle();
    s.material.poisson_ratio = 0.5;
    EXPECT_THROW(lammps_settle_input(s), InvalidInput);
    s = settle();
    s.steps = 0;
    EXPECT_THROW(liggghts_settle_input(s), InvalidInput);
}

TEST(LammpsData, NotesAreCommentLinesAndHeaderLinesFitTheReaders) {
    Packing p;
    p.add({0.5, 0.5, 0.5}, 0.5);
    const AxisBox box{{0, 0, 0}, {1, 1, 1}};
    const std::string plain = "1 spheres (test)\n\n1 atoms\n1 atom types\n\n0 1 xlo xhi\n0 1 ylo "
                              "yhi\n0 1 zlo zhi\n\nAtoms # sphere\n\n1 1 1 2500 0.5 0.5 0.5\n";
    EXPECT_EQ(lammps_data(p, 2500, box, "1 spheres (test)"), plain); // no notes: as before
    const std::string noted = lammps_data(p, 2500, box, "1 spheres (test)", {"box: given"});
    EXPECT_EQ(noted, "1 spheres (test)\n# box: given" + plain.substr(16));
    EXPECT_NO_THROW(lammps_data(p, 2500, box, std::string(max_data_header_line, 'x')));
    EXPECT_THROW(lammps_data(p, 2500, box, std::string(max_data_header_line + 1, 'x')),
                 InvalidInput);
    EXPECT_THROW(lammps_data(p, 2500, box, "t", {std::string(max_data_header_line, 'x')}),
                 InvalidInput); // "# " + 250
    EXPECT_THROW(lammps_data(p, 2500, box, "t", {"two\nlines"}), InvalidInput);
}

// A bed in a box. The data file's box holds the box with the same margin rule (its
// depth, half the narrower width, for Rt), and the settle inputs name its four faces.
TEST(ContainerBox, HoldsABoxWithTheStatedMargin) {
    // Box [0, 4] x [0, 3], Dp = 1: m = max(0.5, 1.5 / 100) = 0.5.
    const AxisBox b = container_box(Container(Box(4.0, 3.0)), 5.0, 1.0);
    EXPECT_EQ(b.lo.x, -0.5);
    EXPECT_EQ(b.hi.x, 4.5);
    EXPECT_EQ(b.lo.y, -0.5);
    EXPECT_EQ(b.hi.y, 3.5);
    EXPECT_EQ(b.lo.z, -0.5);
    EXPECT_EQ(b.hi.z, 5.5);
    // A wide box off the origin, [-100, 300] x [0, 500]: depth 200, m = 2 > Dp / 2.
    const AxisBox wide = container_box(Container(Box(-100.0, 300.0, 0.0, 500.0)), 10.0, 1.0);
    EXPECT_EQ(wide.lo.x, -102.0);
    EXPECT_EQ(wide.hi.x, 302.0);
    EXPECT_EQ(wide.lo.y, -2.0);
    EXPECT_EQ(wide.hi.y, 502.0);
    EXPECT_EQ(wide.lo.z, -2.0);
    EXPECT_EQ(wide.hi.z, 12.0);
    // A cylinder through Container: the same bits as before.
    const AxisBox old = container_box(0.006, 0.02, 0.003);
    const AxisBox now = container_box(Container(Cylinder(0.006)), 0.02, 0.003);
    EXPECT_EQ(now.lo, old.lo);
    EXPECT_EQ(now.hi, old.hi);
    EXPECT_THROW(container_box(Container(Box(0.0, 1.0)), 1.0, 1.0), InvalidInput);
    EXPECT_THROW(container_box(Container(Box(1.0, 1.0)), 0.0, 1.0), InvalidInput);
}

TEST(SettleInput, ABoxIsABlockRegionForLammpsAndItsFacesForLiggghts) {
    DemSettle s = settle();
    s.container = Box(0.012, 0.009);
    const std::string lmp = lammps_settle_input(s);
    EXPECT_NE(lmp.find("region          container block 0 0.012 0 0.009 0 0.0186 side in open 5 "
                       "open 6 units box\n"
                       "fix             side all wall/gran/region granular "),
              std::string::npos)
        << lmp;
    EXPECT_NE(lmp.find("its four sides as a block region open at the floor and the top"),
              std::string::npos);
    EXPECT_EQ(lmp.find("cylinder"), std::string::npos);
    EXPECT_NE(lmp.find("the container is the box x in [0, 0.012], y in\n# [0, 0.009] from the "
                       "floor z = 0 to z = 0.0186, and the data file's box\n# holds it "
                       "(docs/dem.md).\n"),
              std::string::npos)
        << lmp;
    const std::string lig = liggghts_settle_input(s);
    EXPECT_NE(lig.find("# The container from packbed's STL: its side (the box's four faces) and "
                       "floor.\n"
                       "fix             side all mesh/surface file bed.data.wall.stl type 1\n"),
              std::string::npos)
        << lig;
    EXPECT_EQ(lig.find("cylinder"), std::string::npos);
    // The cylinder's head, word for word as earlier versions wrote it.
    EXPECT_NE(lammps_settle_input(settle()).find(
                  "# Lengths as in bed.data with units si (metres); the container is the "
                  "cylinder of radius\n# 0.006 about the z axis from the floor z = 0 to z = "
                  "0.0186, and the data file's\n# box holds it (docs/dem.md).\n"
                  "# Material:"),
              std::string::npos);
    s.container = Cylinder(0.0);
    EXPECT_THROW(lammps_settle_input(s), InvalidInput);
}
