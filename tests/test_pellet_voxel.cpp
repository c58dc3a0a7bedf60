// Voxel images of pellet beds and the pellets' volume in a box (voxel.hpp, the shapes'
// volume_in_box): closed forms, the sum over a partition, the image's sum, its voxels against
// the pore image's, periodic copies, and the same bits for any number of threads.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/box.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder.hpp"
#include "packbed/error.hpp"
#include "packbed/periodic.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/voxel.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// The pellets the tests draw, at size 1 (volume-equivalent radius 1): a cylinder L = D, a ring
/// D = L = 2 DI, a trilobe and a spherocylinder L = D.
std::vector<std::pair<std::string, PelletShape>> shapes() {
    CylinderShape ring = MultilobeShape::of(1, 1.0, 0.0, 1.0).lobe;
    const double scale = std::cbrt(1.0 / 0.75); // the ring's volume is 3/4 the cylinder's
    ring = {ring.radius * scale, ring.half_length * scale, 0.5 * ring.radius * scale};
    return {{"cylinder", MultilobeShape::of(1, 1.0, 0.0, 1.0)},
            {"ring", MultilobeShape::cylinder(ring)},
            {"trilobe", MultilobeShape::of(3, 1.0, 0.8, 1.5)},
            {"spherocylinder", SpherocylinderShape::of_aspect(1.0)}};
}

double volume_in_box(const PelletShape& s, const Placement& p, const Vec3& low, const Vec3& high) {
    return std::visit([&](const auto& shape) { return shape.volume_in_box(p, low, high); }, s);
}

double volume(const PelletShape& s, double size) {
    return std::visit([&](const auto& shape) { return shape.volume(size); }, s);
}

Quaternion turned(double angle, Vec3 axis) {
    axis = axis * (1.0 / norm(axis));
    return {std::cos(0.5 * angle), axis.x * std::sin(0.5 * angle), axis.y * std::sin(0.5 * angle),
            axis.z * std::sin(0.5 * angle)};
}

double sum(const Voxels<double>& image) {
    double s = 0.0;
    for (const double v : image)
        s += v;
    return s;
}

} // namespace

TEST(PelletVolumeInABox, ClosedForms) {
    // A spherocylinder lying along x, cut by the box's face x = c across its cylinder part: a
    // cap's hemisphere and the cylinder from its end to c, 2 pi R^3 / 3 + pi R^2 (c + L / 2).
    const SpherocylinderShape rod = SpherocylinderShape::of_aspect(1.0);
    const double r = rod.radius, h = rod.half_length;
    const Placement lying{{0.0, 0.0, 2.0}, turned(pi / 2, {0.0, 1.0, 0.0}), 1.0};
    for (const double c : {-0.7 * h, 0.0, 0.4 * h})
        EXPECT_NEAR(rod.volume_in_box(lying, {-5.0, -5.0, 0.0}, {c, 5.0, 5.0}),
                    2.0 * pi * r * r * r / 3.0 + pi * r * r * (c + h), 1e-13)
            << c;
    // Into a cap: the hemisphere's part beyond the plane x = h + s is a cap of height r - s.
    const double s = 0.3 * r;
    EXPECT_NEAR(rod.volume_in_box(lying, {h + s, -5.0, 0.0}, {5.0, 5.0, 5.0}),
                pi * (r - s) * (r - s) * (2.0 * r + s) / 3.0, 1e-13);
    // An upright trilobe (lobes towards 0, 120 and 240 degrees) is mirror-symmetric about
    // y = 0: each half holds half its volume; a cylinder's quarter about its axis a quarter.
    const MultilobeShape tri = MultilobeShape::of(3, 1.0, 0.8, 1.5);
    const Placement upright{{0.0, 0.0, 2.0}, {}, 1.0};
    EXPECT_NEAR(tri.volume_in_box(upright, {-5.0, 0.0, 0.0}, {5.0, 5.0, 5.0}), tri.volume(1.0) / 2,
                1e-13);
    const MultilobeShape cyl = MultilobeShape::of(1, 1.0, 0.0, 1.0);
    EXPECT_NEAR(cyl.volume_in_box(upright, {0.0, 0.0, 0.0}, {5.0, 5.0, 5.0}), cyl.volume(1.0) / 4,
                1e-13);
}

TEST(PelletVolumeInABox, EightBoxesAboutAnyPointAddUpToThePellet) {
    // The eight boxes that part space at a point inside a turned pellet hold it all, for every
    // shape, a point near its surface and one well inside.
    for (const auto& [name, shape] : shapes()) {
        const Placement p{{0.1, -0.2, 0.3}, turned(1.1, {0.6, 0.2, 0.8}), 0.8};
        for (const Vec3 at : {Vec3{0.05, 0.1, 0.2}, Vec3{0.4, -0.5, 0.9}, Vec3{0.13, -0.21, 0.3}}) {
            double total = 0.0;
            for (int k = 0; k < 8; ++k) {
                const Vec3 low{k & 1 ? at.x : -5.0, k & 2 ? at.y : -5.0, k & 4 ? at.z : -5.0};
                const Vec3 high{k & 1 ? 5.0 : at.x, k & 2 ? 5.0 : at.y, k & 4 ? 5.0 : at.z};
                total += volume_in_box(shape, p, low, high);
            }
            EXPECT_NEAR(total, volume(shape, 0.8), 1e-12) << name;
        }
    }
}

TEST(PelletVoxels, OnePelletsImageHoldsItsVolumeAndAgreesWithThePoreImage) {
    const Container box(Box(0.0, 3.0, 0.0, 3.0));
    VoxelGrid grid;
    grid.low = {0.0, 0.0, 0.0};
    grid.size = 0.04;
    grid.count = {75, 75, 75};
    for (const auto& [name, shape] : shapes()) {
        Packing packing;
        packing.centers = {{1.47, 1.52, 1.5}};
        packing.radii = {0.6};
        packing.orientations = {turned(0.9, {0.3, -0.7, 0.4})};
        const Voxels<double> fraction = solid_fraction_image<double>(packing, shape, box, grid);
        const Voxels<std::uint8_t> pore = pore_image(packing, shape, box, grid);
        // The image's sum times h^3 is the pellet's volume: each voxel cut by its surface to
        // the integration's tolerance, each voxel deeper than its half-diagonal whole.
        EXPECT_NEAR(sum(fraction) * std::pow(grid.size, 3), volume(shape, 0.6),
                    1e-10 * volume(shape, 0.6))
            << name;
        // A voxel wholly solid has its centre solid; one with nothing solid its centre in the
        // pore space; the count of solid centres is the volume to the grid's resolution.
        std::size_t solid = 0, disagree = 0;
        for (std::size_t v = 0; v < fraction.size(); ++v) {
            solid += pore[v] == 0;
            disagree +=
                (fraction[v] == 1.0 && pore[v] != 0) || (fraction[v] == 0.0 && pore[v] != 1);
        }
        EXPECT_EQ(disagree, 0u) << name;
        EXPECT_NEAR(static_cast<double>(solid) * std::pow(grid.size, 3), volume(shape, 0.6),
                    0.02 * volume(shape, 0.6))
            << name;
    }
}

TEST(PelletVoxels, APelletAcrossAPeriodicSideComesBackWhole) {
    // A trilobe lying across the cell's side x = 0: its copy beyond x = 2 fills the rest, so
    // the image of the cell holds all of it.
    const Container cell(Periodic(2.0, 2.0));
    const PelletShape tri = MultilobeShape::of(3, 1.0, 0.8, 1.5);
    Packing packing;
    packing.centers = {{0.05, 1.0, 0.7}};
    packing.radii = {0.5};
    packing.orientations = {turned(pi / 2, {0.2, 1.0, 0.1})};
    const VoxelImage image = voxelize(packing, cell, 0.05, std::nullopt, VoxelType::float64, &tri);
    EXPECT_EQ(image.grid.count[0], 40u);
    EXPECT_NEAR(sum(image.fraction) * std::pow(0.05, 3), volume(tri, 0.5), 1e-10);
}

TEST(PelletVoxels, TheSameBitsForAnyNumberOfThreads) {
    // Twelve rings in a tube, overlapping freely (the image adds their volumes).
    const Container tube = Container::tube_of_radius(1.5);
    const PelletShape ring = shapes()[1].second;
    Packing packing;
    for (int k = 0; k < 12; ++k) {
        packing.centers.push_back({0.8 * std::cos(k), 0.8 * std::sin(k), 0.5 + 0.25 * k});
        packing.radii.push_back(0.5);
        packing.orientations.push_back(turned(0.3 * k, {std::sin(k), 1.0, 0.2}));
    }
    omp_set_num_threads(1);
    const VoxelImage one = voxelize(packing, tube, 0.06, std::nullopt, VoxelType::float32, &ring);
    const VoxelImage one_pore =
        voxelize(packing, tube, 0.06, std::nullopt, VoxelType::boolean, &ring);
    omp_set_num_threads(2);
    const VoxelImage two = voxelize(packing, tube, 0.06, std::nullopt, VoxelType::float32, &ring);
    const VoxelImage two_pore =
        voxelize(packing, tube, 0.06, std::nullopt, VoxelType::boolean, &ring);
    EXPECT_TRUE(one.fraction32 == two.fraction32);
    EXPECT_TRUE(one_pore.pore == two_pore.pore);
    // The default region reaches the pellets' highest point, above the spheres of d_v's.
    EXPECT_GE(one.grid.high().z, pellet_bed_top(packing, ring));
    EXPECT_GT(pellet_bed_top(packing, ring), 0.5 + 0.25 * 11 + 0.5);
}

TEST(PelletVoxels, APelletWithoutAnOrientationIsRefused) {
    Packing packing;
    packing.centers = {{0.0, 0.0, 1.0}};
    packing.radii = {0.5};
    const PelletShape cyl = MultilobeShape::of(1, 1.0, 0.0, 1.0);
    EXPECT_THROW(voxelize(packing, Container::tube_of_radius(1.0), 0.1, std::nullopt,
                          VoxelType::boolean, &cyl),
                 InvalidInput);
}
