// The containers' export step: the annulus and the periodic cell in the lattice regions, the
// surfaces, the OpenFOAM case, the DEM data files and settles, and the hydraulics' wall
// correction.
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/hydraulics.hpp"
#include "packbed/io.hpp"
#include "packbed/lattice.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/surface.hpp"

#include "run_packbed.hpp"

using namespace packbed;
namespace fs = std::filesystem;
constexpr double pi = std::numbers::pi;

namespace {

struct Outcome {
    int status = -1;
    std::string out;
    std::string err;
};

using packbed::test::slurp;

/// A fresh directory private to the running test.
fs::path scratch(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test = std::string(info->test_suite_name()) + "." + info->name();
    const fs::path d = fs::temp_directory_path() / "packbed-test-container-export" / test / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

/// Run `packbed ARGS` with stdin closed and CI unset; capture both streams.
Outcome run_packbed(const std::string& args) {
    const fs::path d = scratch("streams");
    const std::string cmd = std::string("env -u CI ") + PACKBED_EXE + " " + args + " >" +
                            (d / "out").string() + " 2>" + (d / "err").string() + " </dev/null";
    const int raw = std::system(cmd.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(d / "out"), slurp(d / "err")};
}

/// The spheres of a particles.csv (x, y, z, r per row).
std::vector<std::array<double, 4>> spheres_of(const fs::path& csv_path) {
    std::istringstream csv(slurp(csv_path));
    std::string row;
    std::getline(csv, row);
    std::vector<std::array<double, 4>> out;
    while (std::getline(csv, row)) {
        std::array<double, 4> v{};
        char comma = 0;
        std::istringstream(row) >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
        out.push_back(v);
    }
    return out;
}

/// The last frame of a `dump custom ... id type x y z radius`: x, y, z, radius per atom.
std::vector<std::vector<std::array<double, 4>>> dump_frames(const std::string& dump) {
    std::vector<std::vector<std::array<double, 4>>> frames;
    std::istringstream in(dump);
    std::size_t atoms = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("ITEM: NUMBER OF ATOMS", 0) == 0) {
            in >> atoms;
        } else if (line.rfind("ITEM: ATOMS id type x y z radius", 0) == 0) {
            // In the order of the atoms' ids (LAMMPS writes them in its own order).
            std::vector<std::array<double, 4>>& frame = frames.emplace_back(atoms);
            for (std::size_t k = 0; k < atoms; ++k) {
                std::size_t id = 0, type = 0;
                std::array<double, 4> s{};
                in >> id >> type >> s[0] >> s[1] >> s[2] >> s[3];
                EXPECT_TRUE(id >= 1 && id <= atoms) << id;
                if (id >= 1 && id <= atoms)
                    frame[id - 1] = s;
            }
        }
    }
    return frames;
}

std::vector<std::array<double, 4>> last_dump_frame(const std::string& dump) {
    auto frames = dump_frames(dump);
    return frames.empty() ? std::vector<std::array<double, 4>>{} : frames.back();
}

bool has_lmp() {
    return std::system("command -v lmp >/dev/null 2>&1") == 0;
}

} // namespace

// --- Surfaces --------------------------------------------------------------------------------

TEST(ContainerExport, AnnulusSolidsAreNamedClosedOutwardAndClearOfTheSpace) {
    const double R = 3.0, Ri = 1.0, H = 2.0;
    const std::vector<Solid> solids = Container(Annulus(R, Ri)).solids(0.0, H, 0.25);
    ASSERT_EQ(solids.size(), 4u);
    EXPECT_EQ(solids[0].name, "wall");
    EXPECT_EQ(solids[1].name, "rod");
    EXPECT_EQ(solids[2].name, "bottom");
    EXPECT_EQ(solids[3].name, "top");
    // sides = ceil(2 pi 3 / 0.25) = 76; the tube's corners at R / cos(pi / 76).
    const int sides = 76;
    const double corner = R / std::cos(pi / sides);
    for (const Vec3& v : solids[0].mesh.vertices)
        EXPECT_NEAR(std::hypot(v.x, v.y), corner, 1e-12);
    for (const Vec3& v : solids[1].mesh.vertices)
        EXPECT_NEAR(std::hypot(v.x, v.y), Ri, 1e-12);
    // The tube's triangles lie outside the tube: seen from above each is a triangle the axis
    // is outside of, so its nearest point to the axis is on an edge; the rod's lie inside it
    // (their vertices do, and the rod's cross-section is convex).
    const auto segment_distance = [](const Vec3& a, const Vec3& b) { // from the axis, in x, y
        const double ex = b.x - a.x, ey = b.y - a.y;
        const double t = std::clamp(-(a.x * ex + a.y * ey) / (ex * ex + ey * ey), 0.0, 1.0);
        return std::hypot(a.x + t * ex, a.y + t * ey);
    };
    for (const auto& t : solids[0].mesh.triangles) {
        const Vec3 a = solids[0].mesh.vertices[t[0]], b = solids[0].mesh.vertices[t[1]],
                   c = solids[0].mesh.vertices[t[2]];
        EXPECT_GE(
            std::min({segment_distance(a, b), segment_distance(b, c), segment_distance(c, a)}),
            R * (1.0 - 1e-12));
        const Vec3 centroid = (a + b + c) * (1.0 / 3.0);
        EXPECT_GT(dot(cross(b - a, c - a), Vec3{centroid.x, centroid.y, 0.0}), 0.0); // outward
    }
    for (const auto& t : solids[1].mesh.triangles) {
        const Vec3 a = solids[1].mesh.vertices[t[0]], b = solids[1].mesh.vertices[t[1]],
                   c = solids[1].mesh.vertices[t[2]];
        const Vec3 centroid = (a + b + c) * (1.0 / 3.0);
        EXPECT_LE(std::hypot(centroid.x, centroid.y), Ri);
        EXPECT_LT(dot(cross(b - a, c - a), centroid), 0.0); // normal towards the axis
    }
    // Closed: the four together, vertices merged by their coordinates, every edge used twice,
    // once each way; outward: the enclosed volume is the annulus' to the facets' error.
    TriangleMesh all;
    for (const Solid& s : solids)
        all.append(s.mesh);
    std::map<std::tuple<double, double, double>, std::uint32_t> ids;
    std::vector<std::uint32_t> id(all.vertices.size());
    for (std::size_t i = 0; i < all.vertices.size(); ++i) {
        const Vec3 v = all.vertices[i];
        id[i] = ids.emplace(std::tuple{v.x, v.y, v.z}, static_cast<std::uint32_t>(ids.size()))
                    .first->second;
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& t : all.triangles)
        for (int k = 0; k < 3; ++k)
            ++edges[{id[t[k]], id[t[(k + 1) % 3]]}];
    for (const auto& [edge, count] : edges) {
        EXPECT_EQ(count, 1);
        EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
    }
    const double exact = pi * (R * R - Ri * Ri) * H;
    EXPECT_NEAR(all.volume() / exact, 1.0, 3e-3);
}

TEST(ContainerExport, PeriodicCellHasOnlyAFloorAndATop) {
    const std::vector<Solid> solids = Container(Periodic(4.0, 2.0)).solids(0.0, 3.0, 1);
    ASSERT_EQ(solids.size(), 2u);
    EXPECT_EQ(solids[0].name, "bottom");
    EXPECT_EQ(solids[1].name, "top");
    EXPECT_EQ(solids[0].mesh.triangles.size(), 2u * 4u * 2u);
}

// --- OpenFOAM ----------------------------------------------------------------------------------

namespace {

/// Twelve balls of diameter 1 at z = 0.5 in the annulus R = 3, Ri = 1 (sc lattice points
/// with 1.5 <= rho <= 2.5, see the lattice test below), touching the floor and eight pairs.
Packing ring_of_balls() {
    Packing p;
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y)
            if (const int q = x * x + y * y; q >= 4 && q <= 5)
                p.add({static_cast<double>(x), static_cast<double>(y), 0.5}, 0.5);
    return p;
}

/// The spheres tessellated at icosphere level 2.
SurfaceOptions level_two() {
    SurfaceOptions o;
    o.level = 2;
    return o;
}

} // namespace

TEST(ContainerExport, OpenFoamCaseOfAnAnnulusCutsTheTubeAndTheRod) {
    const Packing packing = ring_of_balls();
    ASSERT_EQ(packing.size(), 12u);
    const SurfaceContainer container{Annulus(3.0, 1.0), 2.0};
    const Contacts caps{ContactTreatment::caps, 0.05};
    const TreatedBed bed = treat_contacts(packing, caps, container);
    const TreatmentVolumes v = treatment_volumes(packing, bed, container);
    // By hand: the annulus 8 pi x 2, twelve balls less 16 caps at the 8 contacts (planes 0.025
    // from the touching point, 0.475 from each centre) and 12 at the floor (0.45).
    const auto cap = [](double s) { return spherical_cap_volume(0.5, s); };
    const double solid = 12.0 * pi / 6.0 - 16.0 * cap(0.475) - 12.0 * cap(0.45);
    EXPECT_NEAR(v.container_volume, 16.0 * pi, 1e-12);
    EXPECT_NEAR(v.treated_solid, solid, 1e-12);
    const OpenFoamCase c = openfoam_case(bed, container, v, "caps:0.05", 1.0, level_two());
    EXPECT_NEAR(c.fluid_volume, 16.0 * pi - solid, 1e-12);
    ASSERT_EQ(c.wall.size(), 1u);
    ASSERT_EQ(c.rod.size(), 1u);
    EXPECT_EQ(c.wall[0].name, "wall");
    EXPECT_EQ(c.rod[0].name, "rod");
    const double rho = std::hypot(c.location_in_mesh.x, c.location_in_mesh.y);
    EXPECT_GT(rho, 1.0 + c.clearance - 1e-12);
    EXPECT_LT(rho, 3.0 - c.clearance + 1e-12);
    std::map<std::string, std::string> files(c.files.begin(), c.files.end());
    const std::string& snappy = files["system/snappyHexMeshDict"];
    EXPECT_NE(snappy.find("    rod.stl { type triSurfaceMesh; name rod; }\n"), std::string::npos);
    EXPECT_NE(snappy.find("        rod { level (1 1); patchInfo { type wall; } }\n"),
              std::string::npos);
    EXPECT_NE(files["system/blockMeshDict"].find(
                  "// Box around the annulus (tube radius 3, rod radius 1, height 2)"),
              std::string::npos)
        << files["system/blockMeshDict"];
    // The box one cell beyond the tube: ceil(6 / 0.25) + 2 = 26 cells across, 8 up.
    EXPECT_NE(files["system/blockMeshDict"].find("(26 26 8) simpleGrading"), std::string::npos);
}

TEST(ContainerExport, LayersAreAskedOnTheParticlesAndOnWhatSnappyHexMeshCuts) {
    const Packing packing = ring_of_balls();
    const SurfaceContainer container{Annulus(3.0, 1.0), 2.0};
    const Contacts caps{ContactTreatment::caps, 0.05};
    const TreatedBed bed = treat_contacts(packing, caps, container);
    const TreatmentVolumes v = treatment_volumes(packing, bed, container);
    const auto files_with = [&](int layers) {
        OpenFoamMeshOptions mesh;
        mesh.layers = layers;
        const OpenFoamCase c =
            openfoam_case(bed, container, v, "caps:0.05", 1.0, level_two(), mesh);
        return std::map<std::string, std::string>(c.files.begin(), c.files.end());
    };
    // None by default: the dictionary as without the option, and the creeping flow stops on
    // its residuals alone.
    auto files = files_with(0);
    EXPECT_NE(files["system/snappyHexMeshDict"].find("addLayers false;"), std::string::npos);
    EXPECT_NE(files["system/snappyHexMeshDict"].find("    layers {}\n    expansionRatio 1.0;\n"),
              std::string::npos);
    EXPECT_EQ(files["system/controlDict"].find("steadyPressureDrop"), std::string::npos);
    EXPECT_EQ(files["README.md"].find("prism layers"), std::string::npos);
    EXPECT_NE(files["system/snappyHexMeshDict"].find("featureAngle 60;"), std::string::npos);
    // Three on the particles, the tube and the rod; the run also stops on a steady pressure
    // drop, since U's residual levels off near residualControl's 1e-6 on such meshes.
    files = files_with(3);
    const std::string& snappy = files["system/snappyHexMeshDict"];
    EXPECT_NE(snappy.find("addLayers true;"), std::string::npos);
    EXPECT_NE(snappy.find("    layers\n    {\n        particles { nSurfaceLayers 3; }\n"
                          "        wall { nSurfaceLayers 3; }\n        rod { nSurfaceLayers 3; }\n"
                          "    }\n    expansionRatio 1.2;\n    finalLayerThickness 0.5;\n"),
              std::string::npos)
        << snappy;
    EXPECT_NE(snappy.find("nRelaxedIter 20;"), std::string::npos);
    // carried over every edge, thinned only at the medial axis (60 and 0.3 without layers)
    EXPECT_NE(snappy.find("featureAngle 180;"), std::string::npos);
    EXPECT_NE(snappy.find("maxThicknessToMedialRatio 1.0;"), std::string::npos);
    EXPECT_NE(files["system/controlDict"].find("steadyPressureDrop"), std::string::npos);
    EXPECT_NE(
        files["README.md"].find("- 3 prism layers asked on the particles, the wall and the rod"),
        std::string::npos)
        << files["README.md"];
    EXPECT_THROW(files_with(11), InvalidInput);
    EXPECT_THROW(files_with(-1), InvalidInput);
}

TEST(ContainerExport, OpenFoamCaseOfAPeriodicCellHasCyclicSidesAndCopies) {
    // Two balls of Dp = 1 in the cell 3 x 3, touching across the side x = 0 (centres 0.3 and
    // 2.3: 1 apart by the minimum image), both on the floor; a third in the corner x = 0,
    // y = 3, alone.
    Packing packing;
    packing.add({0.3, 1.0, 0.5}, 0.5);
    packing.add({2.3, 1.0, 0.5}, 0.5);
    packing.add({0.2, 2.9, 1.5}, 0.5);
    const SurfaceContainer cell{Periodic(3.0, 3.0), 3.0};
    const Contacts caps{ContactTreatment::caps, 0.05};
    const TreatedBed bed = treat_contacts(packing, caps, cell);
    // The pair's caps at x = -0.175 and 2.775: the middle of the gap, -0.2 (or 2.8), +- 0.025.
    ASSERT_EQ(bed.bodies[0].cuts.size(), 2u); // the pair and the floor
    EXPECT_NEAR(bed.bodies[0].cuts[0].normal.x, -1.0, 1e-15);
    EXPECT_NEAR(bed.bodies[0].cuts[0].offset, 0.175, 1e-15);
    EXPECT_NEAR(bed.bodies[1].cuts[0].normal.x, 1.0, 1e-15);
    EXPECT_NEAR(bed.bodies[1].cuts[0].offset, 2.775, 1e-15);
    EXPECT_TRUE(bed.bodies[2].cuts.empty());
    const TreatmentVolumes v = treatment_volumes(packing, bed, cell);
    const auto cap = [](double c) { return pi * c * c * (1.5 - c) / 3.0; }; // r = 0.5
    EXPECT_DOUBLE_EQ(v.container_volume, 27.0);
    EXPECT_NEAR(v.treated_solid, 3.0 * pi / 6.0 - 2.0 * cap(0.025) - 2.0 * cap(0.05), 1e-14);
    // Copies: the first across x = 0 (+3), the second none (2.3 + 0.5 < 3), the third across
    // x = 0 and y = 3 and the corner: 3 + 1 + 0 + 3 = 7 bodies, the copies' cuts moved along.
    const TreatedBed imaged = periodic_images(bed, Periodic(3.0, 3.0));
    ASSERT_EQ(imaged.bodies.size(), 7u);
    EXPECT_EQ(imaged.bodies[3].center, (Vec3{3.3, 1.0, 0.5}));
    EXPECT_NEAR(imaged.bodies[3].cuts[0].offset, 0.175 - 3.0, 1e-14); // x >= 2.825
    EXPECT_EQ(imaged.bodies[4].center, (Vec3{0.2, 2.9 - 3.0, 1.5}));
    EXPECT_EQ(imaged.bodies[5].center, (Vec3{3.2, 2.9, 1.5}));
    EXPECT_EQ(imaged.bodies[6].center, (Vec3{3.2, 2.9 - 3.0, 1.5}));
    // The case: the cell as background, its sides cyclic pairs; no wall surface.
    const OpenFoamCase c = openfoam_case(bed, cell, v, "caps:0.05", 1.0, level_two());
    EXPECT_TRUE(c.wall.empty());
    EXPECT_TRUE(c.rod.empty());
    std::map<std::string, std::string> files(c.files.begin(), c.files.end());
    const std::string& block = files["system/blockMeshDict"];
    EXPECT_NE(block.find("(12 12 12) simpleGrading"), std::string::npos) << block;
    for (const auto& [side, other, faces] :
         {std::tuple{"x_low", "x_high", "(3 0 4 7)"}, std::tuple{"x_high", "x_low", "(1 2 6 5)"},
          std::tuple{"y_low", "y_high", "(0 1 5 4)"}, std::tuple{"y_high", "y_low", "(2 3 7 6)"}})
        EXPECT_NE(block.find(fmt::format("    {}\n    {{\n        type cyclic;\n        "
                                         "neighbourPatch {};\n        faces ({});\n",
                                         side, other, faces)),
                  std::string::npos)
            << side << block;
    EXPECT_EQ(block.find("wall"), std::string::npos);
    const std::string& snappy = files["system/snappyHexMeshDict"];
    EXPECT_NE(snappy.find("maxBoundarySkewness 4;"), std::string::npos);
    EXPECT_EQ(snappy.find("wall.stl"), std::string::npos);
    EXPECT_NE(files["README.md"].find("3 particles of diameter 1 in the periodic cell x 0 to 3, "
                                      "y 0 to 3"),
              std::string::npos);
    // Layers go on the particles alone: the cyclic sides are the background's own faces.
    OpenFoamMeshOptions layered;
    layered.layers = 2;
    const OpenFoamCase l = openfoam_case(bed, cell, v, "caps:0.05", 1.0, level_two(), layered);
    std::map<std::string, std::string> lf(l.files.begin(), l.files.end());
    EXPECT_NE(lf["system/snappyHexMeshDict"].find(
                  "    layers\n    {\n        particles { nSurfaceLayers 2; }\n    }\n"),
              std::string::npos)
        << lf["system/snappyHexMeshDict"];
    EXPECT_EQ(lf["README.md"].find("and the wall"), std::string::npos);
    // The particles' surface holds the 7 bodies: 7 closed parts (Euler characteristic 2 each).
    const TriangleMesh& m = c.particles[0].mesh;
    EXPECT_EQ(static_cast<long>(m.vertices.size()) * 2 - static_cast<long>(m.triangles.size()),
              7 * 4);
    // A cell narrower than twice the largest diameter and the caps' gap is refused: in one
    // 2.05 wide, a sphere 1 from another on one side is 1.05 from its copy on the other, both
    // within the gap, and the minimum image would cap only the first. Without caps, 2.05 is
    // allowed.
    for (const double width : {1.5, 2.05})
        try {
            treat_contacts(packing, caps, SurfaceContainer{Periodic(width, 8.0), 3.0});
            FAIL() << "no exception";
        } catch (const InvalidInput& e) {
            EXPECT_EQ(std::string(e.what()),
                      fmt::format("--container periodic:{},8 is not allowed for spheres of "
                                  "diameter up to 1 with --contacts caps:0.05; allowed: periods "
                                  "at least twice the largest diameter and the caps' gap, 2.1 "
                                  "(the minimum image)",
                                  width));
        }
    EXPECT_NO_THROW(treat_contacts(packing, {ContactTreatment::none, 0.0},
                                   SurfaceContainer{Periodic(2.05, 8.0), 3.0}));
    // Enlarge and bridges are refused in a cell.
    try {
        treat_contacts(packing, {ContactTreatment::enlarge, 0.01}, cell);
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--contacts enlarge:0.01 is not allowed in the periodic cell "
                               "periodic:3,3; allowed: caps:H, shrink:F or none (the unions of "
                               "enlarge and bridges are not copied across the sides)");
    }
}

// --- DEM ---------------------------------------------------------------------------------------

namespace {

DemSettle settle_in(const Container& container) {
    DemSettle s;
    s.data_file = "bed.data";
    s.wall_stl = "bed.data.wall.stl";
    s.bottom_stl = "bed.data.bottom.stl";
    s.dump = "bed.data.lammps.dump";
    s.container = container;
    s.container_height = 0.02;
    s.smallest_radius = 0.0015;
    s.diameter = 0.003;
    s.density = 2500.0;
    return s;
}

} // namespace

TEST(ContainerExport, SettleInputsOfAnAnnulusAndAPeriodicCell) {
    const std::string ring = lammps_settle_input(settle_in(Annulus(0.012, 0.003)));
    EXPECT_NE(ring.find("boundary        f f f\n"), std::string::npos);
    EXPECT_NE(ring.find("region          tube cylinder z 0 0 0.012 0 0.02 side in open 1 open 2 "
                        "units box\n"
                        "region          rod cylinder z 0 0 0.003 0 0.02 side out open 1 open 2 "
                        "units box\n"
                        "fix             side all wall/gran/region granular hertz/material"),
              std::string::npos)
        << ring;
    EXPECT_NE(ring.find("fix             side_rod all wall/gran/region granular hertz/material "
                        "${youngs} ${restitution} ${poisson} tangential mindlin NULL 1.0 "
                        "${friction} damping tsuji region rod\n"),
              std::string::npos);
    const std::string cell = lammps_settle_input(settle_in(Periodic(0.012, 0.009)));
    EXPECT_NE(cell.find("boundary        p p f\n"), std::string::npos);
    EXPECT_EQ(cell.find("wall/gran/region"), std::string::npos);
    EXPECT_EQ(cell.find("region "), std::string::npos);
    EXPECT_NE(cell.find("fix             floor all wall/gran granular"), std::string::npos);
    const std::string lig = liggghts_settle_input(settle_in(Periodic(0.012, 0.009)));
    EXPECT_NE(lig.find("boundary        p p f\n"), std::string::npos);
    EXPECT_EQ(lig.find("mesh/surface"), std::string::npos);
    EXPECT_NE(lig.find("fix             floor all wall/gran model hertz tangential history "
                       "primitive type 1 zplane 0.0\n"),
              std::string::npos);
    // The box of the data file: the cell itself in x and y, Dp / 2 below and above in z; an
    // annulus' the box of its tube with the margin max(Dp / 2, R / 100).
    const AxisBox b = container_box(Periodic(0.012, 0.009), 0.02, 0.003);
    EXPECT_EQ(b.lo.x, 0.0);
    EXPECT_EQ(b.hi.x, 0.012);
    EXPECT_EQ(b.lo.y, 0.0);
    EXPECT_EQ(b.hi.y, 0.009);
    EXPECT_EQ(b.lo.z, -0.0015);
    EXPECT_EQ(b.hi.z, 0.02 + 0.0015);
    const AxisBox a = container_box(Annulus(2.0, 0.5), 3.0, 0.01);
    const AxisBox t = container_box(2.0, 3.0, 0.01);
    EXPECT_EQ(std::tie(a.lo.x, a.lo.y, a.lo.z, a.hi.x, a.hi.y, a.hi.z),
              std::tie(t.lo.x, t.lo.y, t.lo.z, t.hi.x, t.hi.y, t.hi.z));
    EXPECT_EQ(a.hi.x, 2.02);
}

// --- Hydraulics --------------------------------------------------------------------------------

TEST(ContainerExport, HydraulicDiameters) {
    EXPECT_EQ(*hydraulic_diameter(Cylinder(0.012)), 0.024);
    // 4 pi (R^2 - Ri^2) / (2 pi (R + Ri)) = 2 (R - Ri) = D - DI.
    EXPECT_DOUBLE_EQ(*hydraulic_diameter(Annulus(0.012, 0.004)), 0.016);
    // 4 (0.03 x 0.01) / (2 (0.03 + 0.01)) = 0.015.
    EXPECT_DOUBLE_EQ(*hydraulic_diameter(Box(0.03, 0.01)), 0.015);
    EXPECT_FALSE(hydraulic_diameter(Periodic(0.03, 0.01)).has_value());
}

// --- Lattices ----------------------------------------------------------------------------------

TEST(ContainerExport, ScLatticeInAnAnnulusKeepsTheBallsBetweenRodAndTube) {
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.diameter = 1.0;
    p.region = LatticeRegion{Annulus(0.5 * 6.0, 0.5 * 2.0), 1.0};
    const Packing packing = fill_lattice(p);
    // One layer at z = 0.5 of the integer points with 1.5 <= rho <= 2.5: (+-2, 0), (0, +-2),
    // (+-2, +-1), (+-1, +-2).
    std::set<std::pair<int, int>> by_hand;
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y)
            if (x * x + y * y >= 4 && x * x + y * y <= 5)
                by_hand.insert({x, y});
    ASSERT_EQ(by_hand.size(), 12u);
    ASSERT_EQ(packing.size(), 12u);
    for (const Vec3& c : packing.centers) {
        EXPECT_EQ(c.z, 0.5);
        EXPECT_EQ(
            by_hand.count({static_cast<int>(std::lround(c.x)), static_cast<int>(std::lround(c.y))}),
            1u);
    }
    // Centres: every point with 1 <= rho <= 3, a brute-force count over a wider square.
    p.keep = LatticeKeep::centres;
    std::size_t brute = 0;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            brute += x * x + y * y >= 1 && x * x + y * y <= 9 ? 1 : 0;
    EXPECT_EQ(fill_lattice(p).size(), brute); // 28
    EXPECT_EQ(brute, 28u);
    EXPECT_NEAR(region_volume(p.region), 8.0 * pi, 1e-12);
}

TEST(ContainerExport, FccLatticeInAPeriodicCellRepeatsAcrossIt) {
    LatticeParameters p;
    p.type = LatticeType::fcc;
    p.diameter = 1.0;
    const double period = std::sqrt(2.0);
    p.region = LatticeRegion{Periodic(2.0 * period, 2.0 * period), 2.0 * period};
    const Packing packing = fill_lattice(p);
    // Three layers (z = 0.5, 0.5 + 1/sqrt 2, 0.5 + sqrt 2) of 8 balls each.
    ASSERT_EQ(packing.size(), 24u);
    for (const Vec3& c : packing.centers) {
        EXPECT_GE(c.x, 0.0);
        EXPECT_LT(c.x, 2.0 * period);
        EXPECT_GE(c.y, 0.0);
        EXPECT_LT(c.y, 2.0 * period);
    }
    // By the minimum image: 12 contacts in the middle layer, 8 in the bottom and top ones.
    const LatticeContacts contacts =
        lattice_contacts(packing, Periodic(2.0 * period, 2.0 * period));
    std::map<std::uint32_t, int> histogram;
    for (const std::uint32_t k : contacts.contacts)
        ++histogram[k];
    EXPECT_EQ(histogram, (std::map<std::uint32_t, int>{{8, 16}, {12, 8}}));
    EXPECT_NEAR(contacts.closest, 1.0, 1e-12);
}

TEST(ContainerExport, PeriodicLatticeRefusals) {
    LatticeParameters p;
    p.type = LatticeType::fcc;
    p.region = LatticeRegion{Periodic(3.0, 3.0), 3.0};
    try {
        fill_lattice(p);
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--region periodic:3,3,3 is not allowed with the fcc lattice of "
                               "--diameter 1; allowed: LX and LY whole multiples of its periods "
                               "1.4142135623730951 (x) and 1.4142135623730951 (y), each at least "
                               "2 d, e.g. periodic:2.8284271247461903,2.8284271247461903,3");
    }
    p.region = LatticeRegion{Periodic(2.0 * std::sqrt(2.0), 2.0 * std::sqrt(2.0)), 3.0};
    p.rotations = {{'z', 10.0}};
    try {
        fill_lattice(p);
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--rotate is not allowed with --region "
                               "periodic:2.8284271247461903,2.8284271247461903,3; allowed: no "
                               "rotation (the lattice must repeat across the periodic cell)");
    }
}

// --- The command line --------------------------------------------------------------------------

TEST(ContainerExportCli, LatticeInAnAnnulusAndItsSurfaces) {
    const fs::path d = scratch("ring");
    const Outcome o =
        run_packbed("lattice --type sc --region annulus:6,2,1 -q --out " + (d / "bed").string());
    ASSERT_EQ(o.status, 0) << o.err;
    const auto s = nlohmann::json::parse(slurp(d / "bed" / "summary.json"));
    EXPECT_EQ(s["balls"], 12);
    EXPECT_EQ(s["container"]["shape"], "annulus");
    EXPECT_EQ(s["container"]["spec"], "annulus:6,2");
    EXPECT_EQ(s["region"]["inner_diameter"], 2.0);
    // 12 whole balls in pi (9 - 1) x 1: 1 - 12 (pi / 6) / (8 pi) = 3/4.
    EXPECT_NEAR(s["porosity_region"].get<double>(), 0.75, 1e-12);
    // The surface: the particles, then the tube, the rod, the floor and the top as named solids.
    const std::string csv = (d / "bed" / "particles.csv").string();
    const Outcome e =
        run_packbed("export " + csv + " --format stl-ascii -q --out " + (d / "ring.stl").string());
    ASSERT_EQ(e.status, 0) << e.err;
    std::vector<std::string> names;
    std::istringstream stl(slurp(d / "ring.stl"));
    for (std::string line; std::getline(stl, line);)
        if (line.rfind("solid ", 0) == 0)
            names.push_back(line.substr(6));
    EXPECT_EQ(names, (std::vector<std::string>{"particles", "wall", "rod", "bottom", "top"}));
    const auto report = nlohmann::json::parse(slurp(d / "ring.stl.json"));
    EXPECT_EQ(report["container"]["shape"], "annulus");
    EXPECT_EQ(report["container"]["inner_radius"], 1.0);
    // The container's volume, pi (9 - 1) x (the top 1 + 1 Dp).
    EXPECT_NEAR(report["volumes"]["container"].get<double>(), 16.0 * pi, 1e-12);
}

TEST(ContainerExportCli, ALatticeKeptByItsCentresIsAnalysedFromItsOwnFiles) {
    // Balls cut by the tube's wall (--keep centres) reach out of the region by up to their
    // radius: analyze takes the bed from its files as lattice measured it, and a container given
    // by hand still checks the balls whole.
    const fs::path d = scratch("centres");
    const Outcome l = run_packbed(
        "lattice --type sc --region cylinder:5,4 --keep centres -q --out " + (d / "bed").string());
    ASSERT_EQ(l.status, 0) << l.err;
    const auto s = nlohmann::json::parse(slurp(d / "bed" / "summary.json"));
    const std::string csv = (d / "bed" / "particles.csv").string();
    const Outcome a = run_packbed("analyze " + csv + " -q --out " + (d / "an").string());
    ASSERT_EQ(a.status, 0) << a.err;
    const auto an = nlohmann::json::parse(slurp(d / "an" / "summary.json"));
    EXPECT_EQ(an["void_fraction"], s["analysis"]["void_fraction"]);
    EXPECT_GT(an["wall_contacts"].get<double>(), 0.0);
    const Outcome given = run_packbed("analyze " + csv + " --container cylinder:5 -q --out " +
                                      (d / "given").string());
    EXPECT_EQ(given.status, 2);
    EXPECT_NE(given.err.find("sticks out of the container"), std::string::npos) << given.err;
    EXPECT_FALSE(fs::exists(d / "given"));
}

TEST(ContainerExportCli, ACellNarrowerThanTheDefaultRangeOfGOfRIsAnalysed) {
    // A simple cubic cell of period 2 d: analyze's g(r) goes to the period, as lattice's own
    // analysis does, where the default 3 d was refused; asked for, 3 d still is.
    const fs::path d = scratch("narrow");
    ASSERT_EQ(
        run_packbed("lattice --type sc --region periodic:2,2,4 -q --out " + (d / "bed").string())
            .status,
        0);
    const std::string csv = (d / "bed" / "particles.csv").string();
    const Outcome a = run_packbed("analyze " + csv + " -q --out " + (d / "an").string());
    ASSERT_EQ(a.status, 0) << a.err;
    const auto an = nlohmann::json::parse(slurp(d / "an" / "summary.json"));
    EXPECT_EQ(an["options"]["rdf_range"], 2.0);
    // the cell holds whole cubes of the lattice: its porosity, 1 - pi / 6
    EXPECT_NEAR(an["void_fraction"].get<double>(), 1.0 - pi / 6.0, 1e-12);
    const Outcome asked =
        run_packbed("analyze " + csv + " --rdf-range 3 -q --out " + (d / "asked").string());
    EXPECT_EQ(asked.status, 2);
    EXPECT_EQ(asked.err, "packbed analyze: --rdf-range 3 Dp (3) is not allowed in --container "
                         "periodic:2,2; allowed: at most the smaller period, 2 (2 Dp)\n");
}

TEST(ContainerExportCli, LatticeInAPeriodicCell) {
    const fs::path d = scratch("cell");
    const double period = std::sqrt(2.0);
    const std::string region =
        fmt::format("periodic:{},{},{}", 2.0 * period, 2.0 * period, 2.0 * period);
    const Outcome o =
        run_packbed("lattice --type fcc --region " + region + " -q --out " + (d / "bed").string());
    ASSERT_EQ(o.status, 0) << o.err;
    const auto s = nlohmann::json::parse(slurp(d / "bed" / "summary.json"));
    EXPECT_EQ(s["balls"], 24);
    EXPECT_EQ(s["container"]["shape"], "periodic");
    EXPECT_EQ(s["container"]["size"][0].get<double>(), 2.0 * period);
    EXPECT_EQ(s["periods"], nlohmann::json::array({2.0, 2.0}));
    // 24 whole balls in 8 x 2 sqrt 2: 1 - 4 pi / (16 sqrt 2).
    EXPECT_NEAR(s["porosity_region"].get<double>(), 1.0 - pi / (4.0 * period), 1e-12);
    EXPECT_NEAR(s["contacts"]["mean"].get<double>(), 224.0 / 24.0, 1e-12);

    const Outcome bad =
        run_packbed("lattice --type fcc --region periodic:3,3,3 -q --out " + (d / "bad").string());
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err,
              "packbed lattice: --region periodic:3,3,3 is not allowed with the fcc lattice of "
              "--diameter 1; allowed: LX and LY whole multiples of its periods "
              "1.4142135623730951 (x) and 1.4142135623730951 (y), each at least 2 d, "
              "e.g. periodic:2.8284271247461903,2.8284271247461903,3\n");
    EXPECT_FALSE(fs::exists(d / "bad"));

    // The data file: the cell's box, periodic in x and y; STL is refused, OpenFOAM not.
    const std::string csv = (d / "bed" / "particles.csv").string();
    const Outcome l = run_packbed("export " + csv + " -q --out " + (d / "bed.data").string());
    ASSERT_EQ(l.status, 0) << l.err;
    const std::string data = slurp(d / "bed.data");
    // z: the top layer's top, 0.5 + sqrt 2 + 0.5, plus 1 Dp (the container), plus Dp / 2.
    const double zhi = (0.5 + period) + 0.5 + 1.0 + 0.5;
    EXPECT_NE(data.find(fmt::format("\n0 {0} xlo xhi\n0 {0} ylo yhi\n-0.5 {1} zlo zhi\n",
                                    2.0 * period, zhi)),
              std::string::npos)
        << data.substr(0, 400);
    EXPECT_NE(slurp(d / "bed.data.lammps.in").find("boundary        p p f\n"), std::string::npos);
    const Outcome boxed =
        run_packbed("export " + csv + " --box 0,3,0,3,0,4 -q --out " + (d / "boxed.data").string());
    EXPECT_EQ(boxed.status, 2);
    EXPECT_EQ(boxed.err, "packbed export: --box 0,3,0,3,0,4 is not allowed with the periodic cell "
                         "periodic:2.82842712,2.82842712; allowed: no --box (the data file's box "
                         "is the cell, its periods), or --no-container\n");
    EXPECT_FALSE(fs::exists(d / "boxed.data"));
    const Outcome stl =
        run_packbed("export " + csv + " --format stl -q --out " + (d / "cell.stl").string());
    EXPECT_EQ(stl.status, 2);
    EXPECT_EQ(
        stl.err,
        fmt::format("packbed export: --container {} is not allowed with --format stl; allowed: "
                    "cylinder:D, box:LX,LY, annulus:D,DI or cone:DB,DT,H (a periodic cell has "
                    "no closed "
                    "surface: it is exported as an openfoam case with cyclic sides, or by "
                    "lammps-data and liggghts-data)\n",
                    s["container"]["spec"].get<std::string>()));
    EXPECT_FALSE(fs::exists(d / "cell.stl"));
    const Outcome foam =
        run_packbed("export " + csv + " --format openfoam -q --out " + (d / "case").string());
    ASSERT_EQ(foam.status, 0) << foam.err; // cyclic sides
    EXPECT_NE(slurp(d / "case" / "system" / "blockMeshDict").find("type cyclic;"),
              std::string::npos);
    const Outcome enlarge = run_packbed("export " + csv +
                                        " --format openfoam --contacts "
                                        "enlarge:0.01 -q --out " +
                                        (d / "enlarged").string());
    EXPECT_EQ(enlarge.status, 2);
    EXPECT_EQ(enlarge.err,
              fmt::format("packbed export: --contacts enlarge:0.01 is not allowed in the periodic "
                          "cell {}; allowed: caps:H, shrink:F or none (the unions of enlarge and "
                          "bridges are not copied across the sides)\n",
                          s["container"]["spec"].get<std::string>()));
    EXPECT_FALSE(fs::exists(d / "enlarged"));
}

TEST(ContainerExportCli, HydraulicsOfAnAnnulusABoxAndAPeriodicCell) {
    // d = 2 mm, e = 0.4, u = 0.01 m/s, water (the defaults); annulus D = 24 mm, DI = 8 mm.
    const std::string fluid = "hydraulics -e 0.4 -d 0.002 -u 0.01 --json --container ";
    const Outcome ring = run_packbed(fluid + "annulus:0.024,0.008");
    ASSERT_EQ(ring.status, 0) << ring.err;
    const auto r = nlohmann::json::parse(ring.out)["pressure_gradient"];
    EXPECT_DOUBLE_EQ(r["hydraulic_diameter_m"].get<double>(), 0.016);
    EXPECT_DOUBLE_EQ(r["aspect_ratio"].get<double>(), 8.0);
    EXPECT_NE(r["aspect_ratio_from"].get<std::string>().find(
                  "the hydraulic diameter 4 A / P = D - DI = 0.016 m over the particle diameter "
                  "(exact for the wall term A_w, the wall-to-particle surface ratio; an "
                  "assumption for B_w, fitted to tubes)"),
              std::string::npos)
        << r;
    // By hand, psi = K1 Aw^2 (1-e)^2 / (Re e^3) + (Aw / Bw) (1-e) / e^3, dP/L = psi rho u^2 / d.
    const auto by_hand = [](double a) {
        const double e = 0.4, u = 0.01, d = 0.002, rho = 998.2, mu = 1.002e-3;
        const double re = rho * u * d / mu;
        const double aw = 1.0 + 2.0 / (3.0 * a * (1.0 - e));
        const double bw = (1.15 / (a * a) + 0.87) * (1.15 / (a * a) + 0.87);
        const double psi = 154.0 * aw * aw * (1.0 - e) * (1.0 - e) / (re * e * e * e) +
                           aw / bw * (1.0 - e) / (e * e * e);
        return psi * rho * u * u / d;
    };
    EXPECT_NEAR(r["eisfeld_schnitzlein_Pa_m"].get<double>() / by_hand(8.0), 1.0, 1e-12);
    // A box 30 x 10 mm: D_h = 2 LX LY / (LX + LY) = 15 mm, a = 7.5.
    const Outcome box = run_packbed(fluid + "box:0.03,0.01");
    ASSERT_EQ(box.status, 0) << box.err;
    const auto b = nlohmann::json::parse(box.out)["pressure_gradient"];
    EXPECT_DOUBLE_EQ(b["aspect_ratio"].get<double>(), 7.5);
    EXPECT_NEAR(b["eisfeld_schnitzlein_Pa_m"].get<double>() / by_hand(7.5), 1.0, 1e-12);
    // A periodic cell: no wall, Ergun only.
    const Outcome cell = run_packbed(fluid + "periodic:0.03,0.03");
    ASSERT_EQ(cell.status, 0) << cell.err;
    const auto c = nlohmann::json::parse(cell.out)["pressure_gradient"];
    EXPECT_FALSE(c.contains("aspect_ratio"));
    EXPECT_FALSE(c.contains("eisfeld_schnitzlein_Pa_m"));
    EXPECT_EQ(c["wall_correction"], "none: --container periodic:0.03,0.03 is a periodic cell, it "
                                    "has no wall (Ergun, no wall correction)");
    const Outcome text = run_packbed("hydraulics -e 0.4 -d 0.002 -u 0.01 --container "
                                     "annulus:0.024,0.008");
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("Eisfeld & Schnitzlein (a = 8) "), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("\nwall correction: a = --container annulus:0.024,0.008: the "
                            "hydraulic diameter 4 A / P = D - DI = 0.016 m"),
              std::string::npos)
        << text.out;
    // From a bed's summary.json: a = D_h / d in the bed's unit, whatever --diameter says.
    const fs::path bed = scratch("bed");
    ASSERT_EQ(run_packbed("lattice --type sc --diameter 0.002 --region annulus:0.024,0.008,0.01 "
                          "-q --out " +
                          bed.string())
                  .status,
              0);
    for (const auto& [given, metres] : {std::pair{"", 0.016}, {" --diameter 0.004", 0.032}}) {
        const Outcome h = run_packbed("hydraulics --json -u 0.01 --bed " + bed.string() + given);
        ASSERT_EQ(h.status, 0) << h.err;
        const auto j = nlohmann::json::parse(h.out)["pressure_gradient"];
        EXPECT_DOUBLE_EQ(j["aspect_ratio"].get<double>(), 8.0) << given;
        EXPECT_DOUBLE_EQ(j["hydraulic_diameter_m"].get<double>(), metres) << given;
        EXPECT_EQ(j["aspect_ratio_from"].get<std::string>().rfind("the annulus:0.024,0.008 of ", 0),
                  0u)
            << j;
    }
    // A bed of pellets: Ergun's diameter is a pellet's 6 V / S (a spherocylinder of D = L = 3 mm:
    // V = pi r^2 L + 4/3 pi r^3 = 11.25e-9 pi, S = 2 pi r L + 4 pi r^2 = 18e-6 pi, 3.75 mm) and
    // a is on d_v, as generate -a (4); in pellet diameters (D = 1) or of several sizes it is not
    // known, and --diameter is asked for.
    const fs::path rods = scratch("rods");
    ASSERT_EQ(run_packbed("generate --shape spherocylinder:0.003,0.003 -a 4 -n 40 -s 1 -q --out " +
                          (rods / "m").string())
                  .status,
              0);
    const Outcome p = run_packbed("hydraulics --json -u 0.1 --bed " + (rods / "m").string());
    ASSERT_EQ(p.status, 0) << p.err;
    const auto pj = nlohmann::json::parse(p.out);
    EXPECT_NEAR(pj["fluid_and_particles"]["diameter_m"].get<double>(), 3.75e-3, 1e-17);
    EXPECT_NEAR(pj["pressure_gradient"]["aspect_ratio"].get<double>(), 4.0, 1e-12);
    ASSERT_EQ(run_packbed("generate --shape spherocylinder:1,1 -a 4 -n 40 -s 1 -q --out " +
                          (rods / "one").string())
                  .status,
              0);
    const Outcome unitless = run_packbed("hydraulics --bed " + (rods / "one").string());
    EXPECT_EQ(unitless.status, 2);
    EXPECT_EQ(unitless.err, "packbed hydraulics: --bed " +
                                (rods / "one" / "summary.json").string() +
                                ": shape spherocylinder:1,1, a pellet's D = 1 (lengths in pellet "
                                "diameters, no unit); allowed: give --diameter in metres (a "
                                "pellet's 6 V / S, Ergun's diameter)\n");
    // A gap narrower than a particle.
    const Outcome narrow =
        run_packbed("hydraulics -e 0.4 -d 0.002 --container annulus:0.024,0.023");
    EXPECT_EQ(narrow.status, 2);
    EXPECT_EQ(narrow.err,
              "packbed hydraulics: --container annulus:0.024,0.023: the hydraulic diameter D - DI "
              "= 0.0010000000000000009 m over the particle diameter (0.002 m) is a = "
              "0.5; allowed: a from 1 to 10000\n");
}

namespace {

/// A diamond lattice of 3 mm balls in `region` (in folder d), exported as a LAMMPS data file and
/// settled by its example input in lmp (2000 steps): the last frame of the dump, each ball (x, y,
/// z, r); no ball lost on the way (the test fails otherwise).
std::vector<std::array<double, 4>> settled_lattice(const fs::path& d, const std::string& region) {
    const Outcome l = run_packbed("lattice --type diamond --region " + region +
                                  " --diameter 0.003 -q --out " + d.string());
    EXPECT_EQ(l.status, 0) << l.err;
    const std::size_t balls = spheres_of(d / "particles.csv").size();
    const Outcome e = run_packbed("export " + (d / "particles.csv").string() + " -q --out " +
                                  (d / "bed.data").string());
    EXPECT_EQ(e.status, 0) << e.err;
    const std::string cmd =
        "cd " + d.string() + " && lmp -in bed.data.lammps.in -log none > lmp.out 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(d / "lmp.out");
    const std::string log = slurp(d / "lmp.out");
    EXPECT_EQ(log.find("Lost"), std::string::npos) << log;
    EXPECT_NE(log.find(fmt::format("packbed settle: {} atoms after 2000 steps", balls)),
              std::string::npos)
        << log;
    auto last = last_dump_frame(slurp(d / "bed.data.lammps.dump"));
    EXPECT_EQ(last.size(), balls);
    return last;
}

} // namespace

TEST(ContainerExportCli, LammpsSettlesAnAnnulusBedBetweenRodAndTube) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // A diamond lattice of 3 mm balls in the annulus D = 24 mm, DI = 6 mm, 12 mm tall: under
    // gravity it collapses against both walls.
    const auto last = settled_lattice(scratch("ring") / "bed", "annulus:0.024,0.006,0.012");
    ASSERT_GT(last.size(), 10u);
    const double tolerance = 0.01 * 0.003;
    std::size_t at_rod = 0, at_tube = 0;
    for (const auto& s : last) {
        const double rho = std::hypot(s[0], s[1]);
        EXPECT_GE(rho - s[3], 0.003 - tolerance); // outside the rod
        EXPECT_LE(rho + s[3], 0.012 + tolerance); // inside the tube
        EXPECT_GE(s[2] - s[3], -tolerance);
        at_rod += rho - s[3] < 0.003 + 0.01 * 0.003 ? 1 : 0;
        at_tube += rho + s[3] > 0.012 - 0.01 * 0.003 ? 1 : 0;
    }
    EXPECT_GT(at_rod, 0u); // both walls hold spheres
    EXPECT_GT(at_tube, 0u);
}

TEST(ContainerExportCli, LammpsSettlesAConeBedAgainstTheSlantedWall) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // A diamond lattice of 3 mm balls in a hopper, floor diameter 18 mm widening to 30 mm at
    // z = 24 mm, 12 mm of it: LAMMPS's cone region (the settle input's wall) holds the bed
    // as it collapses, every ball inside the slanted wall, R(z) = 9 + 0.25 z mm, distances
    // along its normal (cos = 24 / sqrt(24^2 + 6^2)).
    const fs::path d = scratch("cone") / "bed";
    const auto last = settled_lattice(d, "cone:0.018,0.030,0.024,0.012");
    ASSERT_GT(last.size(), 10u);
    EXPECT_NE(slurp(d / "bed.data.lammps.in").find("region          container cone z 0 0 0.009 "),
              std::string::npos);
    const double tolerance = 0.01 * 0.003, cos = 24.0 / std::hypot(24.0, 6.0);
    std::size_t at_wall = 0;
    for (const auto& s : last) {
        const double from_wall = cos * (0.009 + 0.25 * s[2] - std::hypot(s[0], s[1])) - s[3];
        EXPECT_GE(from_wall, -tolerance);
        EXPECT_GE(s[2] - s[3], -tolerance);
        at_wall += from_wall < tolerance ? 1 : 0;
    }
    EXPECT_GT(at_wall, 0u); // the slanted wall holds spheres
}

/// A pellet bed (`generate` with `shape_args`) in d/bed, exported as LAMMPS clumps to
/// d/bed.data and its example settle run by lmp in d: the data file, the input and LAMMPS's
/// output.
struct SettledClumps {
    std::string data, input, log;
};
SettledClumps settle_clumps(const fs::path& d, const std::string& shape_args) {
    SettledClumps out;
    const Outcome g =
        run_packbed("generate " + shape_args + " -q --out " + (d / "bed").string() + " --force");
    EXPECT_EQ(g.status, 0) << g.err;
    const Outcome e = run_packbed("export " + (d / "bed" / "particles.csv").string() +
                                  " --format lammps-data -q --out " + (d / "bed.data").string());
    EXPECT_EQ(e.status, 0) << e.err;
    out.data = slurp(d / "bed.data");
    out.input = slurp(d / "bed.data.lammps.in");
    const std::string cmd =
        "cd " + d.string() + " && lmp -in bed.data.lammps.in -log none > lmp.out 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(d / "lmp.out");
    out.log = slurp(d / "lmp.out");
    return out;
}

TEST(ContainerExportCli, LammpsSettlesPelletsAsRigidClumps) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // 12 cylinders D = L = 3 mm in a tube of a = 4, each exported as its clump of 24 spheres
    // (CylinderShape::dem_spheres) and settled by LAMMPS as one rigid body: the clumps keep
    // their shape (every distance between two spheres of one clump as exported), stay in the
    // tube and above the floor, and none is lost.
    const fs::path d = scratch("clumps");
    const auto [data, input, log] =
        settle_clumps(d, "--shape cylinder:0.003,0.003 -a 4 -n 12 -s 3");
    EXPECT_NE(data.find("288 atoms\n"), std::string::npos);
    // The Molecules section: atom k in clump (k - 1) / 24 + 1.
    const std::size_t at = data.find("\nMolecules\n\n");
    ASSERT_NE(at, std::string::npos);
    std::istringstream molecules(data.substr(at + 12));
    for (std::size_t k = 1; k <= 288; ++k) {
        std::size_t id = 0, mol = 0;
        molecules >> id >> mol;
        EXPECT_EQ(id, k);
        EXPECT_EQ(mol, (k - 1) / 24 + 1) << k;
    }
    EXPECT_NE(input.find("fix             integrate all rigid/small molecule\n"),
              std::string::npos);
    EXPECT_NE(log.find("12 rigid bodies with 288 atoms"), std::string::npos) << log;
    EXPECT_NE(log.find("packbed settle: 288 atoms after 2000 steps"), std::string::npos) << log;
    EXPECT_EQ(log.find("Lost"), std::string::npos) << log;
    const auto frames = dump_frames(slurp(d / "bed.data.lammps.dump"));
    ASSERT_EQ(frames.size(), 2u);
    ASSERT_EQ(frames[0].size(), 288u);
    ASSERT_EQ(frames[1].size(), 288u);
    const auto distance = [](const std::array<double, 4>& a, const std::array<double, 4>& b) {
        return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    };
    // Walls and floor within 1 % of D (the DEM's own soft overlap under load, as for spheres);
    // the dump's positions to 6 digits, so the distances within a clump to 1e-5 D.
    const double rt = 0.5 * 4.0 * std::cbrt(1.5) * 0.003, tolerance = 0.01 * 0.003;
    double moved = 0.0;
    for (std::size_t k = 0; k < 288; ++k) {
        const std::size_t first = k / 24 * 24;
        EXPECT_NEAR(distance(frames[1][k], frames[1][first]),
                    distance(frames[0][k], frames[0][first]), 1e-5 * 0.003)
            << k;
        const auto& s = frames[1][k];
        EXPECT_LE(std::hypot(s[0], s[1]) + s[3], rt + tolerance) << k;
        EXPECT_GE(s[2] - s[3], -tolerance) << k;
        moved = std::max(moved, distance(frames[1][k], frames[0][k]));
    }
    EXPECT_GT(moved, 1e-3 * 0.003); // the clumps did settle
}

TEST(ContainerExportCli, LammpsSettlesTrilobesAsRigidClumps) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // 8 trilobes (lobes 1 mm on a circle of 0.8 mm, 1.5 mm long), each its three lobes' clumps
    // of 40 spheres as one rigid body. A trilobe's clump reaches farther than its spheres'
    // neighbour cutoff: without the input's ghost cutoff LAMMPS stops ("Rigid body extent >
    // ghost cutoff"). The clumps keep their shape, and none is lost.
    const fs::path d = scratch("trilobe-clumps");
    const auto [data, input, log] =
        settle_clumps(d, "--shape trilobe:0.001,0.0008,0.0015 -a 4 -n 8 -s 1");
    EXPECT_NE(data.find("960 atoms\n"), std::string::npos);
    EXPECT_NE(log.find("8 rigid bodies with 960 atoms"), std::string::npos) << log;
    EXPECT_NE(log.find("packbed settle: 960 atoms after 2000 steps"), std::string::npos) << log;
    EXPECT_EQ(log.find("Lost"), std::string::npos) << log;
    const auto frames = dump_frames(slurp(d / "bed.data.lammps.dump"));
    ASSERT_EQ(frames.size(), 2u);
    ASSERT_EQ(frames[1].size(), 960u);
    const auto distance = [](const std::array<double, 4>& a, const std::array<double, 4>& b) {
        return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    };
    for (std::size_t k = 0; k < 960; ++k) {
        const std::size_t first = k / 120 * 120;
        EXPECT_NEAR(distance(frames[1][k], frames[1][first]),
                    distance(frames[0][k], frames[0][first]), 3e-8)
            << k; // the dump's 6 digits of millimetres
    }
}

TEST(ContainerExportCli, LammpsSettlesRingsAsRigidClumps) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // 3 rings (D = L = 1 mm, bore 0.5 mm), each a clump of 1710 spheres in its wall as one
    // rigid body, none in the bore: the clumps keep their shape, and none is lost.
    const fs::path d = scratch("ring-clumps");
    const auto [data, input, log] =
        settle_clumps(d, "--shape ring:0.001,0.0005,0.001 -a 3 -n 3 -s 1");
    EXPECT_NE(data.find("5130 atoms\n"), std::string::npos);
    EXPECT_NE(log.find("3 rigid bodies with 5130 atoms"), std::string::npos) << log;
    EXPECT_EQ(log.find("Lost"), std::string::npos) << log;
    const auto frames = dump_frames(slurp(d / "bed.data.lammps.dump"));
    ASSERT_EQ(frames.size(), 2u);
    ASSERT_EQ(frames[1].size(), 5130u);
    const auto distance = [](const std::array<double, 4>& a, const std::array<double, 4>& b) {
        return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    };
    for (std::size_t k = 0; k < 5130; ++k) {
        const std::size_t first = k / 1710 * 1710;
        EXPECT_NEAR(distance(frames[1][k], frames[1][first]),
                    distance(frames[0][k], frames[0][first]), 3e-8)
            << k;
    }
}

TEST(ContainerExportCli, LammpsSettlesSpherocylindersAsRigidClumps) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // 4 spherocylinders (D = L = 1 mm), each a row of 5 spheres of diameter D from cap centre
    // to cap centre (L / (D / 4) = 4 steps) as one rigid body: the rows keep their shape, and
    // none is lost.
    const fs::path d = scratch("rod-clumps");
    const auto [data, input, log] =
        settle_clumps(d, "--shape spherocylinder:0.001,0.001 -a 3 -n 4 -s 1");
    EXPECT_NE(data.find("20 atoms\n"), std::string::npos);
    EXPECT_NE(log.find("4 rigid bodies with 20 atoms"), std::string::npos) << log;
    EXPECT_EQ(log.find("Lost"), std::string::npos) << log;
    const auto frames = dump_frames(slurp(d / "bed.data.lammps.dump"));
    ASSERT_EQ(frames.size(), 2u);
    ASSERT_EQ(frames[1].size(), 20u);
    for (std::size_t k = 0; k < 20; ++k) {
        const auto& a = frames[1][k];
        const auto& first = frames[1][k / 5 * 5];
        // The k-th sphere of its row lies (k mod 5) L / 4 from the first, both before and after.
        EXPECT_NEAR(std::hypot(a[0] - first[0], a[1] - first[1], a[2] - first[2]),
                    0.25e-3 * static_cast<double>(k % 5), 3e-8)
            << k;
    }
}

TEST(ContainerExportCli, LatticeRegionsRefusedWithOneLine) {
    const fs::path d = scratch("bad");
    const std::string allowed =
        "allowed: a container's spec and the region's height after its numbers, "
        "cylinder:D,HEIGHT, box:LX,LY,HEIGHT, annulus:D,DI,HEIGHT, periodic:LX,LY,HEIGHT, "
        "cone:DB,DT,H,HEIGHT, with lengths > 0 and at most 1e+15; its container: ";
    // each with what its kind's own numbers allow
    const std::string annulus = "annulus:D,DI, between a tube of diameter D and a coaxial rod of "
                                "diameter DI, 0 < DI < D <= 2e+15\n";
    const std::string periodic = "periodic:LX,LY, a cell periodic in x and y, each in (0, 1e+15]\n";
    for (const auto& [region, kind] :
         {std::pair<std::string, std::string>{"annulus:2,6,1", annulus},
          {"annulus:6,2", annulus},
          {"periodic:4,4", periodic}}) {
        const Outcome o = run_packbed("lattice --region " + region + " --out " + d.string());
        EXPECT_EQ(o.status, 2);
        EXPECT_EQ(o.err,
                  "packbed lattice: --region '" + region + "' is not allowed; " + allowed + kind);
    }
    // A cone's apex at z = 5 x 5 / 4 = 6.25: a region 12 tall would end in a point.
    const Outcome apex = run_packbed("lattice --region cone:10,2,5,12 --out " + d.string());
    EXPECT_EQ(apex.status, 2);
    EXPECT_EQ(apex.err, "packbed lattice: --region 'cone:10,2,5,12' is not allowed: cone:10,2,5 "
                        "has no cross-section at the region's height 12 (its apex is below it); "
                        "allowed: a height where it has one\n");
    const Outcome turned = run_packbed("lattice --type sc --region periodic:4,4,2 --rotate z:30 "
                                       "--out " +
                                       d.string());
    EXPECT_EQ(turned.status, 2);
    EXPECT_EQ(turned.err, "packbed lattice: --rotate is not allowed with --region periodic:4,4,2; "
                          "allowed: no rotation (the lattice must repeat across the periodic "
                          "cell)\n");
    // hcp repeats every d along x and sqrt(3) d along y.
    const Outcome hcp =
        run_packbed("lattice --type hcp --region periodic:4,4,2 --out " + d.string());
    EXPECT_EQ(hcp.status, 2);
    EXPECT_NE(hcp.err.find("its periods 1 (x) and 1.7320508075688772 (y), each at least 2 d, e.g. "
                           "periodic:4,3.4641016151377544,2\n"),
              std::string::npos)
        << hcp.err;
    EXPECT_TRUE(fs::is_empty(d));
}

TEST(ContainerExportCli, LiggghtsSettlesAnAnnulusAConeAndAPeriodicBed) {
    if (std::system("command -v liggghts >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "liggghts (Debian package liggghts) is not installed";
    for (const std::string region : {"annulus:0.024,0.006,0.012", "cone:0.018,0.030,0.024,0.012",
                                     "periodic:0.012,0.012,0.009"}) {
        const fs::path d = scratch(region.substr(0, 7)) / "bed";
        ASSERT_EQ(run_packbed("lattice --type " + std::string(region[0] == 'a' ? "diamond" : "sc") +
                              " --region " + region + " --diameter 0.003 -q --out " + d.string())
                      .status,
                  0);
        const std::size_t balls = spheres_of(d / "particles.csv").size();
        ASSERT_EQ(run_packbed("export " + (d / "particles.csv").string() +
                              " --format liggghts-data -q --out " + (d / "bed.data").string())
                      .status,
                  0);
        EXPECT_EQ(fs::exists(d / "bed.data.wall.stl"), region[0] != 'p');
        const std::string cmd =
            "cd " + d.string() + " && liggghts -in bed.data.liggghts.in -log none > lig.out 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(d / "lig.out");
        EXPECT_NE(slurp(d / "lig.out")
                      .find(fmt::format("packbed settle: {} atoms after 2000 steps", balls)),
                  std::string::npos)
            << slurp(d / "lig.out");
        if (region[0] == 'c') { // inside the cone's prism: R(z) = 9 + 0.25 z mm at its sides
            for (const auto& s : last_dump_frame(slurp(d / "bed.data.liggghts.dump"))) {
                EXPECT_LE(std::hypot(s[0], s[1]) + s[3] * std::hypot(24.0, 6.0) / 24.0,
                          (0.009 + 0.25 * s[2]) / std::cos(pi / 48.0) + 0.01 * 0.003);
            }
        }
        if (region[0] != 'a')
            continue;
        // Between the rod and the tube's prism (corners at R / cos(pi / 48) at most).
        for (const auto& s : last_dump_frame(slurp(d / "bed.data.liggghts.dump"))) {
            const double rho = std::hypot(s[0], s[1]);
            EXPECT_GE(rho - s[3], 0.003 - 0.01 * 0.003);
            EXPECT_LE(rho + s[3], 0.012 / std::cos(pi / 48.0) + 0.01 * 0.003);
        }
    }
}

TEST(ContainerExportCli, LammpsSettlesAPeriodicBed) {
    if (!has_lmp())
        GTEST_SKIP() << "lmp (Debian package lammps) is not installed";
    // A simple cubic lattice of 3 mm balls in the periodic cell 12 x 12 mm (4 periods), 9 mm
    // tall: 3 layers of 16, nothing lost through the periodic sides.
    const fs::path d = scratch("cell") / "bed";
    ASSERT_EQ(
        run_packbed("lattice --type sc --region periodic:0.012,0.012,0.009 --diameter 0.003 -q "
                    "--out " +
                    d.string())
            .status,
        0);
    ASSERT_EQ(spheres_of(d / "particles.csv").size(), 48u);
    ASSERT_EQ(run_packbed("export " + (d / "particles.csv").string() + " -q --out " +
                          (d / "bed.data").string())
                  .status,
              0);
    const std::string cmd =
        "cd " + d.string() + " && lmp -in bed.data.lammps.in -log none > lmp.out 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(d / "lmp.out");
    const std::string log = slurp(d / "lmp.out");
    EXPECT_NE(log.find("packbed settle: 48 atoms after 2000 steps"), std::string::npos) << log;
    for (const auto& s : last_dump_frame(slurp(d / "bed.data.lammps.dump"))) {
        EXPECT_GE(s[0], 0.0);
        EXPECT_LT(s[0], 0.012);
        EXPECT_GE(s[2] - s[3], -0.01 * 0.003);
    }
}
