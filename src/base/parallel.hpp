// Internal: when the library's OpenMP loops go parallel.
#pragma once

#include <cstddef>

namespace packbed::detail {

/// Below this many spheres a parallel iteration costs more in thread synchronisation than it
/// saves (1.1-1.2x on 2 threads at 500 spheres, a barrier costing as much as the work split;
/// 1.86x at 5 000: docs/notes/threads.md, docs/performance.md "One step"), and
/// several small runs at once would oversubscribe the cores. Loops over fewer spheres run on
/// one thread; the results are the same either way.
inline constexpr std::size_t parallel_min_spheres = 1000;

} // namespace packbed::detail
