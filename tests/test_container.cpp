// Contact and wall geometry of the containers (cylinder: Salvat et al. 2005, nomenclature
// delta_iw; box), and what Container answers for each.
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "packbed/container.hpp"
#include "packbed/volume.hpp"

#include <nlohmann/json.hpp>

using packbed::Cylinder;
using packbed::Vec3;

TEST(Cylinder, WallOverlapIsRadialDistancePlusRadiusMinusRt) {
    const Cylinder c(2.5);
    // Centre at r = 2.0 (3-4-5 triangle scaled), radius 0.5: touches the wall exactly.
    const auto touching = c.wall_contact({1.2, 1.6, 7.0}, 0.5);
    EXPECT_NEAR(touching.overlap, 0.0, 1e-15);
    // r = 2.1: overlap 0.1, push towards the axis along -(x, y)/r.
    const auto pressed = c.wall_contact({2.1 * 0.6, 2.1 * 0.8, 3.0}, 0.5);
    EXPECT_NEAR(pressed.overlap, 0.1, 1e-14);
    EXPECT_NEAR(pressed.push.x, -0.6, 1e-15);
    EXPECT_NEAR(pressed.push.y, -0.8, 1e-15);
    EXPECT_EQ(pressed.push.z, 0.0);
    // On the axis: clear of the wall, overlap = 0.5 - 2.5.
    EXPECT_DOUBLE_EQ(c.wall_contact({0, 0, 1}, 0.5).overlap, -2.0);
}

TEST(Cylinder, ContainsChecksRadiusAndFloor) {
    const Cylinder c(1.0);
    EXPECT_TRUE(c.contains({0.0, 0.0, 0.0}));
    EXPECT_TRUE(c.contains({0.6, 0.8, 5.0})); // on the wall
    EXPECT_FALSE(c.contains({0.6, 0.81, 5.0}));
    EXPECT_FALSE(c.contains({0.0, 0.0, -1e-12}));
}

TEST(Vec3, Arithmetic) {
    const Vec3 a{1, 2, 3}, b{-2, 0.5, 4};
    EXPECT_EQ(a + b, (Vec3{-1, 2.5, 7}));
    EXPECT_EQ(a - b, (Vec3{3, 1.5, -1}));
    EXPECT_DOUBLE_EQ(dot(a, b), -2 + 1 + 12);
    EXPECT_DOUBLE_EQ(norm(Vec3{3, 4, 12}), 13.0);
    EXPECT_FALSE(is_finite(Vec3{0, NAN, 0}));
}

using packbed::Box;
using packbed::Container;

TEST(Box, WallDistanceIsToTheNearestFace) {
    const Box b(3.0, 2.0);                                   // x in [0, 3], y in [0, 2]
    EXPECT_DOUBLE_EQ(b.wall_distance({1.5, 1.0, 4.0}), 1.0); // the middle: half the narrower
    EXPECT_DOUBLE_EQ(b.wall_distance({0.2, 1.0, 4.0}), 0.2);
    EXPECT_NEAR(b.wall_distance({2.9, 0.5, 4.0}), 0.1, 1e-15); // x = 3 is 0.1 away
    EXPECT_DOUBLE_EQ(b.wall_distance({-0.5, 1.0, 4.0}), -0.5); // outside
    EXPECT_DOUBLE_EQ(b.depth(), 1.0);
    EXPECT_TRUE(b.contains({0.0, 2.0, 0.0}));
    EXPECT_FALSE(b.contains({3.01, 1.0, 1.0}));
    EXPECT_FALSE(b.contains({1.0, 1.0, -0.01}));
    // A sphere of radius 0.3 at (0.5, 1, z): nearest point 0.2 from x = 0, farthest 0.8.
    const auto [nearest, farthest] = b.wall_distances({0.5, 1.0, 1.0}, 0.3);
    EXPECT_DOUBLE_EQ(nearest, 0.2);
    EXPECT_DOUBLE_EQ(farthest, 0.8);
}

TEST(Box, ShrunkBoxesAndTheirFramesAddUpToTheCrossSection) {
    const Box b(3.0, 2.0);
    EXPECT_DOUBLE_EQ(b.cross_section_area(), 6.0);
    // Shrunk by 0.25: 2.5 x 1.5; the frame between 0 and 0.25 is 6 - 3.75.
    EXPECT_DOUBLE_EQ(b.shrunk(0.25).cross_section_area(), 3.75);
    EXPECT_DOUBLE_EQ(b.shell_area(0.0, 0.25), 2.25);
    EXPECT_DOUBLE_EQ(b.shrunk(0.25).x_low(), 0.25);
    EXPECT_DOUBLE_EQ(b.shrunk(0.25).y_high(), 1.75);
    // Beyond the depth the box is a segment at the middle: no area.
    EXPECT_DOUBLE_EQ(b.shrunk(1.5).cross_section_area(), 0.0);
    double sum = 0.0;
    for (int k = 0; k < 10; ++k)
        sum += b.shell_area(0.1 * k, 0.1 * (k + 1));
    EXPECT_NEAR(sum, 6.0, 1e-12);
}

TEST(Container, CylinderAndBoxAnswerTheSameQuestions) {
    const double pi = 3.14159265358979323846;
    const Container c = packbed::Cylinder(2.0), b = Box(4.0, 4.0);
    EXPECT_EQ(c.name(), "cylinder");
    EXPECT_EQ(b.name(), "box");
    EXPECT_EQ(c.spec(), "cylinder:4");
    EXPECT_EQ(b.spec(), "box:4,4");
    EXPECT_EQ(b.shrunk(0.5).spec(), "box:3,3@0.5,0.5");
    EXPECT_DOUBLE_EQ(c.cross_section_area(0.0, 1.0), 4.0 * pi);
    EXPECT_DOUBLE_EQ(c.shell_area(0.0, 1.0, 0.0, 1.0), pi * (4.0 - 1.0));
    EXPECT_DOUBLE_EQ(c.shrunk(0.5).depth(0.0, 1.0), 1.5);
    EXPECT_DOUBLE_EQ(c.wall_distance({0.6, 0.8, 1.0}), 1.0);
    EXPECT_DOUBLE_EQ(b.wall_distance({0.6, 0.8, 1.0}), 0.6);
    // A sphere of radius 0.5 wholly inside, then the half of one centred on a face.
    const double ball = 4.0 / 3.0 * pi * 0.125;
    EXPECT_DOUBLE_EQ(b.sphere_volume({2.0, 2.0, 2.0}, 0.5, 0.0, 10.0), ball);
    EXPECT_NEAR(b.sphere_volume({0.0, 2.0, 2.0}, 0.5, 0.0, 10.0), 0.5 * ball, 1e-15);
    // On the cylinder's wall: less than half (the wall curves inwards), as the volume routine.
    EXPECT_EQ(c.sphere_volume({2.0, 0.0, 2.0}, 0.5, 0.0, 10.0),
              packbed::sphere_volume_in_cylinder_slab({2.0, 0.0, 2.0}, 0.5, 2.0, 0.0, 10.0));
    EXPECT_LT(c.sphere_volume({2.0, 0.0, 2.0}, 0.5, 0.0, 10.0), 0.5 * ball);
    // ...and a quarter of one on a vertical edge of the box, cut by the plane z = 2 too.
    EXPECT_NEAR(b.sphere_volume({0.0, 0.0, 2.0}, 0.5, 0.0, 2.0), 0.125 * ball, 1e-12);
    EXPECT_EQ(b.bounds().x_high, 4.0);
    EXPECT_EQ(c.bounds().x_low, -2.0);
    EXPECT_EQ(c.profile_position_name(), "radial_position");
    EXPECT_DOUBLE_EQ(c.profile_position(0.5), 1.5);
    EXPECT_EQ(b.profile_position_name(), "wall_distance");
    EXPECT_DOUBLE_EQ(b.profile_position(0.5), 0.5);
}

TEST(Container, EachShapeNamesItselfInMessages) {
    using namespace packbed;
    EXPECT_EQ(Container(Cylinder(10.0)).describe(), "a cylinder of radius 10");
    EXPECT_EQ(Container(Box(6.0, 6.0)).describe(), "a box (box:6,6)");
    EXPECT_EQ(Container(Annulus(5.0, 1.0)).describe(), "annulus:10,2");
    EXPECT_EQ(Container(Periodic(8.0, 8.0)).describe(), "periodic:8,8");
    for (const std::string_view spec : {"cylinder:20", "box:6,6", "annulus:10,2", "periodic:8,8"})
        EXPECT_FALSE(parse_container(spec)->describe().empty()) << spec;
}

TEST(Container, ItsExactSpecReadsBackAsTheSameContainer) {
    // Lengths that 9 significant digits round (2 sqrt 2, pi, 1/3): the exact spec writes the
    // shortest text of each double, so a bed rebuilt with Python's bed.container sits in its own
    // container, not one 1e-9 off; the spec of messages and titles keeps 9 digits.
    const double root8 = std::sqrt(8.0), pi = 3.14159265358979323846, third = 1.0 / 3.0;
    const Container kinds[] = {packbed::Cylinder(root8), Box(pi, root8),
                               packbed::Annulus(root8, third), packbed::Periodic(root8, pi),
                               packbed::Cone(root8, third, pi)};
    for (const Container& c : kinds) {
        const std::optional<Container> back = packbed::parse_container(c.exact_spec());
        ASSERT_TRUE(back) << c.exact_spec();
        EXPECT_EQ(back->exact_spec(), c.exact_spec());
        EXPECT_EQ(back->summary_json(), c.summary_json()) << c.exact_spec();
    }
    EXPECT_EQ(Container(packbed::Cylinder(root8)).exact_spec(), "cylinder:5.656854249492381");
    EXPECT_EQ(Container(packbed::Cylinder(root8)).spec(), "cylinder:5.65685425");
    EXPECT_NE(packbed::parse_container("cylinder:5.65685425")->summary_json(),
              Container(packbed::Cylinder(root8)).summary_json());
}
