// The spherocylinder pellet (spherocylinder_shape.hpp): its volume and size, depths of two
// pellets by hand (crossing, side by side, end to end, an end on a side, axes that meet) and
// against a dense search of the segments' distance, the springs of each contact, the volumes in
// slabs, boxes and tubes against closed forms and a grid, the triangulated surface and the DEM
// spheres.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "packbed/box.hpp"
#include "packbed/container.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/spherocylinder_shape.hpp"
#include "packbed/volume.hpp"
#include "rotations.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// A pellet of radius 0.5 and segment half-length 0.5 (D = L = 1), at size 1.
const SpherocylinderShape rod{0.5, 0.5};

Placement at(const Vec3& position, const Quaternion& turn = {}) {
    return {position, turn, 1.0};
}

/// The body z axis laid along x (a quarter turn about y).
const Quaternion along_x = about({0.0, 1.0, 0.0}, 0.5 * pi);
const Quaternion along_y = about({1.0, 0.0, 0.0}, -0.5 * pi);

TEST(SpherocylinderShape, VolumeIsTheUnitBallsAtEveryAspect) {
    for (const double aspect : {0.0, 0.45, 1.0, 3.0, 10.0}) {
        const SpherocylinderShape s = SpherocylinderShape::of_aspect(aspect);
        EXPECT_NEAR(s.volume(1.0), 4.0 / 3.0 * pi, 1e-13) << aspect;
        EXPECT_NEAR(s.half_length / s.radius, aspect, 1e-13);
        EXPECT_DOUBLE_EQ(s.smallest_dimension(), s.radius);
        EXPECT_NEAR(s.bounding_radius(2.0), 2.0 * (s.radius + s.half_length), 1e-15);
    }
    // L = D: pi R^2 2R + 4 pi R^3 / 3 = 10 pi R^3 / 3, R = 0.4^(1/3).
    EXPECT_NEAR(SpherocylinderShape::of_aspect(1.0).radius, std::cbrt(0.4), 1e-15);
    EXPECT_NEAR(rod.surface_area(1.0), 2.0 * pi * 0.5 * 1.0 + 4.0 * pi * 0.25, 1e-15);
}

TEST(SpherocylinderShape, SupportIsTheFarEndMovedOutAlongTheDirection) {
    const Placement p = at({1.0, 2.0, 3.0}, along_x);
    const Vec3 low = rod.support(p, {0.0, 0.0, -1.0});
    EXPECT_NEAR(low.z, 2.5, 1e-15);
    const Vec3 right = rod.support(p, {2.0, 0.0, 0.0});
    EXPECT_NEAR(right.x, 2.0, 1e-15);
    const Vec3 slant = rod.support(p, {1.0, 0.0, 1.0});
    EXPECT_NEAR(slant.x, 1.5 + 0.5 / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(slant.z, 3.0 + 0.5 / std::sqrt(2.0), 1e-15);
}

TEST(SpherocylinderShape, DepthsOfTwoByHand) {
    // Crossing at right angles, one 0.9 above the other: 1 - 0.9 along z.
    PairOverlap o =
        rod.pair_overlap(at({}, along_x), rod, at({0.2, 0.1, 0.9}, along_y), {0.2, 0.1, 0.9});
    EXPECT_NEAR(o.depth, 0.1, 1e-15);
    EXPECT_NEAR(o.normal.z, 1.0, 1e-15);
    EXPECT_NEAR(o.point.z, 0.45, 1e-15);
    EXPECT_NEAR(o.point.x, 0.2, 1e-15);
    // Side by side, parallel, 0.95 apart and shifted 0.6 along their axes: the contact in the
    // middle of the overlap of their segments (x from 0.1 to 0.5).
    o = rod.pair_overlap(at({}, along_x), rod, at({0.6, 0.95, 0.0}, along_x), {0.6, 0.95, 0.0});
    EXPECT_NEAR(o.depth, 0.05, 1e-15);
    EXPECT_NEAR(o.normal.y, 1.0, 1e-15);
    EXPECT_NEAR(o.point.x, 0.3, 1e-15);
    // End to end on one line: 2 R + 2 h - 1.9.
    o = rod.pair_overlap(at({}, along_x), rod, at({1.9, 0.0, 0.0}, along_x), {1.9, 0.0, 0.0});
    EXPECT_NEAR(o.depth, 0.1, 1e-15);
    EXPECT_NEAR(o.normal.x, 1.0, 1e-15);
    // An upright one standing on a lying one's side: its lower cap's centre 0.98 above the axis.
    o = rod.pair_overlap(at({}, along_x), rod, at({0.3, 0.0, 1.48}), {0.3, 0.0, 1.48});
    EXPECT_NEAR(o.depth, 0.02, 1e-15);
    EXPECT_NEAR(o.normal.z, 1.0, 1e-15);
    EXPECT_NEAR(rod.pair_gap(at({}, along_x), rod, at({0.3, 0.0, 1.48}), {0.3, 0.0, 1.48}), -0.02,
                1e-15);
    // Apart: minus the gap.
    EXPECT_NEAR(rod.pair_gap(at({}, along_x), rod, at({0.0, 0.0, 1.3}, along_y), {0.0, 0.0, 1.3}),
                0.3, 1e-15);
    // The axes meet: out across both, 2 R deep, towards b.
    o = rod.pair_overlap(at({}, along_x), rod, at({0.0, 0.0, 1e-20}, along_y), {0.0, 0.0, 1e-20});
    EXPECT_NEAR(o.depth, 1.0, 1e-15);
    EXPECT_NEAR(std::abs(o.normal.z), 1.0, 1e-15);
}

/// The least distance of the segments of two placed pellets by the test's own search: 20 001
/// points along a, each one's distance from b's segment in closed form, the least refined by
/// golden-section search between its neighbours.
double segment_distance(const SpherocylinderShape& s, const Placement& a, const Placement& b) {
    const Vec3 ua = rotate(a.orientation, {0.0, 0.0, 1.0}), ub = rotate(b.orientation, {0, 0, 1});
    const double ha = s.half_length * a.size, hb = s.half_length * b.size;
    const auto from_b = [&](double t) {
        const Vec3 q = a.position + ua * t;
        const double along = std::clamp(dot(q - b.position, ub), -hb, hb);
        return norm(q - b.position - ub * along);
    };
    const int n = 20000;
    int best = 0;
    for (int k = 1; k <= n; ++k)
        if (from_b(-ha + 2.0 * ha * k / n) < from_b(-ha + 2.0 * ha * best / n))
            best = k;
    double lo = -ha + 2.0 * ha * std::max(best - 1, 0) / n;
    double hi = -ha + 2.0 * ha * std::min(best + 1, n) / n;
    for (int it = 0; it < 100; ++it) {
        const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
        (from_b(m1) < from_b(m2) ? hi : lo) = from_b(m1) < from_b(m2) ? m2 : m1;
    }
    return from_b(0.5 * (lo + hi));
}

TEST(SpherocylinderShape, DepthsOfRandomPairsAgreeWithASearchOfTheSegments) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const SpherocylinderShape s = SpherocylinderShape::of_aspect(2.0);
    for (int k = 0; k < 40; ++k) {
        const Placement a = at({0.0, 0.0, 0.0}, uniform_rotation(u(rng), u(rng), u(rng)));
        const Vec3 ab{2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0};
        const Placement b = at(ab, uniform_rotation(u(rng), u(rng), u(rng)));
        const PairOverlap o = s.pair_overlap(a, s, b, ab);
        EXPECT_NEAR(o.depth, 2.0 * s.radius - segment_distance(s, a, b), 1e-9) << k;
    }
}

/// The springs of one contact: their count, the largest depth and their forces' sum.
struct Springs {
    int count = 0;
    double deepest = 0.0;
    Vec3 force;
};
Springs springs_of(const Placement& a, const Placement& b) {
    Springs out;
    rod.pair_springs(a, rod, b, b.position - a.position,
                     [&](double depth, const Vec3& normal, const Vec3&) {
                         ++out.count;
                         out.deepest = std::max(out.deepest, depth);
                         out.force += normal * depth;
                     });
    return out;
}

TEST(SpherocylinderShape, OneSpringWhereTheyCrossTwoWhereTheyLieSideBySide) {
    // Crossing over their middles: the segments' nearest points, inside both; no end reaches
    // (each end 1.03 from the other's axis).
    Springs s = springs_of(at({}, along_x), at({0.0, 0.0, 0.9}, along_y));
    EXPECT_EQ(s.count, 1);
    EXPECT_NEAR(s.deepest, 0.1, 1e-15);
    // An end on a side: the end's sphere alone, the nearest points adding nothing.
    s = springs_of(at({}, along_x), at({0.3, 0.0, 1.48}));
    EXPECT_EQ(s.count, 1);
    EXPECT_NEAR(s.deepest, 0.02, 1e-15);
    // Side by side, shifted: a's end over b and b's end over a, each 0.05 deep, along y.
    s = springs_of(at({}, along_x), at({0.6, 0.95, 0.0}, along_x));
    EXPECT_EQ(s.count, 2);
    EXPECT_NEAR(s.force.y, 0.1, 1e-15);
    EXPECT_NEAR(s.force.x, 0.0, 1e-15);
    // Turned a little from parallel, the two springs' depths change smoothly: the force moves
    // by no more than its slope allows between 1e-6 rad either way (the nearest points alone
    // would jump from one end of the overlap to the other).
    const Springs plus =
        springs_of(at({}, along_x), at({0.6, 0.95, 0.0}, about({0, 0, 1}, 1e-6) * along_x));
    const Springs minus =
        springs_of(at({}, along_x), at({0.6, 0.95, 0.0}, about({0, 0, 1}, -1e-6) * along_x));
    EXPECT_NEAR(plus.force.y, minus.force.y, 1e-5);
    EXPECT_EQ(plus.count, 2);
    EXPECT_EQ(minus.count, 2);
}

TEST(SpherocylinderShape, WallSpringsAreTheCapsSpheres) {
    // Upright against a tube's wall (radius 1), 0.01 through it: both caps press, each 0.01.
    const Container tube = Container::tube(2.0);
    const Placement p = at({0.51, 0.0, 2.0});
    int count = 0;
    rod.wall_springs(tube, p, [&](double depth, const Vec3& push, const Vec3&) {
        ++count;
        EXPECT_NEAR(depth, 0.01, 1e-12);
        EXPECT_NEAR(push.x, -1.0, 1e-12);
    });
    EXPECT_EQ(count, 2);
    EXPECT_NEAR(rod.wall_overlap(tube, p), 0.01, 1e-9);
    // Lying on the floor 0.02 deep: the two caps' spheres.
    count = 0;
    rod.wall_springs(tube, at({0.0, 0.0, 0.48}, along_x),
                     [&](double depth, const Vec3& push, const Vec3&) {
                         ++count;
                         EXPECT_NEAR(depth, 0.02, 1e-15);
                         EXPECT_DOUBLE_EQ(push.z, 1.0);
                     });
    EXPECT_EQ(count, 2);
}

TEST(SpherocylinderShape, VolumeInASlabByClosedForms) {
    const Container wide = Container::tube(100.0);
    const double whole = rod.volume(1.0);
    // Upright: cut through its middle, half; the top cap's part above h + s, pi (2 r^3 / 3 -
    // r^2 s + s^3 / 3).
    const Placement up = at({0.0, 0.0, 5.0});
    EXPECT_NEAR(rod.volume_in(wide, up, 0.0, 5.0), 0.5 * whole, 1e-12);
    const double s = 0.2;
    EXPECT_NEAR(rod.volume_in(wide, up, 5.5 + s, 10.0),
                pi * (2.0 / 3.0 * 0.125 - 0.25 * s + s * s * s / 3.0), 1e-12);
    // Lying: its axis' plane halves it; every tilt too (the centre is a centre of symmetry).
    EXPECT_NEAR(rod.volume_in(wide, at({0.0, 0.0, 5.0}, along_x), 0.0, 5.0), 0.5 * whole, 1e-10);
    const Placement tilted = at({0.0, 0.0, 5.0}, rotation_by(Vec3{0.3, 0.6, 0.15}));
    EXPECT_NEAR(rod.volume_in(wide, tilted, 0.0, 5.0), 0.5 * whole, 1e-10);
    EXPECT_NEAR(rod.volume_in(wide, tilted, 0.0, 10.0), whole, 1e-15);
}

/// The volume of a placed rod inside the container between two heights by a grid of n^3
/// points over its bounding box, each tested by its own distance from the segment.
double grid_volume(const Placement& p, const Container& c, double z_low, double z_high, int n) {
    const Vec3 axis = rotate(p.orientation, {0.0, 0.0, 1.0});
    const double reach = rod.bounding_radius(1.0), cell = 2.0 * reach / n;
    double inside = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const Vec3 q = p.position + Vec3{(i + 0.5) * cell - reach, (j + 0.5) * cell - reach,
                                                 (k + 0.5) * cell - reach};
                if (q.z < z_low || q.z > z_high || c.sticks_out(q, 0.0) > 0.0)
                    continue;
                const double t = std::clamp(dot(q - p.position, axis), -0.5, 0.5);
                inside += norm(q - p.position - axis * t) <= 0.5 ? 1.0 : 0.0;
            }
    return inside * cell * cell * cell;
}

TEST(SpherocylinderShape, VolumeCutByAWallByClosedFormsAndAGrid) {
    const double whole = rod.volume(1.0);
    const Container box(Box(0.0, 4.0, 0.0, 4.0));
    // Lying across a box's wall at its middle: half; upright in its corner: a quarter.
    EXPECT_NEAR(rod.volume_in(box, at({0.0, 2.0, 2.0}, along_x), 0.0, 10.0), 0.5 * whole, 1e-8);
    EXPECT_NEAR(rod.volume_in(box, at({0.0, 0.0, 2.0}), 0.0, 10.0), 0.25 * whole, 1e-8);
    // Turned through a tube's wall and cut by a slab: against a 140^3 grid (its error about
    // the surface's area times a cell, 0.4 %).
    const Container tube = Container::tube(3.0);
    const Placement p = at({1.3, 0.4, 1.0}, rotation_by(Vec3{0.33, -1.1, 0.44}));
    const double exact = rod.volume_in(tube, p, 0.8, 5.0);
    EXPECT_GT(exact, 0.2 * whole);
    EXPECT_LT(exact, 0.8 * whole);
    EXPECT_NEAR(exact, grid_volume(p, tube, 0.8, 5.0, 140), 4e-3 * whole);
    // The volume from the wall: the tube shrunk by 0.2 (a shell's outer part).
    EXPECT_NEAR(rod.volume_from_wall(tube, 0, 0.2, p, 0.8, 5.0),
                grid_volume(p, Container::tube(2.6), 0.8, 5.0, 140), 4e-3 * whole);
}

TEST(SpherocylinderShape, CapsInATubeMakeTheSphereTheWallCuts) {
    // L = 0: the two caps are a ball of radius 0.5, whatever the turn that parts them; its
    // volume in a tube and a slab against the sphere's own (volume.hpp, no code shared with
    // the caps' sections), cut by the wall and by the slab, the flat faces upright, level and
    // turned, the ball's centre inside the tube and beyond its wall.
    const SpherocylinderShape ball{0.5, 0.0};
    const Container tube = Container::tube(3.0);
    const std::vector<Quaternion> turns{{},
                                        along_x,
                                        rotation_by(Vec3{0.33, -1.1, 0.44}),
                                        rotation_by(Vec3{1e-9, 0.0, 0.0}),
                                        rotation_by(Vec3{0.5 * pi - 1e-7, 0.0, 0.0})};
    int cut = 0;
    for (const Vec3& centre :
         {Vec3{1.3, 0.0, 1.0}, Vec3{0.9, 1.0, 1.0}, Vec3{-1.6, 0.2, 0.8}, Vec3{0.0, 1.2, 1.3}})
        for (const Quaternion& turn : turns)
            for (const auto& [low, high] : {std::pair{0.0, 5.0}, std::pair{0.8, 1.1}}) {
                const double exact = sphere_volume_in_cylinder_slab(centre, 0.5, 1.5, low, high);
                cut += exact < 0.99 * ball.volume(1.0) ? 1 : 0;
                EXPECT_NEAR(ball.volume_in(tube, at(centre, turn), low, high), exact, 1e-9)
                    << centre.x << " " << centre.y << " " << low;
                EXPECT_NEAR(ball.volume_from_wall(tube, 0, 0.2, at(centre, turn), low, high),
                            sphere_volume_in_cylinder_slab(centre, 0.5, 1.3, low, high), 1e-9);
            }
    EXPECT_EQ(cut, 40); // every case cut by the wall or the slab
}

TEST(SpherocylinderShape, SurfaceIsClosedOutwardAndInside) {
    for (const int level : {0, 2}) {
        const TriangleMesh m = rod.unit_surface(level);
        // Euler's V - E + F = 2 for a closed surface of genus 0 (E = 3 F / 2).
        const auto v = static_cast<long>(m.vertices.size()),
                   f = static_cast<long>(m.triangles.size());
        EXPECT_EQ(v - 3 * f / 2 + f, 2) << level;
        // Every vertex on the surface; the inscribed polyhedron's volume below the exact one
        // and within its chord error (the surface's area times R (1 - cos(pi / n))).
        for (const Vec3& p : m.vertices) {
            const double t = std::clamp(p.z, -0.5, 0.5);
            EXPECT_NEAR(std::hypot(p.x, p.y, p.z - t), 0.5, 1e-12);
        }
        const double n = 12 << level;
        const double chord = 0.5 * (1.0 - std::cos(pi / n));
        EXPECT_LT(m.volume(), rod.volume(1.0)) << level;
        EXPECT_GT(m.volume(), rod.volume(1.0) - 2.0 * rod.surface_area(1.0) * chord) << level;
    }
    // L = 0, the sphere: one equator.
    const TriangleMesh ball = SpherocylinderShape{1.0, 0.0}.unit_surface(1);
    const auto v = static_cast<long>(ball.vertices.size()),
               f = static_cast<long>(ball.triangles.size());
    EXPECT_EQ(v - 3 * f / 2 + f, 2);
}

TEST(SpherocylinderShape, DemSpheresFillTheAxisFromCapToCap) {
    std::vector<DemSphere> spheres;
    const Placement p = at({1.0, 1.0, 1.0}, about({0.0, 1.0, 0.0}, 0.5 * pi));
    rod.dem_spheres(p, [&](const DemSphere& s) { spheres.push_back(s); });
    // 4 h / R = 4 steps of R / 2, five spheres, the first and last the caps.
    ASSERT_EQ(spheres.size(), 5u);
    EXPECT_NEAR(spheres.front().centre.x, 1.0 - 0.5, 1e-15);
    EXPECT_NEAR(spheres.back().centre.x, 1.0 + 0.5, 1e-15);
    for (const DemSphere& s : spheres)
        EXPECT_DOUBLE_EQ(s.radius, 0.5);
}

} // namespace
