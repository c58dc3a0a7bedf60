// Internal: FNV-1a, 64 bits (Fowler, Noll and Vo), the hash of the checkpoints' hash line, of
// the sizes a pellet checkpoint records and of the host identity of temporaries' names.
#pragma once

#include <cstdint>
#include <string_view>

namespace packbed::detail {

/// FNV-1a 64 of `bytes`, continued from `h` (the offset basis by default).
inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 0xcbf29ce484222325ULL) {
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

} // namespace packbed::detail
