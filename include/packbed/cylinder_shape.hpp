// The cylinder pellet: a right circular cylinder, the first model of the ParticleShape concept
// with an orientation (docs/design.md, "Particles"), and the ring (a hollow cylinder, the
// Raschig ring) as the cylinder with a coaxial bore. Its answers: closed forms where they exist
// (volume, support function), GJK/EPA on the support functions for the overlap of two pellets
// (Debian's libccd), the container's own search for how far a convex body reaches into its
// walls, and its volumes in a region by integration over its cross-sections. A ring is not
// convex and no finite union of convex pieces: its answers are the cylinder's (the ring's
// hull) where the bore cannot change them, and otherwise a search over its surface of the other
// body's signed distance (cylinder_shape.cpp's highest_on_surface).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <utility>
#include <vector>

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
    double bore = 0.0;        ///< DI / 2 in units of the size: a ring where > 0 (< radius)

    /// The cylinder of L / D = `aspect` (> 0) whose volume at size 1 is 4 pi / 3: pi R^2 L =
    /// 4 pi / 3 with L = 2 R aspect, so R = (2 / (3 aspect))^(1/3) (D / d_v = 0.8736 at L = D).
    static CylinderShape of_aspect(double aspect);
    /// The ring of outer diameter `d`, bore `di` (0 < di < d) and length `l` (any one length
    /// unit) whose volume at size 1 is 4 pi / 3: pi (D^2 - DI^2) L / 4 = pi d_v^3 / 6.
    static CylinderShape ring(double d, double di, double l);
    /// The area of the section across the axis at size 1: pi (R^2 - R_i^2).
    double section_area() const;

    /// sqrt(R^2 + (L/2)^2) times the size: the sphere about the centre through the rims.
    double bounding_radius(double size) const;
    /// pi (R^2 - R_i^2) L times size^3.
    double volume(double size) const;
    /// The body frame's farthest point along v turned into it: the rim point R w_xy / |w_xy| at
    /// the end sign(w_z) L / 2, w = v in the body frame (the axis, or the end's centre, where
    /// w_xy or w_z is 0).
    Vec3 support(const Placement& p, const Vec3& v) const;
    /// Container::convex_wall_overlap on the support function; with `grow` > 0, of the
    /// cylinder grown by that much all round (its support moved out along each direction).
    /// A ring whose hull reaches a wall: the most its surface sticks out of the container
    /// (Container::sticks_out of each point, grown), found by highest_on_surface: the same as
    /// the hull's at a wall seen from inside, less where a rod enters the bore.
    double wall_overlap(const Container& c, const Placement& p, double grow = 0.0) const;
    /// Container::convex_wall_contacts on the support function: f(contact) for each side wall
    /// it presses (the floor is the solver's: support(-z)).
    void wall_contacts(const Container& c, const Placement& p, const ConvexWallFunction& f) const;
    /// The penetration depth, exactly: libccd's MPR (ccdMPRPenetration) says whether they
    /// overlap and gives a first direction, then the least over the unit directions of the
    /// closed-form support of their Minkowski difference (cylinder_shape.cpp's
    /// cylinder_depth: the ends' normals, the sides' great circles, their crossings and the
    /// smooth minima between), b placed at a.position + ab; the normal
    /// from a towards b and the point halfway between the two deepest points. Depth 0 when
    /// they are apart, the normal along ab. Where either is a ring and their hulls overlap:
    /// the deepest point of either's surface inside the other (highest_on_surface of the
    /// other's signed_depth), the normal that of the surface it is nearest.
    PairOverlap pair_overlap(const Placement& a, const CylinderShape& other, const Placement& b,
                             const Vec3& ab) const;
    /// The gap between two pellets, exactly: the least over the unit directions of the
    /// closed-form support of their Minkowski difference (cylinder_shape.cpp's cylinder_depth),
    /// b placed at a.position + ab, searched from the line of centres. Their distance negated
    /// when they are apart (the least support is minus the distance from the origin to the
    /// Minkowski difference), their penetration depth when they overlap: gap = -that. Where
    /// either is a ring: minus the highest of each surface's signed depth in the other (their
    /// distance, or the deepest point's depth).
    double pair_gap(const Placement& a, const CylinderShape& other, const Placement& b,
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
    /// The volume in an axis-aligned box: the section's disc inside the box's section, in
    /// closed form, integrated along the axis (section_volume.hpp's box_volume_by_sections); a
    /// ring's, the disc's less the bore's.
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const;
    /// The closed outward surface at size 1: 12 * 2^level segments around (chord error
    /// R (1 - cos(pi / n))), each end a fan about its centre, the side one band of quads split
    /// into triangles; a ring's ends are bands of quads to the bore, its bore a band facing
    /// the axis (its chords R_i (1 - cos(pi / n)) inside the bore).
    TriangleMesh unit_surface(int level) const;
    /// Nodes on the surface at size 1 at most about `spacing` apart (> 0): rings at radii
    /// j R / p (j = 0 .. p, p = ceil(R / spacing)) on each end and rows at heights -L/2 ..
    /// L/2 (ceil(L / spacing) steps) on the side, ceil(2 pi R / spacing) nodes about the rim
    /// and each row, proportionally fewer about an inner ring. The rims are shared by an end
    /// and the side. Each node stands for the area of its ring's or row's band about it (the
    /// halves of the neighbouring steps): the areas add up to 2 pi R^2 + 2 pi R L. Without
    /// `rows`, the side's rows (rims included) are left out: surface_circles has them whole.
    /// A ring's ends are rings from R_i to R (p = ceil((R - R_i) / spacing) steps) and its
    /// bore has rows as the side's: the areas add up to 2 pi (R^2 - R_i^2) + 2 pi (R + R_i) L.
    std::vector<SurfaceNode> surface_nodes(double spacing, bool rows = true) const;
    /// The side's rows of surface_nodes (the rims first) as circles, each with the area its
    /// nodes stand for per unit length; a ring's bore rows after them (its rims first), the
    /// rows of both at most `row_spacing` apart where that is > 0.
    std::vector<SurfaceCircle> surface_circles(double spacing, double row_spacing = 0.0) const;
    /// The body-frame point q (size 1)'s depth inside (inside(q).depth) where it is inside;
    /// outside, minus its distance from the cylinder (from the rectangle R_i <= r <= R,
    /// |z| <= L/2 of the plane through the axis: a solid of revolution's distance).
    double signed_depth(const Vec3& q) const {
        const double r = std::sqrt(q.x * q.x + q.y * q.y);
        const double side = bore > 0.0 ? std::max(r - radius, bore - r) : r - radius;
        const double end = std::abs(q.z) - half_length;
        if (side <= 0.0 && end <= 0.0)
            return -std::max(side, end);
        const double s = std::max(side, 0.0), e = std::max(end, 0.0);
        return -std::sqrt(s * s + e * e);
    }
    /// How deep the body-frame point q (size 1) lies inside: min(R - r, L/2 - |z|) where both
    /// are positive, out through the side or the end it is nearer (the side where equal); in a
    /// ring the side's depth is min(R - r, r - R_i), out through the nearer of side and bore.
    /// With `blend` > 0, the least of the two is the polynomial smooth minimum of that width
    /// (m - blend h (1 - h), h = clamp(1/2 + (b - a) / (2 blend)), a the side's, b the
    /// end's; at most blend / 4 less where they are equal) and the normal its gradient, h times
    /// the side's and 1 - h times the end's, not of unit length: the depth of a point then
    /// changes smoothly as it passes under an edge, and depth times normal is the gradient of
    /// depth^2 / 2.
    InsideDepth inside(const Vec3& q, double blend = 0.0) const {
        const double r = std::sqrt(q.x * q.x + q.y * q.y);
        double side = radius - r;
        const double end = half_length - std::abs(q.z);
        if (side <= 0.0 || end <= 0.0)
            return {};
        Vec3 out_side = r > 0.0 ? Vec3{q.x / r, q.y / r, 0.0} : Vec3{1.0, 0.0, 0.0};
        if (bore > 0.0 && r - bore < side) {
            side = r - bore;
            if (side <= 0.0)
                return {};
            out_side = -1.0 * out_side;
        }
        const Vec3 out_end{0.0, 0.0, q.z < 0.0 ? -1.0 : 1.0};
        if (blend > 0.0 && std::abs(side - end) < blend) {
            const double h = 0.5 + 0.5 * (end - side) / blend;
            const double depth = h * side + (1.0 - h) * end - blend * h * (1.0 - h);
            if (depth <= 0.0)
                return {};
            return {depth, out_side * h + out_end * (1.0 - h)};
        }
        if (side <= end)
            return {side, out_side};
        return {end, out_end};
    }
    /// A clump of equal spheres inside the cylinder, as LIGGGHTS' multisphere templates
    /// approximate one: radius s = min(R, L/2) / 2, centres on rings of radius 0 .. R - s
    /// (steps of at most s, ceil(2 pi r / s) about each) at axial positions -(L/2 - s) ..
    /// L/2 - s (steps of at most s). Each sphere touches no point outside the cylinder; the
    /// outermost touch its side and ends. A ring's: s = min((R - R_i) / 2, L/2) / 2, rings of
    /// radius R_i + s .. R - s, the innermost touching the bore.
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
    const double s = 0.5 * std::min(bore > 0.0 ? 0.5 * (radius - bore) : radius, half_length);
    const auto steps = [s](double span) {
        return span > 0.0 ? static_cast<int>(std::ceil(span / s - 1e-9)) : 0;
    };
    const int axial = steps(2.0 * (half_length - s));
    const double inner = bore > 0.0 ? bore + s : 0.0; // the innermost ring's radius
    const int rings = steps(radius - s - inner);
    for (int i = 0; i <= axial; ++i) {
        const double z =
            axial == 0 ? 0.0 : -(half_length - s) + 2.0 * (half_length - s) * i / axial;
        for (int j = 0; j <= rings; ++j) {
            const double r = bore > 0.0
                                 ? (rings == 0 ? inner : inner + (radius - s - inner) * j / rings)
                                 : (rings == 0 ? 0.0 : (radius - s) * j / rings);
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
