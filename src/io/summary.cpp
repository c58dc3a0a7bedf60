#include "packbed/summary.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include "packbed/analysis_files.hpp"
#include "packbed/version.hpp"
#include "packbed/volume.hpp"

namespace packbed {

nlohmann::json soft_sphere_summary(const SoftSphereParameters& p, const SoftSphereResult& result,
                                   double band_clearance, int threads) {
    using nlohmann::json;
    const double d = p.diameter;
    json summary;
    summary["version"] = std::string(version);
    summary["generator"] = "soft-sphere (Salvat et al. 2005)";
    if (result.container.tube_diameter())
        summary["aspect_ratio"] = p.aspect_ratio; // another container has none: its spec
    summary["particles"] = p.particles;
    summary["seed"] = p.seed;
    summary["diameter"] = d;
    summary["container"] = result.container.summary_json();
    summary["container"]["height"] = bed_top(result.packing);
    summary["container"]["bottom"] = 0.0;
    if (const std::string_view axis = result.container.axis(); !axis.empty())
        summary["container"]["axis"] = axis;

    const auto band = band_clear_of_ends(result.packing, band_clearance * d);
    if (band) {
        summary["void_fraction"] =
            void_fraction(result.packing, result.container, band->z_low, band->z_high);
        summary["void_fraction_band"] = {band->z_low, band->z_high};
    } else {
        summary["void_fraction"] = nullptr;
        summary["void_fraction_band"] = nullptr;
        summary["void_fraction_note"] =
            "the bed is not taller than twice the band clearance; lower --band-clearance";
    }
    summary["band_clearance"] = band_clearance;
    summary["max_overlap_pair"] = result.max_overlap_pair;
    summary["max_overlap_wall"] = result.max_overlap_wall;
    summary["iterations"] = result.iterations;
    summary["initial_height"] = result.initial_height;
    summary["neighbor_list_builds"] = result.neighbor_builds;
    summary["layers"] = result.layers;
    json stages = json::array();
    for (const auto& s : result.stages)
        stages.push_back({{"name", s.name},
                          {"iterations", s.iterations},
                          {"steps", s.steps},
                          {"cg", s.cg},
                          {"max_overlap_pair", s.max_overlap_pair},
                          {"max_overlap_wall", s.max_overlap_wall},
                          {"mass_centre_z", s.mass_centre_z * d}});
    summary["stages"] = stages;
    summary["parameters"] = soft_sphere_parameters_json(p);
    summary["parameters"].erase("aspect_ratio"); // these four are at the top level
    summary["parameters"].erase("particles");
    summary["parameters"].erase("seed");
    summary["parameters"].erase("diameter");
    summary["parameters"]["band_clearance"] = band_clearance;
    summary["parameters"]["threads"] = threads;
    summary["units"] = {{"length", "diameter units as given by --diameter"},
                        {"max_overlap_pair", "Dp"},
                        {"max_overlap_wall", "Dp"},
                        {"overlap_low", "Dp"},
                        {"overlap_high", "Dp"},
                        {"tolerance", "Dp"},
                        {"mc_tolerance", "percent"},
                        {"skin", "Dp"},
                        {"layer_height", "Dp"},
                        {"band_clearance", "Dp"}};
    summary["seconds"] = result.seconds;
    return summary;
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

nlohmann::json size_statistics_summary(const SizeStatistics& s) {
    nlohmann::json classes = nlohmann::json::array();
    for (const SizeClass& c : s.classes)
        classes.push_back({{"low", c.low},
                           {"high", c.high},
                           {"count", c.count},
                           {"number_fraction", c.number_fraction},
                           {"volume_fraction", c.volume_fraction}});
    return {{"count", s.count},
            {"d10", s.d10},
            {"d50", s.d50},
            {"d90", s.d90},
            {"sauter_mean_d32", s.sauter_mean},
            {"volume_mean_d43", s.volume_mean},
            {"number_mean", s.number_mean},
            {"number_sd", s.number_sd},
            {"smallest", s.smallest},
            {"largest", s.largest},
            {"size_ratio", s.size_ratio},
            {"classes", classes}};
}

nlohmann::json lattice_summary(const LatticeParameters& p, const Packing& packing) {
    using nlohmann::json;
    const UnitCell cell = unit_cell(p.type);
    const double d = p.diameter;
    const double r = 0.5 * d;
    json summary;
    summary["version"] = std::string(version);
    summary["generator"] = "lattice";
    summary["type"] = to_string(p.type);
    summary["diameter"] = d;
    summary["keep"] = lattice_keeps().name(p.keep);
    const double volume = region_volume(p.region);
    // A periodic cell is the container (analyze reads it): no side wall, so each ball counts
    // whole between the floor and the top (Periodic::sphere_volume).
    const Container& container = p.region.container;
    const double height = p.region.height;
    summary["region"] = container.region_json(height);
    summary["container"] = container.summary_json();
    const std::optional<Periods> period = container.periods();
    if (period) {
        const Vec3 edges = unit_cell(p.type).edges * d;
        summary["periods"] = {std::round(period->lx() / edges.x),
                              std::round(period->ly() / edges.y)};
    }
    double solid = 0.0;
    for (const Vec3& centre : packing.centers)
        solid += container.sphere_volume(centre, r, 0.0, height);
    const Vec3 origin =
        p.origin.value_or(container.axis().empty() ? Vec3{r, r, r} : Vec3{0.0, 0.0, r});
    summary["origin"] = {origin.x, origin.y, origin.z};
    summary["rotations"] = json::array();
    for (const auto& [axis, degrees] : p.rotations)
        summary["rotations"].push_back({{"axis", std::string(1, axis)}, {"degrees", degrees}});
    summary["balls"] = packing.size();
    summary["lattice"] = {{"porosity", cell.porosity},
                          {"coordination", cell.coordination},
                          {"cell_edges", {cell.edges.x * d, cell.edges.y * d, cell.edges.z * d}},
                          {"balls_per_cell", cell.balls.size()}};
    summary["porosity_region"] = 1.0 - solid / volume;
    const LatticeContacts contacts =
        period ? lattice_contacts(packing, *period) : lattice_contacts(packing);
    std::vector<std::uint64_t> histogram;
    double total = 0.0;
    for (const std::uint32_t k : contacts.contacts) {
        if (histogram.size() <= k)
            histogram.resize(k + 1, 0);
        ++histogram[k];
        total += k;
    }
    summary["contacts"] = {
        {"tolerance_d", 1e-9},
        {"mean", packing.size() ? total / static_cast<double>(packing.size()) : 0.0},
        {"histogram", histogram},
        {"closest_distance_d",
         std::isfinite(contacts.closest) ? json(contacts.closest) : json(nullptr)}};
    return summary;
}

} // namespace packbed
