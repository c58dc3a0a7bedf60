// The uniform cell grid behind every neighbour search: NeighborList's Verlet lists, the spatial
// order of the solvers, and the analysis' pair searches (contacts, g(r)), which visit pairs
// without storing them. Internal to the library (src/).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/vec3.hpp"

namespace packbed::detail {

/// A uniform grid of cubic cells over the bounding box of the centres, with the spheres
/// sorted by cell (counting sort). With a cell edge >= the longest distance searched, the
/// spheres near a sphere lie in its own and the 26 adjacent cells. Memory O(N) whatever the
/// edge: the cells are at most 8 N + 64. Read-only once built: may be searched from several
/// threads.
struct CellGrid {
    Vec3 origin;
    double edge = 1.0;
    double inv_edge = 1.0;
    int nx = 1, ny = 1, nz = 1;
    std::vector<std::uint32_t> cell_start; // size ncells + 1
    std::vector<std::uint32_t> sorted;     // sphere indices ordered by cell
    std::vector<std::uint32_t> cell_of;    // cell of each sphere
    std::uint32_t largest_cell = 0;        // the most spheres in one cell

    CellGrid() = default;
    CellGrid(std::span<const Vec3> centers, double cell_edge) { build(centers, cell_edge); }

    /// Sort `centers` into cells of edge `cell_edge`, grown (x 1.5) until there are at most
    /// 8 N + 64 cells, so that spheres spread far apart cannot make the grid huge.
    void build(std::span<const Vec3> centers, double cell_edge) {
        Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                std::numeric_limits<double>::max()};
        Vec3 hi{-lo.x, -lo.y, -lo.z};
        for (const auto& c : centers) {
            lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
            hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
        }
        const double max_cells = 8.0 * static_cast<double>(centers.size()) + 64.0;
        auto count = [&](double e) {
            return std::floor((hi.x - lo.x) / e + 1) * std::floor((hi.y - lo.y) / e + 1) *
                   std::floor((hi.z - lo.z) / e + 1);
        };
        while (!(count(cell_edge) <= max_cells)) // also ends on an extent that overflows
            cell_edge *= 1.5;
        origin = lo;
        edge = cell_edge;
        inv_edge = 1.0 / cell_edge;
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
        largest_cell = 0;
        for (std::size_t c = 0; c < ncells; ++c) {
            largest_cell = std::max(largest_cell, cell_start[c + 1]);
            cell_start[c + 1] += cell_start[c];
        }
        sorted.resize(centers.size());
        std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
        for (std::size_t i = 0; i < centers.size(); ++i)
            sorted[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
    }

    int clamp_index(double v, int n) const {
        const double k = std::floor(v * inv_edge); // clamped in double: no UB on overflow
        if (!(k > 0.0))
            return 0;
        return k >= n - 1 ? n - 1 : static_cast<int>(k);
    }

    std::size_t cell(int ix, int iy, int iz) const {
        return (static_cast<std::size_t>(iz) * ny + iy) * nx + ix;
    }

    /// \return how many cells out a search must look to find every sphere within `reach` of
    /// a centre (at least 1, at most the grid).
    int cells_within(double reach) const {
        const double k = std::ceil(reach * inv_edge);
        return static_cast<int>(std::clamp(k, 1.0, static_cast<double>(std::max({nx, ny, nz}))));
    }

    /// Call f(begin, end) for the runs of `sorted` that hold the spheres of the cells up to
    /// `k` cells out from the cell of sphere i (27 cells for k = 1): the cells of a row along x
    /// are one run.
    template <class F> void for_each_run(std::size_t i, F&& f, int k = 1) const {
        const std::size_t c = cell_of[i];
        const int ix = static_cast<int>(c % nx);
        const int iy = static_cast<int>((c / nx) % ny);
        const int iz = static_cast<int>(c / (static_cast<std::size_t>(nx) * ny));
        const int x0 = std::max(ix - k, 0), x1 = std::min(ix + k, nx - 1);
        for (int z = std::max(iz - k, 0); z <= std::min(iz + k, nz - 1); ++z)
            for (int y = std::max(iy - k, 0); y <= std::min(iy + k, ny - 1); ++y)
                f(cell_start[cell(x0, y, z)], cell_start[cell(x1, y, z) + 1]);
    }

    /// Call f(j) for every sphere j (sphere i included) up to `k` cells out from sphere i.
    template <class F> void for_each_near(std::size_t i, int k, F&& f) const {
        for_each_run(
            i,
            [&](std::uint32_t begin, std::uint32_t end) {
                for (std::uint32_t s = begin; s < end; ++s)
                    f(sorted[s]);
            },
            k);
    }

    /// \return the work of for_each_near(i, k): the spheres it visits plus the runs of cells.
    std::uint64_t work(std::size_t i, int k) const {
        std::uint64_t w = 0;
        for_each_run(
            i, [&](std::uint32_t begin, std::uint32_t end) { w += 1 + (end - begin); }, k);
        return w;
    }
};

/// The points a search in a periodic cell runs on: the centres moved into the cell
/// (`points[i]` = cell.wrapped(centers[i]) for i < n), followed by their copies shifted by one
/// period in x, y or both (and z when it repeats) that lie within `cut` of the cell,
/// [-cut, L + cut) each way, each standing for its sphere (`owner[k]` is the sphere of point n +
/// k). A search from a sphere's own point then finds every copy of every sphere within `cut` of it,
/// for cut up to the smaller period (NeighborList::wrap, the analysis' contacts and g(r) in a
/// periodic cell).
inline void periodic_images(const Periods& cell, std::span<const Vec3> centers, double cut,
                            std::vector<Vec3>& points, std::vector<std::uint32_t>& owner) {
    const std::size_t n = centers.size();
    points.resize(n);
    owner.clear();
    for (std::size_t i = 0; i < n; ++i)
        points[i] = cell.wrapped(centers[i]);
    const int z_copies = cell.lz() > 0.0 ? 1 : 0; // copies across z when z repeats
    const double lz = cell.lz();
    for (std::size_t i = 0; i < n; ++i)
        for (int sx = -1; sx <= 1; ++sx)
            for (int sy = -1; sy <= 1; ++sy)
                for (int sz = -z_copies; sz <= z_copies; ++sz) {
                    if (sx == 0 && sy == 0 && sz == 0)
                        continue;
                    const Vec3 p{points[i].x + sx * cell.lx(), points[i].y + sy * cell.ly(),
                                 points[i].z + sz * lz};
                    if (p.x >= -cut && p.x < cell.lx() + cut && p.y >= -cut &&
                        p.y < cell.ly() + cut &&
                        (z_copies == 0 || (p.z >= -cut && p.z < lz + cut))) {
                        points.push_back(p);
                        owner.push_back(static_cast<std::uint32_t>(i));
                    }
                }
}

} // namespace packbed::detail
