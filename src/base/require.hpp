// Internal: the one wording of a refused value.
#pragma once

#include <string_view>

#include <fmt/format.h>

#include "packbed/error.hpp"

namespace packbed::detail {

/// Throw InvalidInput unless `ok`: "NAME = VALUE is not allowed; allowed: ALLOWED".
inline void require(bool ok, std::string_view name, double value, std::string_view allowed) {
    if (!ok)
        throw InvalidInput(
            fmt::format("{} = {} is not allowed; allowed: {}", name, value, allowed));
}

} // namespace packbed::detail
