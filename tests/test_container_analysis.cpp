// The analysis in every container: the wall law, inside test and distances of the
// annulus, the box and the periodic cell against hand-computed cases; exact volumes of spheres
// cut by the rod, a box face and a periodic side; the annulus' two wall profiles; a periodic
// lattice (void fraction and contacts by the minimum image); summary.json round trips; and the
// command line's refusal of a sphere outside an annulus.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "packbed/analysis.hpp"
#include "packbed/analysis_files.hpp"
#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/json_text.hpp"
#include "packbed/read.hpp"

#include "run_packbed.hpp"

using namespace packbed;
namespace fs = std::filesystem;
constexpr double pi = std::numbers::pi;

namespace {

/// The wall contacts of a sphere as (overlap, push) pairs, in the order the container gives.
std::vector<std::pair<double, Vec3>> contacts_of(const Container& c, const Vec3& p, double r) {
    std::vector<std::pair<double, Vec3>> out;
    c.wall_contacts(p, r, [&](double o, const Vec3& push) { out.emplace_back(o, push); });
    return out;
}

void expect_vec(const Vec3& a, const Vec3& b) {
    EXPECT_NEAR(a.x, b.x, 1e-15);
    EXPECT_NEAR(a.y, b.y, 1e-15);
    EXPECT_NEAR(a.z, b.z, 1e-15);
}

/// A simple cubic lattice of spacing 1 (spheres of diameter 1) filling the periodic cell
/// [0, n) x [0, n), `layers` layers from the floor.
Packing cubic_lattice(int n, int layers) {
    Packing p;
    for (int k = 0; k < layers; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                p.add({i + 0.5, j + 0.5, k + 0.5}, 0.5);
    return p;
}

using packbed::test::slurp;

fs::path scratch(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path d = fs::temp_directory_path() / "packbed-test-container-analysis" /
                       (std::string(info->test_suite_name()) + "." + info->name()) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

struct Outcome {
    int status = -1;
    std::string out;
    std::string err;
};

/// Run `packbed ARGS` with stdin closed; capture both streams.
Outcome run_packbed(const std::string& args) {
    const fs::path d = scratch("streams");
    const std::string cmd = std::string("env -u CI ") + PACKBED_EXE + " " + args + " >" +
                            (d / "out").string() + " 2>" + (d / "err").string() + " </dev/null";
    const int raw = std::system(cmd.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(d / "out"), slurp(d / "err")};
}

} // namespace

TEST(ContainerWalls, AnnulusWallLawInsideAndDistances) {
    const Container a = Annulus(2.0, 0.5);
    // Pressed into the tube by 1.8 + 0.3 - 2 = 0.1, pushed towards the axis.
    const auto outer = contacts_of(a, {1.8, 0.0, 1.0}, 0.3);
    ASSERT_EQ(outer.size(), 1u);
    EXPECT_NEAR(outer[0].first, 0.1, 1e-15);
    expect_vec(outer[0].second, {-1.0, 0.0, 0.0});
    // Pressed onto the rod by 0.5 + 0.3 - 0.6 = 0.2, pushed away from the axis (along -y here).
    const auto inner = contacts_of(a, {0.0, -0.6, 1.0}, 0.3);
    ASSERT_EQ(inner.size(), 1u);
    EXPECT_NEAR(inner[0].first, 0.2, 1e-15);
    expect_vec(inner[0].second, {0.0, -1.0, 0.0});
    EXPECT_TRUE(contacts_of(a, {1.2, 0.0, 1.0}, 0.3).empty());
    EXPECT_FALSE(a.contains({0.4, 0.0, 1.0})); // in the rod
    EXPECT_TRUE(a.contains({1.0, 0.0, 1.0}));
    EXPECT_FALSE(a.contains({2.1, 0.0, 1.0})); // beyond the tube
    EXPECT_FALSE(a.contains({1.0, 0.0, -0.1}));
    // Distances: from the nearer wall, and from each.
    EXPECT_DOUBLE_EQ(a.wall_distance({1.5, 0.0, 0.0}), 0.5);
    EXPECT_NEAR(a.wall_distance({0.0, 0.8, 0.0}), 0.3, 1e-15);
    ASSERT_EQ(a.profile_walls().size(), 2u);
    EXPECT_EQ(a.profile_walls()[0], "outer");
    EXPECT_EQ(a.profile_walls()[1], "inner");
    EXPECT_DOUBLE_EQ(a.wall_distance_from(0, {0.8, 0.0, 0.0}), 1.2);
    EXPECT_NEAR(a.wall_distance_from(1, {0.8, 0.0, 0.0}), 0.3, 1e-15);
    EXPECT_EQ(a.nearest_wall({0.8, 0.0, 0.0}), 1u);
    EXPECT_EQ(a.nearest_wall({1.5, 0.0, 0.0}), 0u);
    EXPECT_EQ(a.nearest_wall({1.25, 0.0, 0.0}), 0u); // the middle goes with the tube
    // Each wall's part, up to the middle 1.25: areas pi (2^2 - 1.25^2) and pi (1.25^2 - 0.5^2).
    EXPECT_NEAR(a.shell_area_from(0, 0.0, 10.0, 0.0, 1.0), pi * (4.0 - 1.5625), 1e-14);
    EXPECT_NEAR(a.shell_area_from(1, 0.0, 10.0, 0.0, 1.0), pi * (1.5625 - 0.25), 1e-14);
    EXPECT_NEAR(a.shell_area_from(0, 0.25, 0.5, 0.0, 1.0), pi * (1.75 * 1.75 - 1.5 * 1.5), 1e-14);
    EXPECT_DOUBLE_EQ(a.profile_position_from(0, 0.25), 1.75);
    EXPECT_DOUBLE_EQ(a.profile_position_from(1, 0.25), 0.75);
    // Sticking out: into the rod by 0.5 - (0.6 - 0.3) = 0.2.
    EXPECT_NEAR(a.sticks_out({0.6, 0.0, 1.0}, 0.3), 0.2, 1e-15);
    EXPECT_LE(a.sticks_out({1.0, 0.0, 1.0}, 0.3), 0.0);
}

TEST(ContainerWalls, BoxCornerPressesTwoFaces) {
    const Container b = Box(0.0, 2.0, 0.0, 3.0);
    // 0.1 from x = 0 and 0.05 from y = 3, radius 0.2: overlaps 0.1 and 0.15.
    const auto c = contacts_of(b, {0.1, 2.95, 1.0}, 0.2);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_NEAR(c[0].first, 0.1, 1e-15);
    expect_vec(c[0].second, {1.0, 0.0, 0.0});
    EXPECT_NEAR(c[1].first, 0.15, 1e-15);
    expect_vec(c[1].second, {0.0, -1.0, 0.0});
    EXPECT_TRUE(b.contains({2.0, 3.0, 0.0}));
    EXPECT_FALSE(b.contains({2.01, 1.0, 0.0}));
    EXPECT_DOUBLE_EQ(b.wall_distance({0.5, 1.0, 0.0}), 0.5);
    ASSERT_EQ(b.profile_walls().size(), 1u);
    EXPECT_EQ(b.profile_walls()[0], "wall");
    EXPECT_DOUBLE_EQ(b.wall_distance_from(0, {0.5, 1.0, 0.0}), 0.5);
    EXPECT_DOUBLE_EQ(b.shell_area_from(0, 0.0, 0.5, 0.0, 1.0), 6.0 - 1.0 * 2.0);
    EXPECT_NEAR(b.sticks_out({0.1, 1.0, 1.0}, 0.3), 0.2, 1e-15);
}

TEST(ContainerWalls, PeriodicCellHasNoWall) {
    const Container p = Periodic(8.0, 6.0);
    EXPECT_TRUE(contacts_of(p, {0.0, 0.0, 1.0}, 0.5).empty());
    EXPECT_TRUE(p.contains({-3.0, 100.0, 0.0}));
    EXPECT_FALSE(p.contains({1.0, 1.0, -0.5}));
    EXPECT_TRUE(std::isinf(p.wall_distance({1.0, 1.0, 1.0})));
    EXPECT_TRUE(p.profile_walls().empty());
    // The minimum image: 7.5 apart in x is 0.5 the other way.
    const Periods cell = *p.periods();
    expect_vec(cell.separation({7.75, 1.0, 0.0}, {0.25, 1.0, 0.0}), {0.5, 0.0, 0.0});
    expect_vec(cell.wrapped({-0.5, 6.5, 2.0}), {7.5, 0.5, 2.0});
    // "Sticks out": the centre outside [0, 8] x [0, 6], the radius not counted.
    EXPECT_EQ(p.sticks_out({0.0, 3.0, 1.0}, 0.5), 0.0);
    EXPECT_DOUBLE_EQ(p.sticks_out({-0.25, 3.0, 1.0}, 0.5), 0.25);
    EXPECT_DOUBLE_EQ(p.sticks_out({1.0, 6.5, 1.0}, 0.1), 0.5);
}

TEST(ContainerVolumes, SphereThroughTheRodKeepsTheClosedForm) {
    // A sphere of radius r on the axis, a rod of radius a < r through it: 4/3 pi (r^2 -
    // a^2)^(3/2) (the sphere less the rod's cylinder and its two caps).
    const double r = 1.0, a = 0.5;
    const Container annulus = Annulus(3.0, a);
    const double expected = 4.0 / 3.0 * pi * std::pow(r * r - a * a, 1.5);
    EXPECT_NEAR(annulus.sphere_volume({0.0, 0.0, 5.0}, r, 0.0, 10.0), expected, 1e-9 * expected);
    EXPECT_NEAR(annulus.ball_volume({0.0, 0.0, 5.0}, r, 0.0, 10.0), expected, 1e-8 * expected);
}

TEST(ContainerVolumes, SphereOnABoxFaceIsHalf) {
    const Container box = Box(4.0, 4.0);
    const double half = 2.0 / 3.0 * pi;
    EXPECT_NEAR(box.sphere_volume({0.0, 2.0, 2.0}, 1.0, 0.0, 10.0), half, 1e-12);
    EXPECT_NEAR(box.sphere_volume({2.0, 4.0, 2.0}, 1.0, 0.0, 10.0), half, 1e-12);
    EXPECT_NEAR(box.sphere_volume({0.0, 0.0, 2.0}, 1.0, 0.0, 10.0), half / 2.0, 1e-12); // corner
}

TEST(ContainerVolumes, SphereCutByAPeriodicSideIsWhole) {
    const Container cell = Periodic(4.0, 4.0);
    const double whole = 4.0 / 3.0 * pi;
    EXPECT_NEAR(cell.sphere_volume({0.0, 0.0, 2.0}, 1.0, 0.0, 10.0), whole, 1e-12);
    EXPECT_NEAR(cell.sphere_volume({3.9, 2.0, 2.0}, 1.0, 0.0, 10.0), whole, 1e-12);
    // Cut by the plane z = 2 only: a half.
    EXPECT_NEAR(cell.sphere_volume({0.0, 0.0, 2.0}, 1.0, 0.0, 2.0), whole / 2.0, 1e-12);
}

TEST(ContainerAnalysis, AnnulusMeasuresEachWallOnItsOwn) {
    // R = 4, Ri = 1 (middle 2.5, depth 1.5); spheres of radius 0.5 on the floor: A touches
    // the tube (rho 3.5), B the rod (rho 1.5).
    const Container annulus = Annulus(4.0, 1.0);
    Packing p;
    p.add({3.5, 0.0, 0.5}, 0.5);
    p.add({-1.5, 0.0, 0.5}, 0.5);
    AnalysisOptions o;
    o.band = Band{0.0, 1.0};
    o.shell_width = 0.5;
    o.centre_bin = 0.5;
    const BedAnalysis a = analyze_bed(p, annulus, o);
    ASSERT_EQ(a.walls.size(), 2u);
    EXPECT_EQ(a.walls[0].name, "outer");
    EXPECT_EQ(a.walls[1].name, "inner");
    EXPECT_TRUE(a.radial_void_fraction.empty()); // no single "nearest wall" profile
    const double sphere = pi / 6.0;
    for (std::size_t w = 0; w < 2; ++w) {
        const auto& e = a.walls[w].void_fraction;
        ASSERT_EQ(e.size(), 3u) << w; // [0, 0.5], [0.5, 1], [1, 1.5]
        // Each wall's shells hold exactly its own sphere, and nothing lies in the third.
        double solid = 0.0;
        for (std::size_t k = 0; k < e.size(); ++k)
            solid += (1.0 - e[k].value) * annulus.shell_area_from(w, e[k].low, e[k].high, 0.0, 1.0);
        EXPECT_NEAR(solid, sphere, 1e-12) << w;
        EXPECT_DOUBLE_EQ(e[2].value, 1.0) << w;
        EXPECT_DOUBLE_EQ(e[2].high, 1.5);
        EXPECT_LT(e[0].value, 1.0);
        EXPECT_LT(e[1].value, 1.0);
        // Centres: one per wall, at 0.5 from it (bin [0.5, 1)), over the mean density
        // 2 / (pi (16 - 1)): outer shell area pi (3.5^2 - 3^2), inner pi (2^2 - 1.5^2).
        const auto& c = a.walls[w].centre_distribution;
        ASSERT_EQ(c.size(), 3u);
        EXPECT_EQ(c[0].value, 0.0);
        EXPECT_NEAR(c[1].value, w == 0 ? 15.0 / (2.0 * 3.25) : 15.0 / (2.0 * 1.75), 1e-12);
        EXPECT_EQ(c[2].value, 0.0);
        EXPECT_EQ(a.walls[w].wall_contacts, 1u);
        EXPECT_EQ(a.walls[w].wall_contacts_in_band, 1u);
    }
    // The tube's shells against the same sphere alone: the inner sphere adds nothing there.
    Packing only_a;
    only_a.add({3.5, 0.0, 0.5}, 0.5);
    only_a.add({-1.5, 0.0, 0.5}, 0.5);
    only_a.centers[1] = {0.0, 1.5, 0.5}; // moved round the rod: the tube's profile unchanged
    const BedAnalysis b = analyze_bed(only_a, annulus, o);
    for (std::size_t k = 0; k < 3; ++k)
        EXPECT_EQ(b.walls[0].void_fraction[k].value, a.walls[0].void_fraction[k].value);
    EXPECT_EQ(a.coordination.wall_contacts, 2u);
    EXPECT_NEAR(a.void_fraction, 1.0 - 2.0 * sphere / (15.0 * pi), 1e-12);
    // The tables: each wall's, against the distance from the axis.
    const auto files = analysis_files(a, annulus);
    std::vector<std::string> names;
    for (const auto& [name, text] : files)
        names.push_back(name);
    EXPECT_EQ(names, (std::vector<std::string>{
                         "radial_void_fraction_outer.csv", "radial_centre_distribution_outer.csv",
                         "radial_void_fraction_inner.csv", "radial_centre_distribution_inner.csv",
                         "axial_void_fraction.csv", "coordination.csv", "pair_correlation.csv"}));
    // The rod's centre table: radial positions Ri + d, the rod's sphere in the second bin.
    const std::string rod_centres =
        fmt::format("radial_position,x_from_wall_d,relative_density\n1.25,0.25,0\n1.75,0.75,{}"
                    "\n2.25,1.25,0\n",
                    a.walls[1].centre_distribution[1].value);
    EXPECT_EQ(files[3].second, rod_centres);
    const nlohmann::json summary = analysis_summary(a, o);
    EXPECT_EQ(summary["walls"][0]["name"], "outer");
    EXPECT_EQ(summary["walls"][1]["wall_contacts"], 1);
    EXPECT_EQ(summary["files"][0], "radial_void_fraction_outer.csv");
}

TEST(ContainerAnalysis, PeriodicCubicLatticeByTheMinimumImage) {
    // Simple cubic, spacing 1 = the diameter, in periodic:4,4, 6 layers: the band [1, 5] (one
    // Dp from floor and top) holds the 4 middle layers whole: e = 1 - pi/6, and every sphere
    // there touches 4 neighbours in its layer (through the sides for those at the sides) and
    // 2 above and below.
    const Container cell = Periodic(4.0, 4.0);
    const Packing p = cubic_lattice(4, 6);
    const BedAnalysis a = analyze_bed(p, cell, {});
    EXPECT_DOUBLE_EQ(a.band.z_low, 1.0);
    EXPECT_DOUBLE_EQ(a.band.z_high, 5.0);
    EXPECT_NEAR(a.void_fraction, 1.0 - pi / 6.0, 1e-13);
    EXPECT_EQ(a.coordination.spheres, 64u);
    EXPECT_DOUBLE_EQ(a.coordination.mean, 6.0);
    ASSERT_EQ(a.coordination.histogram.size(), 7u);
    EXPECT_EQ(a.coordination.histogram[6], 64u);
    EXPECT_EQ(a.coordination.rattlers, 0u);
    EXPECT_EQ(a.coordination.wall_contacts, 0u);
    EXPECT_TRUE(a.walls.empty());
    EXPECT_TRUE(a.radial_void_fraction.empty());
    EXPECT_TRUE(a.centre_distribution.empty());
    // The axial profile: a layer's middle slab [k + 0.5 - 0.025, ...] is mostly solid.
    ASSERT_FALSE(a.axial_void_fraction.empty());
    // g(r): no pair closer than the spacing; pairs at 1 by the minimum image.
    double below = 0.0, at_one = 0.0;
    for (const auto& b : a.pair_correlation) {
        if (b.high < 0.99)
            below += b.value;
        if (b.low <= 1.0 && b.high > 1.0)
            at_one += b.value;
    }
    EXPECT_EQ(below, 0.0);
    EXPECT_GT(at_one, 1.0);
    // No table against a wall, and the summary says why.
    for (const auto& [name, text] : analysis_files(a, cell))
        EXPECT_EQ(name.find("radial"), std::string::npos) << name;
    const nlohmann::json summary = analysis_summary(a, {});
    EXPECT_TRUE(summary["walls"].empty());
    EXPECT_FALSE(summary.contains("wall_contacts"));
    EXPECT_TRUE(summary.contains("no_walls"));
    EXPECT_EQ(summary["files"], (nlohmann::json{"axial_void_fraction.csv", "coordination.csv",
                                                "pair_correlation.csv"}));
    // The same lattice shifted by half a period (spheres across the sides) measures the same.
    Packing shifted = p;
    for (Vec3& c : shifted.centers)
        c.x = std::fmod(c.x + 2.25, 4.0);
    const BedAnalysis s = analyze_bed(shifted, cell, {});
    EXPECT_DOUBLE_EQ(s.coordination.mean, 6.0);
    EXPECT_NEAR(s.void_fraction, 1.0 - pi / 6.0, 1e-13);
}

TEST(ContainerAnalysis, PeriodicResultsDoNotDependOnThreads) {
    const Container cell = Periodic(4.0, 4.0);
    Packing p = cubic_lattice(4, 70);          // 1 120 spheres: the parallel loops run
    for (std::size_t i = 0; i < p.size(); ++i) // break the symmetry a little
        p.centers[i].x += 1e-3 * static_cast<double>(i % 7);
    omp_set_num_threads(1);
    const BedAnalysis one = analyze_bed(p, cell, {});
    omp_set_num_threads(2);
    const BedAnalysis two = analyze_bed(p, cell, {});
    EXPECT_EQ(one.void_fraction, two.void_fraction);
    EXPECT_EQ(one.coordination.histogram, two.coordination.histogram);
    ASSERT_EQ(one.pair_correlation.size(), two.pair_correlation.size());
    for (std::size_t k = 0; k < one.pair_correlation.size(); ++k)
        EXPECT_EQ(one.pair_correlation[k].value, two.pair_correlation[k].value) << k;
    ASSERT_EQ(one.axial_void_fraction.size(), two.axial_void_fraction.size());
    for (std::size_t k = 0; k < one.axial_void_fraction.size(); ++k)
        EXPECT_EQ(one.axial_void_fraction[k].value, two.axial_void_fraction[k].value) << k;
}

TEST(ContainerAnalysis, PeriodicCellNarrowerThanTheRangeIsRefused) {
    const Packing p = cubic_lattice(4, 6);
    AnalysisOptions o;
    o.rdf_range = 5.0;
    try {
        analyze_bed(p, Periodic(4.0, 4.0), o);
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--rdf-range 5 Dp (5) is not allowed in --container "
                               "periodic:4,4; allowed: at most the smaller period, 4 (4 Dp)");
    }
}

TEST(ContainerSummary, AnnulusAndPeriodicRoundTrip) {
    for (const Container& c : {Container(Annulus(5.0, 1.25)), Container(Periodic(8.0, 6.5))}) {
        nlohmann::json json;
        json["container"] = c.summary_json();
        std::istringstream text(json.dump());
        const BedSummary s = read_bed_summary(text, "summary.json");
        ASSERT_TRUE(s.container) << c.spec();
        EXPECT_EQ(s.container->name(), c.name());
        EXPECT_EQ(s.container->spec(), c.spec());
    }
    // An inner radius not below the radius is refused, naming both.
    std::istringstream bad(
        R"({"container": {"shape": "annulus", "radius": 1, "inner_radius": 2}})");
    try {
        read_bed_summary(bad, "s.json");
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "s.json: container {\"inner_radius\":2,\"radius\":1,\"shape\":"
                               "\"annulus\"} is not allowed; allowed: annulus: radius and "
                               "inner_radius with 0 < inner_radius < radius <= 1e+15");
    }
}

TEST(ContainerCli, AnalyzeFindsTheAnnulusBesideTheFile) {
    const fs::path d = scratch("beside");
    // Two rings of spheres of diameter 1 in annulus:8,2 (R = 4, Ri = 1), three layers: 12 on
    // the tube (rho 3.5), 6 on the rod (rho 1.5).
    std::ofstream csv(d / "particles.csv");
    csv << "x,y,z,r\n";
    for (int k = 0; k < 3; ++k)
        for (const auto& [rho, count] : {std::pair{3.5, 12}, std::pair{1.5, 6}})
            for (int m = 0; m < count; ++m) {
                const double angle = 2.0 * pi * m / count;
                csv << fmt::format("{},{},{},0.5\n", rho * std::cos(angle), rho * std::sin(angle),
                                   k + 0.5);
            }
    csv.close();
    nlohmann::json summary;
    summary["container"] = Container(Annulus(4.0, 1.0)).summary_json();
    std::ofstream(d / "summary.json") << summary.dump();
    const Outcome o =
        run_packbed("analyze " + (d / "particles.csv").string() + " --out " + (d / "out").string());
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_NE(o.out.find("36 spheres touch the outer wall, 18 spheres touch the inner wall"),
              std::string::npos)
        << o.out;
    const auto written = nlohmann::json::parse(slurp(d / "out" / "summary.json"));
    EXPECT_EQ(written["container"]["shape"], "annulus");
    EXPECT_EQ(written["walls"][0]["wall_contacts_in_band"], 12);
    EXPECT_EQ(written["walls"][1]["wall_contacts_in_band"], 6);
    EXPECT_TRUE(fs::exists(d / "out" / "radial_void_fraction_inner.csv"));
    EXPECT_FALSE(fs::exists(d / "out" / "radial_void_fraction.csv"));
}

TEST(ContainerCli, AnalyzeRefusesASphereInTheRod) {
    const fs::path d = scratch("rod");
    std::ofstream(d / "bed.csv") << "x,y,z,r\n1.5,0,0.5,0.25\n0.3,0,0.5,0.25\n";
    const Outcome o = run_packbed("analyze " + (d / "bed.csv").string() +
                                  " --container annulus:4,1 --out " + (d / "out").string());
    EXPECT_EQ(o.status, 2);
    EXPECT_EQ(o.err, "packbed analyze: " + (d / "bed.csv").string() +
                         ":3: the sphere at (0.3, 0, 0.5) sticks out of the container "
                         "(annulus:4,1, floor z = 0) by 0.45; allowed: up to 0.005 "
                         "(--outside-tolerance times Dp, in the file's units)\n");
    EXPECT_FALSE(fs::exists(d / "out"));
}

TEST(ContainerCli, AnalyzeRefusesACentreOutsideThePeriodicCell) {
    const fs::path d = scratch("cell");
    std::ofstream(d / "bed.csv") << "x,y,z,r\n1,1,0.5,0.5\n4.5,1,0.5,0.5\n";
    const Outcome o = run_packbed("analyze " + (d / "bed.csv").string() +
                                  " --container periodic:4,4 --out " + (d / "out").string());
    EXPECT_EQ(o.status, 2);
    EXPECT_EQ(o.err, "packbed analyze: " + (d / "bed.csv").string() +
                         ":3: the sphere at (4.5, 1, 0.5) sticks out of the container "
                         "(periodic:4,4, floor z = 0) by 0.5; allowed: up to 0.01 "
                         "(--outside-tolerance times Dp, in the file's units)\n");
}
