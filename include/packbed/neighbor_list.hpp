// Neighbour search: a cell grid that builds a Verlet list, rebuilt only when something moved
// far enough. Like nanoflann's adaptors it owns no positions: it reads the caller's arrays.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// Full (both directions) Verlet neighbour list in compressed-row form: the neighbours of
/// sphere i are `neighbors[offsets[i] .. offsets[i+1])`, in increasing index order (or in
/// increasing order of a caller's key, see build()).
/// A pair (i, j) is listed when |x_i - x_j| < r_i + r_j + skin at build time.
/// Building costs O(N) through a uniform cell grid; the list then stays valid while no sphere
/// has moved more than skin/2 since the build (`needs_rebuild`).
/// Not synchronised: build from one thread, then read from any number of threads.
class NeighborList {
public:
    /// Build the list for the given spheres.
    /// \param centers sphere centres (read, not kept)
    /// \param radii sphere radii (> 0, same length)
    /// \param skin extra distance kept in the list (length, > 0)
    /// \param key when not empty, rows are ordered by increasing key[j] instead of j (one
    /// value per sphere, all different): a caller that stores its spheres in another order
    /// than its own numbering keeps the order in which neighbours are summed.
    /// \param with_pair_numbers false: rows only, no pair numbers (upper_neighbors_of,
    /// pair_numbers_of, pairs() and the pair arrays are empty), which saves their memory
    /// (twice that of the rows) for callers that only walk the rows.
    void build(std::span<const Vec3> centers, std::span<const double> radii, double skin,
               std::span<const std::uint32_t> key = {}, bool with_pair_numbers = true);

    /// Make the next builds periodic in x and y with the cell's periods: a pair is listed
    /// when the distance between their nearest copies (the minimum image,
    /// Periodic::separation) is below the cut, whatever side of the cell either centre lies on
    /// (the search sees the centres moved into the cell; a pair is listed once even where two
    /// of its copies are within the cut). For forces by the minimum image, the cell must be at
    /// least twice the largest r_i + r_j wide, so that a touching pair has one nearest copy.
    void wrap(const Periods& cell) { m_cell = cell; }

    /// \return true when some sphere has moved more than skin/2 since the last build (or
    /// there was no build yet, or the number of spheres changed).
    bool needs_rebuild(std::span<const Vec3> centers) const;

    /// \return the neighbours of sphere i.
    std::span<const std::uint32_t> neighbors_of(std::size_t i) const {
        return {m_neighbors.data() + m_offsets[i], m_neighbors.data() + m_offsets[i + 1]};
    }

    /// \return the neighbours j > i of sphere i, in the order of its row: each listed pair once.
    /// Pair number first_pair_of(i) + m is the m-th of them.
    std::span<const std::uint32_t> upper_neighbors_of(std::size_t i) const {
        return {m_upper.data() + m_upper_offsets[i], m_upper.data() + m_upper_offsets[i + 1]};
    }
    /// \return the number of the first pair of upper_neighbors_of(i).
    std::size_t first_pair_of(std::size_t i) const { return m_upper_offsets[i]; }
    /// \return for each entry of neighbors_of(i), the number of its pair: a quantity computed
    /// once per pair is read from both of its rows.
    std::span<const std::uint32_t> pair_numbers_of(std::size_t i) const {
        if (m_pair_of.empty()) // built without pair numbers
            return {};
        return {m_pair_of.data() + m_offsets[i], m_pair_of.data() + m_offsets[i + 1]};
    }
    /// \return the number of listed pairs (each counted once).
    std::size_t pairs() const { return m_upper.size(); }
    /// \return pair p is (pair_first()[p], pair_second()[p]), first < second; pairs are
    /// numbered row after row (see upper_neighbors_of).
    std::span<const std::uint32_t> pair_first() const { return m_owner; }
    std::span<const std::uint32_t> pair_second() const { return m_upper; }

    /// \return the number of builds since construction (for statistics).
    std::size_t builds() const { return m_builds; }

    /// \return the positions at the last build: a caller that tracks how far its spheres
    /// moved while it moves them can skip needs_rebuild().
    std::span<const Vec3> reference() const { return m_reference; }
    /// \return (skin/2)^2: a list stays valid while no sphere has moved farther than this
    /// (squared) since the build.
    double drift_limit2() const { return 0.25 * m_skin * m_skin; }

private:
    void number_pairs();
    /// The centres moved into the cell, then their copies within `cut` of its sides (owner:
    /// the sphere of each copy).
    void add_ghosts(std::span<const Vec3> centers, double cut, std::vector<Vec3>& points,
                    std::vector<std::uint32_t>& owner) const;

    std::vector<std::uint32_t> m_offsets;
    std::vector<std::uint32_t> m_neighbors;
    std::vector<std::uint32_t> m_upper_offsets; // rows of upper neighbours (j > i)
    std::vector<std::uint32_t> m_upper;
    std::vector<std::uint32_t> m_owner;   // first sphere of each pair
    std::vector<std::uint32_t> m_pair_of; // pair number of each entry of m_neighbors
    std::vector<Vec3> m_reference;        // positions at the last build
    std::optional<Periods> m_cell;        // periodic in x and y (wrap())
    double m_skin = 0.0;
    std::size_t m_builds = 0;
};

/// \return the sphere indices ordered by the cells of a uniform grid of edge `edge` (z, then
/// y, then x; by index within a cell): neighbours in space become neighbours in memory.
/// O(N); the same order for the same input.
std::vector<std::uint32_t> spatial_order(std::span<const Vec3> centers, double edge);

/// All pairs (i < j) with |x_i - x_j| < r_i + r_j + margin, by brute force, O(N^2).
/// The reference the fast search is tested against; not for production use.
std::vector<std::pair<std::uint32_t, std::uint32_t>>
brute_force_pairs(std::span<const Vec3> centers, std::span<const double> radii, double margin);

} // namespace packbed
