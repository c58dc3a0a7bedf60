// A bed read from a file: its container and the check that it fits (pipeline.hpp).
#include <algorithm>
#include <filesystem>
#include <variant>

#include <fmt/format.h>

#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"
#include "packbed/volume.hpp"

namespace packbed {

namespace {

/// The summary.json beside a particle file, when there is one.
std::optional<BedSummary> summary_beside(const std::filesystem::path& particles) {
    const std::filesystem::path summary = particles.parent_path() / "summary.json";
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(summary, ec)))
        return std::nullopt;
    return read_bed_summary(summary);
}

} // namespace

std::optional<Container> container_beside(const std::filesystem::path& particles) {
    const std::optional<BedSummary> summary = summary_beside(particles);
    return summary ? summary->container : std::nullopt;
}

std::optional<double> friction_beside(const std::filesystem::path& particles) {
    const std::optional<BedSummary> summary = summary_beside(particles);
    return summary ? summary->friction : std::nullopt;
}

std::optional<double> wall_friction_beside(const std::filesystem::path& particles) {
    const std::optional<BedSummary> summary = summary_beside(particles);
    return summary ? summary->wall_friction : std::nullopt;
}

std::optional<double> period_z_beside(const std::filesystem::path& particles) {
    const std::optional<BedSummary> summary = summary_beside(particles);
    return summary ? summary->period_z : std::nullopt;
}

std::optional<PelletSpec> shape_beside(const std::filesystem::path& particles) {
    const std::optional<BedSummary> summary = summary_beside(particles);
    if (!summary || !summary->shape)
        return std::nullopt;
    std::optional<PelletSpec> pellet = parse_pellet_shape(*summary->shape);
    if (!pellet)
        throw InvalidInput(
            fmt::format("{}: shape '{}' is not allowed; allowed: {}",
                        printable((particles.parent_path() / "summary.json").native()),
                        printable(*summary->shape), allowed_shapes()));
    if (summary->size_range)
        pellet->scales = {summary->size_range->first / pellet->diameter,
                          summary->size_range->second / pellet->diameter};
    return pellet;
}

Container container_from_spec(std::string_view option, const std::string& spec) {
    const auto parsed = parse_container(spec);
    if (!parsed)
        throw InvalidInput(container_not_allowed(option, spec));
    return *parsed;
}

std::optional<Container> find_container(const std::filesystem::path& particles,
                                        const std::string& container, double cylinder_radius) {
    if (!container.empty())
        return container_from_spec("--container", container);
    if (cylinder_radius > 0.0)
        return Container::tube_of_radius(cylinder_radius);
    return container_beside(particles);
}

namespace {

/// Refuse a bed of pellets where the spheres' measures would read each as a ball of d_v.
void refuse_pellets(const std::filesystem::path& particles) {
    if (const std::optional<PelletSpec> pellet = shape_beside(particles))
        throw InvalidInput(fmt::format(
            "{}: a bed of {} pellets (its summary.json's shape) is not allowed here; allowed: a "
            "bed of spheres (packbed analyze measures a pellet bed, and export --format stl, obj "
            "or openfoam writes its surfaces)",
            printable(particles.native()), pellet->text));
}

} // namespace

BedInContainer read_bed_in_container(const std::filesystem::path& particles,
                                     const ReadOptions& options, const std::string& container,
                                     double cylinder_radius, double outside_tolerance) {
    BedInContainer bed{read_particles(particles, options),
                       find_container(particles, container, cylinder_radius), std::nullopt};
    refuse_pellets(particles);
    // A table with orientations and no shape beside it: its pellets would be read as balls.
    if (!bed.file.packing.orientations.empty())
        throw InvalidInput(fmt::format(
            "{}: its particles have orientations (qw, qx, qy, qz: a bed of pellets) but no "
            "summary.json beside it names their shape; allowed: a bed of spheres, or a pellet "
            "bed with the summary.json generate --shape wrote beside it",
            printable(particles.native())));
    if (!bed.container)
        return bed;
    // A lattice kept by its centres (lattice --keep centres) in its own region: its balls, all
    // of one diameter, reach out by up to their radius, half of it; their centres are checked.
    const std::optional<BedSummary> summary = summary_beside(particles);
    const bool own_region = container.empty() && cylinder_radius <= 0.0;
    const double reach = own_region && summary && summary->centres_kept ? 0.5 : 0.0;
    check_file_inside(bed.file, options, particles.string(), *bed.container,
                      outside_tolerance + reach, summary ? summary->period_z : std::nullopt);
    return bed;
}

BedInContainer read_bed_or_pellets(const std::filesystem::path& particles,
                                   const ReadOptions& options, const std::string& container,
                                   double cylinder_radius, double outside_tolerance) {
    std::optional<PelletSpec> pellet = shape_beside(particles);
    if (!pellet)
        return read_bed_in_container(particles, options, container, cylinder_radius,
                                     outside_tolerance);
    BedInContainer bed{read_particles(particles, options),
                       find_container(particles, container, cylinder_radius), std::move(pellet)};
    if (bed.container)
        check_pellets_inside(bed.file.packing, bed.file.lines, particles.string(), *bed.container,
                             *bed.pellet, outside_tolerance);
    return bed;
}

void check_pellets_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                          std::string_view name, const Container& container,
                          const PelletSpec& pellet, double outside_tolerance) {
    if (packing.orientations.size() != packing.size())
        return; // read_particles gives every pellet its orientation
    const double tolerance = outside_tolerance * pellet.volume_diameter;
    std::visit(
        [&](const auto& shape) {
            for (std::size_t i = 0; i < packing.size(); ++i) {
                const Placement p{packing.centers[i], packing.orientations[i], packing.radii[i]};
                const double out =
                    std::max({shape.wall_overlap(container, p), -shape.support(p, {0, 0, -1}).z,
                              container.sticks_out(p.position, 0.0)});
                if (out > tolerance)
                    throw InvalidInput(fmt::format(
                        "{}:{}: the pellet at ({}, {}, {}) reaches out of the container ({}, "
                        "floor z = 0) by {:.4g}; allowed: up to {:.4g} (--outside-tolerance "
                        "times d_v, in the file's units)",
                        printable(name), i < lines.size() ? lines[i] : i + 1, p.position.x,
                        p.position.y, p.position.z, describe(container), out, tolerance));
            }
        },
        pellet.shape);
}

void check_file_inside(const ParticleFile& file, const ReadOptions& options, std::string_view name,
                       const Container& container, double outside_tolerance,
                       std::optional<double> period_z) {
    if (file.packing.size() == 0)
        return;
    const double dp = options.radius ? 2.0 * *options.radius : file.packing.mean_diameter();
    const bool shifted = options.axis[0] != 0.0 || options.axis[1] != 0.0 || options.floor != 0.0;
    check_inside(file.packing, file.lines, name, container, outside_tolerance * dp, shifted,
                 period_z);
}

FrameSeries void_fraction_series(const std::filesystem::path& particles, const ReadOptions& options,
                                 const Container& container, const AnalysisOptions& analysis,
                                 double outside_tolerance) {
    refuse_pellets(particles);
    const std::string name = particles.string();
    const std::optional<double> period_z = period_z_beside(particles); // once, not per frame
    FrameSeries series;
    bool any = false;
    for_each_particle_frame(particles, options, [&](ParticleFile&& frame) {
        FrameVoidFraction row{frame.frame, frame.timestep, std::nullopt, frame.packing.size()};
        if (frame.packing.size() > 0) {
            try {
                check_file_inside(frame, options, name, container, outside_tolerance, period_z);
            } catch (const InvalidInput& error) {
                throw InvalidInput(fmt::format(
                    "frame {}{}: {}", frame.frame,
                    frame.timestep ? fmt::format(" (timestep {})", *frame.timestep) : std::string(),
                    error.what()));
            }
            // Only the void fraction: the rest of analyze_bed (contacts, g(r)) is for the last
            // frame. A fixed band above the frame's top: not yet filled, no value.
            const double dp =
                analysis.diameter ? *analysis.diameter : frame.packing.mean_diameter();
            const std::optional<Band> band =
                analysis.band ? (analysis.band->z_high > bed_top(frame.packing) ? std::nullopt
                                                                                : analysis.band)
                              : band_clear_of_ends(frame.packing, analysis.band_clearance * dp);
            if (band)
                row.void_fraction =
                    void_fraction(frame.packing, container, band->z_low, band->z_high);
            series.last = std::move(frame);
            any = true;
        }
        series.frames.push_back(row);
    });
    if (!any)
        throw InvalidInput(fmt::format("{}: no frame has spheres; allowed: a file with spheres in "
                                       "at least one frame",
                                       printable(name)));
    return series;
}

std::string frame_series_table(const FrameSeries& series) {
    std::string table = "frame,timestep,void_fraction,particles\n";
    for (const FrameVoidFraction& row : series.frames)
        table += fmt::format(
            "{},{},{},{}\n", row.frame, row.timestep ? std::to_string(*row.timestep) : "",
            row.void_fraction ? fmt::format("{}", *row.void_fraction) : "", row.particles);
    return table;
}

void check_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                  std::string_view name, const Container& container, double tolerance, bool shifted,
                  std::optional<double> period_z) {
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double r = packing.radii[i];
        const double out_wall = container.sticks_out(c, r);
        const double below = period_z ? std::max(-c.z, c.z - *period_z) : -(c.z - r);
        if (out_wall > tolerance || below > tolerance)
            throw InvalidInput(
                fmt::format("{}:{}: the sphere at ({}, {}, {}){} sticks out of the container ({}, "
                            "floor z = 0) by {:.4g}; allowed: up to {:.4g} (--outside-tolerance "
                            "times Dp, in the file's units)",
                            printable(name), i < lines.size() ? lines[i] : i + 1, c.x, c.y, c.z,
                            shifted ? " (from --axis and --floor)" : "", describe(container),
                            std::max(out_wall, below), tolerance));
    }
}

} // namespace packbed
