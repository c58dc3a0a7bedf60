#include "packbed/surface.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/error.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// Closed and consistently oriented: every directed edge once, and its reverse once. Vertices
/// at the same position count as one (STL has no shared vertices either).
bool closed_and_oriented(const std::vector<const TriangleMesh*>& meshes) {
    std::map<std::tuple<double, double, double>, int> id;
    auto vid = [&](const Vec3& v) {
        return id.try_emplace({v.x, v.y, v.z}, static_cast<int>(id.size())).first->second;
    };
    std::map<std::pair<int, int>, int> edges;
    for (const TriangleMesh* m : meshes)
        for (const auto& t : m->triangles)
            for (int e = 0; e < 3; ++e)
                ++edges[{vid(m->vertices[t[e]]), vid(m->vertices[t[(e + 1) % 3]])}];
    for (const auto& [edge, count] : edges) {
        if (edge.first == edge.second)
            continue; // a zero-length edge of a degenerate sliver
        const auto back = edges.find({edge.second, edge.first});
        if (count != 1 || back == edges.end() || back->second != 1)
            return false;
    }
    return true;
}

double sphere_volume(double r) {
    return 4.0 / 3.0 * pi * r * r * r;
}

Packing two_touching() {
    Packing p;
    p.add({-0.5, 0.0, 1.0}, 0.5);
    p.add({0.5, 0.0, 1.0}, 0.5);
    return p;
}

SurfaceContainer cylinder(double radius, double height) {
    return {Cylinder(radius), height};
}

} // namespace

TEST(Surface, IcosphereIsAClosedPolyhedronInscribedInTheUnitSphere) {
    for (int level = 0; level <= 4; ++level) {
        const TriangleMesh m = icosphere(level);
        const double four_l = std::ldexp(1.0, 2 * level);
        EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(20 * four_l));
        EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(10 * four_l + 2));
        for (const Vec3& v : m.vertices)
            EXPECT_NEAR(norm(v), 1.0, 1e-15);
        EXPECT_TRUE(closed_and_oriented({&m}));
        // Inside the sphere, and closer with each level: the icosahedron holds 60.5 % of the
        // ball (5/12 (3 + sqrt 5) a^3 with a = 1.0515), level 4 above 99.5 %.
        EXPECT_LT(m.volume(), sphere_volume(1.0));
        if (level == 0) {
            EXPECT_NEAR(m.volume() / sphere_volume(1.0), 0.6055, 1e-4);
        }
        if (level == 4) {
            EXPECT_GT(m.volume() / sphere_volume(1.0), 0.995);
        }
    }
    EXPECT_EQ(icosphere_level_for_edge(0.5, 0.5), 1);
    EXPECT_EQ(icosphere_level_for_edge(0.5, 0.05), 4);
}

TEST(Surface, VolumeFacetsHoldTheSpheresVolume) {
    // Level 0 in closed form: the icosahedron inscribed in the unit sphere has the edge
    // a = 4 / sqrt(10 + 2 sqrt 5) and the volume 5/12 (3 + sqrt 5) a^3.
    const double a = 4.0 / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
    const double icosahedron = 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * a * a * a;
    EXPECT_NEAR(volume_facets_scale(0), std::cbrt(sphere_volume(1.0) / icosahedron), 1e-14);
    EXPECT_NEAR(volume_facets_scale(0), 1.18206, 1e-5);
    EXPECT_NEAR(volume_facets_scale(3), 1.00289, 1e-5); // 0.8606 % of the volume short
    EXPECT_NEAR(volume_facets_scale(5), 1.00018, 1e-5); // 0.0541 %
    // Two spheres far apart, whole: the surfaces hold exactly the spheres' volume, where the
    // inscribed ones hold 0.86 % less.
    Packing p;
    p.add({-1.0, 0.0, 1.0}, 0.5);
    p.add({1.0, 0.0, 1.0}, 0.5);
    const SurfaceContainer c = cylinder(3.0, 2.0);
    const TreatedBed bed = treat_contacts(p, {}, c);
    SurfaceOptions o;
    o.container = c;
    o.write_container = false;
    const double inscribed = bed_surface(bed, o)[0].mesh.volume();
    o.facets = Facets::volume;
    const double held = bed_surface(bed, o)[0].mesh.volume();
    EXPECT_NEAR(held / (2.0 * sphere_volume(0.5)), 1.0, 1e-13);
    EXPECT_NEAR(1.0 - inscribed / held, 0.008606, 1e-6);
    // A touching pair with caps: each body keeps to its side of its plane, and the surface
    // holds the exact capped volume to 1e-4 (the inscribed one 0.86 % less).
    const Packing touching = two_touching();
    const TreatedBed capped = treat_contacts(touching, parse_contacts("caps:0.02"), c);
    const TreatmentVolumes v = treatment_volumes(touching, capped, c);
    const TriangleMesh mesh = bed_surface(capped, o)[0].mesh;
    EXPECT_TRUE(closed_and_oriented({&mesh}));
    for (const Vec3& x : mesh.vertices)
        EXPECT_GE(std::abs(x.x), 0.01 - 1e-15);
    EXPECT_NEAR(mesh.volume() / v.treated_solid, 1.0, 1e-4);
}

TEST(Surface, VolumeFacetsAreRefusedWhereTheyWouldMeet) {
    SurfaceOptions o;
    o.facets = Facets::volume;
    o.container = cylinder(3.0, 2.0);
    const Packing touching = two_touching();
    // Touching as they are: the grown facets would cross.
    try {
        bed_surface(treat_contacts(touching, {}, o.container), o);
        FAIL() << "touching spheres accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("sphere 1's facets by 0.00144"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("its gap to sphere 2 is 0"), std::string::npos)
            << e.what();
    }
    // Shrunk by 0.1 %: a gap of 0.001 Dp, below the two growths of 0.00144 each (level 3);
    // by 2 %: 0.02 Dp, room enough.
    EXPECT_THROW(
        bed_surface(treat_contacts(touching, parse_contacts("shrink:0.001"), o.container), o),
        InvalidInput);
    EXPECT_NO_THROW(
        bed_surface(treat_contacts(touching, parse_contacts("shrink:0.02"), o.container), o));
    // At the wall: shrink:0.002 leaves 0.001 Dp to it, below the growth; caps cut at the wall.
    Packing wall;
    wall.add({2.5, 0.0, 1.0}, 0.5);
    try {
        bed_surface(treat_contacts(wall, parse_contacts("shrink:0.002"), o.container), o);
        FAIL() << "a sphere 0.001 from the wall accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("gap to the wall is 0.001"), std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(bed_surface(treat_contacts(wall, parse_contacts("caps:0.01"), o.container), o));
    // On the floor, not cut: refused; capped: the cut keeps it clear.
    Packing floor;
    floor.add({0.0, 0.0, 0.5}, 0.5);
    EXPECT_THROW(bed_surface(treat_contacts(floor, {}, o.container), o), InvalidInput);
    EXPECT_NO_THROW(
        bed_surface(treat_contacts(floor, parse_contacts("caps:0.01"), o.container), o));
    // In a periodic cell a pair capped across a side is apart (its copy's cut moved with it).
    Packing across;
    across.add({0.4, 1.5, 1.0}, 0.5);
    across.add({2.4, 1.5, 1.0}, 0.5); // touching its neighbour's image at x = -0.6
    SurfaceOptions cell = o;
    cell.container = SurfaceContainer{Periodic(3.0, 3.0), 2.0};
    EXPECT_NO_THROW(
        bed_surface(treat_contacts(across, parse_contacts("caps:0.02"), cell.container), cell));
    EXPECT_THROW(bed_surface(treat_contacts(across, {}, cell.container), cell), InvalidInput);
}

TEST(Surface, AutomaticFacetsHoldTheVolumeWhereTheGapsAllow) {
    SurfaceOptions o;
    o.facets = Facets::automatic;
    o.container = cylinder(3.0, 2.0);
    o.write_container = false;
    const Packing touching = two_touching();
    // Touching as they are: no room, so inscribed (the exact inscribed surface, 0.86 % short).
    const TreatedBed bare = treat_contacts(touching, {}, o.container);
    EXPECT_EQ(facets_for(bare, o), Facets::inscribed);
    ASSERT_TRUE(volume_facets_conflict(bare, o.container, o.level));
    EXPECT_NE(volume_facets_conflict(bare, o.container, o.level)->find("its gap to sphere 2"),
              std::string::npos);
    SurfaceOptions inscribed = o;
    inscribed.facets = Facets::inscribed;
    EXPECT_EQ(bed_surface(bare, o)[0].mesh.vertices, bed_surface(bare, inscribed)[0].mesh.vertices);
    // Capped 0.02 Dp apart: room, so volume, the same surface as asked for by name.
    const TreatedBed capped = treat_contacts(touching, parse_contacts("caps:0.02"), o.container);
    EXPECT_EQ(facets_for(capped, o), Facets::volume);
    EXPECT_FALSE(volume_facets_conflict(capped, o.container, o.level));
    SurfaceOptions volume = o;
    volume.facets = Facets::volume;
    const TriangleMesh automatic = bed_surface(capped, o)[0].mesh;
    EXPECT_EQ(automatic.vertices, bed_surface(capped, volume)[0].mesh.vertices);
    const TreatmentVolumes v = treatment_volumes(touching, capped, *o.container);
    EXPECT_NEAR(automatic.volume() / v.treated_solid, 1.0, 1e-4);
    // At level 1 the growth is 4.6 % of the radius: shrink:0.02 leaves a gap of 0.02, below the
    // two growths of 0.0226; shrink:0.05 leaves 0.05 against 0.0438.
    o.level = 1;
    EXPECT_NEAR(volume_facets_scale(1), 1.04613, 1e-5);
    EXPECT_EQ(facets_for(treat_contacts(touching, parse_contacts("shrink:0.02"), o.container), o),
              Facets::inscribed);
    EXPECT_EQ(facets_for(treat_contacts(touching, parse_contacts("shrink:0.05"), o.container), o),
              Facets::volume);
}

TEST(Surface, ClippingKeepsTheMeshClosedAndCutsWhereAsked) {
    const TriangleMesh ball = icosphere(5);
    const TriangleMesh cut = clip_convex(ball, {{0.0, 0.0, 1.0}, 0.6}); // keep z <= 0.6
    EXPECT_TRUE(closed_and_oriented({&cut}));
    for (const Vec3& v : cut.vertices)
        EXPECT_LE(v.z, 0.6 + 1e-15);
    // The kept volume against the exact ball minus a cap of height 0.4, within the
    // tessellation's own deficit (level 5: below 0.15 %).
    const double exact = sphere_volume(1.0) - spherical_cap_volume(1.0, 0.6);
    EXPECT_NEAR(cut.volume() / exact, 1.0, 1.5e-3);
    EXPECT_LT(cut.volume(), exact);
    // Two cuts, and a half-space that keeps all or nothing.
    const TriangleMesh two = clip_convex(cut, {{1.0, 0.0, 0.0}, -0.2});
    EXPECT_TRUE(closed_and_oriented({&two}));
    EXPECT_EQ(clip_convex(ball, {{0.0, 0.0, 1.0}, 2.0}).triangles.size(), ball.triangles.size());
    EXPECT_TRUE(clip_convex(ball, {{0.0, 0.0, 1.0}, -2.0}).triangles.empty());
}

TEST(Surface, CapAndLensVolumesByHand) {
    // Cap of height 0.01 on a ball of radius 0.5: pi 0.01^2 (1.5 - 0.01) / 3.
    EXPECT_NEAR(spherical_cap_volume(0.5, 0.49), pi * 1e-4 * 1.49 / 3.0, 1e-18);
    EXPECT_EQ(spherical_cap_volume(0.5, 0.5), 0.0);
    EXPECT_NEAR(spherical_cap_volume(0.5, -0.5), sphere_volume(0.5), 1e-15);
    // Equal balls: pi (4 r + d) (2 r - d)^2 / 12.
    EXPECT_NEAR(lens_volume(0.5, 0.5, 0.999), pi * 2.999 * 1e-6 / 12.0, 1e-17);
    EXPECT_EQ(lens_volume(0.5, 0.5, 1.0), 0.0);
    EXPECT_NEAR(lens_volume(1.0, 0.25, 0.5), sphere_volume(0.25), 1e-15);
}

TEST(Surface, CapsOnTwoTouchingSpheres) {
    const Packing p = two_touching();
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const auto bodies = treat_contacts(p, parse_contacts("caps:0.02"), box);
    ASSERT_EQ(bodies.bodies[0].cuts.size(), 1u); // floor 0.5 away, wall 2 away: the pair only
    ASSERT_EQ(bodies.bodies[1].cuts.size(), 1u);
    // Planes at x = -0.01 and x = +0.01: faces 0.02 Dp apart, a cap of height 0.01 off each.
    EXPECT_NEAR(bodies.bodies[0].cuts[0].offset, -0.01, 1e-15);
    EXPECT_NEAR(bodies.bodies[1].cuts[0].offset, -0.01, 1e-15); // normal -x: -x <= -0.01
    const TreatmentVolumes v = treatment_volumes(p, bodies, box);
    const double cap = pi * 0.01 * 0.01 * (1.5 - 0.01) / 3.0; // 1.5603e-4
    EXPECT_NEAR(v.untouched_solid, 2.0 * sphere_volume(0.5), 1e-14);
    EXPECT_NEAR(v.treated_solid, 2.0 * (sphere_volume(0.5) - cap), 1e-14);
    EXPECT_NEAR(v.container_volume, pi * 9.0 * 2.0, 1e-13);
    EXPECT_NEAR(v.treated_void_fraction - v.untouched_void_fraction, 2.0 * cap / (18.0 * pi),
                1e-15);
    // The tessellated bodies: closed, each on its side of its plane, volume near the exact.
    SurfaceOptions o;
    o.level = 5;
    o.container = box;
    const auto solids = bed_surface(bodies, o);
    ASSERT_EQ(solids.size(), 4u);
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh}));
    EXPECT_TRUE(closed_and_oriented({&solids[1].mesh, &solids[2].mesh, &solids[3].mesh}));
    for (const Vec3& v2 : solids[0].mesh.vertices) {
        if (v2.x < 0.0)
            EXPECT_LE(v2.x, -0.01 + 1e-15);
        else
            EXPECT_GE(v2.x, 0.01 - 1e-15);
    }
    EXPECT_NEAR(solids[0].mesh.volume() / v.treated_solid, 1.0, 1.5e-3);
}

TEST(Surface, CapsOnASphereTouchingTheWallAndTheFloor) {
    Packing p;
    p.add({1.5, 0.0, 0.5}, 0.5); // touches the wall of radius 2 and the floor
    const SurfaceContainer c = cylinder(2.0, 2.0);
    const auto bodies = treat_contacts(p, parse_contacts("caps:0.02"), c);
    ASSERT_EQ(bodies.bodies[0].cuts.size(), 2u);
    // Floor: plane z = 0.02; wall: plane x = 1.98 (gap 0.02 Dp to the wall at the face's
    // centre). Each removes a cap of height 0.02: pi 0.02^2 (1.5 - 0.02) / 3 = 6.1994e-4.
    const double cap = pi * 0.02 * 0.02 * (1.5 - 0.02) / 3.0;
    const TreatmentVolumes v = treatment_volumes(p, bodies, c);
    EXPECT_NEAR(v.untouched_solid, sphere_volume(0.5), 1e-13);
    EXPECT_NEAR(v.treated_solid, sphere_volume(0.5) - 2.0 * cap, 1e-14);
    SurfaceOptions o;
    o.level = 4;
    o.container = c;
    const auto solids = bed_surface(bodies, o);
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh}));
    for (const Vec3& v2 : solids[0].mesh.vertices) {
        EXPECT_LE(v2.x, 1.98 + 1e-15);
        EXPECT_GE(v2.z, 0.02 - 1e-15);
    }
    // The gap to the wall is smallest at the rim of the flat face, where the cylinder curves
    // towards it: x = 1.98, y = sqrt(2 r c - c^2) = 0.14, at sqrt(3.94) = 1.98494 from the axis
    // (a gap of 0.753 H).
    for (const Vec3& v2 : solids[0].mesh.vertices)
        EXPECT_LE(std::hypot(v2.x, v2.y), std::sqrt(3.94) + 1e-12);
}

TEST(Surface, ShrinkOnTwoTouchingSpheresAndOnASphereAtTheWall) {
    const Packing p = two_touching();
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const auto bodies = treat_contacts(p, parse_contacts("shrink:0.02"), box);
    EXPECT_DOUBLE_EQ(bodies.bodies[0].radius, 0.49);
    const TreatmentVolumes v = treatment_volumes(p, bodies, box);
    EXPECT_NEAR(v.treated_solid, 2.0 * 4.0 / 3.0 * pi * 0.117649, 1e-14); // 0.49^3
    Packing wall;
    wall.add({1.5, 0.0, 1.0}, 0.5);
    const SurfaceContainer c = cylinder(2.0, 2.0);
    const auto shrunk = treat_contacts(wall, parse_contacts("shrink:0.02"), c);
    const TreatmentVolumes w = treatment_volumes(wall, shrunk, c);
    EXPECT_NEAR(w.untouched_solid - w.treated_solid, 4.0 / 3.0 * pi * (0.125 - 0.117649), 1e-14);
    SurfaceOptions o;
    o.level = 3;
    o.container = c;
    const auto solids = bed_surface(shrunk, o);
    for (const Vec3& v2 : solids[0].mesh.vertices)
        EXPECT_LE(std::hypot(v2.x, v2.y), 1.99 + 1e-12);
}

TEST(Surface, OverlapsAreCountedOnceAndRefusedWhereATreatmentCannotSeparate) {
    Packing p;
    p.add({0.0, 0.0, 1.0}, 0.5);
    p.add({0.99, 0.0, 1.0}, 0.5); // overlap 0.01 Dp
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const auto untouched = treat_contacts(p, {}, box);
    const TreatmentVolumes v = treatment_volumes(p, untouched, box);
    EXPECT_NEAR(v.untouched_solid, 2.0 * sphere_volume(0.5) - pi * 2.99 * 1e-4 / 12.0, 1e-14);
    EXPECT_EQ(v.treated_solid, v.untouched_solid);
    EXPECT_THROW(treat_contacts(p, parse_contacts("shrink:0.005"), box), InvalidInput);
    EXPECT_NO_THROW(treat_contacts(p, parse_contacts("shrink:0.02"), box));
    // Caps of one sphere that would meet: three spheres touching in a triangle (60 degrees)
    // with H = 0.45 Dp (each cap's angular radius 56.6 degrees).
    Packing t;
    t.add({0.0, 0.0, 1.0}, 0.5);
    t.add({1.0, 0.0, 1.0}, 0.5);
    t.add({0.5, std::sqrt(0.75), 1.0}, 0.5);
    EXPECT_THROW(treat_contacts(t, parse_contacts("caps:0.45"), box), InvalidInput);
    EXPECT_NO_THROW(treat_contacts(t, parse_contacts("caps:0.05"), box));
}

TEST(Surface, ContactsTextIsParsedOrRefused) {
    EXPECT_EQ(parse_contacts("none").treatment, ContactTreatment::none);
    const Contacts c = parse_contacts("caps:0.01");
    EXPECT_EQ(c.treatment, ContactTreatment::caps);
    EXPECT_DOUBLE_EQ(c.parameter, 0.01);
    for (const char* bad : {"caps", "caps:", "caps:0", "caps:0.5", "caps:x", "shrink:-0.1",
                            "none:0.1", "bridges:0.5", "enlarge:0", "caps:0.01x", "glue:0.1"})
        EXPECT_THROW(parse_contacts(bad), InvalidInput) << bad;
}

TEST(Surface, BinaryStlHasTheFormatsSizeAndAsciiNamesEverySolid) {
    const Packing p = two_touching();
    SurfaceOptions o;
    o.level = 2;
    o.container = cylinder(3.0, 2.0);
    const auto solids = bed_surface(treat_contacts(p, parse_contacts("caps:0.02"), o.container), o);
    std::size_t triangles = 0;
    for (const Solid& s : solids)
        triangles += s.mesh.triangles.size();
    const auto dir = std::filesystem::temp_directory_path() / "packbed_test_surface";
    std::filesystem::create_directories(dir);
    write_surface(solids, SurfaceFormat::stl_binary, dir / "bed.stl");
    EXPECT_EQ(std::filesystem::file_size(dir / "bed.stl"), 84 + 50 * triangles);
    std::ifstream binary(dir / "bed.stl", std::ios::binary);
    binary.seekg(80);
    std::uint32_t count = 0;
    binary.read(reinterpret_cast<char*>(&count), 4);
    EXPECT_EQ(count, triangles);
    write_surface(solids, SurfaceFormat::stl_ascii, dir / "bed_ascii.stl");
    std::ifstream ascii(dir / "bed_ascii.stl");
    std::string line, names;
    std::size_t facets = 0;
    while (std::getline(ascii, line)) {
        if (line.rfind("solid ", 0) == 0)
            names += line.substr(6) + ",";
        facets += line.rfind(" facet normal", 0) == 0 ? 1 : 0;
    }
    EXPECT_EQ(names, "particles,wall,bottom,top,");
    EXPECT_EQ(facets, triangles);
    std::filesystem::remove_all(dir);
}

TEST(Surface, SnappingAvoidsSliverTrianglesAtTheCut) {
    const TriangleMesh ball = icosphere(3);
    const double edge = 1.0515 / 8.0;
    auto smallest_area = [](const TriangleMesh& m) {
        double least = 1.0;
        for (const auto& t : m.triangles) {
            const Vec3 a = m.vertices[t[1]] - m.vertices[t[0]];
            const Vec3 b = m.vertices[t[2]] - m.vertices[t[0]];
            const Vec3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
            least = std::min(least, 0.5 * norm(c));
        }
        return least;
    };
    double worst_plain = 1.0, worst_snapped = 1.0;
    for (int k = 0; k < 50; ++k) { // planes at many heights and tilts
        const double tilt = 0.03 * k;
        const Vec3 n{std::sin(tilt), 0.0, std::cos(tilt)};
        const HalfSpace h{n, 0.3 + 0.011 * k};
        const TriangleMesh plain = clip_convex(ball, h);
        const TriangleMesh snapped = clip_convex(ball, h, 0.02 * edge);
        EXPECT_TRUE(closed_and_oriented({&snapped}));
        for (const Vec3& v : snapped.vertices) {
            EXPECT_LE(dot(n, v), h.offset + 1e-15); // never beyond the plane
            EXPECT_LE(norm(v), 1.0 + 1e-15);        // never outside the ball
        }
        worst_plain = std::min(worst_plain, smallest_area(plain));
        worst_snapped = std::min(worst_snapped, smallest_area(snapped));
    }
    // A triangle of the level-3 icosphere has an area of about 0.0048.
    // Measured: 2.5e-10 without snapping, 6.2e-6 with it (short edges of the cut's fan).
    EXPECT_LT(worst_plain, 1e-8);
    EXPECT_GT(worst_snapped, 2e-6);
}

TEST(Surface, TheSameMeshesWhateverTheThreads) {
    Packing p;
    for (int i = 0; i < 40; ++i) // a column of touching spheres, zigzag
        p.add({0.3 * (i % 2), 0.0, 0.5 + 0.954 * i}, 0.5);
    SurfaceOptions o;
    o.level = 2;
    o.container = cylinder(2.0, 40.0);
    const auto bodies = treat_contacts(p, parse_contacts("caps:0.02"), o.container);
    omp_set_num_threads(1);
    const auto one = bed_surface(bodies, o);
    omp_set_num_threads(2);
    const auto two = bed_surface(bodies, o);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t s = 0; s < one.size(); ++s) {
        EXPECT_EQ(one[s].mesh.vertices, two[s].mesh.vertices);
        EXPECT_EQ(one[s].mesh.triangles, two[s].mesh.triangles);
    }
    std::size_t cut = 0;
    for (const TreatedBody& b : bodies.bodies)
        cut += b.cuts.size();
    EXPECT_EQ(cut, 2u * 39u + 1u); // every neighbour pair capped, the lowest on the floor too
}

TEST(Surface, EnlargeOnTwoTouchingSpheresIsTheirUnion) {
    const Packing p = two_touching();
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("enlarge:0.02"), box);
    EXPECT_TRUE(bed.unite);
    EXPECT_DOUBLE_EQ(bed.bodies[0].radius, 0.51);
    EXPECT_TRUE(bed.bodies[0].cuts.empty()); // floor 0.49 away: no cap
    // Two balls of radius 0.51, centres 1 apart, minus their lens
    // pi (4 r + d) (2 r - d)^2 / 12 = pi 3.04 0.02^2 / 12.
    const double ball = 4.0 / 3.0 * pi * 0.51 * 0.51 * 0.51;
    const double lens = pi * 3.04 * 0.0004 / 12.0;
    const TreatmentVolumes v = treatment_volumes(p, bed, box);
    EXPECT_NEAR(v.treated_solid, 2.0 * ball - lens, 1e-14);
    SurfaceOptions o;
    o.level = 5;
    o.container = box;
    o.write_container = false;
    const auto solids = bed_surface(bed, o);
    ASSERT_EQ(solids.size(), 1u);
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh})); // one closed body, the union
    EXPECT_NEAR(solids[0].mesh.volume() / v.treated_solid, 1.0, 1.5e-3);
    EXPECT_LT(solids[0].mesh.volume(), v.treated_solid);
}

TEST(Surface, EnlargeOnASphereTouchingTheWallAndTheFloor) {
    Packing p;
    p.add({1.5, 0.0, 0.5}, 0.5);
    const SurfaceContainer c = cylinder(2.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("enlarge:0.02"), c);
    ASSERT_EQ(bed.bodies[0].cuts.size(), 2u);
    // Radius 0.51 pressing 0.01 into the floor and the wall, cut 0.02 from each: two caps of
    // height 0.03, pi 0.03^2 (1.53 - 0.03) / 3 each.
    const double cap = pi * 0.0009 * 1.5 / 3.0;
    const TreatmentVolumes v = treatment_volumes(p, bed, c);
    EXPECT_NEAR(v.treated_solid, 4.0 / 3.0 * pi * 0.51 * 0.51 * 0.51 - 2.0 * cap, 1e-14);
    SurfaceOptions o;
    o.level = 4;
    o.container = c;
    const auto solids = bed_surface(bed, o);
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh}));
    for (const Vec3& x : solids[0].mesh.vertices) {
        EXPECT_LE(x.x, 1.98 + 1e-12);
        EXPECT_GE(x.z, 0.02 - 1e-12);
    }
}

TEST(Surface, BridgesOnTwoTouchingSpheres) {
    const Packing p = two_touching();
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("bridges:0.2"), box);
    ASSERT_EQ(bed.bridges.size(), 1u);
    EXPECT_DOUBLE_EQ(bed.bridges[0].radius, 0.1);
    // The bridge adds what lies within 0.1 of the axis between the two spheres: the gap at
    // distance s from the axis is 1 - 2 sqrt(0.25 - s^2), so the volume is the integral of
    // 2 pi s (1 - 2 sqrt(0.25 - s^2)) ds from 0 to 0.1 = pi 0.01 - 4 pi / 3 (0.125 - 0.24^1.5).
    const double added = pi * 0.01 - 4.0 * pi / 3.0 * (0.125 - std::pow(0.24, 1.5));
    EXPECT_NEAR(added, 3.163e-4, 1e-7);
    const TreatmentVolumes v = treatment_volumes(p, bed, box);
    EXPECT_NEAR(v.treated_solid, 2.0 * sphere_volume(0.5) + added, 1e-14);
    SurfaceOptions o;
    o.level = 5;
    o.container = box;
    o.write_container = false;
    const auto solids = bed_surface(bed, o);
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh}));
    // The tessellation loses 0.1 % of each ball and of the bridge's prism.
    EXPECT_NEAR(solids[0].mesh.volume() / v.treated_solid, 1.0, 1.5e-3);
}

TEST(Surface, CapsAndBridgesBetweenUnequalSpheres) {
    // Radii 0.5 and 1 touching at x = 0 (centres at -0.5 and 1, z = 1.5); the mean
    // diameter Dp = 1.5 sets the treatments' lengths.
    Packing p;
    p.add({-0.5, 0.0, 1.5}, 0.5);
    p.add({1.0, 0.0, 1.5}, 1.0);
    const SurfaceContainer tube = cylinder(3.0, 3.0);
    // caps:0.02: faces 0.03 apart about the contact point, a cap of height 0.015 off each
    // sphere, each with its own radius: pi h^2 (3 r - h) / 3.
    const TreatedBed capped = treat_contacts(p, parse_contacts("caps:0.02"), tube);
    ASSERT_EQ(capped.bodies[0].cuts.size(), 1u);
    ASSERT_EQ(capped.bodies[1].cuts.size(), 1u);
    EXPECT_NEAR(capped.bodies[0].cuts[0].offset, -0.015, 1e-15); // x <= -0.015
    EXPECT_NEAR(capped.bodies[1].cuts[0].offset, -0.015, 1e-15); // -x <= -0.015
    const double h = 0.015;
    const double small_cap = pi * h * h * (1.5 - h) / 3.0, large_cap = pi * h * h * (3.0 - h) / 3.0;
    const TreatmentVolumes v = treatment_volumes(p, capped, tube);
    EXPECT_NEAR(v.untouched_solid, sphere_volume(0.5) + sphere_volume(1.0), 1e-14);
    EXPECT_NEAR(v.treated_solid, sphere_volume(0.5) + sphere_volume(1.0) - small_cap - large_cap,
                1e-14);
    // bridges:0.2: a cylinder of radius 0.15 about the line of centres adds, at distance s from
    // it, the gap (1 - sqrt(1 - s^2)) + (0.5 - sqrt(0.25 - s^2)); integrated,
    // pi rho^2 1.5 - 2 pi / 3 ((1 - (1 - rho^2)^1.5) + (0.125 - (0.25 - rho^2)^1.5)).
    const TreatedBed bridged = treat_contacts(p, parse_contacts("bridges:0.2"), tube);
    ASSERT_EQ(bridged.bridges.size(), 1u);
    const double rho = 0.15;
    EXPECT_DOUBLE_EQ(bridged.bridges[0].radius, rho);
    const double added = pi * rho * rho * 1.5 - 2.0 * pi / 3.0 *
                                                    ((1.0 - std::pow(1.0 - rho * rho, 1.5)) +
                                                     (0.125 - std::pow(0.25 - rho * rho, 1.5)));
    EXPECT_NEAR(treatment_volumes(p, bridged, tube).treated_solid,
                sphere_volume(0.5) + sphere_volume(1.0) + added, 1e-14);
}

TEST(Surface, BridgesOnASphereTouchingTheWall) {
    Packing p;
    p.add({1.5, 0.0, 1.0}, 0.5); // touches the wall of radius 2 only
    const SurfaceContainer c = cylinder(2.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("bridges:0.2"), c);
    EXPECT_TRUE(bed.bridges.empty());
    ASSERT_EQ(bed.bodies[0].cuts.size(), 1u);
    // The wall contact is capped bridge_gap = 0.01 Dp from the wall: a cap of height 0.01.
    const TreatmentVolumes v = treatment_volumes(p, bed, c);
    EXPECT_NEAR(v.treated_solid, sphere_volume(0.5) - pi * 1e-4 * (1.5 - 0.01) / 3.0, 1e-14);
}

TEST(Surface, UnionTreatmentsRefuseWhatTheirVolumesCannotHold) {
    Packing deep; // overlapping by 0.1 Dp: the lens rim has radius 0.218
    deep.add({0.0, 0.0, 1.0}, 0.5);
    deep.add({0.9, 0.0, 1.0}, 0.5);
    const SurfaceContainer box = cylinder(3.0, 2.0);
    EXPECT_THROW(treat_contacts(deep, parse_contacts("bridges:0.2"), box), InvalidInput);
    EXPECT_NO_THROW(treat_contacts(deep, parse_contacts("bridges:0.45"), box));
    Packing t; // three spheres touching in a triangle
    t.add({0.0, 0.0, 1.0}, 0.5);
    t.add({1.0, 0.0, 1.0}, 0.5);
    t.add({0.5, std::sqrt(0.75), 1.0}, 0.5);
    EXPECT_THROW(treat_contacts(t, parse_contacts("enlarge:0.45"), box), InvalidInput);
    // Where they are accepted, the closed forms are the volume of the union CGAL builds, to
    // the tessellation's deficit (level 5: below 0.15 %).
    for (const char* text : {"enlarge:0.05", "bridges:0.3"}) {
        const TreatedBed bed = treat_contacts(t, parse_contacts(text), box);
        SurfaceOptions o;
        o.level = 5;
        o.container = box;
        o.write_container = false;
        const auto solids = bed_surface(bed, o);
        EXPECT_TRUE(closed_and_oriented({&solids[0].mesh})) << text;
        const double exact = treatment_volumes(t, bed, box).treated_solid;
        EXPECT_NEAR(solids[0].mesh.volume() / exact, 1.0, 1.5e-3) << text;
        EXPECT_LT(solids[0].mesh.volume(), exact) << text;
    }
}

TEST(Surface, NoneOnTwoTouchingSpheresAndOnASphereTouchingTheWall) {
    const SurfaceContainer box = cylinder(3.0, 2.0);
    const Packing two = two_touching();
    const TreatedBed bed = treat_contacts(two, parse_contacts("none"), box);
    EXPECT_FALSE(bed.unite);
    const TreatmentVolumes v = treatment_volumes(two, bed, box);
    EXPECT_NEAR(v.untouched_solid, 2.0 * sphere_volume(0.5), 1e-14); // touching: no lens
    EXPECT_EQ(v.treated_solid, v.untouched_solid);
    Packing wall;
    wall.add({1.5, 0.0, 1.0}, 0.5);
    const SurfaceContainer c = cylinder(2.0, 2.0);
    const TreatmentVolumes w = treatment_volumes(wall, treat_contacts(wall, {}, c), c);
    EXPECT_NEAR(w.untouched_solid, sphere_volume(0.5), 1e-12); // inside, touching the wall
    EXPECT_NEAR(w.untouched_void_fraction, 1.0 - sphere_volume(0.5) / (8.0 * pi), 1e-12);
}

TEST(Surface, ObjSharesVerticesAndNamesItsGroups) {
    const Packing p = two_touching();
    SurfaceOptions o;
    o.level = 2;
    o.container = cylinder(3.0, 2.0);
    const auto solids =
        bed_surface(treat_contacts(p, parse_contacts("bridges:0.2"), o.container), o);
    std::size_t vertices = 0, triangles = 0;
    for (const Solid& s : solids) {
        vertices += s.mesh.vertices.size();
        triangles += s.mesh.triangles.size();
    }
    const auto dir = std::filesystem::temp_directory_path() / "packbed_test_obj";
    std::filesystem::create_directories(dir);
    write_surface(solids, SurfaceFormat::obj, dir / "bed.obj");
    std::ifstream in(dir / "bed.obj");
    std::string line, groups;
    std::size_t v = 0, f = 0, largest_index = 0;
    while (std::getline(in, line)) {
        v += line.rfind("v ", 0) == 0 ? 1 : 0;
        if (line.rfind("f ", 0) == 0) {
            ++f;
            std::istringstream row(line.substr(2));
            for (std::size_t k; row >> k;)
                largest_index = std::max(largest_index, k);
        }
        if (line.rfind("g ", 0) == 0)
            groups += line.substr(2) + ",";
    }
    EXPECT_EQ(v, vertices);
    EXPECT_EQ(f, triangles);
    EXPECT_EQ(largest_index, vertices); // 1-based, global
    EXPECT_EQ(groups, "particles,wall,bottom,top,");
    std::filesystem::remove_all(dir);
}

TEST(Surface, TheSameUnionWhateverTheThreads) {
    Packing p;
    for (int i = 0; i < 6; ++i)
        p.add({0.3 * (i % 2), 0.0, 0.5 + 0.954 * i}, 0.5);
    SurfaceOptions o;
    o.level = 2;
    o.container = cylinder(2.0, 7.0);
    o.write_container = false;
    const TreatedBed bed = treat_contacts(p, parse_contacts("enlarge:0.02"), o.container);
    omp_set_num_threads(1);
    const auto one = bed_surface(bed, o);
    omp_set_num_threads(2);
    const auto two = bed_surface(bed, o);
    EXPECT_EQ(one[0].mesh.vertices, two[0].mesh.vertices);
    EXPECT_EQ(one[0].mesh.triangles, two[0].mesh.triangles);
    EXPECT_TRUE(closed_and_oriented({&one[0].mesh}));
}

TEST(Surface, TheSameBridgedUnionWhateverTheThreadsAndTheRun) {
    // 27 touching balls of a simple cubic block and their 54 bridges: CGAL's corefinement
    // numbers its output by memory addresses, which two threads change from run to run (it gave
    // other bytes nearly every run); the union is built in one order whatever they are.
    Packing p;
    for (int i = 0; i < 27; ++i)
        p.add({1.0 + (i % 3), 1.0 + (i / 3 % 3), 0.5 + (i / 9)}, 0.5);
    SurfaceOptions o;
    o.level = 2;
    o.container = cylinder(8.0, 4.0);
    o.write_container = false;
    const TreatedBed bed = treat_contacts(p, parse_contacts("bridges:0.2"), o.container);
    ASSERT_EQ(bed.bridges.size(), 54u);
    omp_set_num_threads(1);
    const auto one = bed_surface(bed, o);
    omp_set_num_threads(2);
    for (int run = 0; run < 3; ++run) {
        const auto two = bed_surface(bed, o);
        EXPECT_EQ(one[0].mesh.vertices, two[0].mesh.vertices) << run;
        EXPECT_EQ(one[0].mesh.triangles, two[0].mesh.triangles) << run;
    }
    EXPECT_TRUE(closed_and_oriented({&one[0].mesh}));
}

// A bed in a box. The wall cuts are one per face closer than the gap (two in a
// corner), the container's volume is LX LY H, and the solids are the box's faces.
namespace {

SurfaceContainer box(double lx, double ly, double height) {
    return {Box(lx, ly), height};
}

/// The volume of the cap a plane s from the centre cuts from a ball of radius r, by hand.
double cap(double r, double s) {
    const double c = r - s;
    return pi * c * c * (3.0 * r - c) / 3.0;
}

} // namespace

TEST(SurfaceBox, WallCutsAreOnePerNearFaceTwoInACorner) {
    const Container b = Box(4.0, 3.0);
    // In the corner (x_low, y_low), touching both faces: two planes, normals -x and -y.
    const std::vector<WallPlane> corner = b.walls_within({0.5, 0.5, 1.0}, 0.5, 0.05);
    ASSERT_EQ(corner.size(), 2u);
    EXPECT_EQ(corner[0].normal, (Vec3{-1.0, 0.0, 0.0}));
    EXPECT_EQ(corner[0].offset, 0.0);
    EXPECT_EQ(corner[1].normal, (Vec3{0.0, -1.0, 0.0}));
    // At the middle of the face x = 4, 0.04 from it: one plane; 0.06 from it: none.
    const std::vector<WallPlane> face = b.walls_within({3.46, 1.5, 1.0}, 0.5, 0.05);
    ASSERT_EQ(face.size(), 1u);
    EXPECT_EQ(face[0].normal, (Vec3{1.0, 0.0, 0.0}));
    EXPECT_EQ(face[0].offset, 4.0);
    EXPECT_TRUE(b.walls_within({3.44, 1.5, 1.0}, 0.5, 0.05).empty());
    // The far corner (x_high, y_high), and a box off the origin.
    const std::vector<WallPlane> far = b.walls_within({3.5, 2.5, 1.0}, 0.5, 0.01);
    ASSERT_EQ(far.size(), 2u);
    EXPECT_EQ(far[1].normal, (Vec3{0.0, 1.0, 0.0}));
    EXPECT_EQ(far[1].offset, 3.0);
    // Tangent to x = -2, 0.1 beyond y = 9.
    const std::vector<WallPlane> off =
        Container(Box(-2.0, 1.0, 5.0, 9.0)).walls_within({-1.5, 8.6, 1.0}, 0.5, 0.01);
    ASSERT_EQ(off.size(), 2u);
    EXPECT_EQ(off[0].offset, 2.0); // -x <= 2: x >= -2
    EXPECT_EQ(off[1].offset, 9.0);
    // The cylinder's, as the treatments always cut it: the tangent plane at the nearest point.
    const std::vector<WallPlane> tube =
        Container(Cylinder(2.0)).walls_within({0.0, 1.5, 1.0}, 0.5, 0.02);
    ASSERT_EQ(tube.size(), 1u);
    EXPECT_EQ(tube[0].normal, (Vec3{0.0, 1.0, 0.0}));
    EXPECT_EQ(tube[0].offset, 2.0);
    EXPECT_TRUE(Container(Cylinder(2.0)).walls_within({0.0, 0.0, 1.0}, 0.5, 2.0).empty());
}

TEST(SurfaceBox, CapsOnASphereInACornerOfTheFloor) {
    Packing p;
    p.add({0.5, 0.5, 0.5}, 0.5); // touches the floor and the faces x = 0 and y = 0
    const SurfaceContainer c = box(4.0, 3.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("caps:0.05"), c);
    ASSERT_EQ(bed.bodies[0].cuts.size(), 3u); // floor, x = 0, y = 0
    const TreatmentVolumes v = treatment_volumes(p, bed, c);
    EXPECT_DOUBLE_EQ(v.container_volume, 24.0);
    EXPECT_NEAR(v.untouched_solid, sphere_volume(0.5), 1e-15); // whole, tangent to three faces
    // Three caps of height 0.05: pi 0.05^2 (1.5 - 0.05) / 3 = 3.7961e-3 each.
    EXPECT_NEAR(cap(0.5, 0.45), 3.79609e-3, 1e-8);
    EXPECT_NEAR(v.treated_solid, sphere_volume(0.5) - 3.0 * cap(0.5, 0.45), 1e-15);
    EXPECT_NEAR(v.treated_void_fraction, 1.0 - v.treated_solid / 24.0, 1e-15);
    SurfaceOptions o;
    o.level = 5;
    o.container = c;
    const auto solids = bed_surface(bed, o);
    ASSERT_EQ(solids.size(), 7u); // particles and the six faces of the box
    EXPECT_TRUE(closed_and_oriented({&solids[0].mesh}));
    // H Dp from every face it touched, flat there.
    for (const Vec3& x : solids[0].mesh.vertices) {
        EXPECT_GE(x.x, 0.05 - 1e-15);
        EXPECT_GE(x.y, 0.05 - 1e-15);
        EXPECT_GE(x.z, 0.05 - 1e-15);
    }
    EXPECT_NEAR(solids[0].mesh.volume() / v.treated_solid, 1.0, 1.5e-3);
    EXPECT_LT(solids[0].mesh.volume(), v.treated_solid);
}

TEST(SurfaceBox, CapsOnASimpleCubicBlockCountEveryContactAndFace) {
    // 2 x 2 x 1 touching balls of diameter 1 filling the box [0, 2] x [0, 2]: each ball
    // touches two neighbours, two faces and the floor.
    Packing p;
    for (const double x : {0.5, 1.5})
        for (const double y : {0.5, 1.5})
            p.add({x, y, 0.5}, 0.5);
    const SurfaceContainer c = box(2.0, 2.0, 2.0);
    const TreatedBed bed = treat_contacts(p, parse_contacts("caps:0.05"), c);
    for (const TreatedBody& b : bed.bodies)
        EXPECT_EQ(b.cuts.size(), 5u);
    const TreatmentVolumes v = treatment_volumes(p, bed, c);
    EXPECT_DOUBLE_EQ(v.container_volume, 8.0);
    EXPECT_NEAR(v.untouched_solid, 4.0 * sphere_volume(0.5), 1e-14);
    EXPECT_NEAR(v.untouched_void_fraction, 1.0 - pi / 12.0, 1e-15); // 4 pi / 6 in 8
    // Pair caps of height H / 2 = 0.025 on each side; wall and floor caps of height H.
    EXPECT_NEAR(v.treated_solid,
                4.0 * (sphere_volume(0.5) - 2.0 * cap(0.5, 0.475) - 3.0 * cap(0.5, 0.45)), 1e-14);
    SurfaceOptions o;
    o.level = 3;
    o.container = c;
    const auto solids = bed_surface(bed, o);
    ASSERT_EQ(solids.size(), 7u); // particles and the box's six faces
    EXPECT_EQ(solids[1].name, "x_low");
    EXPECT_EQ(solids[6].name, "top");
    EXPECT_TRUE(closed_and_oriented({&solids[1].mesh, &solids[2].mesh, &solids[3].mesh,
                                     &solids[4].mesh, &solids[5].mesh, &solids[6].mesh}));
    for (const Vec3& x : solids[0].mesh.vertices) { // inside, 0.05 clear of every face
        EXPECT_GE(std::min({x.x, x.y, 2.0 - x.x, 2.0 - x.y, x.z}), 0.05 - 1e-14);
    }
}

TEST(SurfaceBox, ShrinkEnlargeAndBridgesAtTheFaces) {
    // Tangent to the face x = 0: shrink separates it; a sphere poking 0.01 through the face
    // needs F above 0.02.
    Packing tangent;
    tangent.add({0.5, 1.0, 1.0}, 0.5);
    const SurfaceContainer c = box(2.0, 2.0, 2.0);
    EXPECT_NO_THROW(treat_contacts(tangent, parse_contacts("shrink:0.01"), c));
    Packing poking;
    poking.add({0.49, 1.0, 1.0}, 0.5);
    EXPECT_THROW(treat_contacts(poking, parse_contacts("shrink:0.02"), c), InvalidInput);
    EXPECT_NO_THROW(treat_contacts(poking, parse_contacts("shrink:0.03"), c));
    // Enlarge in the corner of the floor: radius 0.51 pressing 0.01 into three faces, cut
    // 0.02 from each: three caps of height 0.03.
    Packing corner;
    corner.add({0.5, 0.5, 0.5}, 0.5);
    const TreatedBed big = treat_contacts(corner, parse_contacts("enlarge:0.02"), c);
    ASSERT_EQ(big.bodies[0].cuts.size(), 3u);
    EXPECT_NEAR(treatment_volumes(corner, big, c).treated_solid,
                4.0 / 3.0 * pi * 0.51 * 0.51 * 0.51 - 3.0 * cap(0.51, 0.48), 1e-14);
    // Bridges: the face contact capped bridge_gap = 0.01 Dp from the face.
    const TreatedBed bridged = treat_contacts(tangent, parse_contacts("bridges:0.2"), c);
    ASSERT_EQ(bridged.bodies[0].cuts.size(), 1u);
    EXPECT_EQ(bridged.bodies[0].cuts[0].offset, -0.01); // -x <= -0.01
    EXPECT_NEAR(treatment_volumes(tangent, bridged, c).treated_solid,
                sphere_volume(0.5) - cap(0.5, 0.49), 1e-15);
}

TEST(SurfaceBox, ContainerSolidsAreTheBoxClosedOutwardAndWatertight) {
    // The box [1, 2] x [-1, 0.5] from z = 0 to 3, triangles about 0.3 wide: 4, 5 and 10 cells
    // along x, y, z (1.5 / 0.3 is 5 to the last bits). One named solid per face.
    const Box b(1.0, 2.0, -1.0, 0.5);
    const auto solids = b.solids(0.0, 3.0, 0.3);
    ASSERT_EQ(solids.size(), 6u);
    std::vector<std::string> names;
    std::vector<const TriangleMesh*> meshes;
    for (const Solid& s : solids) {
        names.push_back(s.name);
        meshes.push_back(&s.mesh);
    }
    EXPECT_EQ(names,
              (std::vector<std::string>{"x_low", "x_high", "y_low", "y_high", "bottom", "top"}));
    EXPECT_EQ(solids[0].mesh.triangles.size(), 2u * 5u * 10u); // x faces: 5 cells along y
    EXPECT_EQ(solids[1].mesh.triangles.size(), 2u * 5u * 10u);
    EXPECT_EQ(solids[2].mesh.triangles.size(), 2u * 4u * 10u); // y faces: 4 cells along x
    EXPECT_EQ(solids[3].mesh.triangles.size(), 2u * 4u * 10u);
    EXPECT_EQ(solids[4].mesh.triangles.size(), 2u * 4u * 5u);
    EXPECT_EQ(solids[5].mesh.triangles.size(), 2u * 4u * 5u);
    // Closed and outward together (shared rims at the same bits), not without any one face.
    EXPECT_TRUE(closed_and_oriented(meshes));
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        std::vector<const TriangleMesh*> five = meshes;
        five.erase(five.begin() + static_cast<std::ptrdiff_t>(k));
        EXPECT_FALSE(closed_and_oriented(five)) << names[k];
    }
    TriangleMesh all;
    for (const Solid& s : solids)
        all.append(s.mesh);
    EXPECT_NEAR(all.volume(), 1.0 * 1.5 * 3.0, 1e-13);
    // Every vertex of a face on its plane, every normal pointing out of the box, no edge
    // longer than a cell's diagonal (0.25 x 0.3 x 0.3).
    const auto on_face = [](std::size_t face, const Vec3& v) {
        const double value[6] = {v.x, v.x, v.y, v.y, v.z, v.z};
        const double plane[6] = {1.0, 2.0, -1.0, 0.5, 0.0, 3.0};
        return value[face] == plane[face];
    };
    const Vec3 outward[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    double area = 0.0;
    for (std::size_t face = 0; face < 6; ++face)
        for (const auto& t : solids[face].mesh.triangles) {
            const Vec3 a = solids[face].mesh.vertices[t[0]], p = solids[face].mesh.vertices[t[1]],
                       q = solids[face].mesh.vertices[t[2]];
            const Vec3 n = cross(p - a, q - a);
            if (face < 4)
                area += 0.5 * norm(n);
            EXPECT_NEAR(dot(n, outward[face]) / norm(n), 1.0, 1e-12) << names[face];
            for (const Vec3& v : {a, p, q}) {
                EXPECT_TRUE(on_face(face, v)) << names[face];
                EXPECT_GE(v.x, 1.0);
                EXPECT_LE(v.x, 2.0);
                EXPECT_GE(v.y, -1.0);
                EXPECT_LE(v.y, 0.5);
            }
            EXPECT_LE(std::max({norm(a - p), norm(q - p), norm(a - q)}),
                      std::hypot(0.3, 0.3) + 1e-12);
        }
    EXPECT_NEAR(area, 2.0 * (1.0 + 1.5) * 3.0, 1e-12);
    // Through Container, the same solids; a cylinder's through Container are its own.
    const auto again = Container(b).solids(0.0, 3.0, 0.3);
    for (std::size_t k = 0; k < 6; ++k)
        EXPECT_EQ(again[k].mesh.vertices, solids[k].mesh.vertices);
    const auto tube = Container(Cylinder(2.0)).solids(0.0, 3.0, 0.3);
    EXPECT_EQ(tube[0].mesh.vertices, Cylinder(2.0).solids(0.0, 3.0, 0.3)[0].mesh.vertices);
    // A side shorter than the edge is one cell.
    for (const Solid& s : Box(0.1, 0.1).solids(0.0, 0.1, 1.0))
        EXPECT_EQ(s.mesh.triangles.size(), 2u) << s.name;
}
