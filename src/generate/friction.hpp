// Internal: friction of the soft-sphere contacts (the fire solver with --friction or
// --wall-friction; docs/generate.md, "Friction").
//
// The tangential law is Cundall & Strack's, "A discrete numerical model for granular
// assemblies", Geotechnique 29 (1979) 47-65, in the form of LAMMPS's gran/hooke/history: each
// contact keeps a spring xi, the tangential displacement of the contact points since the
// contact began, projected into the contact's current tangent plane; the tangential force is k_t
// xi, capped by Coulomb's law |F_t| <= mu F_n (on the cap the spring is shortened to mu F_n / k_t:
// the contact slides). F_n = k_n delta with the solvers' unit stiffness k_n = 1.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "generate/soft_bed.hpp"
#include "packbed/vec3.hpp"

namespace packbed::detail {

/// k_t / k_n = 2/7: the tangential and the normal oscillation of a contact between two solid
/// spheres have the same frequency (a tangential spring moves the contact point through both the
/// translation, 1/m, and the rotation, r^2 / I = 5/(2m): k_t (1 + 5/2) = k_n), so the fire
/// solver's largest step stays stable; LAMMPS's gran/hooke/history takes the same default.
inline constexpr double tangential_stiffness = 2.0 / 7.0;

/// One step of a tangential spring. `spring` is the tangential displacement of the other body's
/// contact point relative to this one's, `normal` the unit normal of the contact now, `slip` the
/// relative displacement of the contact points in this step (its normal part is dropped) and
/// `cap` = mu F_n, the largest tangential force. The spring is first projected into the tangent
/// plane of `normal` (as LAMMPS's gran/hooke/history turns its shear history; the normal turns
/// by at most about 0.02 rad in a step, each sphere moving at most 0.01 Dp). \return the tangential
/// force on this body (k_t xi: it is dragged along the other's displacement); the other body gets
/// its opposite. `stiffness` is k_t (the pellets' contacts give each its own).
inline Vec3 tangential_spring(Vec3& spring, const Vec3& normal, const Vec3& slip, double cap,
                              double stiffness = tangential_stiffness) {
    Vec3 xi = spring + slip;
    xi -= normal * dot(xi, normal);
    const double force2 = stiffness * stiffness * norm2(xi);
    if (force2 > cap * cap) [[unlikely]] // Coulomb: the contact slides, the spring holds mu F_n
        xi *= cap / std::sqrt(force2);
    spring = xi;
    return xi * stiffness;
}

/// The springs of a sphere's contacts with the container's walls: one per wall it touches,
/// told apart by the wall's inward normal (a box's corner, an annulus' two walls).
struct WallSprings {
    static constexpr std::size_t capacity = 4;
    std::array<Vec3, capacity> normal{}; ///< a zero normal marks a free place
    std::array<Vec3, capacity> spring{};

    /// \return the spring of the wall whose stored normal lies within 25 degrees of `n`, zero
    /// when none does (a new contact).
    Vec3 along(const Vec3& n) const {
        for (std::size_t w = 0; w < capacity && norm2(normal[w]) > 0.0; ++w)
            if (dot(normal[w], n) > 0.9)
                return spring[w];
        return Vec3{};
    }
    /// Keep `s` as the spring of the wall of normal `n` (dropped when all places are taken).
    void add(const Vec3& n, const Vec3& s) {
        for (std::size_t w = 0; w < capacity; ++w)
            if (norm2(normal[w]) == 0.0) {
                normal[w] = n;
                spring[w] = s;
                return;
            }
    }
};

/// The spring of each listed pair carried from one Verlet list to the next: pairs are numbered
/// anew at each build, and a pair's two spheres may swap places. Keys are generation indices.
class PairSpringCarry {
public:
    /// Keep the springs that hold something, each as seen from the sphere of lower generation
    /// index; `order` maps stored indices to generation indices.
    void save(std::span<const std::uint32_t> first, std::span<const std::uint32_t> second,
              std::span<const Vec3> springs, std::span<const std::uint32_t> order) {
        m_kept.clear();
        for (std::size_t p = 0; p < springs.size(); ++p) {
            if (norm2(springs[p]) == 0.0)
                continue;
            const std::uint32_t a = order[first[p]], b = order[second[p]];
            m_kept.push_back({key(a, b), a < b ? springs[p] : -springs[p]});
        }
        std::sort(m_kept.begin(), m_kept.end(),
                  [](const Kept& x, const Kept& y) { return x.key < y.key; });
    }
    /// \return the saved spring of the pair (first, second), as seen from `first`; zero when
    /// none was saved.
    Vec3 find(std::uint32_t first_order, std::uint32_t second_order) const {
        const std::uint64_t k = key(first_order, second_order);
        const auto it = std::lower_bound(m_kept.begin(), m_kept.end(), k,
                                         [](const Kept& x, std::uint64_t v) { return x.key < v; });
        if (it == m_kept.end() || it->key != k)
            return Vec3{};
        return first_order < second_order ? it->spring : -it->spring;
    }

private:
    static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
    }
    struct Kept {
        std::uint64_t key;
        Vec3 spring;
    };
    std::vector<Kept> m_kept;
};

/// The friction of a bed's contacts: the springs of its pairs (carried over each rebuild of the
/// Verlet list), walls and floor, and the spheres' rotations. A sphere's rotation is kept as
/// the speed of its surface, u = r omega, and its inertia is a solid sphere's, I = 2/5 m r^2 with
/// the mass m = 1 / SoftBed::mobility that the solvers' steps give it: a torque tau turns u at
/// du/dt = r tau / I = (5/2) mobility (tau / r). Per-sphere arrays are in stored order.
class FrictionalContacts {
public:
    /// \param mu friction coefficient between spheres \param wall_mu between a sphere and the
    /// container's walls and floor (both >= 0)
    FrictionalContacts(double mu, double wall_mu)
        : m_mu(mu)
        , m_wall_mu(wall_mu) {}

    std::vector<Vec3> spin;   ///< u = r omega of each sphere
    std::vector<Vec3> moved;  ///< each sphere's displacement in the last step
    std::vector<Vec3> turned; ///< its rotation in the last step, as r dtheta (u dt)

    /// Start with `n` spheres at rest, no spring held.
    void reset(std::size_t n);
    /// SoftBed::rebuild_list, with the per-sphere arrays moved to the new storage order and
    /// every pair's spring carried to its new number.
    void rebuild_list(SoftBed& bed, double skin);

    /// SoftBed::pair_factors for pairs [begin, end), and each touching pair's tangential spring
    /// moved on by the last step's slip of its contact points (tangential_spring, cap mu F_n).
    /// \return the largest overlap.
    double pair_terms(SoftBed& bed, std::size_t begin, std::size_t end,
                      const LinearOverlapLaw& law);

    /// What moves sphere k after pair_terms: `accel` its acceleration (SoftBed's contact move,
    /// the tangential forces of its pairs and walls, `gravity` (a force: g times the sphere's
    /// weight), the floor, all times its mobility) and `spin_accel` the rate of its u. On the
    /// floor (z <= r) the floor takes any downward force (its reaction N) and holds a spring
    /// capped by wall_mu N. `wall` tracks the largest wall overlap.
    void sphere_terms(const SoftBed& bed, std::size_t k, const LinearOverlapLaw& law,
                      const Vec3& gravity, Vec3& accel, Vec3& spin_accel, double& wall);

    /// Every spring times `factor`: with gravity cut by the same factor, the forces of a bed
    /// whose contacts hold (linear springs) all shrink by it, and the bed, its overlaps and its
    /// springs with them: the stiffer spheres of the final stage (detail::Fire) keep their
    /// contact network, and no stress locked in by friction holds an overlap.
    void scale_springs(double factor);

    /// No friction from now on (mu = 0 at spheres and walls), no spring held.
    void release() {
        m_mu = m_wall_mu = 0.0;
        scale_springs(0.0);
    }

    /// \return the tangential force of listed pair p on its first sphere (for tests).
    Vec3 pair_force(std::size_t p) const { return m_pair_force[p]; }

private:
    template <bool Wrap>
    double pair_terms(SoftBed& bed, std::size_t begin, std::size_t end,
                      const LinearOverlapLaw& law);
    template <bool Wrap>
    void sphere_terms(const SoftBed& bed, std::size_t k, const LinearOverlapLaw& law,
                      const Vec3& gravity, Vec3& accel, Vec3& spin_accel, double& wall);

    double m_mu, m_wall_mu;
    std::vector<Vec3> m_pair_spring; // per listed pair, seen from its first sphere
    std::vector<Vec3> m_pair_force;  // tangential force on the first sphere
    std::vector<Vec3> m_pair_moment; // n x that force: each sphere's torque over its radius
    std::vector<Vec3> m_floor_spring;
    std::vector<WallSprings> m_wall;
    PairSpringCarry m_carry;
};

} // namespace packbed::detail
