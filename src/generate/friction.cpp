#include "generate/friction.hpp"

#include <array>
#include <limits>

namespace packbed::detail {

namespace {

template <class T> void permute(std::vector<T>& values, std::span<const std::uint32_t> perm) {
    std::vector<T> next(perm.size());
    for (std::size_t k = 0; k < perm.size(); ++k)
        next[k] = values[perm[k]];
    values.swap(next);
}

} // namespace

void FrictionalContacts::reset(std::size_t n) {
    spin.assign(n, Vec3{});
    moved.assign(n, Vec3{});
    turned.assign(n, Vec3{});
    m_floor_spring.assign(n, Vec3{});
    m_wall.assign(n, WallSprings{});
    m_pair_spring.clear();
    m_pair_force.clear();
    m_pair_moment.clear();
}

void FrictionalContacts::scale_springs(double factor) {
    for (Vec3& s : m_pair_spring)
        s *= factor;
    for (Vec3& s : m_floor_spring)
        s *= factor;
    for (WallSprings& w : m_wall)
        for (Vec3& s : w.spring)
            s *= factor;
}

void FrictionalContacts::rebuild_list(SoftBed& bed, double skin) {
    m_carry.save(bed.list.pair_first(), bed.list.pair_second(), m_pair_spring, bed.order);
    const std::vector<std::uint32_t> perm = bed.rebuild_list(skin);
    permute(spin, perm);
    permute(moved, perm);
    permute(turned, perm);
    permute(m_floor_spring, perm);
    permute(m_wall, perm);
    const std::size_t pairs = bed.list.pairs();
    const std::span<const std::uint32_t> first = bed.list.pair_first(),
                                         second = bed.list.pair_second();
    m_pair_spring.resize(pairs);
    m_pair_force.assign(pairs, Vec3{});
    m_pair_moment.assign(pairs, Vec3{});
    for (std::size_t p = 0; p < pairs; ++p)
        m_pair_spring[p] = m_carry.find(bed.order[first[p]], bed.order[second[p]]);
}

double FrictionalContacts::pair_terms(SoftBed& bed, std::size_t begin, std::size_t end,
                                      const LinearOverlapLaw& law) {
    return bed.cell ? pair_terms<true>(bed, begin, end, law)
                    : pair_terms<false>(bed, begin, end, law);
}

template <bool Wrap>
double FrictionalContacts::pair_terms(SoftBed& bed, std::size_t begin, std::size_t end,
                                      const LinearOverlapLaw& law) {
    const Vec3* const x = bed.packing.centers.data();
    const double* const radius = bed.packing.radii.data();
    const std::uint32_t* const first = bed.list.pair_first().data();
    const std::uint32_t* const second = bed.list.pair_second().data();
    const Vec3* const moved_by = moved.data();
    const Vec3* const turned_by = turned.data();
    double* const factor = bed.factor.data();
    Vec3* const spring = m_pair_spring.data();
    Vec3* const tangential = m_pair_force.data();
    Vec3* const moment = m_pair_moment.data();
    const double ck = law.ck, mu = m_mu;
    double largest = 0.0;
    // Two passes over each block of pairs, with no branch on whether a pair touches (it is not
    // predictable): the first gives every pair its factor (as SoftBed::pair_factors) and a pair
    // apart a spring and forces of 0, and lists the touching ones; the second moves on the
    // springs of those alone (about half the listed pairs).
    constexpr std::size_t block = 256;
    std::array<std::uint32_t, block> touching_pairs;
    std::array<Vec3, block> normals;
    std::array<double, block> caps;
    for (std::size_t from = begin; from < end; from += block) {
        const std::size_t to = std::min(end, from + block);
        std::size_t count = 0;
        for (std::size_t p = from; p < to; ++p) {
            const std::uint32_t i = first[p], j = second[p];
            const Vec3 rij = bed.separation<Wrap>(x[i], x[j]);
            const double sum = radius[i] + radius[j];
            const double dist2 = norm2(rij);
            const double dist = std::sqrt(dist2);
            const double overlap = sum - dist;
            const bool touching = dist2 < sum * sum;
            const double on = touching ? 1.0 : 0.0;
            // +inf for coincident centres, as pair_factors: sphere_terms pushes them apart
            // vertically, with no tangent plane (n = 0).
            const double inverse = 1.0 / dist;
            factor[p] = touching ? ck * overlap * inverse : 0.0;
            largest = std::max(largest, overlap * on);
            spring[p] *= on;
            tangential[p] = moment[p] = Vec3{};
            touching_pairs[count] = static_cast<std::uint32_t>(p);
            normals[count] = rij * (dist > 0.0 ? inverse : 0.0);
            caps[count] = mu * ck * overlap;
            count += touching ? 1 : 0;
        }
        for (std::size_t t = 0; t < count; ++t) {
            const std::uint32_t p = touching_pairs[t];
            const std::uint32_t i = first[p], j = second[p];
            const Vec3& n = normals[t];
            // The contact point of j relative to i's, moved by both translations and rotations.
            const Vec3 slip =
                moved_by[j] - cross(turned_by[j], n) - moved_by[i] - cross(turned_by[i], n);
            Vec3 xi = spring[p];
            const Vec3 force = tangential_spring(xi, n, slip, caps[t]);
            spring[p] = xi;
            tangential[p] = force;
            moment[p] = cross(n, force);
        }
    }
    return largest;
}

void FrictionalContacts::sphere_terms(const SoftBed& bed, std::size_t k,
                                      const LinearOverlapLaw& law, const Vec3& gravity, Vec3& accel,
                                      Vec3& spin_accel, double& wall) {
    if (bed.cell)
        sphere_terms<true>(bed, k, law, gravity, accel, spin_accel, wall);
    else
        sphere_terms<false>(bed, k, law, gravity, accel, spin_accel, wall);
}

template <bool Wrap>
void FrictionalContacts::sphere_terms(const SoftBed& bed, std::size_t k,
                                      const LinearOverlapLaw& law, const Vec3& gravity, Vec3& accel,
                                      Vec3& spin_accel, double& wall) {
    const Vec3* const x = bed.packing.centers.data();
    const double* const radius = bed.packing.radii.data();
    const Vec3 xk = x[k];
    const double r = radius[k];
    // SoftBed::contact_move_from_factors and the tangential forces in one walk over the row.
    // Torque over radius: d x F for a contact at r d from the centre. A pair's is n x F_t on
    // either sphere (the second sphere's d and F_t both change sign).
    Vec3 force = gravity;
    Vec3 moment{};
    const std::span<const std::uint32_t> row = bed.list.neighbors_of(k);
    const std::uint32_t* const pair_number = bed.list.pair_numbers_of(k).data();
    const double* const factor = bed.factor.data();
    const Vec3* const tangential = m_pair_force.data();
    const Vec3* const pair_moment = m_pair_moment.data();
    for (std::size_t e = 0; e < row.size(); ++e) {
        const std::uint32_t p = pair_number[e];
        const double f = factor[p];
        const std::uint32_t j = row[e];
        if (f == std::numeric_limits<double>::infinity()) [[unlikely]] {
            const double overlap = r + radius[j];
            force.z += bed.order[k] < bed.order[j] ? -law.ck * overlap : law.ck * overlap;
            continue;
        }
        // Every listed pair, touching or not (0 where apart): no branch to mispredict.
        force -= bed.separation<Wrap>(xk, x[j]) * f;
        force += tangential[p] * (k < j ? 1.0 : -1.0); // k is the pair's first sphere
        moment += pair_moment[p];
    }
    // The walls: the normal term of SoftBed::add_wall_term, and the spring of the sphere's
    // contact point against the wall, which stays put.
    const Vec3 own = moved[k], turn = turned[k];
    WallSprings walls;
    bed.container.wall_contacts(xk, r, [&](double overlap, const Vec3& push) {
        wall = std::max(wall, overlap);
        force += push * (law.ck * overlap);
        if (m_wall_mu > 0.0) {
            Vec3 spring = m_wall[k].along(push);
            const Vec3 slip = -(own - cross(turn, push)); // the wall's point relative to ours
            const Vec3 f = tangential_spring(spring, push, slip, m_wall_mu * law.ck * overlap);
            walls.add(push, spring);
            force += f;
            moment += cross(-push, f);
        }
    });
    if (m_wall_mu > 0.0) // else nothing was read or kept: no 192-byte store a sphere a step
        m_wall[k] = walls;
    // The rigid floor: it takes the downward force of a sphere resting on it.
    if (xk.z <= r) {
        const double reaction = std::max(0.0, -force.z);
        force.z += reaction;
        const Vec3 up{0.0, 0.0, 1.0};
        const Vec3 slip = -(own - cross(turn, up));
        const Vec3 f = tangential_spring(m_floor_spring[k], up, slip, m_wall_mu * reaction);
        force += f;
        moment += cross(-up, f);
    } else {
        m_floor_spring[k] = Vec3{};
    }
    const double mobility = bed.mobility(r);
    accel = force * mobility;
    spin_accel = moment * (2.5 * mobility);
}

} // namespace packbed::detail
