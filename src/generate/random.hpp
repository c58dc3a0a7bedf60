// Internal: random numbers that are the same bits on every platform. std::mt19937_64 is fully
// specified by the standard; the distributions of <random> (uniform_real_distribution,
// normal_distribution, shuffle) are not, so their results differ between standard libraries.
// The solvers' generation stage (src/generate/soft_bed.hpp) and the sizes (src/generate/sizes.cpp)
// both draw here.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <utility>

namespace packbed::portable_random {

/// A uniform double in [0, 1) from the top 53 bits of one draw.
inline double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// A number in [0, 1) from one integer alone, no generator: the top 53 bits of splitmix64's
/// finaliser of `key` + 1 (Steele, Lea & Flood 2014). For a per-object value that must not
/// depend on the order objects are visited in.
inline double hash01(std::uint64_t key) {
    std::uint64_t h = (key + 1) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    h ^= h >> 31;
    return static_cast<double>(h >> 11) * 0x1.0p-53;
}

/// A uniform integer in [0, bound), bound >= 1, without bias: draws below 2^64 mod bound are
/// rejected (fewer than one draw in 2^32 for bounds below 2^32).
inline std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t bound) {
    const std::uint64_t rejected = (std::uint64_t{0} - bound) % bound; // 2^64 mod bound
    for (;;) {
        const std::uint64_t r = rng();
        if (r >= rejected)
            return r % bound;
    }
}

/// Shuffle `values` (Fisher-Yates, from the last element down).
template <class T> void shuffle(std::span<T> values, std::mt19937_64& rng) {
    for (std::size_t i = values.size(); i > 1; --i)
        std::swap(values[i - 1], values[uniform_below(rng, i)]);
}

} // namespace packbed::portable_random
