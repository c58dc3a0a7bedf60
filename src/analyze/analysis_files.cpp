#include "packbed/analysis_files.hpp"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

#include "packbed/io.hpp"

namespace packbed {

std::pair<std::string, std::string> wall_table_names(const std::string& wall) {
    return {fmt::format("radial_void_fraction_{}.csv", wall),
            fmt::format("radial_centre_distribution_{}.csv", wall)};
}

namespace {

/// One wall's profile as CSV: the container's position of each bin's middle, its distance
/// from the wall in Dp (12 significant digits, as analysis_tables' profiles), the value.
std::string wall_profile_csv(const Container& container, std::size_t wall, double dp,
                             std::string_view value, const std::vector<ProfileBin>& bins) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{},x_from_wall_d,{}\n",
                   container.profile_position_name_from(wall), value);
    for (const auto& b : bins) {
        const double mid = 0.5 * (b.low + b.high);
        fmt::format_to(std::back_inserter(out), "{:.12g},{:.12g},{}\n",
                       container.profile_position_from(wall, mid), mid / dp, b.value);
    }
    return fmt::to_string(out);
}

} // namespace

std::vector<std::pair<std::string, std::string>> analysis_files(const BedAnalysis& a,
                                                                const Container& container) {
    std::vector<std::pair<std::string, std::string>> tables = analysis_tables(a, container);
    if (a.walls.size() == 1)
        return tables;
    // The tables against "the wall" stand for one wall: dropped, each wall's written instead.
    const std::string dropped[] = {"radial_void_fraction.csv", "radial_centre_distribution.csv",
                                   "centre_distribution_by_size.csv"};
    std::erase_if(tables, [&](const auto& table) {
        return std::find(std::begin(dropped), std::end(dropped), table.first) != std::end(dropped);
    });
    std::vector<std::pair<std::string, std::string>> walls;
    for (std::size_t w = 0; w < a.walls.size(); ++w) {
        const WallAnalysis& wall = a.walls[w];
        const auto [void_name, centre_name] = wall_table_names(wall.name);
        walls.emplace_back(void_name, wall_profile_csv(container, w, a.diameter, "void_fraction",
                                                       wall.void_fraction));
        walls.emplace_back(centre_name,
                           wall_profile_csv(container, w, a.diameter, "relative_density",
                                            wall.centre_distribution));
    }
    tables.insert(tables.begin(), walls.begin(), walls.end());
    return tables;
}

} // namespace packbed
