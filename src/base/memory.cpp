#include "packbed/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/text.hpp"

namespace packbed {

namespace {

/// The value in kB of `key` (e.g. "MemAvailable:") in a /proc file of "key: value kB" lines.
std::optional<std::uint64_t> proc_kilobytes(const char* path, std::string_view key) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (line.starts_with(key)) { // "MemAvailable:   1234 kB"
            const auto words = split_spaces(std::string_view(line).substr(key.size()));
            const auto kb = words.empty() ? std::nullopt : parse_whole<std::uint64_t>(words[0]);
            if (!kb || *kb > std::numeric_limits<std::uint64_t>::max() / 1024)
                return std::nullopt;
            return *kb * 1024;
        }
    return std::nullopt;
}

/// A whole number in a one-line file ("max" and unreadable files: nothing).
std::optional<std::uint64_t> file_number(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    if (!(in >> word))
        return std::nullopt;
    return parse_whole<std::uint64_t>(word);
}

/// What this process's cgroup leaves: v2 (the unified hierarchy) or v1's memory controller.
std::optional<std::uint64_t> cgroup_left() {
    std::ifstream groups("/proc/self/cgroup");
    std::string line;
    while (std::getline(groups, line)) {
        const auto colon = line.find(':'), second = line.find(':', colon + 1);
        if (colon == std::string::npos || second == std::string::npos)
            continue;
        const std::string controllers = line.substr(colon + 1, second - colon - 1);
        const std::string path = line.substr(second + 1);
        std::optional<std::uint64_t> limit, used;
        if (controllers.empty()) { // v2
            limit = file_number("/sys/fs/cgroup" + path + "/memory.max");
            used = file_number("/sys/fs/cgroup" + path + "/memory.current");
        } else if (("," + controllers + ",").find(",memory,") != std::string::npos) { // v1
            limit = file_number("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
            used = file_number("/sys/fs/cgroup/memory" + path + "/memory.usage_in_bytes");
        }
        if (limit && *limit < (std::uint64_t{1} << 60))
            return *limit > used.value_or(0) ? *limit - used.value_or(0) : 0;
    }
    return std::nullopt;
}

} // namespace

std::optional<std::uint64_t> available_memory() {
    std::optional<std::uint64_t> least = proc_kilobytes("/proc/meminfo", "MemAvailable:");
    const auto take = [&](std::optional<std::uint64_t> v) {
        if (v)
            least = least ? std::min(*least, *v) : *v;
    };
    take(cgroup_left());
    rlimit as{};
    if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
        const std::uint64_t mapped = proc_kilobytes("/proc/self/status", "VmSize:").value_or(0);
        take(as.rlim_cur > mapped ? as.rlim_cur - mapped : 0);
    }
    return least;
}

std::string memory_text(std::uint64_t bytes) {
    const double b = static_cast<double>(bytes);
    if (b >= 1024.0 * 1024 * 1024)
        return fmt::format("{:.3g} GiB", b / (1024.0 * 1024 * 1024));
    return fmt::format("{:.3g} MiB", b / (1024.0 * 1024));
}

void check_memory(std::string_view what, std::uint64_t bytes, std::string_view allowed) {
    const std::optional<std::uint64_t> available = available_memory();
    if (available && bytes > *available)
        throw InvalidInput(fmt::format("{} needs about {} of memory; {} is available here; "
                                       "allowed: {}",
                                       what, memory_text(bytes), memory_text(*available), allowed));
}

std::uint64_t generation_memory(std::uint64_t spheres, bool frictional) {
    return (std::uint64_t{32} << 20) + (frictional ? 1650 : 400) * spheres;
}

} // namespace packbed
