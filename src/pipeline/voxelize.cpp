// A bed's voxel image and its file (pipeline.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "packbed/pipeline.hpp"

#include "packbed/error.hpp"
#include "packbed/files.hpp"

namespace packbed {

VoxelType voxel_type(std::string_view kind, std::string_view dtype) {
    if (kind != "binary" && kind != "fraction")
        throw InvalidInput(fmt::format("--kind '{}' is not allowed; allowed: binary, fraction",
                                       printable(kind.substr(0, 80))));
    if (dtype != "float64" && dtype != "float32")
        throw InvalidInput(fmt::format("--dtype '{}' is not allowed; allowed: float64, float32",
                                       printable(dtype.substr(0, 80))));
    if (kind == "binary") {
        if (dtype != "float64")
            throw InvalidInput(fmt::format("--dtype {} is not allowed with --kind binary (a bool "
                                           "image); allowed: float64 or float32 with --kind "
                                           "fraction",
                                           dtype));
        return VoxelType::boolean;
    }
    return dtype == "float32" ? VoxelType::float32 : VoxelType::float64;
}

const void* VoxelImage::data() const {
    switch (type) {
    case VoxelType::boolean:
        return pore.data();
    case VoxelType::float64:
        return fraction.data();
    case VoxelType::float32:
        return fraction32.data();
    }
    return nullptr;
}

double VoxelImage::porosity() const {
    const double voxels = static_cast<double>(grid.voxels());
    switch (type) {
    case VoxelType::boolean: {
        std::size_t pores = 0;
        for (const std::uint8_t v : pore)
            pores += v;
        return static_cast<double>(pores) / voxels;
    }
    case VoxelType::float64:
        return 1.0 - std::accumulate(fraction.begin(), fraction.end(), 0.0) / voxels;
    case VoxelType::float32:
        return 1.0 - std::accumulate(fraction32.begin(), fraction32.end(), 0.0) / voxels;
    }
    return 0.0;
}

VoxelGrid voxelize_grid(const Packing& packing, const Container& container, double voxel_size,
                        const std::optional<std::array<double, 6>>& region, VoxelType type,
                        const PelletShape* pellet, std::optional<double> period_z) {
    const std::optional<double> top =
        pellet ? std::optional(pellet_bed_top(packing, *pellet)) : period_z;
    return voxel_grid(packing, container, voxel_size, region, voxel_bytes(type), top);
}

namespace {

/// `packing` with a copy, a period `period` above or below, of each sphere that crosses z = 0
/// or z = period: a cell periodic along z drawn whole (the lateral copies are the images').
Packing with_z_copies(const Packing& packing, double period) {
    Packing out = packing;
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double r = packing.radii[i];
        for (const double shift : {period, -period})
            if (shift > 0.0 ? c.z - r < 0.0 : c.z + r > period) {
                out.add({c.x, c.y, c.z + shift}, r);
                if (!packing.types.empty())
                    out.types.push_back(packing.types[i]);
            }
    }
    return out;
}

} // namespace

VoxelImage voxelize(const Packing& packing_given, const Container& container, double voxel_size,
                    const std::optional<std::array<double, 6>>& region, VoxelType type,
                    const PelletShape* pellet, std::optional<double> period_z) {
    VoxelImage image;
    image.type = type;
    image.grid =
        voxelize_grid(packing_given, container, voxel_size, region, type, pellet, period_z);
    std::optional<Packing> copies;
    if (period_z && !pellet)
        copies = with_z_copies(packing_given, *period_z);
    const Packing& packing = copies ? *copies : packing_given;
    if (pellet) {
        if (type == VoxelType::boolean)
            image.pore = pore_image(packing, *pellet, container, image.grid);
        else if (type == VoxelType::float64)
            image.fraction = solid_fraction_image<double>(packing, *pellet, container, image.grid);
        else
            image.fraction32 = solid_fraction_image<float>(packing, *pellet, container, image.grid);
    } else if (type == VoxelType::boolean) {
        image.pore = pore_image(packing, container, image.grid);
    } else if (type == VoxelType::float64) {
        image.fraction = solid_fraction_image<double>(packing, container, image.grid);
    } else {
        image.fraction32 = solid_fraction_image<float>(packing, container, image.grid);
    }
    return image;
}

std::string untiled_cell_warning(const VoxelGrid& grid, const Container& container,
                                 bool region_given, std::optional<double> period_z) {
    const std::optional<Periods> cell = container.periods();
    if (!cell || region_given)
        return "";
    const std::array<std::pair<char, double>, 3> periods{
        {{'x', cell->lx()}, {'y', cell->ly()}, {'z', period_z.value_or(0.0)}}};
    for (const auto& [axis, period] : periods) {
        const double voxels = period / grid.size;
        if (period <= 0.0 || std::abs(voxels - std::round(voxels)) <= 1e-9)
            continue;
        // the next whole number of voxels: a size just below the one asked for
        const double whole = std::ceil(voxels);
        return fmt::format("the image of the periodic cell does not tile: its period along {}, "
                           "{}, is {:.6g} voxels of {}, and the whole voxels covering it reach "
                           "past it; a voxel size that divides each period tiles it (along {}: "
                           "{} = {} / {:g})",
                           axis, period, voxels, grid.size, axis, period / whole, period, whole);
    }
    return "";
}

void stage_image(OutputDirectory& out, const std::string& name, ImageFormat format,
                 const VoxelImage& image) {
    write_image(out.reserve(name), format, image.grid, image.type, image.data());
    if (format == ImageFormat::raw)
        out.stage(name + ".json", image_header(image.grid, image.type));
}

} // namespace packbed
