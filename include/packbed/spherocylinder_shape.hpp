// The spherocylinder pellet: a cylinder capped by two hemispheres of its radius, the set of
// points within D / 2 of a segment (its axis). Convex and smooth, its contact has a closed
// form: two spherocylinders overlap by D / 2 + D' / 2 less the distance of their segments,
// along the line between the segments' nearest points. The rod of the jamming studies
// (Williams & Philipse 2003; Imaz Gonzalez et al. 2023) and the closest relative of the soft
// spheres: E = k (d_a / 2 + d_b / 2 - |segment_a - segment_b|)^2 / 2.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <utility>
#include <variant>

#include "packbed/annulus.hpp"
#include "packbed/container.hpp"
#include "packbed/mesh.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// The points within `radius` of the segment of half-length `half_length` along the body z
/// axis, centred on the position (both in units of the particle's size). L is the length of
/// the cylindrical part (the segment), so L / D = 0 is the sphere, as the jamming literature
/// counts the aspect ratio; the pellet's whole length is L + D. A pellet's size is its
/// volume-equivalent radius d_v / 2 (particle_shape.hpp's Placement).
struct SpherocylinderShape {
    static constexpr std::string_view kind = "spherocylinder";
    static constexpr bool oriented = true;

    double radius = 1.0;      ///< D / 2 in units of the size
    double half_length = 0.0; ///< L / 2 in units of the size (the segment's half)

    /// The spherocylinder of L / D = `aspect` (>= 0) whose volume at size 1 is 4 pi / 3:
    /// pi R^2 L + 4 pi R^3 / 3 = 4 pi / 3 with L = 2 R aspect, so R = (1 + 3 aspect / 2)^(-1/3).
    static SpherocylinderShape of_aspect(double aspect);
    /// D / d_v: min(D, L + D) = D, its thinnest, in units of d_v (the tolerance's unit).
    double smallest_dimension() const { return radius; }

    /// (L / 2 + R) times the size: the sphere about the centre through the tips.
    double bounding_radius(double size) const { return size * (half_length + radius); }
    /// (pi R^2 L + 4 pi R^3 / 3) times size^3.
    double volume(double size) const;
    /// (2 pi R L + 4 pi R^2) times size^2.
    double surface_area(double size) const;
    /// The segment's end farthest along v (its middle where v is across the axis) moved R
    /// along v / |v|.
    Vec3 support(const Placement& p, const Vec3& v) const;
    /// Container::convex_wall_overlap on the support function, of the pellet grown by `grow`.
    double wall_overlap(const Container& c, const Placement& p, double grow = 0.0) const;
    /// Container::convex_wall_contacts on the support function (the floor is the solver's).
    void wall_contacts(const Container& c, const Placement& p, const ConvexWallFunction& f) const;
    /// R_a + R_b less the distance of the two segments (b's centre at a.position + ab), exact:
    /// the segments' nearest points by the least squares of the two lines' parameters, each
    /// clamped to its segment and the other's then recomputed (a convex problem in two
    /// unknowns whose minimum lies on the clamped line); the normal along the nearest points'
    /// difference (across both axes where the segments cross), the point halfway into the
    /// overlap. Apart: depth < 0, minus the gap.
    PairOverlap pair_overlap(const Placement& a, const SpherocylinderShape& other,
                             const Placement& b, const Vec3& ab) const;
    /// Minus pair_overlap's depth: the distance when apart, minus the penetration depth (exact:
    /// the Minkowski difference is a parallelogram grown by R_a + R_b).
    double pair_gap(const Placement& a, const SpherocylinderShape& other, const Placement& b,
                    const Vec3& ab) const {
        return -pair_overlap(a, other, b, ab).depth;
    }
    /// The springs that press two spherocylinders apart, each as f(depth, normal, point): the
    /// depth (> 0), the unit normal from a towards b and the point halfway into the overlap,
    /// from a's position. Each cap's sphere (the segment's end, radius R) against the other's
    /// segment, the four of them; and the segments' nearest points (pair_overlap) for what
    /// their depth exceeds the deepest of those. One spring where they cross, one where an end
    /// rests on a side, two where they lie side by side: the force and torque then change
    /// smoothly as two rods turn through parallel, where the nearest points alone jump from one
    /// end of the overlap to the other. The excess pushes along the nearest points' normal, so
    /// the forces are not exactly an energy's gradient (up to 1.5 % off in the pairs measured,
    /// where an end lies near a crossing; docs/notes/pellets.md). \return pair_overlap's depth.
    template <class F>
    double pair_springs(const Placement& a, const SpherocylinderShape& other, const Placement& b,
                        const Vec3& ab, F&& f) const {
        const Placed pa{rotate(a.orientation, Vec3{0.0, 0.0, 1.0}), radius * a.size,
                        half_length * a.size};
        const Placed pb{rotate(b.orientation, Vec3{0.0, 0.0, 1.0}), other.radius * b.size,
                        other.half_length * b.size};
        const Vec3 &ua = pa.axis, &ub = pb.axis;
        const double ra = pa.radius, rb = pb.radius, ha = pa.half_length, hb = pb.half_length;
        double deepest = 0.0;
        // From the point q (from a's position) of one body to its nearest on the other's
        // segment (centre c, axis u, half-length h); `towards` +1 when q is a's.
        const auto end_spring = [&](const Vec3& q, const Vec3& c, const Vec3& u, double h,
                                    double towards) {
            const Vec3 nearest = c + u * std::clamp(dot(q - c, u), -h, h);
            const Vec3 between = (nearest - q) * towards; // from a's side to b's
            const double distance = norm(between);
            const double depth = ra + rb - distance;
            if (!(depth > 0.0) || !(distance > 0.0))
                return;
            const Vec3 normal = between * (1.0 / distance);
            const Vec3 on_a = towards > 0.0 ? q : nearest;
            f(depth, normal, on_a + normal * (ra - 0.5 * depth));
            deepest = std::max(deepest, depth);
        };
        for (const double end : {-1.0, 1.0}) {
            end_spring(ua * (end * ha), ab, ub, hb, 1.0);
            end_spring(ab + ub * (end * hb), Vec3{}, ua, ha, -1.0);
        }
        const PairOverlap o = segments_overlap(pa, pb, ab);
        if (const double excess = o.depth - deepest; excess > 0.0)
            f(excess, o.normal, o.point + o.normal * (0.5 * (o.depth - excess)));
        return o.depth;
    }
    /// The springs that press it out of the container, each as f(depth, push, point) (the
    /// push the wall's inward unit normal, the point in the bed): each cap's sphere against the
    /// floor and the walls (Container::wall_contacts); in an annulus, the pellet's deepest point
    /// (wall_contacts) for what it exceeds them. The distance outside a convex region is convex
    /// along the segment: in a tube, a box, a cone the ends are the deepest, and only an
    /// annulus' rod, bulging into the region, meets the side between them. \return the deepest
    /// of the side walls (the floor left out: the caller has it exactly, support(-z)).
    template <class F> double wall_springs(const Container& c, const Placement& p, F&& f) const {
        const Vec3 axis = rotate(p.orientation, Vec3{0.0, 0.0, 1.0});
        const double r = radius * p.size;
        double deepest = 0.0, side = 0.0;
        for (const double end : {-1.0, 1.0}) {
            const Vec3 centre = p.position + axis * (end * half_length * p.size);
            const auto add = [&](double depth, const Vec3& push) {
                if (!(depth > 0.0))
                    return;
                f(depth, push, centre);
                deepest = std::max(deepest, depth);
            };
            add(r - centre.z, Vec3{0.0, 0.0, 1.0});
            c.wall_contacts(centre, r, [&](double depth, const Vec3& push) {
                add(depth, push);
                side = std::max(side, depth);
            });
        }
        if (std::holds_alternative<Annulus>(c.shape()))
            wall_contacts(c, p, [&](const ConvexWallContact& w) {
                side = std::max(side, w.depth);
                if (const double excess = w.depth - deepest; excess > 0.0)
                    f(excess, w.push, w.point);
            });
        return side;
    }
    /// The body-frame point q (size 1)'s depth inside, R less its distance from the segment:
    /// its distance from the surface, negative outside.
    double signed_depth(const Vec3& q) const {
        const double t = std::clamp(q.z, -half_length, half_length);
        return radius - std::sqrt(q.x * q.x + q.y * q.y + (q.z - t) * (q.z - t));
    }
    /// Bounds: the wall distances of the bounding sphere.
    std::pair<double, double> wall_extent(const Container& c, std::size_t wall,
                                          const Placement& p) const;
    /// The volume inside the container between two heights: the whole where the pellet lies
    /// between them clear of the side; the cylinder's slab sections (cylinder_shape.cpp's
    /// closed-form disc strips) and the caps' (the same discs, radius sqrt(R^2 - s^2) at s past
    /// the segment's end, integrated along the axis by adaptive Gauss-Kronrod) where it keeps
    /// clear of the side (wall_overlap); otherwise the cylinder part's CylinderShape::volume_in
    /// and each cap's sections by the region's polar integral (section_volume.hpp).
    double volume_in(const Container& c, const Placement& p, double z_low, double z_high) const;
    double volume_from_wall(const Container& c, std::size_t wall, double d, const Placement& p,
                            double z_low, double z_high) const;
    /// The volume in an axis-aligned box: the section's disc (radius R, or sqrt(R^2 - s^2) at s
    /// past the segment's end) inside the box's section, in closed form, integrated along the
    /// axis (section_volume.hpp's box_volume_by_sections).
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const;
    /// The closed outward surface at size 1: 12 * 2^level segments around and 3 * 2^level
    /// latitude steps on each cap (chord error R (1 - cos(pi / n)) both ways), the vertices on
    /// the exact surface, the side one band of quads, each cap bands closed by a fan at its tip.
    TriangleMesh unit_surface(int level) const;
    /// Spheres of radius R on the axis from one cap's centre to the other's, at most R / 2
    /// apart (the first and last are the caps themselves; the side between two lies at most
    /// R (1 - sqrt(15) / 4) = 0.032 R inside the exact one).
    template <class F> void dem_spheres(const Placement& p, F&& f) const {
        const int steps =
            half_length > 0.0 ? static_cast<int>(std::ceil(4.0 * half_length / radius - 1e-9)) : 0;
        const Vec3 axis = rotate(p.orientation, Vec3{0.0, 0.0, 1.0});
        for (int k = 0; k <= steps; ++k) {
            const double t = steps == 0 ? 0.0 : -half_length + 2.0 * half_length * k / steps;
            f(DemSphere{p.position + axis * (t * p.size), radius * p.size});
        }
    }

private:
    /// A pellet placed, as its contact needs it: its axis in the bed, its radius and its
    /// segment's half-length at its size.
    struct Placed {
        Vec3 axis;
        double radius, half_length;
    };
    /// pair_overlap of a and b (b's centre at ab from a's).
    static PairOverlap segments_overlap(const Placed& a, const Placed& b, const Vec3& ab);
};

static_assert(ParticleShape<SpherocylinderShape>);

} // namespace packbed
