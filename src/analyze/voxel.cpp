// Voxel images of a bed (voxel.hpp, docs/voxels.md).
#include "packbed/voxel.hpp"
#include "packbed/json_text.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <sys/mman.h>
#if defined(PACKBED_HAVE_MVEC)
#include <emmintrin.h>
// glibc's libmvec: atan on two doubles (SSE2), the x86-64 vector ABI's name
extern "C" __m128d _ZGVbN2v_atan(__m128d);
#endif

#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/memory.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/volume.hpp"

namespace packbed {

namespace {

/// The part of P(x) (voxel.hpp) that holds t, one of b and c:
/// \f$H(x, t) = -\frac{t}{2} S(x) - \frac{1}{2} J_t(x)\f$ with \f$m^2 = 1 - t^2\f$, given the
/// root \f$r = \sqrt{m^2 - x^2}\f$, so that P(x) = H(x, c) + H(x, b) + b c x + pi/4 (x - x^3/3).
/// H depends on x and one of b, c only: a ball's nodes share it along whole planes.
/// Every arcsine is written as an arctangent of the root, \f$\arcsin(x/m) = \arctan(x / r)\f$
/// and \f$\arcsin(t/\sqrt{1 - x^2}) = \arctan(t / r)\f$: at the upper end x = X the roots are
/// exactly the other of b and c, where the arcsines of arguments rounded near 1 would lose half
/// their digits (1e-8 of the ball).
/// The tangent y / r whose arctangent is atan2(y, r) for r >= 0 (+-inf at r = 0): atan of it
/// takes half the time of atan2 and is within an ulp of it (the quotient's rounding).
double tangent(double y, double r) {
    if (r > 0.0)
        return y / r;
    return y == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), y);
}

/// The three tangents whose arctangents H(x, t) holds, given its root r: x / r, t / r and
/// t x / r, each a product with 1 / r (one division, not three; within 2 ulps of the quotient).
std::array<double, 3> half_tangents(double x, double t, double r) {
    if (r > 0.0) {
        const double inverse = 1.0 / r;
        return {x * inverse, t * inverse, t * x * inverse};
    }
    return {tangent(x, r), tangent(t, r), tangent(t * x, r)};
}

/// H from the arctangents `at` of half_tangents(x, t, r).
double half_from_arctangents(double x, double t, double r, const double* at) {
    const double inner = at[0], outer = at[1], product = at[2];
    const double m2 = 1.0 - t * t;
    const double cubic = x - x * x * x / 3.0;
    // S(x) = 1/2 (x r + m^2 arcsin(x / m)), the antiderivative of the chord sqrt(m^2 - x^2)
    const double chord = 0.5 * (x * r + m2 * inner);
    // J_t(x) = int (1 - x^2) arcsin(t / sqrt(1 - x^2)) dx (voxel.hpp), by parts
    const double by_parts =
        cubic * outer - t / 3.0 * (0.5 * (m2 * inner - x * r) - 2.0 * inner) - 2.0 / 3.0 * product;
    return -0.5 * t * chord - 0.5 * by_parts;
}

double half_antiderivative(double x, double t, double r) {
    std::array<double, 3> at = half_tangents(x, t, r);
    for (double& v : at)
        v = std::atan(v);
    return half_from_arctangents(x, t, r, at.data());
}

/// Each value of `v` replaced by its arctangent, two at a time through glibc's vector math
/// (libmvec, within 1 ulp of atan and 2.5 times as fast here: no rounding mode saved and
/// restored per call) where the build has it. The count is padded to even, so every value's
/// bits depend on that value alone, not on its place in the batch.
void arctangents(std::vector<double>& v) {
#if defined(PACKBED_HAVE_MVEC)
    if (v.size() % 2 != 0)
        v.push_back(0.0);
    for (std::size_t n = 0; n < v.size(); n += 2)
        _mm_storeu_pd(v.data() + n, _ZGVbN2v_atan(_mm_loadu_pd(v.data() + n)));
#else
    for (double& x : v)
        x = std::atan(x);
#endif
}

/// The terms of P(x) that hold neither root: b c x + pi/4 (x - x^3/3).
double plain_terms(double x, double b, double c) {
    return b * c * x + 0.25 * std::numbers::pi * (x - x * x * x / 3.0);
}

/// The upper end X = sqrt(1 - b^2 - c^2) of P, where the roots are c and b, and the tangents
/// of its halves H(X, c) (root b) and H(X, b) (root c).
struct UpperEnd {
    double x;
    std::array<double, 6> tangents;
};

UpperEnd upper_end(double b, double c) {
    UpperEnd end{std::sqrt(1.0 - b * b - c * c), {}};
    const auto first = half_tangents(end.x, c, b), second = half_tangents(end.x, b, c);
    std::copy(first.begin(), first.end(), end.tangents.begin());
    std::copy(second.begin(), second.end(), end.tangents.begin() + 3);
    return end;
}

/// P(X) from the arctangents `at` of upper_end(b, c).tangents.
double upper_from_arctangents(double b, double c, double x, const double* at) {
    return half_from_arctangents(x, c, b, at) + half_from_arctangents(x, b, c, at + 3) +
           plain_terms(x, b, c);
}

/// P(X) at the upper end X = sqrt(1 - b^2 - c^2), where the roots are c and b.
double upper_antiderivative(double b, double c) {
    UpperEnd end = upper_end(b, c);
    for (double& v : end.tangents)
        v = std::atan(v);
    return upper_from_arctangents(b, c, end.x, end.tangents.data());
}

/// 1 - a^2 - b^2 for |a|, |b| <= 1, to within rounding of the result: the larger square taken
/// from 1 first and the smaller then (each subtraction exact where the result is small, by
/// Sterbenz's lemma), the squares' own rounding errors (fma) last. Near the sphere's surface
/// this is the square of a root whose arctangents would otherwise lose half their digits.
double one_minus_squares(double a, double b) {
    double big = std::abs(a), small = std::abs(b);
    if (big < small)
        std::swap(big, small);
    const double big2 = big * big, small2 = small * small;
    const double errors = std::fma(big, big, -big2) + std::fma(small, small, -small2);
    return ((1.0 - big2) - small2) - errors;
}

/// ball_orthant_volume for 0 <= a, b, c <= 1: P(X) - P(a).
double orthant_volume_positive(double a, double b, double c) {
    const double rest = 1.0 - b * b - c * c;
    if (a * a >= rest)
        return 0.0;
    const double lower =
        half_antiderivative(a, c, std::sqrt(std::max(0.0, one_minus_squares(c, a)))) +
        half_antiderivative(a, b, std::sqrt(std::max(0.0, one_minus_squares(b, a)))) +
        plain_terms(a, b, c);
    return std::max(0.0, upper_antiderivative(b, c) - lower);
}

/// floor(x) and ceil(x) as whole numbers, x first clamped to [-1e15, 1e15] (NaN to -1e15) so
/// that the conversion is defined. Without a call to glibc's floor and ceil: the baseline
/// x86-64 build has no rounding instruction, and these run per row of every ball.
long long floor_whole(double x) {
    const double v = x > -1e15 ? (x < 1e15 ? x : 1e15) : -1e15;
    const auto t = static_cast<long long>(v); // toward zero
    return static_cast<double>(t) > v ? t - 1 : t;
}
long long ceil_whole(double x) {
    return -floor_whole(-x);
}

/// `x` (a voxel index) clamped to [-2, n + 1]: beyond the grid it only needs to stay beyond it.
long long index_of(long long x, std::size_t n) {
    return std::clamp(x, -2ll, static_cast<long long>(n) + 1);
}

/// The voxel index range [first, last] whose centres low + (i + 1/2) h lie strictly within
/// (from, to); empty (first > last) when none does, clipped to [0, n).
std::pair<long long, long long> centres_within(double from, double to, double low, double h,
                                               std::size_t n) {
    long long first = index_of(ceil_whole((from - low) / h - 0.5), n);
    if (low + (static_cast<double>(first) + 0.5) * h <= from)
        ++first;
    long long last = index_of(floor_whole((to - low) / h - 0.5), n);
    if (low + (static_cast<double>(last) + 0.5) * h >= to)
        --last;
    return {std::max(first, 0ll), std::min(last, static_cast<long long>(n) - 1)};
}

/// The voxel index range [first, last] of the voxels that meet [from, to], clipped to [0, n).
std::pair<long long, long long> voxels_meeting(double from, double to, double low, double h,
                                               std::size_t n) {
    const auto first = index_of(floor_whole((from - low) / h), n);
    const auto last = index_of(floor_whole((to - low) / h), n);
    return {std::max(first, 0ll), std::min(last, static_cast<long long>(n) - 1)};
}

/// A sphere to draw: its centre (a periodic copy's, moved by whole periods) and radius.
struct Ball {
    Vec3 c;
    double r;
};

/// The spheres, with their copies across a periodic cell's sides, that reach the grid, in
/// order (each sphere, then its copies).
std::vector<Ball> balls_reaching(const Packing& packing, const Container& container,
                                 const VoxelGrid& grid) {
    const Vec3 high = grid.high();
    const std::optional<Periods> cell = container.periods();
    std::vector<Ball> balls;
    balls.reserve(packing.size());
    for (std::size_t n = 0; n < packing.size(); ++n) {
        const double r = packing.radii[n];
        for (int sx = cell ? -1 : 0; sx <= (cell ? 1 : 0); ++sx)
            for (int sy = cell ? -1 : 0; sy <= (cell ? 1 : 0); ++sy) {
                Vec3 c = packing.centers[n];
                if (cell) {
                    c.x += sx * cell->lx();
                    c.y += sy * cell->ly();
                }
                if (c.x + r > grid.low.x && c.x - r < high.x && c.y + r > grid.low.y &&
                    c.y - r < high.y && c.z + r > grid.low.z && c.z - r < high.z)
                    balls.push_back({c, r});
            }
    }
    return balls;
}

/// For each x plane i of the grid, the balls that reach it (those whose x extent meets voxel
/// i's slab, or, with `centres`, holds a voxel centre of it), in ball order: compressed rows.
struct PlaneLists {
    std::vector<std::size_t> start; // of plane i's entries, count[0] + 1 of them
    std::vector<std::uint32_t> ball;
};

/// The lists of `count` bodies whose x extents, extent(n) = (from, to), reach each plane.
template <class Extent>
PlaneLists plane_lists(std::size_t count, Extent&& extent, const VoxelGrid& grid, bool centres) {
    const std::size_t nx = grid.count[0];
    auto range = [&](std::size_t n) {
        const auto [from, to] = extent(n);
        return centres ? centres_within(from, to, grid.low.x, grid.size, nx)
                       : voxels_meeting(from, to, grid.low.x, grid.size, nx);
    };
    PlaneLists lists;
    lists.start.assign(nx + 1, 0);
    for (std::size_t n = 0; n < count; ++n) {
        const auto [first, last] = range(n);
        for (long long i = first; i <= last; ++i)
            ++lists.start[static_cast<std::size_t>(i) + 1];
    }
    for (std::size_t i = 0; i < nx; ++i)
        lists.start[i + 1] += lists.start[i];
    lists.ball.resize(lists.start[nx]);
    std::vector<std::size_t> next(lists.start.begin(), lists.start.end() - 1);
    for (std::size_t n = 0; n < count; ++n) {
        const auto [first, last] = range(n);
        for (long long i = first; i <= last; ++i)
            lists.ball[next[static_cast<std::size_t>(i)]++] = static_cast<std::uint32_t>(n);
    }
    return lists;
}

PlaneLists plane_lists(const std::vector<Ball>& balls, const VoxelGrid& grid, bool centres) {
    return plane_lists(
        balls.size(),
        [&](std::size_t n) {
            return std::pair(balls[n].c.x - balls[n].r, balls[n].c.x + balls[n].r);
        },
        grid, centres);
}

double centre_of(double low, double h, std::size_t i) {
    return low + (static_cast<double>(i) + 0.5) * h;
}

} // namespace

void* detail::allocate_image(std::size_t bytes, bool huge) {
    constexpr std::size_t large = std::size_t{64} << 20, huge_page = std::size_t{2} << 20;
    void* p = nullptr;
    if (bytes < large) {
        p = std::malloc(std::max<std::size_t>(bytes, 1));
    } else {
        const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
        p = std::aligned_alloc(huge_page, rounded);
#if defined(MADV_HUGEPAGE)
        // a hint: where the kernel has no huge pages to give, the image is the same
        if (p && huge)
            madvise(p, rounded, MADV_HUGEPAGE);
#else
        (void)huge;
#endif
    }
    if (!p)
        throw std::bad_alloc();
    return p;
}

void detail::free_image(void* p) noexcept {
    std::free(p);
}

Vec3 VoxelGrid::high() const {
    return {low.x + static_cast<double>(count[0]) * size,
            low.y + static_cast<double>(count[1]) * size,
            low.z + static_cast<double>(count[2]) * size};
}

VoxelGrid voxel_grid(const Packing& packing, const Container& container, double size,
                     const std::optional<std::array<double, 6>>& region,
                     std::size_t bytes_per_voxel, std::optional<double> top) {
    const double max_voxels = limits::max_image_bytes / static_cast<double>(bytes_per_voxel);
    check_option("voxel-size", size, option_range::voxel_size);
    std::array<double, 6> box{};
    if (region) {
        box = *region;
    } else {
        const Rectangle b = container.bounds();
        box = {b.x_low, b.y_low, 0.0, b.x_high, b.y_high, top ? *top : bed_top(packing)};
    }
    for (int d = 0; d < 3; ++d)
        if (!(std::isfinite(box[d]) && std::isfinite(box[d + 3]) && box[d] < box[d + 3] &&
              std::abs(box[d]) <= limits::max_length && std::abs(box[d + 3]) <= limits::max_length))
            throw InvalidInput(fmt::format(
                "--region {},{},{},{},{},{} is not allowed; allowed: XLOW,YLOW,ZLOW,XHIGH,YHIGH,"
                "ZHIGH with each low below its high, within {:g}{}",
                box[0], box[1], box[2], box[3], box[4], box[5], limits::max_length,
                region ? ""
                       : " (the default region: the container across, the floor to the "
                         "bed's top: is the bed empty?)"));
    VoxelGrid grid;
    grid.low = {box[0], box[1], box[2]};
    grid.size = size;
    double voxels = 1.0;
    for (int d = 0; d < 3; ++d) {
        // whole voxels covering the region (a quotient within 1e-9 of a whole number is it)
        const double n = std::max(1.0, std::ceil((box[d + 3] - box[d]) / size - 1e-9));
        voxels *= n;
        if (!(voxels <= max_voxels))
            throw InvalidInput(fmt::format(
                "--voxel-size {} is not allowed for this region ({:g} x {:g} x {:g}): the image "
                "would hold more than {:g} voxels ({:g} GiB); allowed: a voxel size of at least "
                "{:.4g}",
                size, box[3] - box[0], box[4] - box[1], box[5] - box[2], max_voxels,
                limits::max_image_bytes / 1073741824.0,
                std::cbrt((box[3] - box[0]) * (box[4] - box[1]) * (box[5] - box[2]) / max_voxels)));
        grid.count[static_cast<std::size_t>(d)] = static_cast<std::size_t>(n);
    }
    check_memory(fmt::format("--voxel-size {} (an image of {:.4g} voxels of {} byte{})", size,
                             voxels, bytes_per_voxel, bytes_per_voxel > 1 ? "s" : ""),
                 static_cast<std::uint64_t>(voxels * static_cast<double>(bytes_per_voxel)) +
                     generation_memory(packing.size()),
                 "a larger --voxel-size or a smaller --region, or a machine with more memory");
    return grid;
}

double ball_orthant_volume(double a, double b, double c) {
    a = std::clamp(a, -1.0, 1.0);
    b = std::clamp(b, -1.0, 1.0);
    c = std::clamp(c, -1.0, 1.0);
    // {x > a} with a < 0 is everything but {x < a}, the mirror of {x > -a}; and the half
    // {x > 0} is half of everything by symmetry.
    if (a < 0.0)
        return 2.0 * ball_orthant_volume(0.0, b, c) - ball_orthant_volume(-a, b, c);
    if (b < 0.0)
        return 2.0 * ball_orthant_volume(a, 0.0, c) - ball_orthant_volume(a, -b, c);
    if (c < 0.0)
        return 2.0 * ball_orthant_volume(a, b, 0.0) - ball_orthant_volume(a, b, -c);
    return orthant_volume_positive(a, b, c);
}

double ball_box_volume(const Vec3& center, double radius, const Vec3& low, const Vec3& high) {
    const double lo[3] = {(low.x - center.x) / radius, (low.y - center.y) / radius,
                          (low.z - center.z) / radius};
    const double hi[3] = {(high.x - center.x) / radius, (high.y - center.y) / radius,
                          (high.z - center.z) / radius};
    // vol(box) = sum over its corners of (-1)^(number of upper ends) V(corner).
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const bool ux = corner & 1, uy = corner & 2, uz = corner & 4;
        const double v =
            ball_orthant_volume(ux ? hi[0] : lo[0], uy ? hi[1] : lo[1], uz ? hi[2] : lo[2]);
        sum += ((ux + uy + uz) % 2 == 0) ? v : -v;
    }
    return std::max(0.0, sum) * radius * radius * radius;
}

namespace {

/// Plane i of the pore image before any particle: 1 where the voxel's centre is inside the
/// container, 0 outside. The containers are upright prisms above the floor: a column (i, j) is
/// inside or not at every height above z = 0.
void container_plane(std::uint8_t* plane, std::size_t i, const VoxelGrid& grid,
                     const Container& container) {
    const std::size_t ny = grid.count[1], nz = grid.count[2];
    const double h = grid.size;
    const auto k_floor =
        centres_within(0.0, std::numeric_limits<double>::infinity(), grid.low.z, h, nz).first;
    const double x = centre_of(grid.low.x, h, i);
    for (std::size_t j = 0; j < ny; ++j) {
        const double y = centre_of(grid.low.y, h, j);
        const bool inside = container.contains({x, y, std::max(0.0, grid.low.z)});
        std::uint8_t* row = plane + j * nz;
        std::memset(row, 0, nz);
        if (inside && k_floor < static_cast<long long>(nz))
            std::memset(row + k_floor, 1, nz - static_cast<std::size_t>(k_floor));
    }
}

} // namespace

Voxels<std::uint8_t> pore_image(const Packing& packing, const Container& container,
                                const VoxelGrid& grid) {
    // plain names, not a structured binding: clang 14 cannot name those inside OpenMP regions
    const std::size_t nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
    const double h = grid.size;
    Voxels<std::uint8_t> image(grid.voxels()); // every voxel written below
    const std::vector<Ball> balls = balls_reaching(packing, container, grid);
    const PlaneLists lists = plane_lists(balls, grid, true);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < nx; ++i) {
        std::uint8_t* plane = image.data() + i * ny * nz;
        const double x = centre_of(grid.low.x, h, i);
        container_plane(plane, i, grid, container);
        for (std::size_t e = lists.start[i]; e < lists.start[i + 1]; ++e) {
            const Ball& b = balls[lists.ball[e]];
            const double dx = x - b.c.x;
            const double across = b.r * b.r - dx * dx;
            if (across <= 0.0)
                continue;
            const double w = std::sqrt(across);
            const auto [j0, j1] = centres_within(b.c.y - w, b.c.y + w, grid.low.y, h, ny);
            for (long long j = j0; j <= j1; ++j) {
                const double dy = centre_of(grid.low.y, h, static_cast<std::size_t>(j)) - b.c.y;
                const double up = across - dy * dy;
                if (up <= 0.0)
                    continue;
                const double dz = std::sqrt(up);
                const auto [k0, k1] = centres_within(b.c.z - dz, b.c.z + dz, grid.low.z, h, nz);
                if (k0 <= k1)
                    std::memset(plane + static_cast<std::size_t>(j) * nz + k0, 0,
                                static_cast<std::size_t>(k1 - k0 + 1));
            }
        }
    }
    return image;
}

namespace {

/// The exact volumes of one ball in the voxels of a block of planes, from ball_orthant_volume at
/// the voxel corners (grid nodes).
///
/// By the ball's symmetry a box is measured in the octant its corners are in, reflected to
/// a, b, c >= 0 (a voxel that straddles a plane through the centre is split there): no
/// reflection formula, one positive evaluation per node, V = P(X) - P(a). P splits into
/// parts of two of a, b, c each (half_antiderivative), computed once per line of nodes: P(X)
/// per line along x, H(a, c) per line along y, H(a, b) per line along z. Every node's value
/// is then a few additions, computed for the whole box at once (branch-free loops); the
/// arctangents are spent per line, not per node. One object per thread, reused ball after ball.
class BallInVoxels {
public:
    explicit BallInVoxels(const VoxelGrid& grid)
        : m_grid(grid) {}

    /// Measure `ball` in the voxels first..last (inclusive) from now on.
    void start(const Ball& ball, std::array<long long, 3> first, std::array<long long, 3> last) {
        m_first = first;
        const double centre[3] = {ball.c.x, ball.c.y, ball.c.z};
        const double low[3] = {m_grid.low.x, m_grid.low.y, m_grid.low.z};
        for (int d = 0; d < 3; ++d) {
            // the nodes of the voxels first..last, and one more slot for the centre's plane
            const auto n = static_cast<std::size_t>(last[d] - first[d] + 3);
            m_nodes[d] = n;
            m_offset[d].resize(n);
            for (std::size_t s = 0; s + 1 < n; ++s) {
                const double at =
                    low[d] +
                    static_cast<double>(first[d] + static_cast<long long>(s)) * m_grid.size;
                // |node - centre| / r, clamped to 1
                m_offset[d][s] = std::min(1.0, std::abs(at - centre[d]) / ball.r);
            }
            m_offset[d][n - 1] = 0.0;
            m_coordinate_low[d] = low[d];
            m_centre[d] = centre[d];
        }
        m_line.resize(m_nodes[2]);
        m_radius_in_voxels = ball.r / m_grid.size;
        m_centre_in_voxels =
            (ball.c.z - (low[2] + static_cast<double>(first[2]) * m_grid.size)) / m_grid.size;
        const std::size_t nx = m_nodes[0], ny = m_nodes[1], nz = m_nodes[2];
        const std::vector<double>&ax = m_offset[0], &by = m_offset[1], &cz = m_offset[2];
        // every voxel's segments along z, the same for all its rows
        m_z_segments.resize(static_cast<std::size_t>(last[2] - first[2] + 1));
        for (std::size_t k = 0; k < m_z_segments.size(); ++k)
            m_z_segments[k].count =
                segments_of(2, first[2] + static_cast<long long>(k), m_z_segments[k].slots);
        // The parts of P, where a node can be inside the ball (elsewhere unused: 0). Each
        // table's arctangents are taken in one batch (arctangents), then its entries.
        m_upper.assign(ny * nz, 0.0);
        m_where.clear();
        m_root.clear();
        m_tangent.clear();
        for (std::size_t y = 0; y < ny; ++y)
            for (std::size_t z = 0; z < nz; ++z)
                if (by[y] * by[y] + cz[z] * cz[z] < 1.0) {
                    const UpperEnd end = upper_end(by[y], cz[z]);
                    m_where.push_back(y * nz + z);
                    m_root.push_back(end.x);
                    m_tangent.insert(m_tangent.end(), end.tangents.begin(), end.tangents.end());
                }
        arctangents(m_tangent);
        for (std::size_t e = 0; e < m_where.size(); ++e)
            m_upper[m_where[e]] = upper_from_arctangents(by[m_where[e] / nz], cz[m_where[e] % nz],
                                                         m_root[e], m_tangent.data() + 6 * e);
        const auto halves = [&](std::vector<double>& table, const std::vector<double>& t) {
            table.assign(nx * t.size(), 0.0);
            m_where.clear();
            m_root.clear();
            m_tangent.clear();
            for (std::size_t x = 0; x < nx; ++x)
                for (std::size_t u = 0; u < t.size(); ++u)
                    if (ax[x] * ax[x] + t[u] * t[u] < 1.0) {
                        const double a = ax[x];
                        const double r = std::sqrt(std::max(0.0, one_minus_squares(t[u], a)));
                        m_where.push_back(x * t.size() + u);
                        m_root.push_back(r);
                        const auto tangents = half_tangents(a, t[u], r);
                        m_tangent.insert(m_tangent.end(), tangents.begin(), tangents.end());
                    }
            arctangents(m_tangent);
            for (std::size_t e = 0; e < m_where.size(); ++e) {
                const std::size_t x = m_where[e] / t.size(), u = m_where[e] % t.size();
                table[m_where[e]] =
                    half_from_arctangents(ax[x], t[u], m_root[e], m_tangent.data() + 3 * e);
            }
        };
        halves(m_half_c, cz);
        halves(m_half_b, by);
        // V = P(X) - P(a) at every node inside the ball, 0 outside.
        m_value.resize(nx * ny * nz);
        for (std::size_t x = 0; x < nx; ++x) {
            const double a = ax[x], a2 = a * a, plain = plain_terms(a, 0.0, 0.0);
            const double* half_c = m_half_c.data() + x * nz;
            for (std::size_t y = 0; y < ny; ++y) {
                const double b = by[y], rest = 1.0 - b * b, ab = a * b;
                const double lower_ab = m_half_b[x * ny + y] + plain;
                const double* upper = m_upper.data() + y * nz;
                double* value = m_value.data() + (x * ny + y) * nz;
                // Only the grid nodes within the ball's chord along z (and one beyond each
                // end) can be inside it; the rest hold 0. The centre's plane is slot nz - 1.
                // plain names, not a structured binding: clang 14 cannot name those in the
                // omp simd loop
                const std::pair<std::size_t, std::size_t> chord =
                    chord_slots(std::sqrt(std::max(0.0, rest - a2)));
                const std::size_t z0 = chord.first, z1 = chord.second;
                std::fill(value, value + z0, 0.0);
                std::fill(value + z1, value + nz - 1, 0.0);
                const double* c = cz.data();
                // V at node z, 0 outside the ball (branch-free, so that the loop is vectorised)
                const auto node = [&](std::size_t z) {
                    const double v = upper[z] - (half_c[z] + lower_ab + ab * c[z]);
                    const double positive = v > 0.0 ? v : 0.0;
                    value[z] = a2 < rest - c[z] * c[z] ? positive : 0.0;
                };
#pragma omp simd
                for (std::size_t z = z0; z < z1; ++z)
                    node(z);
                node(nz - 1);
            }
        }
    }

    /// Take row (i, j) of the ball's box: from now on voxel_in_row(k) measures voxel (i, j, k)
    /// for k in `first` or `second` (voxel ranges, inclusive, maybe empty). The row's x and y
    /// segments are fixed, so their corners' signed sum is made once per node along z (m_line),
    /// at the nodes of those voxels and the centre's plane, and each voxel is then a
    /// difference of two (or four) of those.
    void start_row(long long i, long long j, std::pair<long long, long long> first,
                   std::pair<long long, long long> second) {
        const long long index[2] = {i, j};
        std::array<std::array<std::size_t, 2>, 2> segments[2];
        int count[2];
        for (int d = 0; d < 2; ++d)
            count[d] = segments_of(d, index[d], segments[d]);
        const std::size_t nz = m_nodes[2];
        // the node slots: those of each range's voxels, then the centre's plane
        std::pair<std::size_t, std::size_t> slots[3];
        int ranges = 0;
        for (const auto& [from, to] : {first, second})
            if (from <= to)
                slots[ranges++] = {static_cast<std::size_t>(from - m_first[2]),
                                   static_cast<std::size_t>(to + 2 - m_first[2])};
        slots[ranges++] = {nz - 1, nz};
        double* line = m_line.data();
        if (count[0] == 1 && count[1] == 1) {
            // one segment each way (most rows): the four corners in one pass, in the order and
            // with the signs of the general sum below (the same bits)
            const auto column = [&](int fx, int fy) {
                return m_value.data() + (segments[0][0][fx] * m_nodes[1] + segments[1][0][fy]) * nz;
            };
            const double *v00 = column(0, 0), *v10 = column(1, 0), *v01 = column(0, 1),
                         *v11 = column(1, 1);
            for (int s = 0; s < ranges; ++s)
#pragma omp simd
                for (std::size_t z = slots[s].first; z < slots[s].second; ++z)
                    line[z] = ((v00[z] - v10[z]) - v01[z]) + v11[z];
            return;
        }
        for (int s = 0; s < ranges; ++s)
            std::fill(m_line.begin() + static_cast<std::ptrdiff_t>(slots[s].first),
                      m_line.begin() + static_cast<std::ptrdiff_t>(slots[s].second), 0.0);
        for (int sx = 0; sx < count[0]; ++sx)
            for (int sy = 0; sy < count[1]; ++sy)
                for (int corner = 0; corner < 4; ++corner) {
                    const int fx = corner & 1, fy = corner >> 1;
                    const double* v = m_value.data() +
                                      (segments[0][sx][fx] * m_nodes[1] + segments[1][sy][fy]) * nz;
                    const double sign = (fx + fy) % 2 == 0 ? 1.0 : -1.0;
                    for (int s = 0; s < ranges; ++s)
#pragma omp simd
                        for (std::size_t z = slots[s].first; z < slots[s].second; ++z)
                            line[z] += sign * v[z];
                }
    }

    /// \return the volume of the ball in voxel (i, j, k) over r^3, (i, j) the row start_row
    /// took: the sum over the voxel's corners, each signed by how many of its bounds are the
    /// far ones, of ball_orthant_volume there.
    double voxel_in_row(long long k) const {
        const ZSegments& z = m_z_segments[static_cast<std::size_t>(k - m_first[2])];
        double sum = 0.0;
        for (int sz = 0; sz < z.count; ++sz)
            sum += m_line[z.slots[sz][0]] - m_line[z.slots[sz][1]];
        return std::max(0.0, sum);
    }

private:
    double coordinate(int d, long long n) const {
        return m_coordinate_low[d] + static_cast<double>(n) * m_grid.size;
    }

    /// The grid node slots [first, last) along z within `half` r of the centre, and one more
    /// each side, clipped to the box's nodes. In units of h from the box's first node (no
    /// division per line: the slot beyond each end absorbs the rounding, and a node outside
    /// the ball holds 0 whether computed or not).
    std::pair<std::size_t, std::size_t> chord_slots(double half) const {
        const double reach = half * m_radius_in_voxels;
        const auto grid_nodes = static_cast<long long>(m_nodes[2]) - 1;
        const long long from = floor_whole(m_centre_in_voxels - reach) - 1;
        const long long to = ceil_whole(m_centre_in_voxels + reach) + 2;
        return {static_cast<std::size_t>(std::clamp(from, 0ll, grid_nodes)),
                static_cast<std::size_t>(std::clamp(to, 0ll, grid_nodes))};
    }

    /// Voxel `index`'s extent along axis d as one or two segments, each (near, far) from the
    /// centre: the slots of a node of the grid or of the centre's plane (a voxel that
    /// straddles the plane through the centre is split there). \return how many.
    int segments_of(int d, long long index,
                    std::array<std::array<std::size_t, 2>, 2>& segments) const {
        const double low = coordinate(d, index), high = coordinate(d, index + 1);
        const auto near = static_cast<std::size_t>(index - m_first[d]);
        if (low >= m_centre[d]) {
            segments[0] = {near, near + 1};
            return 1;
        }
        if (high <= m_centre[d]) {
            segments[0] = {near + 1, near};
            return 1;
        }
        const std::size_t centre = m_nodes[d] - 1;
        segments[0] = {centre, near + 1};
        segments[1] = {centre, near};
        return 2;
    }

    const VoxelGrid& m_grid;
    std::array<long long, 3> m_first{};
    std::array<std::size_t, 3> m_nodes{};
    double m_coordinate_low[3]{};
    double m_centre[3]{};
    double m_radius_in_voxels = 0.0; // r / h
    double m_centre_in_voxels = 0.0; // (centre - the box's first node) / h, along z
    std::vector<double> m_offset[3]; // |node - centre| / r per slot and axis
    std::vector<double> m_value;     // per node
    std::vector<double> m_line;      // per node along z: the row's x and y corners summed
    struct ZSegments {
        int count = 0;
        std::array<std::array<std::size_t, 2>, 2> slots{};
    };
    std::vector<ZSegments> m_z_segments; // per voxel along z (segments_of)
    std::vector<double> m_upper;         // P(X) per line (y, z)
    std::vector<double> m_half_c;        // H(a, c) per (x, z)
    std::vector<double> m_half_b;        // H(a, b) per (x, y)
    // a table's entries in the making: where each goes, its root, its tangents
    std::vector<std::size_t> m_where;
    std::vector<double> m_root;
    std::vector<double> m_tangent;
};

} // namespace

template <class Real>
Voxels<Real> solid_fraction_image(const Packing& packing, const Container& container,
                                  const VoxelGrid& grid) {
    // plain names, not a structured binding: clang 14 cannot name those inside OpenMP regions
    const std::size_t nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
    const double h = grid.size;
    Voxels<Real> image(grid.voxels()); // zeroed block by block below
    const std::vector<Ball> balls = balls_reaching(packing, container, grid);
    // Blocks of planes, each a task: a ball's nodes are computed once per block it meets, so
    // blocks are as wide as 2 tasks per thread allow, up to 64 planes (the bits do not depend
    // on it: each voxel sums its balls in the same order, from the floor up).
    const auto tasks = 2 * static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
    const std::size_t block = std::clamp<std::size_t>(nx / tasks, 1, 64);
    const std::size_t blocks = (nx + block - 1) / block;
    VoxelGrid block_grid = grid;
    block_grid.size = h * static_cast<double>(block);
    block_grid.count[0] = blocks;
    const PlaneLists lists = plane_lists(balls, block_grid, false);
    // Strips across y, 4 of the largest radii wide, for the order of the balls in a block.
    double largest = 0.0;
    for (const Ball& ball : balls)
        largest = std::max(largest, ball.r);
    std::vector<long long> strip(balls.size());
    for (std::size_t n = 0; n < balls.size(); ++n)
        strip[n] = index_of(floor_whole((balls[n].c.y - grid.low.y) / (4.0 * largest)), ny);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t b = 0; b < blocks; ++b) {
        const long long i_first = static_cast<long long>(b * block);
        const long long i_last = static_cast<long long>(std::min(nx, (b + 1) * block)) - 1;
        // the block's planes zeroed by the thread that fills them
        std::fill(image.begin() + i_first * static_cast<std::ptrdiff_t>(ny * nz),
                  image.begin() + (i_last + 1) * static_cast<std::ptrdiff_t>(ny * nz), Real(0));
        BallInVoxels exact(grid);
        // The block's balls in strips across y, each from the floor up (ties in ball order):
        // the voxels a ball adds to are then mostly in the cache from its neighbours below,
        // where in the file's order each ball would fetch its rows from memory. The order is
        // the data's, whatever the blocks and threads.
        std::vector<std::uint32_t> order(
            lists.ball.begin() + static_cast<std::ptrdiff_t>(lists.start[b]),
            lists.ball.begin() + static_cast<std::ptrdiff_t>(lists.start[b + 1]));
        std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
            return std::tuple(strip[p], balls[p].c.z, p) < std::tuple(strip[q], balls[q].c.z, q);
        });
        for (const std::uint32_t n : order) {
            const Ball& ball = balls[n];
            const double r2 = ball.r * ball.r;
            const double scale = ball.r * ball.r * ball.r / (h * h * h);
            const auto [ia, ib] =
                voxels_meeting(ball.c.x - ball.r, ball.c.x + ball.r, grid.low.x, h, nx);
            const auto [ja, jb] =
                voxels_meeting(ball.c.y - ball.r, ball.c.y + ball.r, grid.low.y, h, ny);
            const auto [ka, kb] =
                voxels_meeting(ball.c.z - ball.r, ball.c.z + ball.r, grid.low.z, h, nz);
            const long long i0 = std::max(ia, i_first), i1 = std::min(ib, i_last);
            if (i0 > i1 || ja > jb || ka > kb)
                continue;
            exact.start(ball, {i0, ja, ka}, {i1, jb, kb});
            for (long long i = i0; i <= i1; ++i) {
                Real* plane = image.data() + static_cast<std::size_t>(i) * ny * nz;
                const double x0 = grid.low.x + static_cast<double>(i) * h, x1 = x0 + h;
                const double near_x = std::max({x0 - ball.c.x, ball.c.x - x1, 0.0});
                const double far_x = std::max(std::abs(x0 - ball.c.x), std::abs(x1 - ball.c.x));
                if (near_x * near_x >= r2)
                    continue;
                for (long long j = ja; j <= jb; ++j) {
                    // the next row's voxels asked from memory while this row is measured
                    const Real* next = j < jb   ? plane + static_cast<std::size_t>(j + 1) * nz
                                       : i < i1 ? plane + (ny + static_cast<std::size_t>(ja)) * nz
                                                : nullptr;
                    constexpr auto line = static_cast<long long>(64 / sizeof(Real));
                    for (long long k = ka; next && k <= kb + line; k += line)
                        __builtin_prefetch(next + std::min(k, kb), 1, 3);
                    const double y0 = grid.low.y + static_cast<double>(j) * h, y1 = y0 + h;
                    const double near_y = std::max({y0 - ball.c.y, ball.c.y - y1, 0.0});
                    const double far_y = std::max(std::abs(y0 - ball.c.y), std::abs(y1 - ball.c.y));
                    const double near_xy = near_x * near_x + near_y * near_y;
                    if (near_xy >= r2)
                        continue;
                    const double far_xy = far_x * far_x + far_y * far_y;
                    const double reach = std::sqrt(r2 - near_xy);
                    const auto [k0, k1] =
                        voxels_meeting(ball.c.z - reach, ball.c.z + reach, grid.low.z, h, nz);
                    // The voxels wholly inside, far_xy + far_z^2 <= r^2, are a run in the
                    // row's middle: each holds 1; only the ends are measured.
                    long long in0 = k1 + 1, in1 = k1;
                    if (far_xy < r2) {
                        const double inner = std::sqrt(r2 - far_xy);
                        in0 = std::max(
                            k0, index_of(ceil_whole((ball.c.z - inner - grid.low.z) / h), nz));
                        in1 = std::min(
                            k1, index_of(floor_whole((ball.c.z + inner - grid.low.z) / h), nz) - 1);
                        if (in0 > in1)
                            in0 = k1 + 1, in1 = k1;
                    }
                    Real* row = plane + static_cast<std::size_t>(j) * nz;
                    if (in0 <= in1)
                        exact.start_row(i, j, {k0, in0 - 1}, {in1 + 1, k1});
                    else
                        exact.start_row(i, j, {k0, k1}, {1, 0});
                    const auto cut = [&](long long k) {
                        const double z0 = grid.low.z + static_cast<double>(k) * h, z1 = z0 + h;
                        const double near_z = std::max({z0 - ball.c.z, ball.c.z - z1, 0.0});
                        if (near_xy + near_z * near_z < r2)
                            row[k] += static_cast<Real>(exact.voxel_in_row(k) * scale);
                    };
                    for (long long k = k0; k < in0; ++k)
                        cut(k);
                    for (long long k = in0; k <= in1; ++k)
                        row[k] += Real(1);
                    for (long long k = std::max(in1 + 1, in0); k <= k1; ++k)
                        cut(k);
                }
            }
        }
    }
    return image;
}

template Voxels<double> solid_fraction_image(const Packing&, const Container&, const VoxelGrid&);
template Voxels<float> solid_fraction_image(const Packing&, const Container&, const VoxelGrid&);

namespace {

/// A pellet to draw: where it is (a periodic copy's position moved by whole periods), the box
/// that holds it (its support along the axes) and the rotation into its body frame.
struct PlacedPellet {
    Placement p;
    Vec3 low, high;
    Quaternion to_body;
};

void require_orientations(const Packing& packing) {
    if (packing.orientations.size() != packing.size())
        throw InvalidInput("a bed of pellets needs each one's orientation; allowed: a table with "
                           "the columns qw, qx, qy, qz");
}

/// The pellets, with their copies across a periodic cell's sides, whose boxes reach the grid,
/// in order (each pellet, then its copies).
template <class Shape>
std::vector<PlacedPellet> pellets_reaching(const Packing& packing, const Shape& shape,
                                           const Container& container, const VoxelGrid& grid) {
    require_orientations(packing);
    const Vec3 high = grid.high();
    const std::optional<Periods> cell = container.periods();
    std::vector<PlacedPellet> out;
    for (std::size_t n = 0; n < packing.size(); ++n) {
        const Placement p{packing.centers[n], packing.orientations[n], packing.radii[n]};
        const Vec3 low{shape.support(p, {-1.0, 0.0, 0.0}).x, shape.support(p, {0.0, -1.0, 0.0}).y,
                       shape.support(p, {0.0, 0.0, -1.0}).z};
        const Vec3 top{shape.support(p, {1.0, 0.0, 0.0}).x, shape.support(p, {0.0, 1.0, 0.0}).y,
                       shape.support(p, {0.0, 0.0, 1.0}).z};
        for (int sx = cell ? -1 : 0; sx <= (cell ? 1 : 0); ++sx)
            for (int sy = cell ? -1 : 0; sy <= (cell ? 1 : 0); ++sy) {
                const Vec3 shift = cell ? Vec3{sx * cell->lx(), sy * cell->ly(), 0.0} : Vec3{};
                const Vec3 a = low + shift, b = top + shift;
                if (b.x > grid.low.x && a.x < high.x && b.y > grid.low.y && a.y < high.y &&
                    b.z > grid.low.z && a.z < high.z)
                    out.push_back({{p.position + shift, p.orientation, p.size},
                                   a,
                                   b,
                                   conjugate(p.orientation)});
            }
    }
    return out;
}

/// plane_lists of the pellets' boxes.
PlaneLists plane_lists(const std::vector<PlacedPellet>& pellets, const VoxelGrid& grid,
                       bool centres) {
    return plane_lists(
        pellets.size(),
        [&](std::size_t n) { return std::pair(pellets[n].low.x, pellets[n].high.x); }, grid,
        centres);
}

/// The signed depth (length units) of the point x in the pellet: the shape's, in its body frame.
template <class Shape>
double depth_in(const Shape& shape, const PlacedPellet& pellet, const Vec3& x) {
    const double size = pellet.p.size;
    return shape.signed_depth(rotate(pellet.to_body, x - pellet.p.position) * (1.0 / size)) * size;
}

template <class Shape>
Voxels<std::uint8_t> pellet_pore_image(const Packing& packing, const Shape& shape,
                                       const Container& container, const VoxelGrid& grid) {
    const std::size_t nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
    const double h = grid.size;
    Voxels<std::uint8_t> image(grid.voxels()); // every voxel written below
    const std::vector<PlacedPellet> pellets = pellets_reaching(packing, shape, container, grid);
    const PlaneLists lists = plane_lists(pellets, grid, true);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < nx; ++i) {
        std::uint8_t* plane = image.data() + i * ny * nz;
        container_plane(plane, i, grid, container);
        const double x = centre_of(grid.low.x, h, i);
        for (std::size_t e = lists.start[i]; e < lists.start[i + 1]; ++e) {
            const PlacedPellet& pellet = pellets[lists.ball[e]];
            const auto [j0, j1] = centres_within(pellet.low.y, pellet.high.y, grid.low.y, h, ny);
            const auto [k0, k1] = centres_within(pellet.low.z, pellet.high.z, grid.low.z, h, nz);
            for (long long j = j0; j <= j1; ++j) {
                std::uint8_t* row = plane + static_cast<std::size_t>(j) * nz;
                const double y = centre_of(grid.low.y, h, static_cast<std::size_t>(j));
                for (long long k = k0; k <= k1; ++k)
                    if (depth_in(shape, pellet,
                                 {x, y, centre_of(grid.low.z, h, static_cast<std::size_t>(k))}) >
                        0.0)
                        row[k] = 0;
            }
        }
    }
    return image;
}

template <class Real, class Shape>
Voxels<Real> pellet_fraction_image(const Packing& packing, const Shape& shape,
                                   const Container& container, const VoxelGrid& grid) {
    const std::size_t nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
    const double h = grid.size;
    const double cube = h * h * h;
    // A voxel lies within its half-diagonal of its centre.
    const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
    Voxels<Real> image(grid.voxels()); // zeroed plane by plane below
    const std::vector<PlacedPellet> pellets = pellets_reaching(packing, shape, container, grid);
    const PlaneLists lists = plane_lists(pellets, grid, false);
    // Each plane a task, its voxels summing their pellets in order: the bits do not depend on
    // the threads.
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < nx; ++i) {
        Real* plane = image.data() + i * ny * nz;
        std::fill(plane, plane + ny * nz, Real(0));
        const double x0 = grid.low.x + static_cast<double>(i) * h;
        for (std::size_t e = lists.start[i]; e < lists.start[i + 1]; ++e) {
            const PlacedPellet& pellet = pellets[lists.ball[e]];
            const auto [j0, j1] = voxels_meeting(pellet.low.y, pellet.high.y, grid.low.y, h, ny);
            const auto [k0, k1] = voxels_meeting(pellet.low.z, pellet.high.z, grid.low.z, h, nz);
            for (long long j = j0; j <= j1; ++j) {
                Real* row = plane + static_cast<std::size_t>(j) * nz;
                const double y0 = grid.low.y + static_cast<double>(j) * h;
                for (long long k = k0; k <= k1; ++k) {
                    const double z0 = grid.low.z + static_cast<double>(k) * h;
                    const Vec3 low{x0, y0, z0};
                    const double depth =
                        depth_in(shape, pellet, low + Vec3{0.5 * h, 0.5 * h, 0.5 * h});
                    if (depth >= half_diagonal)
                        row[k] += Real(1);
                    else if (depth > -half_diagonal)
                        row[k] += static_cast<Real>(
                            shape.volume_in_box(pellet.p, low, low + Vec3{h, h, h}) / cube);
                }
            }
        }
    }
    return image;
}

} // namespace

Voxels<std::uint8_t> pore_image(const Packing& packing, const PelletShape& shape,
                                const Container& container, const VoxelGrid& grid) {
    return std::visit([&](const auto& s) { return pellet_pore_image(packing, s, container, grid); },
                      shape);
}

template <class Real>
Voxels<Real> solid_fraction_image(const Packing& packing, const PelletShape& shape,
                                  const Container& container, const VoxelGrid& grid) {
    return std::visit(
        [&](const auto& s) { return pellet_fraction_image<Real>(packing, s, container, grid); },
        shape);
}

template Voxels<double> solid_fraction_image(const Packing&, const PelletShape&, const Container&,
                                             const VoxelGrid&);
template Voxels<float> solid_fraction_image(const Packing&, const PelletShape&, const Container&,
                                            const VoxelGrid&);

double pellet_bed_top(const Packing& packing, const PelletShape& shape) {
    require_orientations(packing);
    return std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            return bed_top(ShapedBed<S>(packing, {s}));
        },
        shape);
}

const char* voxel_type_name(VoxelType type) {
    switch (type) {
    case VoxelType::boolean:
        return "bool";
    case VoxelType::float64:
        return "float64";
    case VoxelType::float32:
        return "float32";
    }
    return "";
}

std::size_t voxel_bytes(VoxelType type) {
    return type == VoxelType::boolean ? 1 : type == VoxelType::float64 ? 8 : 4;
}

std::optional<ImageFormat> image_format(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (extension == ".npy")
        return ImageFormat::npy;
    if (extension == ".tif" || extension == ".tiff")
        return ImageFormat::tif;
    if (extension == ".raw")
        return ImageFormat::raw;
    return std::nullopt;
}

std::string image_header(const VoxelGrid& grid, VoxelType type) {
    const bool binary = type == VoxelType::boolean;
    nlohmann::json header;
    header["shape"] = grid.count;
    header["dtype"] = binary ? "uint8" : voxel_type_name(type);
    header["byte_order"] = "little";
    header["order"] = "C (index (i ny + j) nz + k: z fastest; numpy im[i, j, k])";
    header["voxel_size"] = grid.size;
    header["origin"] = {grid.low.x, grid.low.y, grid.low.z};
    header["values"] = binary ? "1 (True): pore space (inside the container, inside no sphere); "
                                "0 (False): solid (a sphere, or outside the container), as "
                                "PoreSpy's images"
                              : "the solid fraction of each voxel, exact (the spheres' volume "
                                "inside it over its volume)";
    return json_file_text(header, "the .raw.json header");
}

namespace {

void put16(std::string& s, std::uint16_t v) {
    s.push_back(static_cast<char>(v & 0xff));
    s.push_back(static_cast<char>(v >> 8));
}
void put32(std::string& s, std::uint32_t v) {
    for (int b = 0; b < 4; ++b)
        s.push_back(static_cast<char>((v >> (8 * b)) & 0xff));
}

/// The .npy header (format version 1.0): magic, header length, the dict padded so that the data
/// starts at a multiple of 64 bytes.
std::string npy_header(const VoxelGrid& grid, VoxelType type) {
    const char* descr = type == VoxelType::boolean   ? "|b1"
                        : type == VoxelType::float64 ? "<f8"
                                                     : "<f4";
    std::string dict = fmt::format("{{'descr': '{}', 'fortran_order': False, 'shape': ({}, {}, "
                                   "{}), }}",
                                   descr, grid.count[0], grid.count[1], grid.count[2]);
    const std::size_t unpadded = 10 + dict.size() + 1;
    dict.append((64 - unpadded % 64) % 64, ' ');
    dict.push_back('\n');
    std::string header("\x93NUMPY\x01\x00", 8);
    put16(header, static_cast<std::uint16_t>(dict.size()));
    return header + dict;
}

} // namespace

void write_image(const std::filesystem::path& path, ImageFormat format, const VoxelGrid& grid,
                 VoxelType type, const void* voxels) {
    const bool binary = type == VoxelType::boolean;
    const char* data = static_cast<const char*>(voxels);
    const std::size_t bytes_per_voxel = voxel_bytes(type);
    const std::size_t bytes = grid.voxels() * bytes_per_voxel;
    std::ofstream out(path, std::ios::binary);
    if (format == ImageFormat::npy) {
        out << npy_header(grid, type);
    } else if (format == ImageFormat::tif) {
        // Baseline TIFF, little-endian: the pixel data of every page first, then one IFD per
        // page (ny rows of nz columns, one strip), each pointing at the next.
        const std::size_t page = grid.count[1] * grid.count[2] * bytes_per_voxel;
        constexpr std::size_t entries = 11, ifd_size = 2 + entries * 12 + 4;
        const std::size_t data_end = 8 + bytes + (bytes & 1); // IFDs start on a word boundary
        const double total =
            static_cast<double>(data_end) + static_cast<double>(grid.count[0]) * ifd_size;
        if (total > 4294967295.0)
            throw InvalidInput(fmt::format(
                "--out {}: a TIFF of {:.4g} bytes is not allowed; allowed: at most 4 GiB (use "
                ".npy or .raw for larger images)",
                printable(path.filename().native()), total));
        std::string header("II", 2);
        put16(header, 42);
        put32(header, static_cast<std::uint32_t>(data_end)); // the first IFD after the data
        out << header;
        out.write(data, static_cast<std::streamsize>(bytes));
        if (bytes & 1)
            out.put('\0');
        std::string ifds;
        for (std::size_t i = 0; i < grid.count[0]; ++i) {
            const std::size_t at = data_end + i * ifd_size;
            auto entry = [&](std::uint16_t tag, std::uint16_t field, std::uint32_t value) {
                put16(ifds, tag);
                put16(ifds, field);
                put32(ifds, 1);
                if (field == 3) { // SHORT, left-justified in the value field
                    put16(ifds, static_cast<std::uint16_t>(value));
                    put16(ifds, 0);
                } else {
                    put32(ifds, value);
                }
            };
            put16(ifds, entries);
            entry(256, 4, static_cast<std::uint32_t>(grid.count[2]));       // ImageWidth
            entry(257, 4, static_cast<std::uint32_t>(grid.count[1]));       // ImageLength
            entry(258, 3, static_cast<std::uint32_t>(8 * bytes_per_voxel)); // BitsPerSample
            entry(259, 3, 1);                                               // no compression
            entry(262, 3, 1);                                               // BlackIsZero
            entry(273, 4, static_cast<std::uint32_t>(8 + i * page));        // StripOffsets
            entry(277, 3, 1);                                               // SamplesPerPixel
            entry(278, 4, static_cast<std::uint32_t>(grid.count[1]));       // RowsPerStrip
            entry(279, 4, static_cast<std::uint32_t>(page));                // StripByteCounts
            entry(284, 3, 1);                                               // contiguous
            entry(339, 3, binary ? 1 : 3); // SampleFormat: unsigned integer or IEEE float
            put32(ifds, i + 1 < grid.count[0] ? static_cast<std::uint32_t>(at + ifd_size) : 0);
        }
        out << ifds;
        out.flush();
        if (!out)
            throw std::runtime_error(fmt::format("cannot write {} ({}); nothing was written",
                                                 printable(path.native()), std::strerror(errno)));
        return;
    }
    out.write(data, static_cast<std::streamsize>(bytes));
    out.flush();
    if (!out)
        throw std::runtime_error(fmt::format("cannot write {} ({}); nothing was written",
                                             printable(path.native()), std::strerror(errno)));
}

} // namespace packbed
