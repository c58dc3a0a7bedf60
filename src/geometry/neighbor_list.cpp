#include "packbed/neighbor_list.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

#include <omp.h>

#include "base/parallel.hpp"
#include "geometry/cell_grid.hpp"

namespace packbed {

using detail::CellGrid;

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
    // A periodic cell: the search runs on the centres moved into the cell, followed by the
    // copies ("ghosts") of those within the longest cut of a side, each numbered after the
    // n centres and standing for its sphere (owner).
    std::vector<Vec3> cell_centres;
    std::vector<std::uint32_t> owner;
    if (m_cell)
        add_ghosts(centers, 2.0 * max_radius + skin, cell_centres, owner);
    const std::span<const Vec3> points = m_cell ? std::span<const Vec3>(cell_centres) : centers;
    CellGrid grid;
    grid.build(points, 2.0 * max_radius + skin);

    auto within = [&](std::size_t i, std::uint32_t j) {
        const std::uint32_t s = j < n ? j : owner[j - n];
        const double cut = radii[i] + radii[s] + skin;
        return s != i && norm2(points[j] - points[i]) < cut * cut;
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
                if (m_cell) // ghosts stand for their spheres, each sphere once
                    for (auto e = row; e != rows.end(); ++e)
                        *e = *e < n ? *e : owner[*e - n];
                if (key.empty())
                    std::sort(row, rows.end());
                else
                    std::sort(row, rows.end(),
                              [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
                if (m_cell)
                    rows.erase(std::unique(row, rows.end()), rows.end());
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

void NeighborList::add_ghosts(std::span<const Vec3> centers, double cut, std::vector<Vec3>& points,
                              std::vector<std::uint32_t>& owner) const {
    // Every copy within `cut` of the cell: a pair's nearest copies are then found from the
    // first sphere's own place in the cell.
    detail::periodic_images(*m_cell, centers, cut, points, owner);
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
