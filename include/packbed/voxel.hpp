// Voxel images of a bed, for image-based tools (PoreSpy, OpenPNM, imageJ): a binary image of
// the pore space and an exact partial-volume image of the solid (docs/voxels.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/pellet_shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A grid of cubic voxels: voxel (i, j, k) spans [low + (i, j, k) h, low + (i + 1, j + 1, k + 1)
/// h]. Images are stored in C order with k (z) fastest: index (i ny + j) nz + k, as numpy's im[i,
/// j, k] of shape (nx, ny, nz).
struct VoxelGrid {
    Vec3 low;                           ///< the lower corner (length)
    double size = 1.0;                  ///< the voxel edge h (length)
    std::array<std::size_t, 3> count{}; ///< voxels along x, y and z
    /// \return the number of voxels.
    std::size_t voxels() const { return count[0] * count[1] * count[2]; }
    /// \return the upper corner, low + count h.
    Vec3 high() const;
};

/// The grid of voxel size `size` over `region` (low x, y, z, high x, y, z; default: the
/// container's bounds across and the floor to the bed's top, bed_top), `count` the region's
/// extent over `size` rounded up to a whole number (one within 1e-9 of a whole number is it):
/// the grid covers the region, its upper sides moved out to whole voxels.
/// \param bytes_per_voxel of the image to be made: 1 binary, 8 fractions
/// \throws InvalidInput naming --voxel-size or --region when the size is not a positive finite
/// length, the region is empty, or the image would take more than limits::max_image_bytes
/// \param top the bed's top for the default region; none: bed_top(packing), the spheres' top
VoxelGrid voxel_grid(const Packing& packing, const Container& container, double size,
                     const std::optional<std::array<double, 6>>& region = std::nullopt,
                     std::size_t bytes_per_voxel = 1, std::optional<double> top = std::nullopt);

namespace detail {
/// `bytes` of memory for an image; from 64 MiB on aligned to 2 MiB and, with `huge`, advised to
/// the kernel as transparent huge pages (madvise, Linux). Throws std::bad_alloc.
void* allocate_image(std::size_t bytes, bool huge);
void free_image(void* p) noexcept;
} // namespace detail

/// An allocator whose new elements are left uninitialised (default-initialised): an image's
/// maker writes every voxel itself, in parallel, so that the pages of a large image are first
/// touched by all threads at once (2 threads: 1.4-2x faster than one zeroing pass here).
/// Images of fractions (floating point) are asked for huge pages: their balls add to rows
/// scattered over the image, a row a page apart, and with 4 KiB pages nearly every row missed
/// the TLB (docs/performance.md, "Voxel images"). A binary image writes its rows in order.
template <class T> struct UninitializedAllocator : std::allocator<T> {
    template <class U> struct rebind { using other = UninitializedAllocator<U>; };
    UninitializedAllocator() = default;
    template <class U> UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
    template <class U> void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
    template <class U, class... Args> void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T))
            throw std::bad_alloc();
        return static_cast<T*>(detail::allocate_image(n * sizeof(T), std::is_floating_point_v<T>));
    }
    void deallocate(T* p, std::size_t) noexcept { detail::free_image(p); }
};

/// A voxel image's values in C order (VoxelGrid), as the image makers return them.
template <class T> using Voxels = std::vector<T, UninitializedAllocator<T>>;

/// The binary image of the pore space, as PoreSpy expects: 1 (True) where the voxel's centre is
/// pore space, inside the container and inside no sphere; 0 (False) where it is solid, inside a
/// sphere (|x - c| < r) or outside the container (the wall, the rod: solid to image tools).
/// In a periodic cell the spheres' copies across the sides count too. Parallel; the same bytes
/// for any number of threads.
Voxels<std::uint8_t> pore_image(const Packing& packing, const Container& container,
                                const VoxelGrid& grid);

/// The exact partial-volume image of the solid: each voxel's volume inside the spheres over its
/// own volume, the sum over spheres of the exact volume of each sphere inside the voxel
/// (ball_orthant_volume by inclusion-exclusion over the voxel's corners; 1 for a voxel wholly
/// inside). Overlaps count twice, as in every void fraction of the analysis (volume.hpp); the
/// generator's beds overlap by at most 1e-4 Dp. The container does not enter: voxels outside it
/// hold 0. In a periodic cell the spheres' copies across the sides count too. The sum over the
/// image times h^3 is the spheres' volume inside the grid's box. Parallel; the same bits for
/// any number of threads (each voxel sums its spheres in their order).
/// \tparam Real double, or float for an image of half the memory: each sphere's volume in a
/// voxel is computed in double and rounded once as it is added (a relative 6e-8 per voxel;
/// rounding to nearest is unbiased, so the image's sum keeps the solid volume to far better
/// than 1e-9: test_voxel).
template <class Real = double>
Voxels<Real> solid_fraction_image(const Packing& packing, const Container& container,
                                  const VoxelGrid& grid);
extern template Voxels<double> solid_fraction_image(const Packing&, const Container&,
                                                    const VoxelGrid&);
extern template Voxels<float> solid_fraction_image(const Packing&, const Container&,
                                                   const VoxelGrid&);

/// The pore image of a bed of pellets of one shape (pellet_shape.hpp: each particle's radius
/// its size d_v / 2, its orientation the packing's): 1 where the voxel's centre is inside the
/// container and inside no pellet (signed_depth > 0 in none), 0 elsewhere, as pore_image for
/// spheres. Parallel; the same bytes for any number of threads.
Voxels<std::uint8_t> pore_image(const Packing& packing, const PelletShape& shape,
                                const Container& container, const VoxelGrid& grid);

/// The solid fraction image of a bed of pellets: each voxel's volume inside the pellets over its
/// own, summed over the pellets in their order. A voxel whose centre lies deeper inside a pellet
/// than its half-diagonal (signed_depth, never more than the distance to the surface) holds
/// it whole, one farther outside none; each other is the shape's volume_in_box (its sections'
/// areas in closed form, integrated along its axis: within 1e-9 of the voxel's volume,
/// docs/voxels.md). Overlaps count twice, the container does not enter, and in a periodic
/// cell the copies across the sides count too, as in solid_fraction_image. Parallel; the same
/// bits for any number of threads.
template <class Real = double>
Voxels<Real> solid_fraction_image(const Packing& packing, const PelletShape& shape,
                                  const Container& container, const VoxelGrid& grid);
extern template Voxels<double> solid_fraction_image(const Packing&, const PelletShape&,
                                                    const Container&, const VoxelGrid&);
extern template Voxels<float> solid_fraction_image(const Packing&, const PelletShape&,
                                                   const Container&, const VoxelGrid&);

/// The height of the highest point of a bed of pellets (each pellet's support along z): the top
/// of voxel_grid's default region for it.
double pellet_bed_top(const Packing& packing, const PelletShape& shape);

/// Volume of the unit ball inside the orthant {x > a, y > b, z > c}, any a, b, c, in closed
/// form. For a, b, c >= 0 (a^2 + b^2 + c^2 < 1), integrating the chord over y and then x,
/// \f$V = P(X) - P(a)\f$ with \f$X = \sqrt{1 - b^2 - c^2}\f$ and
/// \f$P(x) = -\frac{c}{2} S_p(x) - \frac{b}{2} S_q(x) + b c x + \frac{\pi}{4}(x - x^3/3) -
/// \frac12 J_c(x) - \frac12 J_b(x)\f$, where \f$p^2 = 1 - c^2\f$, \f$q^2 = 1 - b^2\f$,
/// \f$S_p(x) = \frac12 (x \sqrt{p^2 - x^2} + p^2 \arcsin(x/p))\f$ and
/// \f$J_b(x) = \int (1 - x^2) \arcsin(b / \sqrt{1 - x^2})\,dx = (x - x^3/3)
/// \arcsin(b/\sqrt{1-x^2}) - \frac{b}{3}(\frac12 (q^2 \arcsin(x/q) - x\sqrt{q^2 - x^2}) - 2
/// \arcsin(x/q)) - \frac23 \arctan(b x / \sqrt{q^2 - x^2})\f$ (by parts; derived for this
/// project, docs/voxels.md, and checked against quadrature in test_voxel). A negative bound
/// reflects: \f$V(a, b, c) = 2 V(0, b, c) - V(-a, b, c)\f$.
double ball_orthant_volume(double a, double b, double c);

/// The volume of the ball (centre, radius) inside the box [low, high], exact: ball_orthant_volume
/// at the box's eight corners by inclusion-exclusion.
double ball_box_volume(const Vec3& center, double radius, const Vec3& low, const Vec3& high);

/// The type of an image's voxels, with numpy's name (voxel_type_name).
enum class VoxelType {
    boolean, ///< the pore image: 1 byte, 0 or 1 (numpy's bool)
    float64, ///< solid fractions in double precision
    float32, ///< solid fractions in single precision
};

/// \return numpy's name of the type: "bool", "float64" or "float32".
const char* voxel_type_name(VoxelType type);

/// \return the bytes of one voxel of the type.
std::size_t voxel_bytes(VoxelType type);

/// Image file formats of voxelize.
enum class ImageFormat {
    npy, ///< numpy's .npy (version 1.0): bool (binary), little-endian float64 or float32
    tif, ///< a multi-page TIFF, one page per i (x) of ny rows by nz columns: tifffile.imread
         ///< gives shape (nx, ny, nz); 8-bit (0/1), 64- or 32-bit IEEE float; at most 4 GiB
    raw, ///< the bytes in C order, and FILE.json with shape, dtype, order, voxel size and origin
};

/// \return the format of a file name's extension (.npy, .tif/.tiff, .raw), or nothing.
std::optional<ImageFormat> image_format(const std::filesystem::path& path);

/// Write an image, `data` the grid's voxels of `type` in C order, to `path` in `format` (a raw
/// image's header, image_header, is the caller's to write beside it). The caller stages `path`
/// (OutputDirectory::reserve).
/// \throws InvalidInput for a TIFF over 4 GiB \throws std::runtime_error when writing fails
void write_image(const std::filesystem::path& path, ImageFormat format, const VoxelGrid& grid,
                 VoxelType type, const void* data);

/// The JSON header of a raw image (and what voxelize records): shape, dtype, order "C" (z
/// fastest), voxel_size, origin (the grid's lower corner), and the convention of the values.
std::string image_header(const VoxelGrid& grid, VoxelType type);

} // namespace packbed
