// Time the voxel images of one bed in one process (docs/performance.md, "Voxel
// images"): the binary image, the exact image in float64 and in float32, each `repeats` times,
// in that order. A driver of the library alone (no Python, no file written), so that two builds
// can be compared in one command, old then new:
//
//     for b in OLD/build NEW/build; do $b/bench/bench_voxel_image BED/particles.csv 0.05 2; done
//
// KINDS (binary,float64,float32 by default) picks the images, e.g. `float32` alone in a fresh
// process. With MALLOC_MMAP_MAX_=0 MALLOC_TRIM_THRESHOLD_=100000000000 in the environment, glibc
// keeps the freed images' memory, so every run after the first times the computation without the
// first touch of fresh pages (what this machine's memory costs).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>

#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"
#include "packbed/voxel.hpp"

using namespace packbed;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_voxel_image PARTICLES [VOXEL_SIZE] [REPEATS] [KINDS]\n");
        return 2;
    }
    const double h = argc > 2 ? std::atof(argv[2]) : 0.05;
    const int repeats = argc > 3 ? std::atoi(argv[3]) : 2;
    // which images, in this order: any of binary, float64, float32 (default all three)
    const std::string kinds = argc > 4 ? argv[4] : "binary,float64,float32";
    const BedInContainer bed = read_bed_in_container(argv[1], ReadOptions{}, "", 0.0, 0.01);
    if (!bed.container) {
        std::fprintf(stderr, "no summary.json with a container next to %s\n", argv[1]);
        return 2;
    }
    for (int r = 0; r < repeats; ++r)
        for (const VoxelType type : {VoxelType::boolean, VoxelType::float64, VoxelType::float32}) {
            if (kinds.find(type == VoxelType::boolean ? "binary" : voxel_type_name(type)) ==
                std::string::npos)
                continue;
            const auto start = std::chrono::steady_clock::now();
            const VoxelImage image =
                voxelize(bed.file.packing, *bed.container, h, std::nullopt, type);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf("%-8s %zu x %zu x %zu voxels: %.2f s, porosity %.12f\n",
                        type == VoxelType::boolean ? "binary" : voxel_type_name(type),
                        image.grid.count[0], image.grid.count[1], image.grid.count[2], seconds,
                        image.porosity());
        }
}
