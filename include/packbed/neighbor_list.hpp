// Neighbour search: a cell grid that builds a Verlet list, rebuilt only when something moved
// far enough. Like nanoflann's adaptors it owns no positions: it reads the caller's arrays.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "packbed/vec3.hpp"

namespace packbed {

/// Full (both directions) Verlet neighbour list in compressed-row form: the neighbours of
/// sphere i are `neighbors[offsets[i] .. offsets[i+1])`, in increasing index order.
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
    void build(std::span<const Vec3> centers, std::span<const double> radii, double skin);

    /// \return true when some sphere has moved more than skin/2 since the last build (or
    /// there was no build yet, or the number of spheres changed).
    bool needs_rebuild(std::span<const Vec3> centers) const;

    /// \return the neighbours of sphere i.
    std::span<const std::uint32_t> neighbors_of(std::size_t i) const {
        return {m_neighbors.data() + m_offsets[i], m_neighbors.data() + m_offsets[i + 1]};
    }

    /// \return the number of builds since construction (for statistics).
    std::size_t builds() const { return m_builds; }

private:
    std::vector<std::uint32_t> m_offsets;
    std::vector<std::uint32_t> m_neighbors;
    std::vector<Vec3> m_reference; // positions at the last build
    double m_skin = 0.0;
    std::size_t m_builds = 0;
};

/// All pairs (i < j) with |x_i - x_j| < r_i + r_j + margin, by brute force, O(N^2).
/// The reference the fast search is tested against; not for production use.
std::vector<std::pair<std::uint32_t, std::uint32_t>>
brute_force_pairs(std::span<const Vec3> centers, std::span<const double> radii, double margin);

} // namespace packbed
