// Cost of one iteration of eq. (4) (Salvat et al. 2005) on a relaxed bed, per update order
// and thread count. The bed is taken after the initial stage, then iterated with gravity on
// (Cg = 2e-5, the paper's typical stationary value), so Verlet-list rebuilds are included at
// their real rate. BM_ListBuild: one Verlet-list build as the solvers do it (spatial order of
// the spheres, then the list with a skin of 0.1 Dp) on the same beds.
#include <map>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <omp.h>

#include "packbed/neighbor_list.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"

namespace {

using packbed::SoftSphereGenerator;
using packbed::SoftSphereParameters;
using packbed::UpdateOrder;

/// Aspect ratio per bed size, so that beds stay a few tens of diameters tall.
double aspect_ratio_for(std::int64_t particles) {
    return particles <= 500 ? 5.0 : particles <= 5000 ? 10.0 : 20.0;
}

/// One relaxed bed per (size, order), built once and reused by every repetition.
SoftSphereGenerator& relaxed_bed(std::int64_t particles, UpdateOrder order) {
    static std::map<std::pair<std::int64_t, int>, std::unique_ptr<SoftSphereGenerator>> beds;
    auto& bed = beds[{particles, static_cast<int>(order)}];
    if (!bed) {
        SoftSphereParameters p;
        p.particles = static_cast<std::uint64_t>(particles);
        p.container = packbed::Container::tube(aspect_ratio_for(particles));
        p.update = order;
        bed = std::make_unique<SoftSphereGenerator>(p);
        bed->run_initial_stage();
    }
    return *bed;
}

void BM_Iteration(benchmark::State& state) {
    const auto particles = state.range(0);
    const auto order = static_cast<UpdateOrder>(state.range(1));
    const int threads = static_cast<int>(state.range(2));
    omp_set_num_threads(threads);
    SoftSphereGenerator& bed = relaxed_bed(particles, order);
    for (auto _ : state)
        benchmark::DoNotOptimize(bed.iterate(2e-5));
    state.SetItemsProcessed(state.iterations() * particles);
    state.counters["ns_per_sphere"] =
        benchmark::Counter(static_cast<double>(state.iterations() * particles),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(order == UpdateOrder::in_place ? "in-place" : "simultaneous");
}

void BM_ListBuild(benchmark::State& state) {
    const auto particles = state.range(0);
    omp_set_num_threads(static_cast<int>(state.range(1)));
    // stored in spatial order, as the solvers keep their spheres between builds
    const packbed::Packing& generated =
        relaxed_bed(particles, UpdateOrder::simultaneous).packing_dp();
    const std::vector<std::uint32_t> key = packbed::spatial_order(generated.centers, 1.1);
    packbed::Packing bed;
    for (const std::uint32_t i : key)
        bed.add(generated.centers[i], generated.radii[i]);
    packbed::NeighborList list;
    for (auto _ : state) {
        benchmark::DoNotOptimize(packbed::spatial_order(bed.centers, 1.1));
        list.build(bed.centers, bed.radii, 0.1, key);
        benchmark::DoNotOptimize(list.pairs());
    }
    state.counters["ns_per_sphere"] =
        benchmark::Counter(static_cast<double>(state.iterations() * particles),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// The size mixes of BM_IterationSizes: the cost per sphere-step of a bed of many
/// sizes against a mono-sized one of the same Np.
enum class Mix { mono = 0, binary4 = 1, lognormal = 2 };

/// Diameters in units of the Sauter mean d32 (the reference Dp), generation order.
std::vector<double> sizes_of(Mix mix, std::size_t n) {
    std::vector<double> d;
    if (mix == Mix::binary4) {
        // Diameters 1 and 4 in equal volumes: 64 small spheres for each large one; d32 =
        // (64 + 64) / (64 + 16) = 1.6.
        for (std::size_t i = 0; i < n; ++i)
            d.push_back((i % 65 == 64 ? 4.0 : 1.0) / 1.6);
    } else if (mix == Mix::lognormal) {
        // GSD 1.5 by volume (the default bounds: a size ratio of 10), as `--sizes
        // lognormal:1,1.5` draws it, in units of its d32.
        d = packbed::draw_diameters(packbed::parse_sizes("lognormal:1,1.5", 1.0), n,
                                    packbed::FractionBasis::volume, 1);
        const double d32 = packbed::size_statistics(d).sauter_mean;
        for (double& x : d)
            x /= d32;
    }
    return d;
}

void BM_IterationSizes(benchmark::State& state) {
    const auto particles = state.range(0);
    const auto mix = static_cast<Mix>(state.range(1));
    omp_set_num_threads(static_cast<int>(state.range(2)));
    static std::map<std::pair<std::int64_t, int>, std::unique_ptr<SoftSphereGenerator>> beds;
    auto& bed = beds[{particles, static_cast<int>(mix)}];
    if (!bed) {
        SoftSphereParameters p;
        p.particles = static_cast<std::uint64_t>(particles);
        p.container = packbed::Container::tube(20.0);
        p.sizes = sizes_of(mix, p.particles);
        bed = std::make_unique<SoftSphereGenerator>(p);
        bed->run_initial_stage();
    }
    for (auto _ : state)
        benchmark::DoNotOptimize(bed->iterate(2e-5));
    state.counters["ns_per_sphere"] =
        benchmark::Counter(static_cast<double>(state.iterations() * particles),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(mix == Mix::mono      ? "mono"
                   : mix == Mix::binary4 ? "binary 1:4 equal volumes"
                                         : "lognormal GSD 1.5");
}

/// The containers of BM_IterationContainers: the cost per sphere-step of the same
/// number of spheres in each, of about the same cross-section (a = 20: 314 Dp^2).
enum class Shape { cylinder = 0, annulus = 1, box = 2, periodic = 3, cone = 4 };

void BM_IterationContainers(benchmark::State& state) {
    const auto particles = state.range(0);
    const auto shape = static_cast<Shape>(state.range(1));
    omp_set_num_threads(static_cast<int>(state.range(2)));
    static std::map<std::pair<std::int64_t, int>, std::unique_ptr<SoftSphereGenerator>> beds;
    auto& bed = beds[{particles, static_cast<int>(shape)}];
    if (!bed) {
        SoftSphereParameters p;
        p.particles = static_cast<std::uint64_t>(particles);
        p.container = packbed::Container::tube(20.0);
        if (shape == Shape::annulus) // pi (10.6^2 - 3^2) = 324.7 Dp^2
            p.container = packbed::Annulus(10.6, 3.0);
        else if (shape == Shape::box)
            p.container = packbed::Box(17.7, 17.7);
        else if (shape == Shape::periodic)
            p.container = packbed::Periodic(17.7, 17.7);
        else if (shape == Shape::cone) // radius 8 at the floor, 10.4 at L0 = 73 Dp
            p.container = packbed::Cone(8.0, 12.0, 120.0);
        bed = std::make_unique<SoftSphereGenerator>(p);
        bed->run_initial_stage();
    }
    for (auto _ : state)
        benchmark::DoNotOptimize(bed->iterate(2e-5));
    state.counters["ns_per_sphere"] =
        benchmark::Counter(static_cast<double>(state.iterations() * particles),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(shape == Shape::cylinder  ? "cylinder a = 20"
                   : shape == Shape::annulus ? "annulus 21.2, 6"
                   : shape == Shape::box     ? "box 17.7 x 17.7"
                   : shape == Shape::cone    ? "cone 16, 24, 120"
                                             : "periodic 17.7 x 17.7");
}

} // namespace

BENCHMARK(BM_IterationContainers)
    ->ArgNames({"Np", "shape", "threads"})
    ->Args({20000, static_cast<int>(Shape::cylinder), 2})
    ->Args({20000, static_cast<int>(Shape::annulus), 2})
    ->Args({20000, static_cast<int>(Shape::box), 2})
    ->Args({20000, static_cast<int>(Shape::periodic), 2})
    ->Args({20000, static_cast<int>(Shape::cone), 2})
    ->UseRealTime();

BENCHMARK(BM_IterationSizes)
    ->ArgNames({"Np", "mix", "threads"})
    ->Args({20000, static_cast<int>(Mix::mono), 2})
    ->Args({20000, static_cast<int>(Mix::binary4), 2})
    ->Args({20000, static_cast<int>(Mix::lognormal), 2})
    ->UseRealTime();

BENCHMARK(BM_ListBuild)
    ->ArgNames({"Np", "threads"})
    ->Args({500, 1})
    ->Args({5000, 1})
    ->Args({50000, 1})
    ->Args({50000, 2})
    ->UseRealTime();

BENCHMARK(BM_Iteration)
    ->ArgNames({"Np", "order", "threads"})
    ->Args({500, static_cast<int>(UpdateOrder::in_place), 1})
    ->Args({500, static_cast<int>(UpdateOrder::simultaneous), 1})
    ->Args({500, static_cast<int>(UpdateOrder::simultaneous), 2})
    ->Args({5000, static_cast<int>(UpdateOrder::in_place), 1})
    ->Args({5000, static_cast<int>(UpdateOrder::simultaneous), 1})
    ->Args({5000, static_cast<int>(UpdateOrder::simultaneous), 2})
    ->Args({50000, static_cast<int>(UpdateOrder::in_place), 1})
    ->Args({50000, static_cast<int>(UpdateOrder::simultaneous), 1})
    ->Args({50000, static_cast<int>(UpdateOrder::simultaneous), 2})
    ->UseRealTime();

BENCHMARK_MAIN();
