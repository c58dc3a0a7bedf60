// A bed read from a file: its container and the check that it fits (pipeline.hpp).
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"

namespace packbed {

std::optional<Container> container_beside(const std::filesystem::path& particles) {
    const std::filesystem::path summary = particles.parent_path() / "summary.json";
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(summary, ec)))
        return std::nullopt;
    return read_bed_summary(summary).container;
}

std::optional<Container> find_container(const std::filesystem::path& particles,
                                        const std::string& container, double cylinder_radius) {
    if (const auto spec = parse_container(container))
        return spec->container();
    if (cylinder_radius > 0.0)
        return Cylinder(cylinder_radius);
    return container_beside(particles);
}

BedInContainer read_bed_in_container(const std::filesystem::path& particles,
                                     const ReadOptions& options, const std::string& container,
                                     double cylinder_radius, double outside_tolerance) {
    BedInContainer bed{read_particles(particles, options),
                       find_container(particles, container, cylinder_radius)};
    if (bed.container)
        check_file_inside(bed.file, options, particles.string(), *bed.container, outside_tolerance);
    return bed;
}

void check_file_inside(const ParticleFile& file, const ReadOptions& options, std::string_view name,
                       const Container& container, double outside_tolerance) {
    if (file.packing.size() == 0)
        return;
    const double dp = options.radius ? 2.0 * *options.radius : file.packing.mean_diameter();
    const bool shifted = options.axis[0] != 0.0 || options.axis[1] != 0.0 || options.floor != 0.0;
    check_inside(file.packing, file.lines, name, container, outside_tolerance * dp, shifted);
}

void check_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                  std::string_view name, const Container& container, double tolerance,
                  bool shifted) {
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double r = packing.radii[i];
        const double out_wall = container.sticks_out(c, r);
        const double below = -(c.z - r);
        if (out_wall > tolerance || below > tolerance)
            throw InvalidInput(fmt::format(
                "{}:{}: the sphere at ({}, {}, {}){} sticks out of the container ({}, "
                "floor z = 0) by {:.4g}; allowed: up to {:.4g} (--outside-tolerance, in Dp)",
                printable(name), i < lines.size() ? lines[i] : i + 1, c.x, c.y, c.z,
                shifted ? " (from --axis and --floor)" : "", describe(container),
                std::max(out_wall, below), tolerance));
    }
}

} // namespace packbed
