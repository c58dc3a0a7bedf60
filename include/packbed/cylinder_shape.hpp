// The cylinder pellet: a right circular cylinder, the first model of the ParticleShape concept
// with an orientation (docs/design.md, "Particles"). Its answers: closed forms where they exist
// (volume, support function), GJK/EPA on the support functions for the overlap of two pellets
// (Debian's libccd), the container's own search for how far a convex body reaches into its
// walls, and its volumes in a region by integration over its cross-sections.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <utility>

#include "packbed/container.hpp"
#include "packbed/mesh.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A cylinder of radius `radius` and half-length `half_length` (in units of the particle's
/// size) about its body z axis, centred on its position. A pellet's size is its
/// volume-equivalent radius d_v / 2 (particle_shape.hpp's Placement): of_aspect builds the
/// cylinder of a given L / D whose volume is that of the unit ball.
struct CylinderShape {
    static constexpr std::string_view kind = "cylinder";
    static constexpr bool oriented = true;

    double radius = 1.0;      ///< D / 2 in units of the size
    double half_length = 1.0; ///< L / 2 in units of the size

    /// The cylinder of L / D = `aspect` (> 0) whose volume at size 1 is 4 pi / 3: pi R^2 L =
    /// 4 pi / 3 with L = 2 R aspect, so R = (2 / (3 aspect))^(1/3) (D / d_v = 0.8736 at L = D).
    static CylinderShape of_aspect(double aspect);

    /// sqrt(R^2 + (L/2)^2) times the size: the sphere about the centre through the rims.
    double bounding_radius(double size) const;
    /// pi R^2 L times size^3.
    double volume(double size) const;
    /// The body frame's farthest point along v turned into it: the rim point R w_xy / |w_xy| at
    /// the end sign(w_z) L / 2, w = v in the body frame (the axis, or the end's centre, where
    /// w_xy or w_z is 0).
    Vec3 support(const Placement& p, const Vec3& v) const;
    /// Container::convex_wall_overlap on the support function.
    double wall_overlap(const Container& c, const Placement& p) const;
    /// Container::convex_wall_contacts on the support function: f(contact) for each side wall
    /// it presses (the floor is the solver's: support(-z)).
    void wall_contacts(const Container& c, const Placement& p, const ConvexWallFunction& f) const;
    /// The penetration depth, exactly: libccd's MPR (ccdMPRPenetration) says whether they
    /// overlap and gives a first direction, then the least over the unit directions of the
    /// closed-form support of their Minkowski difference (cylinder_shape.cpp's
    /// cylinder_depth: the ends' normals, the sides' great circles, their crossings and the
    /// smooth minima between), b placed at a.position + ab; the normal
    /// from a towards b and the point halfway between the two deepest points. Depth 0 when
    /// they are apart, the normal along ab.
    PairOverlap pair_overlap(const Placement& a, const CylinderShape& other, const Placement& b,
                             const Vec3& ab) const;
    /// Bounds: the wall distances of the bounding sphere (the shells between them are measured
    /// exactly by volume_from_wall).
    std::pair<double, double> wall_extent(const Container& c, std::size_t wall,
                                          const Placement& p) const;
    /// The volume inside the container between two heights, by integration over its sections
    /// (cylinder_shape.cpp: closed-form disc-strip areas along the axis where the side cannot
    /// cut it; in a tube, closed-form horizontal sections met with the wall's circle; nested
    /// adaptive Gauss-Kronrod over the cross-sections' polar angle and the axis otherwise).
    double volume_in(const Container& c, const Placement& p, double z_low, double z_high) const;
    /// The same in the container shrunk from wall `wall` by d (Container::shrunk_from).
    double volume_from_wall(const Container& c, std::size_t wall, double d, const Placement& p,
                            double z_low, double z_high) const;
    /// The volume in an axis-aligned box.
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const;
    /// The closed outward surface at size 1: 12 * 2^level segments around (chord error
    /// R (1 - cos(pi / n))), each end a fan about its centre, the side one band of quads split
    /// into triangles.
    TriangleMesh unit_surface(int level) const;
    /// A clump of equal spheres inside the cylinder, as LIGGGHTS' multisphere templates
    /// approximate one: radius s = min(R, L/2) / 2, centres on rings of radius 0 .. R - s
    /// (steps of at most s, ceil(2 pi r / s) about each) at axial positions -(L/2 - s) ..
    /// L/2 - s (steps of at most s). Each sphere touches no point outside the cylinder; the
    /// outermost touch its side and ends.
    template <class F> void dem_spheres(const Placement& p, F&& f) const {
        for_each_clump_sphere([&](const Vec3& body, double r) {
            f(DemSphere{p.position + rotate(p.orientation, body) * p.size, r * p.size});
        });
    }

private:
    template <class F> void for_each_clump_sphere(F&& f) const;
};

static_assert(ParticleShape<CylinderShape>);

template <class F> void CylinderShape::for_each_clump_sphere(F&& f) const {
    const double s = 0.5 * std::min(radius, half_length);
    const auto steps = [s](double span) {
        return span > 0.0 ? static_cast<int>(std::ceil(span / s - 1e-9)) : 0;
    };
    const int axial = steps(2.0 * (half_length - s));
    const int rings = steps(radius - s);
    for (int i = 0; i <= axial; ++i) {
        const double z =
            axial == 0 ? 0.0 : -(half_length - s) + 2.0 * (half_length - s) * i / axial;
        for (int j = 0; j <= rings; ++j) {
            const double r = rings == 0 ? 0.0 : (radius - s) * j / rings;
            const int around =
                r > 0.0 ? std::max(3, static_cast<int>(std::ceil(2.0 * std::numbers::pi * r / s)))
                        : 1;
            for (int k = 0; k < around; ++k) {
                const double phi = 2.0 * std::numbers::pi * k / around;
                f(Vec3{r * std::cos(phi), r * std::sin(phi), z}, s);
            }
        }
    }
}

} // namespace packbed
