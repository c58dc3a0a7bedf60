// The seams of a bed relaxed in layers (the target: "the axial profile of a tall bed without
// interface seams above the scatter of one slab"; docs/validation.md, "A tall bed's axial
// profile"). For each seed, runs the fire solver on a bed of `particles` spheres at aspect ratio
// `a` in layers of `layer_height` Dp, records the highest settled centre after each layer (the
// surface the next layer was laid on), then measures the axial void fraction in slabs of 0.25 Dp
// (exact volumes, analyze_bed, band 2 Dp clear of the ends) and folds the layers onto one: each
// slab below the last surface goes to the 1-Dp bin of u = z - (the first surface above z - 4),
// from u = -0.85 layer_height (a relaxed layer's thickness) to +4, the 5 Dp over the floor left
// out (the floor's own order). Prints, per bin, the mean over interfaces and seeds minus the
// mean of every folded slab, and the slabs in it; the largest such difference; the scatter of
// one 1-Dp slab of the band (RMS about the band mean, pooled over the seeds); steps and void
// fraction per seed:
//
//     build/bench/bench_seams 20 60000 1,2,3 [LAYER_HEIGHT]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "packbed/analysis.hpp"
#include "packbed/soft_sphere.hpp"

using namespace packbed;

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: bench_seams A PARTICLES SEED[,SEED...] [LAYER_HEIGHT]\n");
        return 2;
    }
    const double a = std::atof(argv[1]);
    const auto particles = std::strtoull(argv[2], nullptr, 10);
    std::vector<std::uint64_t> seeds;
    std::stringstream list(argv[3]);
    for (std::string s; std::getline(list, s, ',');)
        seeds.push_back(std::strtoull(s.c_str(), nullptr, 10));
    const double layer_height = argc > 4 ? std::atof(argv[4]) : 30.0;

    constexpr double slab = 0.25;
    constexpr double floor_order = 5.0; // Dp over the floor left out of the folding
    const int u_low = -static_cast<int>(0.85 * layer_height);
    constexpr int u_high = 4;                   // 1-Dp bins of u in [u_low, u_high)
    std::map<int, std::pair<double, int>> bins; // bin -> sum of void fractions, slabs
    double folded = 0.0;                        // every folded slab's void fraction, summed
    int folded_slabs = 0;
    double scatter2 = 0.0;
    int scatter_slabs = 0;
    for (const std::uint64_t seed : seeds) {
        SoftSphereParameters p;
        p.container = packbed::Container::tube(a);
        p.particles = particles;
        p.seed = seed;
        p.layer_height = layer_height;
        std::vector<double> surfaces;
        RunControl control;
        control.on_layer = [&](const LayerCheckpoint& state) { surfaces.push_back(state.top); };
        const auto t0 = std::chrono::steady_clock::now();
        const SoftSphereResult result = relax_with_fire(p, control);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        surfaces.pop_back(); // the last layer's top is the bed's, not an interface
        AnalysisOptions options;
        options.band_clearance = 2.0;
        options.slab_height = slab;
        const BedAnalysis bed = analyze_bed(result.packing, result.container, options);
        const double mean = bed.void_fraction;
        // one 1-Dp slab's scatter: groups of 4 slabs inside the band
        std::vector<double> inside;
        for (const ProfileBin& b : bed.axial_void_fraction)
            if (b.low >= bed.band.z_low && b.high <= bed.band.z_high)
                inside.push_back(b.value);
        for (std::size_t s = 0; s + 4 <= inside.size(); s += 4) {
            const double e = (inside[s] + inside[s + 1] + inside[s + 2] + inside[s + 3]) / 4.0;
            scatter2 += (e - mean) * (e - mean);
            ++scatter_slabs;
        }
        for (const ProfileBin& b : bed.axial_void_fraction) {
            const double z = 0.5 * (b.low + b.high);
            if (b.low < std::max(bed.band.z_low, floor_order) || b.high > bed.band.z_high)
                continue;
            const auto above = std::find_if(surfaces.begin(), surfaces.end(),
                                            [&](double s) { return s + u_high > z; });
            if (above == surfaces.end())
                continue; // the top layer: its free surface, no interface
            const int bin = static_cast<int>(std::floor(z - *above));
            if (bin < u_low || bin >= u_high)
                continue;
            bins[bin].first += b.value;
            bins[bin].second += 1;
            folded += b.value;
            ++folded_slabs;
        }
        std::printf("seed %llu: %zu layers, %llu steps, %.1f s, e = %.4f (band %.1f-%.1f)\n",
                    static_cast<unsigned long long>(seed), surfaces.size() + 1,
                    static_cast<unsigned long long>(result.iterations), seconds, mean,
                    bed.band.z_low, bed.band.z_high);
    }
    std::printf("one 1-Dp slab scatters by %.4f (RMS about the band mean, %d slabs)\n",
                std::sqrt(scatter2 / std::max(1, scatter_slabs)), scatter_slabs);
    const double folded_mean = folded / std::max(1, folded_slabs);
    std::printf("mean of the folded slabs: %.4f (%d slabs)\n", folded_mean, folded_slabs);
    double largest = 0.0;
    std::printf("| u (Dp) | e - folded mean | slabs |\n|---|---|---|\n");
    for (int b = u_low; b < u_high; ++b) {
        const auto& [sum, n] = bins[b];
        const double d = n > 0 ? sum / n - folded_mean : 0.0;
        largest = std::max(largest, std::abs(d));
        std::printf("| %+.1f | %+.4f | %d |\n", b + 0.5, d, n);
    }
    std::printf("largest |e - folded mean| of a bin: %.4f\n", largest);
}
