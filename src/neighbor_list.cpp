#include "packbed/neighbor_list.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

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

    /// Call f(j) for every sphere j in the 27 cells around the cell of sphere i.
    template <class F> void for_each_nearby(std::size_t i, F&& f) const {
        const std::size_t c = cell_of[i];
        const int ix = static_cast<int>(c % nx);
        const int iy = static_cast<int>((c / nx) % ny);
        const int iz = static_cast<int>(c / (static_cast<std::size_t>(nx) * ny));
        for (int z = std::max(iz - 1, 0); z <= std::min(iz + 1, nz - 1); ++z)
            for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, ny - 1); ++y)
                for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, nx - 1); ++x) {
                    const std::size_t n = cell(x, y, z);
                    for (std::uint32_t k = cell_start[n]; k < cell_start[n + 1]; ++k)
                        f(sorted[k]);
                }
    }
};

} // namespace

std::vector<std::uint32_t> spatial_order(std::span<const Vec3> centers, double edge) {
    CellGrid grid;
    grid.build(centers, edge);
    return std::move(grid.sorted);
}

void NeighborList::build(std::span<const Vec3> centers, std::span<const double> radii, double skin,
                         std::span<const std::uint32_t> key) {
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
    // Two passes (count, then fill) so that each row is written by one thread only and the
    // list is the same whatever the number of threads.
    std::vector<std::uint32_t> counts(n);
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t count = 0;
        grid.for_each_nearby(i, [&](std::uint32_t j) { count += within(i, j) ? 1 : 0; });
        counts[i] = count;
    }
    m_offsets.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        m_offsets[i + 1] = m_offsets[i] + counts[i];
    m_neighbors.resize(m_offsets[n]);
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t* out = m_neighbors.data() + m_offsets[i];
        std::uint32_t* const row = out;
        grid.for_each_nearby(i, [&](std::uint32_t j) {
            if (within(i, j))
                *out++ = j;
        });
        if (key.empty())
            std::sort(row, out);
        else
            std::sort(row, out, [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    }
    number_pairs();
    m_reference.assign(centers.begin(), centers.end());
    m_skin = skin;
    ++m_builds;
}

void NeighborList::number_pairs() {
    const std::size_t n = m_offsets.size() - 1;
    m_upper_offsets.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t count = 0;
        for (const std::uint32_t j : neighbors_of(i))
            count += j > i ? 1 : 0;
        m_upper_offsets[i + 1] = m_upper_offsets[i] + count;
    }
    m_upper.resize(m_upper_offsets[n]);
    m_owner.resize(m_upper_offsets[n]);
    m_pair_of.resize(m_neighbors.size());
    // Pair (i, j > i) is numbered in row i; row j finds it among the upper neighbours of i.
    // Each loop writes only its own row: the same numbers for any number of threads.
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t p = m_upper_offsets[i];
        for (std::uint32_t e = m_offsets[i]; e < m_offsets[i + 1]; ++e)
            if (m_neighbors[e] > i) {
                m_upper[p] = m_neighbors[e];
                m_owner[p] = static_cast<std::uint32_t>(i);
                m_pair_of[e] = p++;
            }
    }
#pragma omp parallel for schedule(static) if (n >= detail::parallel_min_spheres)
    for (std::size_t i = 0; i < n; ++i)
        for (std::uint32_t e = m_offsets[i]; e < m_offsets[i + 1]; ++e) {
            const std::uint32_t j = m_neighbors[e];
            if (j > i)
                continue;
            std::uint32_t p = m_upper_offsets[j];
            while (m_upper[p] != i)
                ++p;
            m_pair_of[e] = p;
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
