// A bed's voxel image and its file (pipeline.hpp).
#include <numeric>

#include "packbed/pipeline.hpp"

namespace packbed {

double VoxelImage::porosity() const {
    const double voxels = static_cast<double>(grid.voxels());
    if (binary) {
        std::size_t pores = 0;
        for (const std::uint8_t v : pore)
            pores += v;
        return static_cast<double>(pores) / voxels;
    }
    return 1.0 - std::accumulate(fraction.begin(), fraction.end(), 0.0) / voxels;
}

VoxelImage voxelize(const Packing& packing, const Container& container, double voxel_size,
                    const std::optional<std::array<double, 6>>& region, bool binary) {
    VoxelImage image;
    image.binary = binary;
    image.grid = voxel_grid(packing, container, voxel_size, region, binary ? 1 : sizeof(double));
    if (binary)
        image.pore = pore_image(packing, container, image.grid);
    else
        image.fraction = solid_fraction_image(packing, container, image.grid);
    return image;
}

void stage_image(OutputDirectory& out, const std::string& name, ImageFormat format,
                 const VoxelImage& image) {
    write_image(out.reserve(name), format, image.grid, image.binary ? &image.pore : nullptr,
                image.binary ? nullptr : &image.fraction);
    if (format == ImageFormat::raw)
        out.stage(name + ".json", image_header(image.grid, image.binary));
}

} // namespace packbed
