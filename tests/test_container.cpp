// Contact and wall geometry of the cylinder (Salvat et al. 2005, nomenclature: delta_iw).
#include <cmath>

#include <gtest/gtest.h>

#include "packbed/container.hpp"

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
