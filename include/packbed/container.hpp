// Containers: the walls a bed is packed against. voro++'s vocabulary: contains(), the overlap
// of a sphere with the wall and the wall normal. Every container has a rigid flat floor at z = 0.
#pragma once

#include <cmath>
#include <concepts>

#include "packbed/vec3.hpp"

namespace packbed {

/// How deep a sphere presses into a deformable wall and which way the wall pushes back.
struct WallContact {
    double overlap = 0.0; ///< penetration depth (length); <= 0 means no contact
    Vec3 push; ///< unit vector along which the wall pushes the sphere (into the container)
};

/// What the soft-sphere loops need from a container. The loops are templated on it, so the
/// wall law inlines. Another container (annulus, box) is another type meeting this concept.
template <class C>
concept LateralWall = requires(const C& c, const Vec3& p, double radius) {
    { c.wall_contact(p, radius) } -> std::same_as<WallContact>;
    { c.contains(p) } -> std::same_as<bool>;
};

/// A vertical cylinder of radius `radius` whose axis is the z axis (x = y = 0); the floor is
/// z = 0 and it is open at the top. Immutable after construction: safe to share between threads.
class Cylinder {
public:
    /// \param radius container radius Rt (length, > 0)
    explicit Cylinder(double radius)
        : m_radius(radius) {}

    /// \return the container radius Rt.
    double radius() const { return m_radius; }

    /// \return true if the point lies inside the cylinder above the floor (z >= 0, r <= Rt).
    bool contains(const Vec3& p) const {
        return p.z >= 0.0 && p.x * p.x + p.y * p.y <= m_radius * m_radius;
    }

    /// Overlap of a sphere with the lateral wall, Salvat et al. (2005) nomenclature:
    /// \f$\delta_{iw} = (r_i + D_p/2) - R_t\f$, with the push along \f$-\hat r\f$ (towards the
    /// axis). \param p sphere centre \param radius sphere radius (length, > 0) \return the overlap
    /// (<= 0: no contact) and the push direction (zero vector on the axis).
    WallContact wall_contact(const Vec3& p, double radius) const {
        const double r = std::sqrt(p.x * p.x + p.y * p.y);
        const double overlap = r + radius - m_radius;
        if (overlap <= 0.0 || r == 0.0)
            return {overlap, {}};
        return {overlap, {-p.x / r, -p.y / r, 0.0}};
    }

private:
    double m_radius;
};

static_assert(LateralWall<Cylinder>);

} // namespace packbed
