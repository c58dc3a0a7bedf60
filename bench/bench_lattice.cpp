// Cost of filling a box with a lattice of about a million balls (target: the diamond
// packing in under 5 s), and of counting its contacts.
#include <benchmark/benchmark.h>

#include "packbed/lattice.hpp"

namespace {

using namespace packbed;

/// A cube that holds about a million whole balls of diameter 1 of `type`.
LatticeParameters million(LatticeType type) {
    LatticeParameters p;
    p.type = type;
    const double per_volume = (1.0 - unit_cell(type).porosity) / (3.14159265358979 / 6.0);
    const double side = std::cbrt(1e6 / per_volume) + 1.0;
    p.region = LatticeRegion{packbed::Box(side, side), side};
    return p;
}

void BM_FillLattice(benchmark::State& state) {
    const LatticeParameters p = million(static_cast<LatticeType>(state.range(0)));
    std::size_t balls = 0;
    for (auto _ : state) {
        const Packing bed = fill_lattice(p);
        balls = bed.size();
        benchmark::DoNotOptimize(bed.centers.data());
    }
    state.counters["balls"] = static_cast<double>(balls);
    state.SetLabel(to_string(p.type));
}

void BM_LatticeContacts(benchmark::State& state) {
    const Packing bed = fill_lattice(million(LatticeType::diamond));
    for (auto _ : state)
        benchmark::DoNotOptimize(lattice_contacts(bed).closest);
    state.counters["balls"] = static_cast<double>(bed.size());
}

} // namespace

BENCHMARK(BM_FillLattice)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LatticeContacts)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
