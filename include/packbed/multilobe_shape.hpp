// The multilobe pellet: N equal cylinders (the lobes) whose axes lie on a circle about the
// pellet's axis, their union a right prism whose section is N overlapping discs (a trilobe at
// N = 3, the catalogue's shape; the plain cylinder at N = 1). A union of convex pieces: each
// question about the pellet is asked of its lobes (CylinderShape) and their answers combined,
// never of a convex hull that would fill the grooves between them.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/mesh.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// `lobes` cylinders `lobe` (in units of the particle's size) with their axes parallel to the
/// body z axis at distance `circle` from it, lobe k towards the angle 2 pi k / lobes from the
/// body x axis. circle <= lobe.radius: every lobe holds the axis, so the section is star-shaped
/// about it and has no hole (a wider circle leaves a channel along the axis that the catalogue
/// shapes fill). One lobe at circle 0 is the cylinder, or the ring where the lobe has a bore
/// (CylinderShape::bore; only one lobe may): every answer is then the lobe's own.
struct MultilobeShape {
    static constexpr std::string_view kind = "multilobe";
    static constexpr bool oriented = true;

    CylinderShape lobe;
    int lobes = 1;
    double circle = 0.0;

    /// The cylinder or ring `c` as a pellet of one lobe.
    static MultilobeShape cylinder(const CylinderShape& c) { return {c, 1, 0.0}; }
    /// The pellet of `n` lobes of diameter `lobe_diameter` on a circle of diameter
    /// `circle_diameter`, `length` long (any one length unit), at the size whose volume is the
    /// unit ball's (the pellet's size is its volume-equivalent radius d_v / 2).
    static MultilobeShape of(int n, double lobe_diameter, double circle_diameter, double length);

    /// Lobe k's axis in the body frame (at z = 0, size 1).
    Vec3 lobe_centre(int k) const;
    /// Lobe k placed: its axis' middle in the bed, the pellet's orientation and size.
    Placement lobe_placement(const Placement& p, int k) const;
    /// The section's area at size 1: N times the part of lobe 0's disc in its wedge (the angles
    /// within pi / N of its direction, the points nearer its axis than any other's, so that the
    /// wedges' parts tile the union). In polar coordinates about the axis, the ray at angle
    /// alpha from a lobe's direction leaves it at t(alpha) = c cos alpha + sqrt(r^2 - c^2
    /// sin^2 alpha); the area is the integral of t^2 / 2, in closed form: with s = c sin alpha,
    /// (r^2 alpha + c^2 sin(2 alpha) / 2 + s sqrt(r^2 - s^2) + r^2 asin(s / r)) / 2 between
    /// -pi / N and pi / N (pi r^2 at c = 0).
    double section_area() const;
    /// Where the ray at angle phi from the body x axis leaves the section (t above, of the lobe
    /// whose wedge holds phi), at size 1.
    double section_radius(double phi) const;
    /// Half the angle, about a lobe's own axis, of the arc of its side on the pellet's surface
    /// (pi for one lobe): the arc ends where the side meets the neighbours' on the wedges'
    /// edges.
    double arc_half_angle() const;
    /// min(D_lobe, L) / d_v: the pellet's smallest dimension in units of d_v (the depth
    /// tolerance's unit); a ring's min(L, (D - DI) / 2) / d_v, its wall the thinnest.
    double smallest_dimension() const {
        if (lobe.bore > 0.0)
            return std::min(0.5 * (lobe.radius - lobe.bore), lobe.half_length);
        return std::min(lobe.radius, lobe.half_length);
    }

    double bounding_radius(double size) const {
        return size * std::hypot(circle + lobe.radius, lobe.half_length);
    }
    double volume(double size) const;
    /// The ends' two sections and the side's N arcs of 2 arc_half_angle() r each, times L; a
    /// ring's bore adds 2 pi R_i L.
    double surface_area(double size) const;
    /// The lobes' farthest point along v (the farthest lobe's, the first of equals).
    Vec3 support(const Placement& p, const Vec3& v) const;
    /// The deepest of the lobes' (each convex: CylinderShape::wall_overlap, each grown by
    /// `grow`).
    double wall_overlap(const Container& c, const Placement& p, double grow = 0.0) const;
    /// Each lobe's contacts with the side walls.
    void wall_contacts(const Container& c, const Placement& p, const ConvexWallFunction& f) const;
    /// The deepest overlap of a lobe of a with a lobe of b (CylinderShape::pair_overlap, exact
    /// for each pair of convex pieces), its point from a's position.
    PairOverlap pair_overlap(const Placement& a, const MultilobeShape& other, const Placement& b,
                             const Vec3& ab) const;
    /// The least gap of a lobe of a and a lobe of b (CylinderShape::pair_gap): their distance
    /// when apart, minus the deepest penetration when they overlap.
    double pair_gap(const Placement& a, const MultilobeShape& other, const Placement& b,
                    const Vec3& ab) const;
    std::pair<double, double> wall_extent(const Container& c, std::size_t wall,
                                          const Placement& p) const;
    /// The lobe's volume_in for one lobe; else the section integrated in polar coordinates
    /// about the axis over the container's region (cylinder_shape.cpp's region_volume, the
    /// angle split at the wedges' edges where the section's edge turns).
    double volume_in(const Container& c, const Placement& p, double z_low, double z_high) const;
    double volume_from_wall(const Container& c, std::size_t wall, double d, const Placement& p,
                            double z_low, double z_high) const;
    /// The volume in an axis-aligned box: each lobe's disc in its wedge inside the box's
    /// section, in closed form, integrated along the axis (section_volume.hpp's
    /// box_volume_by_sections).
    double volume_in_box(const Placement& p, const Vec3& low, const Vec3& high) const;
    /// The closed outward surface at size 1: each lobe's arc in segments of at most 2 pi /
    /// (12 * 2^level) about its axis (chord error r (1 - cos(pi / n)), as the cylinder's), the
    /// arcs meeting in the grooves, each end a fan about its centre (the section is star-shaped
    /// about it), the side one band of quads split into triangles.
    TriangleMesh unit_surface(int level) const;
    /// Each lobe's nodes (CylinderShape::surface_nodes) that lie in its wedge: on the ends,
    /// the union's section once; on the side, the lobe's arc.
    std::vector<SurfaceNode> surface_nodes(double spacing, bool rows = true) const;
    /// Each lobe's circles about its own axis, kept to its arc (a ring's: its own, its rows
    /// at most `row_spacing` apart where > 0).
    std::vector<SurfaceCircle> surface_circles(double spacing, double row_spacing = 0.0) const;
    /// The deepest of the lobes' signed depths (the distance outside, negated, is the least).
    double signed_depth(const Vec3& q) const {
        if (lobes == 1)
            return lobe.signed_depth(q);
        double best = lobe.signed_depth(q - lobe_centre(0));
        for (int k = 1; k < lobes; ++k)
            best = std::max(best, lobe.signed_depth(q - lobe_centre(k)));
        return best;
    }
    /// The lobe the point lies deepest in, and its way out (CylinderShape::inside): a level set
    /// that is 0 on the union's surface, at most the distance to it near a groove.
    InsideDepth inside(const Vec3& q, double blend = 0.0) const {
        if (lobes == 1)
            return lobe.inside(q, blend);
        InsideDepth best{};
        for (int k = 0; k < lobes; ++k) {
            const InsideDepth in = lobe.inside(q - lobe_centre(k), blend);
            if (in.depth > best.depth)
                best = in;
        }
        return best;
    }
    /// Each lobe's clump of spheres (CylinderShape::dem_spheres): inside the pellet, the
    /// outermost touching its sides and ends.
    template <class F> void dem_spheres(const Placement& p, F&& f) const {
        if (lobes == 1)
            return lobe.dem_spheres(p, f);
        for (int k = 0; k < lobes; ++k)
            lobe.dem_spheres(lobe_placement(p, k), f);
    }
};

static_assert(ParticleShape<MultilobeShape>);

} // namespace packbed
