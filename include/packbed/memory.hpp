// Memory known before the work starts (docs/reliability.md, "Memory"): what a job will need,
// estimated from its request, against what this process can still have; a job that would not
// fit is refused at once (exit status 2) instead of failing after minutes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace packbed {

/// The bytes this process can still allocate: the least of the machine's available memory
/// (/proc/meminfo MemAvailable), what its cgroup leaves (v2 memory.max less memory.current, or
/// v1's limit less usage) and its address-space limit (RLIMIT_AS, `ulimit -v`) less what it maps
/// now. Nothing when none of them can be read.
std::optional<std::uint64_t> available_memory();

/// `bytes` for people: "37 MiB", "1.2 GiB".
std::string memory_text(std::uint64_t bytes);

/// Refuse a job whose estimate does not fit in available_memory().
/// \param what the job, as the message names it ("generate: 1e+08 spheres")
/// \param allowed what would fit ("fewer spheres")
/// \throws InvalidInput "WHAT needs about X of memory; Y is available here; allowed: ALLOWED"
void check_memory(std::string_view what, std::uint64_t bytes, std::string_view allowed);

/// What a generation of `spheres` keeps at its largest (the bed, its neighbour list, the
/// solver's per-sphere state, the staged CSV and VTU): measured 36 MiB at 1e5 spheres and 257
/// MiB at 1e6 (a = 20 and 50, docs/performance.md); estimated as 32 MiB + 400 bytes a sphere.
/// Also a lattice's (95 MiB for 296 353 balls). With friction (`frictional`), each sphere's
/// rotation and wall springs and each listed pair's spring and forces add about 1 200 bytes a
/// sphere (a = 30, 1e5 spheres in one piece: 171 MiB against 53): 1 250 are counted.
std::uint64_t generation_memory(std::uint64_t spheres, bool frictional = false);

/// What a bed read from a file keeps per sphere: its centre and radius (32 bytes) and its line
/// number (8), and the same again while a vector grows.
inline constexpr std::uint64_t read_sphere_bytes = 40;

} // namespace packbed
