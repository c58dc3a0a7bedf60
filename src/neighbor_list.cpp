#include "packbed/neighbor_list.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

#include <omp.h>

#include "parallel.hpp"

namespace packbed {

namespace {

/// A uniform grid of cubic cells over the bounding box of the centres, with the spheres
/// sorted by cell (counting sort). Cell edge >= the largest interaction distance, so the
/// neighbours of a sphere lie in its own and the 26 adjacent cells.
struct CellGrid {
    Vec3 origin;
    double inv_edge = 0.0;
    int nx = 1, ny = 1, nz = 1;
    std::vector<std::uint32_t> cell_start; // size ncells + 1
    std::vector<std::uint32_t> sorted;     // sphere indices ordered by cell
    std::vector<std::uint32_t> cell_of;    // cell of each sphere

    int clamp_index(double v, int n) const {
        const double k = std::floor(v * inv_edge); // clamped in double: no UB on overflow
        if (!(k > 0.0))
            return 0;
        return k >= n - 1 ? n - 1 : static_cast<int>(k);
    }

    void build(std::span<const Vec3> centers, double edge) {
        Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                std::numeric_limits<double>::max()};
        Vec3 hi{-lo.x, -lo.y, -lo.z};
        for (const auto& c : centers) {
            lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
            hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
        }
        // Keep the number of cells O(N) even if the spheres are spread far apart.
        const double max_cells = 8.0 * static_cast<double>(centers.size()) + 64.0;
        auto count = [&](double e) {
            return std::floor((hi.x - lo.x) / e + 1) * std::floor((hi.y - lo.y) / e + 1) *
                   std::floor((hi.z - lo.z) / e + 1);
        };
        while (count(edge) > max_cells)
            edge *= 1.5;
        origin = lo;
        inv_edge = 1.0 / edge;
        nx = static_cast<int>((hi.x - lo.x) * inv_edge) + 1;
        ny = static_cast<int>((hi.y - lo.y) * inv_edge) + 1;
        nz = static_cast<int>((hi.z - lo.z) * inv_edge) + 1;
        const std::size_t ncells = static_cast<std::size_t>(nx) * ny * nz;
        cell_start.assign(ncells + 1, 0);
        cell_of.resize(centers.size());
        for (std::size_t i = 0; i < centers.size(); ++i) {
            const Vec3 d = centers[i] - origin;
            const std::size_t c =
                cell(clamp_index(d.x, nx), clamp_index(d.y, ny), clamp_index(d.z, nz));
            cell_of[i] = static_cast<std::uint32_t>(c);
            ++cell_start[c + 1];
        }
        for (std::size_t c = 0; c < ncells; ++c)
            cell_start[c + 1] += cell_start[c];
        sorted.resize(centers.size());
        std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
        for (std::size_t i = 0; i < centers.size(); ++i)
            sorted[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
    }

    std::size_t cell(int ix, int iy, int iz) const {
        return (static_cast<std::size_t>(iz) * ny + iy) * nx + ix;
    }

    /// Call f(begin, end) for the runs of `sorted` that hold the spheres of the 27 cells around
    /// the cell of sphere i: the up to 3 cells of a row along x are one run.
    template <class F> void for_each_run(std::size_t i, F&& f) const {
        const std::size_t c = cell_of[i];
        const int ix = static_cast<int>(c % nx);
        const int iy = static_cast<int>((c / nx) % ny);
        const int iz = static_cast<int>(c / (static_cast<std::size_t>(nx) * ny));
        const int x0 = std::max(ix - 1, 0), x1 = std::min(ix + 1, nx - 1);
        for (int z = std::max(iz - 1, 0); z <= std::min(iz + 1, nz - 1); ++z)
            for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, ny - 1); ++y)
                f(cell_start[cell(x0, y, z)], cell_start[cell(x1, y, z) + 1]);
    }
};

} // namespace

std::vector<std::uint32_t> spatial_order(std::span<const Vec3> centers, double edge) {
    CellGrid grid;
    grid.build(centers, edge);
    return std::move(grid.sorted);
}

void NeighborList::build(std::span<const Vec3> centers, std::span<const double> radii, double skin,
                         std::span<const std::uint32_t> key, bool with_pair_numbers) {
    assert(centers.size() == radii.size());
    assert(key.empty() || key.size() == centers.size());
    const std::size_t n = centers.size();
    const double max_radius = n ? *std::max_element(radii.begin(), radii.end()) : 0.0;
    CellGrid grid;
    grid.build(centers, 2.0 * max_radius + skin);

    auto within = [&](std::size_t i, std::uint32_t j) {
        const double cut = radii[i] + radii[j] + skin;
        return j != i && norm2(centers[j] - centers[i]) < cut * cut;
    };
    // One search per sphere: each thread fills the rows of one contiguous range of spheres
    // into its own buffer, then copies them to their place; the rows and their order are the
    // same whatever the number of threads.
    m_offsets.assign(n + 1, 0);
    const bool parallel = n >= detail::parallel_min_spheres;
    std::vector<std::vector<std::uint32_t>> buffers(parallel ? omp_get_max_threads() : 1);
    // An exception (bad_alloc) must not leave the parallel region, which would end the
    // process, nor skip a barrier: it is kept and thrown after the region.
    std::exception_ptr error;
#pragma omp parallel if (parallel)
    {
        const auto threads = static_cast<std::size_t>(omp_get_num_threads());
        const auto t = static_cast<std::size_t>(omp_get_thread_num());
        const std::size_t begin = n * t / threads, end = n * (t + 1) / threads;
        std::vector<std::uint32_t>& rows = buffers[t];
        try {
            rows.reserve(8 * (end - begin));
            for (std::size_t i = begin; i < end; ++i) {
                const std::size_t first = rows.size();
                std::size_t candidates = 0;
                grid.for_each_run(i,
                                  [&](std::uint32_t b, std::uint32_t e) { candidates += e - b; });
                rows.resize(first + candidates);
                std::size_t count = first; // every candidate written, the kept ones counted
                grid.for_each_run(i, [&](std::uint32_t b, std::uint32_t e) {
                    for (std::uint32_t k = b; k < e; ++k) {
                        const std::uint32_t j = grid.sorted[k];
                        rows[count] = j;
                        count += within(i, j) ? 1 : 0;
                    }
                });
                rows.resize(count);
                const auto row = rows.begin() + static_cast<std::ptrdiff_t>(first);
                if (key.empty())
                    std::sort(row, rows.end());
                else
                    std::sort(row, rows.end(),
                              [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
                m_offsets[i + 1] = static_cast<std::uint32_t>(rows.size() - first);
            }
        } catch (...) {
#pragma omp critical(packbed_neighbor_list_error)
            if (!error)
                error = std::current_exception();
        }
#pragma omp barrier
#pragma omp single
        {
            if (!error) {
                for (std::size_t i = 0; i < n; ++i)
                    m_offsets[i + 1] += m_offsets[i];
                try {
                    m_neighbors.resize(m_offsets[n]);
                } catch (...) {
                    error = std::current_exception();
                }
            }
        }
        if (!error)
            std::copy(rows.begin(), rows.end(), m_neighbors.begin() + m_offsets[begin]);
    }
    if (error)
        std::rethrow_exception(error);
    buffers = {}; // freed before the numbering: the peak stays that of rows and pair arrays
    if (with_pair_numbers) {
        number_pairs();
    } else {
        m_upper_offsets.assign(n + 1, 0);
        for (auto* v : {&m_upper, &m_owner, &m_pair_of}) {
            v->clear();
            v->shrink_to_fit();
        }
    }
    m_reference.assign(centers.begin(), centers.end());
    m_skin = skin;
    ++m_builds;
}

void NeighborList::number_pairs() {
    const std::size_t n = m_offsets.size() - 1;
    m_upper_offsets.assign(n + 1, 0);
    const std::uint32_t* const offsets = m_offsets.data();
    const std::uint32_t* const neighbors = m_neighbors.data();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t count = 0;
        for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e)
            count += neighbors[e] > i ? 1 : 0;
        m_upper_offsets[i + 1] = m_upper_offsets[i] + count;
    }
    m_upper.resize(m_upper_offsets[n]);
    m_owner.resize(m_upper_offsets[n]);
    m_pair_of.resize(m_neighbors.size());
    // Local pointers: the loops write through them, and the compiler could not otherwise keep
    // the members' data pointers in registers.
    const std::uint32_t* const upper_offsets = m_upper_offsets.data();
    std::uint32_t* const upper = m_upper.data();
    std::uint32_t* const owner = m_owner.data();
    std::uint32_t* const pair_of = m_pair_of.data();
    // Pair (i, j > i) is numbered in row i; row j finds it among the upper neighbours of i.
    // Each loop writes only its own row: the same numbers for any number of threads.
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t p = upper_offsets[i];
        for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e)
            if (neighbors[e] > i) {
                upper[p] = neighbors[e];
                owner[p] = static_cast<std::uint32_t>(i);
                pair_of[e] = p++;
            }
    }
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i)
        for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
            const std::uint32_t j = neighbors[e];
            if (j > i)
                continue;
            std::uint32_t p = upper_offsets[j];
            while (upper[p] != i)
                ++p;
            pair_of[e] = p;
        }
}

bool NeighborList::needs_rebuild(std::span<const Vec3> centers) const {
    if (m_builds == 0 || centers.size() != m_reference.size())
        return true;
    const double limit2 = drift_limit2();
    for (std::size_t i = 0; i < centers.size(); ++i)
        if (norm2(centers[i] - m_reference[i]) > limit2)
            return true;
    return false;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>>
brute_force_pairs(std::span<const Vec3> centers, std::span<const double> radii, double margin) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::uint32_t i = 0; i < centers.size(); ++i)
        for (std::uint32_t j = i + 1; j < centers.size(); ++j) {
            const double cut = radii[i] + radii[j] + margin;
            if (norm2(centers[j] - centers[i]) < cut * cut)
                pairs.emplace_back(i, j);
        }
    return pairs;
}

} // namespace packbed
