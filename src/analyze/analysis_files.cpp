#include "packbed/analysis_files.hpp"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

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

namespace {

/// A CSV of profile bins: `header`, then per bin two positions of its mid-point,
/// `first(mid)` and `second(mid)`, and the value.
template <class F, class G>
std::string profile_csv(std::string_view header, const std::vector<ProfileBin>& bins, F first,
                        G second) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}\n", header);
    for (const auto& b : bins) {
        const double mid = 0.5 * (b.low + b.high);
        // Positions to 12 significant digits: the bin centre of shell 123 of 0.02 Dp is 2.47,
        // not the 2.4699999999999998 its floating-point sum gives; values as computed.
        fmt::format_to(std::back_inserter(out), "{:.12g},{:.12g},{}\n", first(mid), second(mid),
                       b.value);
    }
    return fmt::to_string(out);
}

} // namespace

std::vector<std::pair<std::string, std::string>> analysis_tables(const BedAnalysis& a,
                                                                 const Container& container) {
    const double dp = a.diameter;
    // The wall profiles: the container's position (a cylinder's radial position), then the
    // distance from the wall in Dp.
    const std::string position(container.profile_position_name());
    auto in_dp = [&](double length) { return length / dp; };
    auto as_is = [](double length) { return length; };
    auto wall_profile = [&](std::string_view value, const std::vector<ProfileBin>& bins) {
        return profile_csv(
            fmt::format("{},x_from_wall_d,{}", position, value), bins,
            [&](double d) { return container.profile_position(d); }, in_dp);
    };
    std::string coordination = "contacts,spheres\n";
    for (std::size_t k = 0; k < a.coordination.histogram.size(); ++k)
        coordination += fmt::format("{},{}\n", k, a.coordination.histogram[k]);
    std::vector<std::pair<std::string, std::string>> by_size;
    if (!a.by_size.empty()) {
        // One row per class; then the centre distribution of each class, a column each.
        std::string classes = "low,high,spheres,number_fraction,volume_fraction,spheres_in_band,"
                              "mean_coordination\n";
        std::string header = fmt::format("{},x_from_wall_d", position);
        for (const SizeClassAnalysis& c : a.by_size) {
            classes +=
                fmt::format("{:.12g},{:.12g},{},{},{},{},{}\n", c.low, c.high, c.spheres,
                            c.number_fraction, c.volume_fraction, c.in_band, c.mean_coordination);
            header += c.low == c.high ? fmt::format(",d_{:.6g}", c.low)
                                      : fmt::format(",d_{:.6g}_{:.6g}", c.low, c.high);
        }
        std::string centres = header + "\n";
        const auto& bins = a.by_size.front().centre_distribution;
        for (std::size_t k = 0; k < bins.size(); ++k) {
            const double mid = 0.5 * (bins[k].low + bins[k].high);
            centres += fmt::format("{:.12g},{:.12g}", container.profile_position(mid), mid / dp);
            for (const SizeClassAnalysis& c : a.by_size)
                centres += fmt::format(",{}", c.centre_distribution[k].value);
            centres += "\n";
        }
        by_size = {{"size_classes.csv", classes}, {"centre_distribution_by_size.csv", centres}};
    }
    std::vector<std::pair<std::string, std::string>> tables{
        {"radial_void_fraction.csv", wall_profile("void_fraction", a.radial_void_fraction)},
        {"axial_void_fraction.csv",
         profile_csv("z,z_d,void_fraction", a.axial_void_fraction, as_is, in_dp)},
        {"radial_centre_distribution.csv", wall_profile("relative_density", a.centre_distribution)},
        {"coordination.csv", coordination},
        {"pair_correlation.csv",
         profile_csv("distance,distance_d,g", a.pair_correlation, as_is, in_dp)},
    };
    tables.insert(tables.end(), by_size.begin(), by_size.end());
    return tables;
}

std::vector<std::pair<std::string, std::string>> pellet_analysis_files(const PelletAnalysis& a,
                                                                       const Container& container) {
    const double dv = a.diameter;
    auto in_dv = [&](double length) { return length / dv; };
    auto as_is = [](double length) { return length; };
    std::string coordination = "contacts,pellets\n";
    for (std::size_t k = 0; k < a.coordination.histogram.size(); ++k)
        coordination += fmt::format("{},{}\n", k, a.coordination.histogram[k]);
    std::vector<std::pair<std::string, std::string>> tables{
        {"axial_void_fraction.csv",
         profile_csv("z,z_d,void_fraction", a.axial_void_fraction, as_is, in_dv)},
        {"coordination.csv", coordination}};
    if (a.radial_void_fraction.empty())
        return tables;
    const std::string position(container.profile_position_name());
    tables.emplace_back("radial_void_fraction.csv",
                        profile_csv(
                            fmt::format("{},x_from_wall_d,void_fraction", position),
                            a.radial_void_fraction,
                            [&](double d) { return container.profile_position(d); }, in_dv));
    std::string orientation =
        fmt::format("{},x_from_wall_d,pellets,mean_cos2,order,mean_cos2_wall\n", position);
    for (const OrientationBin& b : a.orientation) {
        const double mid = 0.5 * (b.low + b.high);
        orientation += fmt::format("{:.12g},{:.12g},{},{},{},{}\n", container.profile_position(mid),
                                   mid / dv, b.pellets, b.mean_cos2, b.order, b.mean_cos2_wall);
    }
    tables.emplace_back("orientation_profile.csv", orientation);
    return tables;
}

nlohmann::ordered_json pellet_analysis_summary(const PelletAnalysis& a, std::string_view shape,
                                               std::size_t pellets, const Container& container,
                                               double contact_tolerance) {
    nlohmann::ordered_json summary;
    summary["pellets"] = pellets;
    summary["shape"] = std::string(shape);
    summary["volume_equivalent_diameter"] = a.diameter;
    summary["container"] = container.summary_json();
    summary["band"] = {a.band.z_low, a.band.z_high};
    summary["void_fraction"] = a.void_fraction;
    summary["orientation"] = {{"pellets", a.overall.pellets},
                              {"mean_cos2", a.overall.mean_cos2},
                              {"order", a.overall.order}};
    if (!a.orientation.empty()) // a container of one wall
        summary["orientation"]["mean_cos2_wall"] = a.overall.mean_cos2_wall;
    summary["orientation"]["about"] =
        "theta between a pellet's axis and the container's z axis, over the pellets with their "
        "centroid in the band; S = (3 <cos^2> - 1) / 2: 1 upright, -1/2 lying, 0 at random; psi "
        "(mean_cos2_wall, with one wall) between the axis and the wall's normal at the "
        "centroid: 1 pointing at the wall, 0 parallel to it, 1/3 at random";
    const Coordination& c = a.coordination;
    summary["coordination"] = {{"mean", c.mean},
                               {"mean_without_rattlers", c.mean_without_rattlers},
                               {"rattlers", c.rattlers},
                               {"rattler_contacts", c.rattler_contacts},
                               {"pellets", c.spheres},
                               {"contact_tolerance", contact_tolerance},
                               {"histogram", c.histogram},
                               {"about", "pellet-pellet contacts per pellet with its centroid in "
                                         "the band: a pair whose exact gap is at most "
                                         "contact_tolerance d_v; a rattler touches nothing"}};
    summary["wall_contacts"] = c.wall_contacts;
    summary["wall_contacts_in_band"] = c.wall_contacts_in_band;
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    for (const auto& [name, text] : pellet_analysis_files(a, container))
        files.push_back(name);
    summary["files"] = files;
    return summary;
}

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

nlohmann::json analysis_summary(const BedAnalysis& a, const AnalysisOptions& o) {
    const auto& c = a.coordination;
    nlohmann::json summary = {
        {"diameter", a.diameter},
        {"void_fraction", a.void_fraction},
        {"void_fraction_band", {a.band.z_low, a.band.z_high}},
        {"coordination",
         {{"mean", c.mean},
          {"mean_without_rattlers", c.mean_without_rattlers},
          {"rattlers", c.rattlers},
          {"rattler_contacts", c.rattler_contacts},
          {"spheres", c.spheres},
          {"contact_tolerance", o.contact_tolerance},
          {"histogram", c.histogram}}},
        {"wall_contacts", c.wall_contacts},
        {"wall_contacts_in_band", c.wall_contacts_in_band},
        {"options",
         {{"band_clearance", o.band_clearance},
          {"shell_width", o.shell_width},
          {"slab_height", o.slab_height},
          {"centre_bin", o.centre_bin},
          {"contact_tolerance", o.contact_tolerance},
          {"rdf_range", o.rdf_range},
          {"rdf_bin", o.rdf_bin},
          {"units", "Dp"}}},
        {"files",
         {"radial_void_fraction.csv", "axial_void_fraction.csv", "radial_centre_distribution.csv",
          "coordination.csv", "pair_correlation.csv"}}};
    if (!a.by_size.empty()) {
        nlohmann::json classes = nlohmann::json::array();
        for (const SizeClassAnalysis& k : a.by_size)
            classes.push_back({{"low", k.low},
                               {"high", k.high},
                               {"spheres", k.spheres},
                               {"number_fraction", k.number_fraction},
                               {"volume_fraction", k.volume_fraction},
                               {"spheres_in_band", k.in_band},
                               {"mean_coordination", k.mean_coordination}});
        summary["by_size"] = classes;
        summary["sizes"] = size_statistics_summary(a.sizes);
        summary["files"].push_back("size_classes.csv");
        if (a.walls.size() == 1)
            summary["files"].push_back("centre_distribution_by_size.csv");
    }
    if (a.walls.size() == 1) // a cylinder or a box: the wall profiles are the files above
        return summary;
    // Several walls (an annulus): each wall's contacts and tables; none (a periodic cell):
    // said so, with no wall contacts and no table against a wall.
    nlohmann::json files = nlohmann::json::array();
    nlohmann::json walls = nlohmann::json::array();
    for (const WallAnalysis& wall : a.walls) {
        const auto [void_name, centre_name] = wall_table_names(wall.name);
        walls.push_back({{"name", wall.name},
                         {"wall_contacts", wall.wall_contacts},
                         {"wall_contacts_in_band", wall.wall_contacts_in_band},
                         {"files", {void_name, centre_name}}});
        files.push_back(void_name);
        files.push_back(centre_name);
    }
    for (const auto& name : summary["files"])
        if (name != "radial_void_fraction.csv" && name != "radial_centre_distribution.csv")
            files.push_back(name);
    summary["files"] = files;
    summary["walls"] = walls;
    if (a.walls.empty()) {
        summary.erase("wall_contacts");
        summary.erase("wall_contacts_in_band");
        summary["no_walls"] = "a periodic cell has no side walls: no wall profile, centre "
                              "distribution or wall contacts; the axial profile, the contacts "
                              "and g(r) count every copy of a sphere (minimum image)";
    }
    return summary;
}

} // namespace packbed
