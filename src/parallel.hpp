// Internal: when the library's OpenMP loops go parallel.
#pragma once

#include <cstddef>

namespace packbed::detail {

/// Below this many spheres a parallel iteration costs more in thread synchronisation than it
/// saves (measured: 1.1x on 2 threads at 500 spheres, 2.1x at 5 000; docs/performance.md), and
/// several small runs at once would oversubscribe the cores. Loops over fewer spheres run on
/// one thread; the results are the same either way.
inline constexpr std::size_t parallel_min_spheres = 1000;

} // namespace packbed::detail
