// The particle seam (particle_shape.hpp): the sphere's answers against closed forms, the
// rotation of a quaternion, the table of shapes a bed's types point into, and the loops that
// are templates on the shape run with a second, oriented shape (a sphere set off its particle's
// position along the body's z axis), whose every answer must be the sphere's at the turned
// centre.
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "packbed/analysis.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/periodic.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/sphere_shape.hpp"
#include "packbed/volume.hpp"
#include "packbed/voxel.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// A test shape with an orientation: a sphere of radius `size` whose centre lies `offset`
/// sizes along its body z axis from the particle's position.
struct OffsetSphere {
    static constexpr std::string_view kind = "offset-sphere";
    static constexpr bool oriented = true;
    double offset = 0.5;

    Vec3 centre(const Placement& p) const {
        return p.position + rotate(p.orientation, Vec3{0.0, 0.0, offset}) * p.size;
    }
    Placement ball(const Placement& p) const { return {centre(p), {}, p.size}; }
    double bounding_radius(double size) const { return size * (1.0 + offset); }
    double volume(double size) const { return sphere.volume(size); }
    Vec3 support(const Placement& p, const Vec3& v) const { return sphere.support(ball(p), v); }
    double wall_overlap(const Container& c, const Placement& p) const {
        return sphere.wall_overlap(c, ball(p));
    }
    PairOverlap pair_overlap(const Placement& a, const OffsetSphere& other, const Placement& b,
                             const Vec3& ab) const {
        const Vec3 centres = ab + (other.centre(b) - b.position) - (centre(a) - a.position);
        return sphere.pair_overlap(ball(a), sphere, other.ball(b), centres);
    }
    std::pair<double, double> wall_extent(const Container& c, std::size_t wall,
                                          const Placement& p) const {
        return sphere.wall_extent(c, wall, ball(p));
    }
    double volume_in(const Container& c, const Placement& p, double z_low, double z_high) const {
        return sphere.volume_in(c, ball(p), z_low, z_high);
    }
    double volume_from_wall(const Container& c, std::size_t wall, double d, const Placement& p,
                            double z_low, double z_high) const {
        return sphere.volume_from_wall(c, wall, d, ball(p), z_low, z_high);
    }
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const {
        return sphere.volume_in_box(ball(p), low, high);
    }
    TriangleMesh unit_surface(int level) const {
        TriangleMesh mesh = sphere.unit_surface(level);
        for (Vec3& v : mesh.vertices)
            v.z += offset;
        return mesh;
    }
    template <class F> void dem_spheres(const Placement& p, F&& f) const {
        sphere.dem_spheres(ball(p), f);
    }

    SphereShape sphere;
};
static_assert(ParticleShape<OffsetSphere>);

/// A random unit quaternion (Shoemake 1992, uniform over rotations).
Quaternion random_rotation(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double u1 = u(rng), u2 = 2.0 * pi * u(rng), u3 = 2.0 * pi * u(rng);
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return {a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)};
}

/// A loose random bed of `n` spheres of radius 0.5 in a tube of diameter 6 (some pressing its
/// wall, centres up to 2.7 from the axis), each set with a
/// random orientation, and the same spheres at the centres an OffsetSphere puts them.
struct TwoViews {
    Packing oriented; ///< positions and orientations of OffsetSpheres
    Packing balls;    ///< the spheres they are
};

TwoViews two_views(std::size_t n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    TwoViews v;
    const OffsetSphere shape;
    for (std::size_t i = 0; i < n; ++i) {
        const double rho = 2.7 * std::sqrt(u(rng)), phi = 2.0 * pi * u(rng);
        const Vec3 centre{rho * std::cos(phi), rho * std::sin(phi), 0.5 + 8.0 * u(rng)};
        const Quaternion q = random_rotation(rng);
        const Vec3 position = centre - rotate(q, Vec3{0.0, 0.0, shape.offset}) * 0.5;
        v.oriented.add(position, 0.5);
        v.oriented.orientations.push_back(q);
        v.balls.add(shape.centre({position, q, 0.5}), 0.5);
    }
    return v;
}

} // namespace

TEST(Quaternion, TurnsAboutItsAxisByTwiceItsHalfAngle) {
    // 90 degrees about z: q = (cos 45, 0, 0, sin 45) takes x to y and y to -x.
    const double h = std::sqrt(0.5);
    const Quaternion q{h, 0.0, 0.0, h};
    const Vec3 x = rotate(q, {1.0, 0.0, 0.0}), y = rotate(q, {0.0, 1.0, 0.0});
    EXPECT_NEAR(x.x, 0.0, 1e-15);
    EXPECT_NEAR(x.y, 1.0, 1e-15);
    EXPECT_NEAR(y.x, -1.0, 1e-15);
    EXPECT_NEAR(y.y, 0.0, 1e-15);
    // 120 degrees about (1,1,1)/sqrt3 cycles the axes: x -> y -> z.
    const Quaternion cycle{0.5, 0.5, 0.5, 0.5};
    const Vec3 z = rotate(cycle, {0.0, 1.0, 0.0});
    EXPECT_NEAR(z.z, 1.0, 1e-15);
    // The identity leaves a vector's bits; a rotation keeps lengths; the conjugate undoes it.
    const Vec3 v{0.3, -1.7, 2.9};
    EXPECT_EQ(rotate(Quaternion{}, v), v);
    std::mt19937_64 rng(7);
    for (int k = 0; k < 100; ++k) {
        const Quaternion r = random_rotation(rng);
        EXPECT_NEAR(norm(rotate(r, v)), norm(v), 1e-14);
        const Vec3 back = rotate(conjugate(r), rotate(r, v));
        EXPECT_NEAR(norm(back - v), 0.0, 1e-14);
        // The product turns by the right factor first, then the left.
        const Quaternion s = random_rotation(rng);
        EXPECT_NEAR(norm(rotate(s * r, v) - rotate(s, rotate(r, v))), 0.0, 1e-14);
    }
    // The exponential map: 90 degrees about z is q above; a zero vector the identity;
    // normalized makes a scaled quaternion unit again.
    const Quaternion quarter = rotation_by({0.0, 0.0, 0.5 * std::numbers::pi});
    EXPECT_NEAR(quarter.w, h, 1e-15);
    EXPECT_NEAR(quarter.z, h, 1e-15);
    EXPECT_EQ(rotation_by({}), Quaternion{});
    const Quaternion unit = normalized({2.0 * h, 0.0, 0.0, 2.0 * h});
    EXPECT_NEAR(unit.w, h, 1e-15);
    EXPECT_NEAR(unit.z, h, 1e-15);
}

TEST(SphereShape, AnswersItsClosedForms) {
    const SphereShape s;
    const Placement p{{1.0, 2.0, 3.0}, {}, 2.0};
    EXPECT_EQ(SphereShape::kind, "sphere");
    EXPECT_FALSE(SphereShape::oriented);
    EXPECT_EQ(s.bounding_radius(2.0), 2.0);
    EXPECT_NEAR(s.volume(2.0), 32.0 * pi / 3.0, 1e-13);
    // The support point lies on the surface, along the direction asked.
    const Vec3 top = s.support(p, {0.0, 0.0, 5.0});
    EXPECT_EQ(top, (Vec3{1.0, 2.0, 5.0}));
    const Vec3 slant = s.support(p, {1.0, 1.0, 1.0}) - p.position;
    EXPECT_NEAR(norm(slant), 2.0, 1e-15);
    EXPECT_NEAR(slant.x, 2.0 / std::sqrt(3.0), 1e-15);
    // Two spheres of radii 2 and 1, 2.5 apart along x, overlap by 0.5 along +x.
    const PairOverlap o = s.pair_overlap(p, s, {{3.5, 2.0, 3.0}, {}, 1.0}, {2.5, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(o.depth, 0.5);
    EXPECT_EQ(o.normal, (Vec3{1.0, 0.0, 0.0}));
    EXPECT_EQ(o.point, (Vec3{1.75, 0.0, 0.0})); // 2 - 0.5 / 2 from the first's centre
    // In a tube of radius 4 a sphere of radius 2 at rho = sqrt 5 presses the wall by
    // sqrt 5 + 2 - 4.
    const Container tube = Cylinder(4.0);
    EXPECT_NEAR(s.wall_overlap(tube, p), std::sqrt(5.0) - 2.0, 1e-15);
    const auto [nearest, farthest] = s.wall_extent(tube, 0, p);
    EXPECT_NEAR(nearest, 4.0 - std::sqrt(5.0) - 2.0, 1e-15);
    EXPECT_NEAR(farthest, 4.0 - std::sqrt(5.0) + 2.0, 1e-15);
    // Volumes: a sphere wholly inside counts whole; the upper half above its centre's plane.
    const Placement inside{{0.0, 0.0, 3.0}, {}, 1.0};
    EXPECT_NEAR(s.volume_in(tube, inside, 0.0, 10.0), 4.0 * pi / 3.0, 1e-13);
    EXPECT_NEAR(s.volume_in(tube, inside, 3.0, 10.0), 2.0 * pi / 3.0, 1e-13);
    // 2.5 from the wall keeps the points within rho <= 1.5: the sphere of radius 1 on the axis
    // is whole; 3.5 from it keeps rho <= 0.5, a cylinder through the ball: 4/3 pi (1 - (1 -
    // 0.25)^1.5) of the ball (the ball less its part beyond rho = 0.5).
    EXPECT_NEAR(s.volume_from_wall(tube, 0, 2.5, inside, 0.0, 10.0), 4.0 * pi / 3.0, 1e-9);
    EXPECT_NEAR(s.volume_from_wall(tube, 0, 3.5, inside, 0.0, 10.0),
                4.0 * pi / 3.0 * (1.0 - std::pow(0.75, 1.5)), 1e-9);
    // The voxel cover: a box holding the ball, and the octant x, y, z > centre.
    EXPECT_NEAR(s.volume_in_box(inside, {-2.0, -2.0, 1.0}, {2.0, 2.0, 5.0}), 4.0 * pi / 3.0, 1e-13);
    EXPECT_NEAR(s.volume_in_box(inside, {0.0, 0.0, 3.0}, {2.0, 2.0, 5.0}), pi / 6.0, 1e-13);
    // Its surface: every vertex on the unit sphere, the volume below the ball's (inscribed),
    // within 1 % at level 3; placed at p, on the sphere of radius 2 about p.
    TriangleMesh mesh = s.unit_surface(3);
    for (const Vec3& v : mesh.vertices)
        EXPECT_NEAR(norm(v), 1.0, 1e-14);
    EXPECT_LT(mesh.volume(), 4.0 * pi / 3.0);
    EXPECT_GT(mesh.volume(), 0.99 * 4.0 * pi / 3.0);
    const double unit_volume = mesh.volume();
    place_surface<SphereShape>(mesh, p);
    EXPECT_NEAR(mesh.volume(), 8.0 * unit_volume, 1e-12);
    for (const Vec3& v : mesh.vertices)
        EXPECT_NEAR(norm(v - p.position), 2.0, 1e-14);
    // Its DEM representation: itself.
    std::vector<DemSphere> dem;
    s.dem_spheres(p, [&](const DemSphere& d) { dem.push_back(d); });
    ASSERT_EQ(dem.size(), 1u);
    EXPECT_EQ(dem[0].centre, p.position);
    EXPECT_EQ(dem[0].radius, 2.0);
}

TEST(ShapedBed, TypesPointIntoTheTableOfShapes) {
    Packing packing;
    packing.add({0.0, 0.0, 1.0}, 1.0);
    packing.add({0.0, 0.0, 3.0}, 1.0);
    // No types: every particle is type 0; no orientations: the identity.
    const Packing identity{packing.centers, packing.radii, {Quaternion{}, Quaternion{}}, {}};
    const ShapedBed<OffsetSphere> one(identity, {OffsetSphere{}});
    EXPECT_EQ(one.shape(1).offset, 0.5);
    EXPECT_EQ(one.placement(1).orientation, Quaternion{});
    packing.types = {1, 0};
    packing.orientations = {Quaternion{}, Quaternion{0.0, 1.0, 0.0, 0.0}};
    const ShapedBed<OffsetSphere> two(packing, {OffsetSphere{0.25, {}}, OffsetSphere{0.75, {}}});
    EXPECT_EQ(two.shape(0).offset, 0.75);
    EXPECT_EQ(two.shape(1).offset, 0.25);
    // Turned half a turn about x, the second one's centre lies below its position.
    EXPECT_NEAR(two.shape(1).centre(two.placement(1)).z, 3.0 - 0.25, 1e-15);
    EXPECT_EQ(two.bounding_radii(), (std::vector<double>{1.75, 1.25}));
    // A type with no shape, types or orientations not one per particle, an oriented shape
    // without orientations: refused.
    EXPECT_THROW(ShapedBed<OffsetSphere>(packing, {OffsetSphere{}}), std::invalid_argument);
    Packing wrong = packing;
    wrong.types = {0};
    EXPECT_THROW(ShapedBed<OffsetSphere>(wrong, {OffsetSphere{}}), std::invalid_argument);
    wrong = packing;
    wrong.types.clear();
    wrong.orientations.pop_back();
    EXPECT_THROW(ShapedBed<OffsetSphere>(wrong, {OffsetSphere{}}), std::invalid_argument);
    wrong.orientations.clear();
    EXPECT_THROW(ShapedBed<OffsetSphere>(wrong, {OffsetSphere{}}), std::invalid_argument);
    EXPECT_NO_THROW(ShapedBed<SphereShape>(wrong, {SphereShape{}}));
}

TEST(ShapedBed, LoopsOnAnOrientedShapeGiveTheSpheresItPlaces) {
    // 300 OffsetSpheres at random orientations against the 300 spheres they are: the loops
    // (overlaps, void fraction, top, the profiles) must use each particle's placement,
    // orientation included, and the bounding radius for the neighbour search.
    const TwoViews v = two_views(300, 11);
    const ShapedBed<OffsetSphere> oriented(v.oriented, {OffsetSphere{}});
    const Container tube = Cylinder(3.0);
    const Overlaps a = measure_overlaps(oriented, tube), b = measure_overlaps(v.balls, tube);
    EXPECT_GT(b.pair, 0.1); // a loose random bed: many overlaps, the largest found by both
    EXPECT_GT(b.wall, 0.0);
    EXPECT_NEAR(a.pair, b.pair, 1e-12);
    EXPECT_NEAR(a.wall, b.wall, 1e-12);
    EXPECT_NEAR(void_fraction(oriented, tube, 1.0, 7.0), void_fraction(v.balls, tube, 1.0, 7.0),
                1e-12);
    EXPECT_NEAR(bed_top(oriented), bed_top(v.balls), 1e-12);
    // A periodic cell: the minimum image of the positions, then each shape's own offset.
    const Container cell = Periodic(6.0, 6.0);
    Packing shifted = v.oriented, shifted_balls = v.balls;
    for (std::size_t i = 0; i < shifted.size(); ++i) {
        const Vec3 move{3.0, 3.0, 0.0};
        shifted.centers[i] += move;
        shifted_balls.centers[i] += move;
        for (Vec3* c : {&shifted.centers[i], &shifted_balls.centers[i]}) {
            c->x = std::fmod(c->x + 6.0, 6.0);
            c->y = std::fmod(c->y + 6.0, 6.0);
        }
    }
    const ShapedBed<OffsetSphere> in_cell(shifted, {OffsetSphere{}});
    EXPECT_NEAR(measure_overlaps(in_cell, cell).pair, measure_overlaps(shifted_balls, cell).pair,
                1e-12);
}

TEST(ShapedBed, TheSpheresThroughTheConceptKeepTheirBits) {
    // The sphere-only entry points are the templates on SphereShape: the same numbers to the
    // bit as the container's own sphere questions summed by hand.
    const TwoViews v = two_views(200, 3);
    const Container tube = Cylinder(3.0);
    double solid = 0.0, top = 0.0, wall = 0.0;
    for (std::size_t i = 0; i < v.balls.size(); ++i) {
        solid += tube.sphere_volume(v.balls.centers[i], v.balls.radii[i], 1.0, 7.0);
        top = std::max(top, v.balls.centers[i].z + v.balls.radii[i]);
        wall = std::max(wall, tube.wall_overlap(v.balls.centers[i], v.balls.radii[i]));
    }
    EXPECT_EQ(void_fraction(v.balls, tube, 1.0, 7.0),
              1.0 - solid / (tube.cross_section_area(1.0, 7.0) * 6.0));
    EXPECT_EQ(bed_top(v.balls), top);
    EXPECT_EQ(measure_overlaps(v.balls, tube).wall, wall);
}
