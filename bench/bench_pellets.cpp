// Cost of what a cylinder pellet answers (cylinder_shape.hpp) beside a sphere's: the pair
// overlap (the exact penetration depth), the wall overlap in a tube, and the volume between two
// heights where the side cannot cut it (closed-form sections) and where a shell's wall does.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "packbed/cone.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/sphere_shape.hpp"

namespace {

using namespace packbed;

/// Uniformly random rotations (Shoemake 1992), seed 7.
std::vector<Quaternion> rotations(std::size_t n) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Quaternion> out(n);
    for (Quaternion& q : out) {
        const double u1 = u(rng), u2 = u(rng), u3 = u(rng);
        q = uniform_rotation(u1, u2, u3);
    }
    return out;
}

/// Pellets of d_v = 1 (size 0.5), L = D, their centres 0.9 apart along random directions:
/// most pairs overlap by a few hundredths.
struct Pairs {
    std::vector<Quaternion> qa = rotations(1024), qb = rotations(2048);
    std::vector<Vec3> ab;
    Pairs() {
        std::mt19937_64 rng(11);
        std::normal_distribution<double> g;
        for (int k = 0; k < 1024; ++k) {
            const Vec3 v{g(rng), g(rng), g(rng)};
            ab.push_back(v * (0.9 / norm(v)));
        }
    }
};

void BM_SpherePair(benchmark::State& state) {
    const Pairs p;
    const SphereShape s;
    std::size_t k = 0;
    for (auto _ : state) {
        const Vec3& ab = p.ab[k++ % 1024];
        benchmark::DoNotOptimize(s.pair_overlap({{}, {}, 0.5}, s, {ab, {}, 0.5}, ab).depth);
    }
}

void BM_CylinderPair(benchmark::State& state) {
    const Pairs p;
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    std::size_t k = 0, overlapping = 0, calls = 0;
    for (auto _ : state) {
        const std::size_t i = k++ % 1024;
        const Vec3& ab = p.ab[i];
        const double depth =
            c.pair_overlap({{}, p.qa[i], 0.5}, c, {ab, p.qb[1024 + i], 0.5}, ab).depth;
        overlapping += depth > 0.0 ? 1 : 0;
        ++calls;
        benchmark::DoNotOptimize(depth);
    }
    state.counters["overlapping"] = static_cast<double>(overlapping) / static_cast<double>(calls);
}

/// Pellets pressed 0.01 into a tube of a = 5 (radius 2.5) at random orientations.
void BM_CylinderWall(benchmark::State& state) {
    const std::vector<Quaternion> q = rotations(1024);
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const Container tube = Container::tube(5.0);
    std::vector<Placement> at(1024);
    for (std::size_t i = 0; i < at.size(); ++i) {
        at[i] = {{0.0, 0.0, 3.0}, q[i], 0.5};
        const double reach = c.support(at[i], {1.0, 0.0, 0.0}).x;
        at[i].position.x = 2.51 - reach;
    }
    std::size_t k = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(c.wall_overlap(tube, at[k++ % 1024]));
}

/// The volume between two heights that cut every pellet: state.range(0) = 0 in the middle of
/// the tube (closed-form sections across the axis), 1 at its shell 0.1 from the wall (closed-form
/// horizontal sections), 2 the same shell of a cone with equal radii (the region's integral).
void BM_CylinderVolume(benchmark::State& state) {
    const std::vector<Quaternion> q = rotations(64);
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const Container tube = Container::tube(5.0);
    const Container cone(Cone(2.5, 2.5, 100.0));
    const auto kind = state.range(0);
    std::size_t k = 0;
    for (auto _ : state) {
        const Placement p{{kind > 0 ? 2.0 : 0.0, 0.0, 3.0}, q[k++ % 64], 0.5};
        benchmark::DoNotOptimize(kind == 0   ? c.volume_in(tube, p, 2.9, 3.2)
                                 : kind == 1 ? c.volume_from_wall(tube, 0, 0.1, p, 2.9, 3.2)
                                             : c.volume_from_wall(cone, 0, 0.1, p, 2.9, 3.2));
    }
    state.SetLabel(kind == 0 ? "slab" : (kind == 1 ? "tube shell" : "cone shell"));
}

} // namespace

BENCHMARK(BM_SpherePair);
BENCHMARK(BM_CylinderPair)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CylinderWall)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CylinderVolume)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
