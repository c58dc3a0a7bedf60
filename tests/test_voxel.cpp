// Voxel images: the closed form of a ball in an orthant, hand-computed voxel cases,
// the partial-volume sum identity and the same bits for any number of threads.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/lattice.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/volume.hpp"
#include "packbed/voxel.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// The cap of the unit ball above z = c: pi (1 - c)^2 (2 + c) / 3.
double cap(double c) {
    return pi * (1 - c) * (1 - c) * (2 + c) / 3.0;
}

Packing one_sphere(Vec3 c, double r) {
    Packing p;
    p.centers = {c};
    p.radii = {r};
    return p;
}

VoxelGrid grid_of(Vec3 low, double h, std::size_t nx, std::size_t ny, std::size_t nz) {
    VoxelGrid g;
    g.low = low;
    g.size = h;
    g.count = {nx, ny, nz};
    return g;
}

template <class Vector> double sum(const Vector& v) {
    double s = 0.0;
    for (const double x : v)
        s += x;
    return s;
}

} // namespace

TEST(Voxel, OrthantVolumeHasTheBallsSymmetriesAndCaps) {
    EXPECT_NEAR(ball_orthant_volume(0, 0, 0), pi / 6, 1e-15);        // an eighth of the ball
    EXPECT_NEAR(ball_orthant_volume(-1, -1, -1), 4 * pi / 3, 1e-14); // all of it
    EXPECT_EQ(ball_orthant_volume(0.6, 0.6, 0.6), 0.0);              // 3 x 0.36 > 1: outside
    for (const double c : {0.0, 0.1, 0.5, 0.9, -0.3, -0.8}) {
        // the cap above z = c, a quarter of it in the quadrant x, y > 0
        EXPECT_NEAR(4 * ball_orthant_volume(0, 0, c), cap(c), 1e-14) << c;
        EXPECT_NEAR(ball_orthant_volume(-1, -1, c), cap(c), 1e-14) << c;
    }
    // symmetric in its arguments
    EXPECT_NEAR(ball_orthant_volume(0.1, 0.3, 0.5), ball_orthant_volume(0.5, 0.1, 0.3), 1e-15);
    EXPECT_NEAR(ball_orthant_volume(-0.2, 0.3, 0.4), ball_orthant_volume(0.4, -0.2, 0.3), 1e-15);
}

TEST(Voxel, BallInABoxAgreesWithTheQuadratureOfVolumeHpp) {
    // 2 000 random boxes about a ball, cut in every way: the closed form against
    // sphere_volume_in_box (tanh-sinh quadrature of closed-form slice areas). The two largest
    // differences, 4.3e-11 and 5.9e-11 of r^3, are the quadrature's: a 30-digit quadrature
    // (mpmath) of those two boxes agrees with the closed form to 2e-16 (docs/voxels.md).
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> u(-1.3, 1.3), w(0.02, 1.5);
    const Vec3 c{0.3, -0.2, 1.1};
    const double r = 0.7;
    double worst = 0.0;
    for (int n = 0; n < 2000; ++n) {
        const Vec3 low{c.x + r * u(random), c.y + r * u(random), c.z + r * u(random)};
        const Vec3 high{low.x + r * w(random), low.y + r * w(random), low.z + r * w(random)};
        const double exact = sphere_volume_in_box(c, r, low, high);
        const double ours = ball_box_volume(c, r, low, high);
        worst = std::max(worst, std::abs(ours - exact) / (r * r * r));
    }
    EXPECT_LT(worst, 1e-10);
}

TEST(Voxel, AnImageOfOver64MiBIsOnHugePageBoundariesAndHoldsItsBall) {
    // 256^3 float32 voxels are 64 MiB, where the images are aligned to 2 MiB and asked for huge
    // pages (voxel.hpp): the same exact volumes as anywhere else. A ball of radius 100 h at an
    // off-grid centre: the image's sum is its volume (4/3 pi 100^3 voxels) to 1e-9.
    const Packing p = one_sphere({128.3, 127.6, 128.45}, 100.0);
    const VoxelGrid g = grid_of({0, 0, 0}, 1.0, 256, 256, 256);
    const Container box(Box(256.0, 256.0));
    const auto fraction = solid_fraction_image<float>(p, box, g);
    ASSERT_EQ(fraction.size(), std::size_t{256} * 256 * 256);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(fraction.data()) % (std::size_t{2} << 20), 0u);
    double total = 0.0;
    for (const float f : fraction)
        total += f;
    EXPECT_NEAR(total / (4.0 / 3.0 * pi * 1e6), 1.0, 1e-9);
    // the corners of the grid are outside the ball, its centre's voxel wholly inside
    EXPECT_EQ(fraction[0], 0.0f);
    EXPECT_EQ(fraction[(std::size_t{128} * 256 + 127) * 256 + 128], 1.0f);
}

TEST(Voxel, ASphereOnAVoxelCornerFillsItsEightVoxelsEqually) {
    // radius 0.8 h on the node (1, 1, 1) of a 2 x 2 x 2 grid of h = 1: each voxel holds an
    // eighth of the ball, and no voxel centre (at sqrt(3)/2 = 0.866 h) is inside it.
    const Packing p = one_sphere({1, 1, 1}, 0.8);
    const VoxelGrid g = grid_of({0, 0, 0}, 1.0, 2, 2, 2);
    const Container box(Box(2.0, 2.0));
    const auto fraction = solid_fraction_image(p, box, g);
    const double eighth = 4.0 / 3.0 * pi * 0.8 * 0.8 * 0.8 / 8.0;
    for (const double f : fraction)
        EXPECT_NEAR(f, eighth, 1e-14);
    for (const auto v : pore_image(p, box, g))
        EXPECT_EQ(v, 1); // all pore
    // radius 0.9 h > 0.866 h: every centre inside, all solid
    for (const auto v : pore_image(one_sphere({1, 1, 1}, 0.9), box, g))
        EXPECT_EQ(v, 0);
}

TEST(Voxel, EveryVoxelHoldsItsBallBoxVolume) {
    // Random balls (radii 0.3 to 3.5 voxels, so some lie within one voxel and some straddle
    // many and the planes through their centres): each voxel of the image against the sum of
    // ball_box_volume over the balls, the closed form at its eight corners, one voxel at a time.
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> where(-0.5, 6.5), size(0.3, 3.5);
    Packing p;
    for (int n = 0; n < 12; ++n) {
        p.centers.push_back({where(random), where(random), where(random)});
        p.radii.push_back(size(random));
    }
    const VoxelGrid g = grid_of({0, 0, 0}, 1.0, 6, 7, 8);
    const Container box(Box(20.0, 20.0));
    const auto image = solid_fraction_image(p, box, g);
    double worst = 0.0;
    for (std::size_t i = 0; i < 6; ++i)
        for (std::size_t j = 0; j < 7; ++j)
            for (std::size_t k = 0; k < 8; ++k) {
                const Vec3 low{double(i), double(j), double(k)}, high{i + 1.0, j + 1.0, k + 1.0};
                double expected = 0.0;
                for (std::size_t n = 0; n < p.size(); ++n)
                    expected += ball_box_volume(p.centers[n], p.radii[n], low, high);
                worst = std::max(worst, std::abs(image[(i * 7 + j) * 8 + k] - expected));
            }
    EXPECT_LT(worst, 1e-12);
}

TEST(Voxel, ASphereCutByTheRegionCountsOnlyItsPartInside) {
    // centre on the region's face x = 0: half the ball inside; on its edge x = y = 0: a quarter;
    // on its corner: an eighth
    const double r = 1.0, h = 0.1;
    const Container box(Box(10.0, 10.0));
    const double ball = 4.0 / 3.0 * pi;
    const VoxelGrid g = grid_of({0, 0, 0}, h, 20, 30, 30);
    auto solid = [&](Vec3 c) {
        return sum(solid_fraction_image(one_sphere(c, r), box, g)) * h * h * h;
    };
    EXPECT_NEAR(solid({0, 1.5, 1.5}), ball / 2, 1e-12);
    EXPECT_NEAR(solid({0, 0, 1.5}), ball / 4, 1e-12);
    EXPECT_NEAR(solid({0, 0, 0}), ball / 8, 1e-12);
    // off the grid's nodes: against the quadrature of volume.hpp
    const Vec3 c{0.337, 2.71, 2.43};
    EXPECT_NEAR(solid(c), sphere_volume_in_box(c, r, g.low, g.high()), 1e-11);
}

TEST(Voxel, PartialVolumesSumToTheSolidVolumeInTheRegion) {
    // a soft-sphere bed (spheres of many sizes) cut by a region inside it: the image's sum times
    // h^3 equals the sum of each sphere's exact volume in the region to 1e-9 relative
    SoftSphereParameters params;
    params.particles = 300;
    params.container = Container::tube(5);
    params.seed = 4;
    const SoftSphereResult bed = generate_soft_sphere(params);
    const std::array<double, 6> region{-2.2, -1.9, 0.7, 2.1, 2.3, 4.9};
    const VoxelImage image = voxelize(bed.packing, bed.container, 0.07, region, VoxelType::float64);
    double expected = 0.0;
    for (std::size_t i = 0; i < bed.packing.size(); ++i)
        expected += sphere_volume_in_box(bed.packing.centers[i], bed.packing.radii[i],
                                         image.grid.low, image.grid.high());
    const double h3 = std::pow(image.grid.size, 3);
    EXPECT_NEAR(sum(image.fraction) * h3 / expected, 1.0, 1e-9);
    EXPECT_GT(expected, 10.0); // the region holds many spheres
    // and no voxel holds more than itself (overlaps are at most 1e-4 Dp)
    for (const double f : image.fraction)
        ASSERT_LE(f, 1.0 + 1e-3);
    // in single precision: each voxel within float's rounding of the double one (a few
    // roundings where spheres share a voxel), and the sum still the solid volume to 1e-9
    const VoxelImage single =
        voxelize(bed.packing, bed.container, 0.07, region, VoxelType::float32);
    ASSERT_EQ(single.fraction32.size(), image.fraction.size());
    double single_sum = 0.0, worst = 0.0;
    for (std::size_t n = 0; n < image.fraction.size(); ++n) {
        single_sum += single.fraction32[n];
        worst = std::max(worst, std::abs(single.fraction32[n] - image.fraction[n]));
    }
    EXPECT_LT(worst, 3e-7);
    EXPECT_GT(worst, 0.0); // rounded indeed: not the double image
    EXPECT_NEAR(single_sum * h3 / expected, 1.0, 1e-9);
    EXPECT_NEAR(single.porosity(), image.porosity(), 1e-9);
}

TEST(Voxel, ALatticesPoreImageHasItsPorosity) {
    // simple cubic lattice of unit balls filling a 4 x 4 x 4 box: porosity 1 - pi/6 = 0.4764;
    // the binary image at 40 voxels per diameter within the sampling's 0.002, the exact image
    // to rounding
    LatticeParameters p;
    p.type = LatticeType::sc;
    p.region = LatticeRegion{Box(4.0, 4.0), 4.0};
    const Packing balls = fill_lattice(p);
    const Container box(Box(4.0, 4.0));
    const VoxelImage binary = voxelize(balls, box, 0.025, std::nullopt, VoxelType::boolean);
    EXPECT_EQ(binary.grid.count[0], 160u);
    EXPECT_EQ(binary.grid.count[2], 160u);
    EXPECT_NEAR(binary.porosity(), 1 - pi / 6, 2e-3);
    const VoxelImage exact = voxelize(balls, box, 0.1, std::nullopt, VoxelType::float64);
    EXPECT_NEAR(exact.porosity(), 1 - pi / 6, 1e-12);
}

TEST(Voxel, ACylindersOutsideIsSolidInThePoreImage) {
    // no spheres: the pore image is the tube's cross-section, pi R^2 / (2R)^2 of the voxels (to
    // the counting error of the 630 voxels the circle cuts, about 3e-4)
    Packing none;
    const Container tube(Cylinder(1.0));
    const VoxelGrid g = grid_of({-1, -1, 0}, 0.01, 200, 200, 3);
    const auto image = pore_image(none, tube, g);
    double pores = 0;
    for (const auto v : image)
        pores += v;
    EXPECT_NEAR(pores / static_cast<double>(image.size()), pi / 4, 1e-3);
    // and nothing below the floor: a grid from z = -0.5 holds no pore there
    const auto below = pore_image(none, tube, grid_of({-1, -1, -0.5}, 0.01, 200, 200, 100));
    for (std::size_t k = 0; k < 50; ++k)
        ASSERT_EQ(below[100 * 100 + 100 * 200 + k] + below[100 * 200 * 100 + 100 * 100 + k], 0);
}

TEST(Voxel, APeriodicCellImagesTheCopiesAcrossItsSides) {
    // a ball centred on the side x = 0 of a periodic cell: half of it inside the cell at x > 0,
    // its copy's half at x < LX: the whole ball's volume in the image
    const Container cell(Periodic(4.0, 4.0));
    const VoxelGrid g = grid_of({0, 0, 0}, 0.1, 40, 40, 20);
    const auto image = solid_fraction_image(one_sphere({0.0, 2.0, 1.0}, 0.5), cell, g);
    EXPECT_NEAR(sum(image) * 1e-3, 4.0 / 3.0 * pi * 0.125, 1e-12);
}

TEST(Voxel, TheSameBitsForAnyNumberOfThreads) {
    SoftSphereParameters params;
    params.particles = 200;
    params.seed = 2;
    const SoftSphereResult bed = generate_soft_sphere(params);
    omp_set_num_threads(1);
    const VoxelImage one =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::float64);
    const VoxelImage one_binary =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::boolean);
    omp_set_num_threads(2);
    const VoxelImage two =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::float64);
    const VoxelImage two_binary =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::boolean);
    EXPECT_TRUE(one.fraction == two.fraction);
    EXPECT_TRUE(one_binary.pore == two_binary.pore);
    omp_set_num_threads(1);
    const VoxelImage one_single =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::float32);
    omp_set_num_threads(2);
    const VoxelImage two_single =
        voxelize(bed.packing, bed.container, 0.05, std::nullopt, VoxelType::float32);
    EXPECT_TRUE(one_single.fraction32 == two_single.fraction32);
}

TEST(Voxel, BadGridsAreRefusedNamingTheOption) {
    const Packing p = one_sphere({0, 0, 0.5}, 0.5);
    const Container tube(Cylinder(2.0));
    EXPECT_THROW(voxel_grid(p, tube, 0.0), InvalidInput);
    EXPECT_THROW(voxel_grid(p, tube, std::nan("")), InvalidInput);
    EXPECT_THROW(voxel_grid(p, tube, 0.1, std::array<double, 6>{0, 0, 0, 1, -1, 1}), InvalidInput);
    try {
        voxel_grid(p, tube, 1e-6);
        FAIL() << "4e18 voxels accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("--voxel-size"), std::string::npos);
    }
}
