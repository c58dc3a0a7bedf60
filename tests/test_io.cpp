// Output files: round-trip CSV, a VTU that is well-formed.
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
