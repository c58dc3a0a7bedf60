// The cone (cone.hpp): its wall law against distances computed by hand in the half-plane
// through the axis, its exact volumes against an independent quadrature, the cylinder's
// answers and beds to the bit where DB = DT, beds with both solvers inside the slanted wall,
// lattices, analysis and the wall's surface outside the cone, its refusals.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "packbed/analysis.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/lattice.hpp"
#include "packbed/read.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/volume.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// The signed distance of the point (rho, z) beyond the line through (rb, 0) and (rt, h) in
/// the half-plane through the axis (positive outside): the cross product of the line's
/// direction with the point's offset, over the line's length.
double beyond_line(double rho, double z, double rb, double rt, double h) {
    const double dx = rt - rb, dz = h;
    return (dz * (rho - rb) - dx * z) / std::hypot(dx, dz);
}

/// The solver's parameters of a bed of `particles` spheres in `container`.
SoftSphereParameters bed_of(const Container& container, std::uint64_t particles, std::uint64_t seed,
                            Solver solver = SoftSphereParameters{}.solver) {
    SoftSphereParameters p;
    p.container = container;
    p.particles = particles;
    p.seed = seed;
    p.solver = solver;
    return p;
}

} // namespace

TEST(Cone, WallOverlapIsTheDistanceAlongTheSlantedWallsNormal) {
    // cone:4,8,10: Rb = 2, Rt = 4, H = 10. A sphere of radius 0.5 at rho = 2.6, z = 5 (the wall
    // at R(5) = 3): by hand, the line through (2, 0) and (4, 10), offset (0.6, 5), cross
    // product 0.6 x 10 - 5 x 2 = -4 over sqrt(104): 0.392232 inside, overlap 0.107768; the
    // push along the inward normal (-10, 2) / sqrt(104), up the wall.
    const Cone cone(2.0, 4.0, 10.0);
    const WallContact w = cone.wall_contact({2.6, 0.0, 5.0}, 0.5);
    EXPECT_NEAR(w.overlap, 0.5 - 4.0 / std::sqrt(104.0), 1e-15);
    EXPECT_NEAR(w.overlap, 0.107767729723632, 1e-15);
    EXPECT_NEAR(w.push.x, -10.0 / std::sqrt(104.0), 1e-15);
    EXPECT_NEAR(w.push.y, 0.0, 1e-15);
    EXPECT_NEAR(w.push.z, 2.0 / std::sqrt(104.0), 1e-15);
    EXPECT_NEAR(cone.wall_distance({2.6, 0.0, 5.0}), 4.0 / std::sqrt(104.0), 1e-15);
    // On the diagonal x = y the push turns with the centre; a narrowing cone pushes down.
    const Cone narrowing(4.0, 2.0, 10.0);
    const double s = 3.0 / std::sqrt(2.0);
    const WallContact n = narrowing.wall_contact({s, s, 5.0}, 0.5); // rho = 3 = R(5): overlap r
    EXPECT_NEAR(n.overlap, 0.5, 1e-14);
    EXPECT_NEAR(n.push.x, n.push.y, 1e-15);
    EXPECT_NEAR(n.push.z, -2.0 / std::sqrt(104.0), 1e-15);
    EXPECT_NEAR(norm(n.push), 1.0, 1e-15);

    // Random points of both cones against the line by hand, and the law's callback.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const Cone& c : {cone, narrowing})
        for (int k = 0; k < 1000; ++k) {
            const double rho = 5.0 * u(rng), angle = 2.0 * pi * u(rng), z = 10.0 * u(rng);
            const double r = 0.1 + 0.5 * u(rng);
            const Vec3 p{rho * std::cos(angle), rho * std::sin(angle), z};
            const double by_hand =
                beyond_line(rho, z, c.floor_radius(), c.top_radius(), c.height()) + r;
            EXPECT_NEAR(c.wall_contact(p, r).overlap, by_hand, 1e-13);
            EXPECT_NEAR(c.wall_distance(p), r - by_hand, 1e-13);
            EXPECT_EQ(c.contains(p), rho <= c.radius_at(z));
            double called = 0.0;
            c.wall_contacts(p, r, [&](double o, const Vec3&) { called = o; });
            EXPECT_EQ(called, by_hand > 1e-12 ? c.wall_contact(p, r).overlap : 0.0);
            // The wall's tangent plane where the sphere comes within 1 of it: the nearest
            // point of the wall lies on it.
            for (const WallPlane& plane : c.walls_within(p, r, 1.0)) {
                const Vec3 foot = p + (c.wall_distance(p)) * plane.normal;
                EXPECT_NEAR(dot(plane.normal, foot), plane.offset, 1e-12);
                EXPECT_NEAR(std::hypot(foot.x, foot.y), c.radius_at(foot.z), 1e-12);
            }
        }
}

TEST(Cone, WithEqualDiametersItIsTheCylinderToTheBit) {
    // The wall law, the initial height and the starting points decide a bed: each is the
    // cylinder's to the bit, so both solvers give the same bytes.
    const Cone cone(4.0, 4.0, 60.0);
    const Cylinder cylinder(4.0);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p{9.0 * u(rng) - 4.5, 9.0 * u(rng) - 4.5, 30.0 * u(rng)};
        const WallContact a = cone.wall_contact(p, 0.5), b = cylinder.wall_contact(p, 0.5);
        EXPECT_EQ(a.overlap, b.overlap);
        EXPECT_EQ(a.push.x, b.push.x);
        EXPECT_EQ(a.push.y, b.push.y);
        EXPECT_EQ(a.push.z, b.push.z);
    }
    for (const Solver solver : {Solver::paper, Solver::fire}) {
        SoftSphereParameters p = bed_of(cone, 150, 5, solver);
        const SoftSphereResult in_cone = generate_soft_sphere(p);
        p.container = cylinder;
        const SoftSphereResult in_cylinder = generate_soft_sphere(p);
        ASSERT_EQ(in_cone.packing.size(), in_cylinder.packing.size());
        EXPECT_EQ(in_cone.iterations, in_cylinder.iterations);
        for (std::size_t i = 0; i < in_cone.packing.size(); ++i) {
            EXPECT_EQ(in_cone.packing.centers[i].x, in_cylinder.packing.centers[i].x);
            EXPECT_EQ(in_cone.packing.centers[i].y, in_cylinder.packing.centers[i].y);
            EXPECT_EQ(in_cone.packing.centers[i].z, in_cylinder.packing.centers[i].z);
        }
    }
}

TEST(Cone, BedsWithBothSolversEndInsideTheSlantedWall) {
    // A hopper (widening upwards) and a cone narrowing upwards; every pair and every wall by
    // brute force below 1e-4 Dp, every centre inside, the bed denser than the start (e0 =
    // 0.47) and looser than the densest packing.
    for (const Cone& cone : {Cone(2.0, 4.0, 30.0), Cone(3.5, 2.5, 30.0)})
        for (const Solver solver : {Solver::paper, Solver::fire}) {
            const SoftSphereResult r = generate_soft_sphere(bed_of(cone, 220, 7, solver));
            const Packing& b = r.packing;
            double pair = 0.0, wall = 0.0, floor = 0.0;
            for (std::size_t i = 0; i < b.size(); ++i) {
                for (std::size_t j = i + 1; j < b.size(); ++j)
                    pair =
                        std::max(pair, b.radii[i] + b.radii[j] - norm(b.centers[j] - b.centers[i]));
                const double rho = std::hypot(b.centers[i].x, b.centers[i].y);
                wall = std::max(wall, beyond_line(rho, b.centers[i].z, cone.floor_radius(),
                                                  cone.top_radius(), cone.height()) +
                                          b.radii[i]);
                floor = std::max(floor, b.radii[i] - b.centers[i].z);
                EXPECT_TRUE(cone.contains(b.centers[i]));
            }
            EXPECT_LT(pair, 1e-4) << cone.spec();
            EXPECT_LT(wall, 1e-4) << cone.spec();
            EXPECT_LT(floor, 1e-4) << cone.spec();
            EXPECT_LT(r.max_overlap_wall, 1e-4);
            const auto band = band_clear_of_ends(b, 2.0);
            ASSERT_TRUE(band);
            const double e = void_fraction(b, cone, band->z_low, band->z_high);
            EXPECT_GT(e, 0.34) << cone.spec();
            EXPECT_LT(e, 0.47) << cone.spec();
        }
}

TEST(Cone, StartingCentresAreInsideTheWallAtTheirHeight) {
    // Section 3.1 over the disk at each height: every centre at least r from the slanted wall,
    // in a cone narrowing upwards as in one widening.
    for (const Cone& cone : {Cone(2.0, 6.0, 40.0), Cone(6.0, 3.0, 40.0)}) {
        SoftSphereParameters p;
        p.container = cone;
        p.particles = 1500;
        const SoftSphereGenerator g(p);
        for (const Vec3& x : g.packing_dp().centers)
            EXPECT_LE(cone.wall_contact(x, 0.5).overlap, 1e-12) << cone.spec();
    }
}

TEST(Cone, InitialHeightHoldsTheSolidAtE0AndABedAboveTheTopIsRefused) {
    // cone:4,8,40 (Rb = 2, k = 0.05): 200 spheres at e0 = 0.47 take V = (pi / 6) 200 / 0.53;
    // the frustum up to L0 holds exactly that.
    SoftSphereParameters p;
    p.particles = 200;
    p.container = Cone(2.0, 4.0, 40.0);
    const double l0 = initial_bed_height(p);
    EXPECT_NEAR(frustum_volume(2.0, 0.05, 0.0, l0), pi / 6.0 * 200.0 / 0.53, 1e-9);
    // Narrowing to a point above: more than the cone to its apex holds cannot start.
    p.container = Cone(4.0, 1.0, 12.0);
    p.particles = 100000;
    EXPECT_TRUE(std::isinf(initial_bed_height(p)));
    EXPECT_THROW(p.validate(), InvalidInput);
    p.container = Cone(2.0, 4.0, 10.0);
    p.particles = 400; // L0 about 16 Dp
    try {
        p.validate();
        FAIL() << "a bed above H was not refused";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("below the container's top at 10 Dp"),
                  std::string::npos)
            << e.what();
    }
    p.particles = 100; // L0 about 4.2 Dp + the largest sphere: below 10
    EXPECT_NO_THROW(p.validate());
    p.container = Cone(0.4, 3.0, 10.0); // a floor narrower than a sphere
    EXPECT_THROW(p.validate(), InvalidInput);
}

TEST(Cone, FrustumVolumesInClosedForm) {
    // pi h (R1^2 + R1 R2 + R2^2) / 3; a cone from its apex at z = 1 (R = z - 1) to z = 3:
    // pi 2 4 / 3; nothing beyond the apex.
    EXPECT_NEAR(frustum_volume(2.0, 0.2, 0.0, 10.0), pi * 10.0 * (4.0 + 8.0 + 16.0) / 3.0, 1e-12);
    EXPECT_NEAR(frustum_volume(-1.0, 1.0, 0.0, 3.0), 8.0 * pi / 3.0, 1e-12);
    EXPECT_EQ(frustum_volume(-1.0, 1.0, -5.0, 1.0), 0.0);
    EXPECT_NEAR(frustum_volume(3.0, -1.0, 0.0, 9.0), 9.0 * pi, 1e-12); // apex at 3
    const Cone cone(2.0, 4.0, 10.0);
    EXPECT_NEAR(cone.cross_section_area(0.0, 10.0), pi * 28.0 / 3.0, 1e-12);
    EXPECT_NEAR(cone.cross_section_area(5.0, 5.0), 9.0 * pi, 1e-12);
    EXPECT_NEAR(Container(cone).prism_volume(10.0), pi * 280.0 / 3.0, 1e-12);
    // Shells from the wall add up to the cross-section; shrunk by d along the normal is the
    // cone whose radii are d / cos smaller.
    double sum = 0.0;
    for (int k = 0; k < 40; ++k)
        sum += cone.shell_area(0.1 * k, 0.1 * (k + 1), 1.0, 6.0);
    EXPECT_NEAR(sum, cone.cross_section_area(1.0, 6.0), 1e-11);
    const Cone in = cone.shrunk(0.5);
    EXPECT_NEAR(in.radius_at(3.0), cone.radius_at(3.0) - 0.5 * std::sqrt(104.0) / 10.0, 1e-14);
    EXPECT_NEAR(in.wall_distance({0.0, 0.0, 3.0}), cone.wall_distance({0.0, 0.0, 3.0}) - 0.5,
                1e-14);
}

TEST(Cone, SphereVolumesAgreeWithAnIndependentQuadrature) {
    // tanh-sinh (tolerance 1e-14) of the lens area between the heights where the slice changes
    // regime, found here by scanning the slice's regime on 4 000 heights and bisecting each
    // change: spheres of radius 0.5 across the walls of random cones (widening and
    // narrowing, some with the apex inside the sphere's heights), cut at random heights.
    std::mt19937_64 rng(2027);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    boost::math::quadrature::tanh_sinh<double> reference;
    double worst = 0.0;
    int cases = 0;
    for (int k = 0; k < 600; ++k) {
        const double slope = (u(rng) - 0.5) * (k % 10 == 0 ? 4.0 : 1.0);
        const double cz = 2.0 * u(rng);
        const double rc = 0.05 + 4.0 * u(rng); // the wall's radius at the centre's height
        const double rb = rc - slope * cz;
        const double rho = std::max(0.0, rc + (u(rng) - 0.5) * 1.2);
        const double z_low = cz - 0.6 + 0.4 * u(rng), z_high = cz + 0.6 - 0.4 * u(rng);
        auto wall = [&](double z) { return std::max(rb + slope * z, 0.0); };
        auto slice = [&](double z) {
            const double t = z - cz;
            return disk_intersection_area(std::sqrt(std::max(0.25 - t * t, 0.0)), wall(z), rho);
        };
        auto regime = [&](double z) {
            const double t = z - cz, s = std::sqrt(std::max(0.25 - t * t, 0.0)), w = wall(z);
            return s + rho <= w ? 0 : s + w <= rho ? 1 : w + rho <= s ? 2 : 3;
        };
        const double lo = std::max(z_low, cz - 0.5), hi = std::min(z_high, cz + 0.5);
        std::vector<double> cuts{lo, hi};
        const int steps = 4000;
        for (int i = 0; i < steps; ++i) {
            double a = lo + (hi - lo) * i / steps, b = lo + (hi - lo) * (i + 1) / steps;
            if (regime(a) == regime(b) && (rb + slope * a) * (rb + slope * b) > 0.0)
                continue;
            for (int j = 0; j < 60; ++j) {
                const double m = 0.5 * (a + b);
                const bool same =
                    regime(a) == regime(m) && (rb + slope * a) * (rb + slope * m) > 0.0;
                (same ? a : b) = m;
            }
            cuts.push_back(0.5 * (a + b));
        }
        std::sort(cuts.begin(), cuts.end());
        double expected = 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            if (cuts[i + 1] > cuts[i])
                expected += reference.integrate(slice, cuts[i], cuts[i + 1], 1e-14);
        const double got =
            sphere_volume_in_cone_slab({rho, 0.0, cz}, 0.5, rb, slope, z_low, z_high);
        if (expected > 1e-6) {
            worst = std::max(worst, std::abs(got - expected) / expected);
            ++cases;
        }
    }
    EXPECT_GT(cases, 400);
    EXPECT_LT(worst, 1e-8);
    std::printf("worst relative difference %.3g over %d cone-cut spheres\n", worst, cases);
    // A straight wall (slope 0) is the cylinder's routine's volume.
    for (int k = 0; k < 200; ++k) {
        const double rc = 0.3 + 3.0 * u(rng), rho = rc + (u(rng) - 0.5);
        const double a = sphere_volume_in_cone_slab({rho, 0.0, 1.0}, 0.5, rc, 0.0, 0.7, 1.4);
        const double b = sphere_volume_in_cylinder_slab({rho, 0.0, 1.0}, 0.5, rc, 0.7, 1.4);
        EXPECT_NEAR(a, b, 1e-9 * std::max(b, 1e-3));
    }
}

TEST(Cone, AnalysisOfAStraightConeIsTheCylinders) {
    // cone:8,8,60 measures from the same wall as cylinder:8: the void fractions, the radial
    // profile and the centre distribution agree to the quadrature's 1e-8.
    const SoftSphereResult r = generate_soft_sphere(bed_of(Cylinder(4.0), 500, 2));
    const BedAnalysis a = analyze_bed(r.packing, Cylinder(4.0), {});
    const BedAnalysis b = analyze_bed(r.packing, Cone(4.0, 4.0, 60.0), {});
    EXPECT_NEAR(a.void_fraction, b.void_fraction, 1e-9);
    ASSERT_EQ(a.radial_void_fraction.size(), b.radial_void_fraction.size());
    for (std::size_t k = 0; k < a.radial_void_fraction.size(); ++k)
        EXPECT_NEAR(a.radial_void_fraction[k].value, b.radial_void_fraction[k].value, 1e-7) << k;
    ASSERT_EQ(a.centre_distribution.size(), b.centre_distribution.size());
    for (std::size_t k = 0; k < a.centre_distribution.size(); ++k)
        EXPECT_NEAR(a.centre_distribution[k].value, b.centre_distribution[k].value, 1e-9) << k;
    for (std::size_t k = 0; k < a.axial_void_fraction.size(); ++k)
        EXPECT_NEAR(a.axial_void_fraction[k].value, b.axial_void_fraction[k].value, 1e-8) << k;
    EXPECT_EQ(a.coordination.mean, b.coordination.mean);
}

TEST(Cone, LatticeInAConeKeepsEveryBallWhollyInsideAndNoneThatFits) {
    // A simple cubic lattice in --region cone:6,10,4,1 (Rb = 3, k = 0.5, 1 Dp tall): the
    // balls of the layer z = 0.5 whose centre lies at least 0.5 from the wall, cos (3.25 - rho)
    // >= 0.5 with cos = 4 / sqrt(20): rho <= 2.691, the 21 points with i^2 + j^2 <= 5.
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.diameter = 1.0;
    p.region = {Cone(3.0, 5.0, 4.0), 1.0};
    const Packing b = fill_lattice(p);
    EXPECT_EQ(b.size(), 21u);
    for (const Vec3& c : b.centers) {
        EXPECT_LE(p.region.container.wall_overlap(c, 0.5), 1e-9);
        EXPECT_NEAR(c.z, 0.5, 1e-12);
    }
    // The exact void fraction of the layer: 21 balls in the frustum from 0 to 1.
    const double frustum = pi / 3.0 * (9.0 + 3.0 * 3.5 + 3.5 * 3.5);
    EXPECT_NEAR(void_fraction(b, p.region.container, 0.0, 1.0), 1.0 - 21.0 * pi / 6.0 / frustum,
                1e-12);
    EXPECT_NEAR(region_volume(p.region), frustum, 1e-12);
    EXPECT_EQ(region_text(p.region), "cone:6,10,4,1");
}

TEST(Cone, SpecReadsBackToTheBitAndBadSpecsAreRefused) {
    const std::optional<Container> c = parse_container("cone:6.1,14.3,40.7");
    ASSERT_TRUE(c);
    EXPECT_EQ(c->name(), "cone");
    EXPECT_EQ(c->spec(), "cone:6.1,14.3,40.7");
    const Container scaled = c->scaled(1.0 / 3.0);
    const std::optional<Container> back = parse_container(scaled.spec());
    ASSERT_TRUE(back);
    EXPECT_EQ(back->spec_numbers(), scaled.spec_numbers());
    EXPECT_FALSE(c->tube_diameter());
    EXPECT_FALSE(c->hydraulic_diameter().value);
    EXPECT_EQ(c->top(), 40.7);
    for (const char* bad : {"cone:1,2", "cone:1,2,0", "cone:0,2,3", "cone:1,-2,3", "cone:1,2,3,4",
                            "cone:1,2,nan", "cone:1,2,2e15"})
        EXPECT_FALSE(parse_container(bad)) << bad;
    // summary.json's container reads back as the same cone; lengths that are not one are refused.
    nlohmann::json summary = {{"container", c->summary_json()}};
    std::istringstream in(summary.dump());
    const BedSummary s = read_bed_summary(in, "summary.json");
    ASSERT_TRUE(s.container);
    EXPECT_EQ(s.container->spec_numbers(), c->spec_numbers());
    summary["container"]["floor_diameter"] = -1.0;
    std::istringstream wrong(summary.dump());
    EXPECT_THROW(read_bed_summary(wrong, "summary.json"), InvalidInput);
}

TEST(Cone, TheWallsSurfaceLiesOutsideTheCone) {
    // The prism about the cone: every vertex, and points inside every triangle, at least
    // R(z) from the axis (the chord argument of tube_solids); its rings at the cone's height.
    const Container cone = Cone(3.0, 5.0, 10.0);
    const std::vector<Solid> solids = cone.solids(-0.2, 8.0, 0.4);
    ASSERT_EQ(solids.size(), 3u);
    EXPECT_EQ(solids[0].name, "wall");
    const TriangleMesh& m = solids[0].mesh;
    const Cone& shape = std::get<Cone>(cone.shape());
    double closest = 1e9;
    for (const auto& t : m.triangles)
        for (const double a : {0.0, 0.2, 1.0 / 3.0, 0.5})
            for (const double b : {0.0, 0.25, 1.0 / 3.0}) {
                if (a + b > 1.0)
                    continue;
                const Vec3 p =
                    (1.0 - a - b) * m.vertices[t[0]] + a * m.vertices[t[1]] + b * m.vertices[t[2]];
                closest = std::min(closest, std::hypot(p.x, p.y) - shape.radius_at(p.z));
            }
    EXPECT_GE(closest, -1e-12);
    EXPECT_LT(closest, 1e-3); // and close to it: the polygon's sides touch the circles
}
