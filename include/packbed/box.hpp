// The box: four flat walls.
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/shape.hpp"

namespace packbed {

/// A rectangular box with four flat walls, x in [x_low, x_high], y in [y_low, y_high]; the
/// floor is z = 0 and it is open at the top. `--container box:LX,LY` is the box from (0, 0) to
/// (LX, LY). The distance from the wall is the distance from the nearest of the four faces, so
/// the set of points at least d from the wall is the box shrunk by d on every side, and a
/// profile against it counts a corner region with the face nearer to it (docs/analysis.md).
/// Immutable after construction.
class Box : public OneProfileWall<Box> {
public:
    /// The box from (0, 0) to (lx, ly). \param lx,ly widths (length, >= 0)
    Box(double lx, double ly)
        : Box(0.0, lx, 0.0, ly) {}
    /// The box [x_low, x_high] x [y_low, y_high] (x_low <= x_high, y_low <= y_high).
    Box(double x_low, double x_high, double y_low, double y_high)
        : m_x_low(x_low)
        , m_x_high(x_high)
        , m_y_low(y_low)
        , m_y_high(y_high) {}

    double x_low() const { return m_x_low; }
    double x_high() const { return m_x_high; }
    double y_low() const { return m_y_low; }
    double y_high() const { return m_y_high; }

    /// \return true if the point lies inside the box above the floor.
    bool contains(const Vec3& p) const {
        return p.z >= 0.0 && p.x >= m_x_low && p.x <= m_x_high && p.y >= m_y_low && p.y <= m_y_high;
    }

    /// The wall law, face by face: call f(overlap, push) for each face the sphere (p, r)
    /// presses into, overlap = r - (distance of p from the face) > 0, push the face's inward
    /// normal. A sphere in a corner presses two faces; each pushes on its own, as each wall of
    /// the paper's eq. (4) would.
    template <class F> void wall_contacts(const Vec3& p, double radius, F&& f) const {
        if (const double o = radius - (p.x - m_x_low); o > 0.0)
            f(o, Vec3{1.0, 0.0, 0.0});
        if (const double o = radius - (m_x_high - p.x); o > 0.0)
            f(o, Vec3{-1.0, 0.0, 0.0});
        if (const double o = radius - (p.y - m_y_low); o > 0.0)
            f(o, Vec3{0.0, 1.0, 0.0});
        if (const double o = radius - (m_y_high - p.y); o > 0.0)
            f(o, Vec3{0.0, -1.0, 0.0});
    }

    /// \return the distance of p from the nearest face (negative outside).
    double wall_distance(const Vec3& p) const {
        return std::min(std::min(p.x - m_x_low, m_x_high - p.x),
                        std::min(p.y - m_y_low, m_y_high - p.y));
    }

    /// \return the nearest and farthest distance from the wall of the points of the sphere
    /// (c, r), bounded by the depth: d - r and min(d + r, depth), d the centre's.
    std::pair<double, double> wall_distances(const Vec3& c, double r) const {
        const double d = wall_distance(c);
        return {d - r, std::min(d + r, depth())};
    }

    /// \return the largest distance from the wall inside: half the narrower width.
    double depth() const { return 0.5 * std::min(m_x_high - m_x_low, m_y_high - m_y_low); }

    /// The faces that come within `gap` of the sphere (c, r) (the centre's distance from the
    /// face less r below gap), in the order x_low, x_high, y_low, y_high: a sphere in a corner
    /// gets two. Normals -x, +x, -y, +y; offsets -x_low, x_high, -y_low, y_high.
    /// \param gap length (may be 0 or negative)
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;

    /// \return the cross-section, LX LY.
    double cross_section_area() const;

    /// \return the area between the distances d_low <= d_high from the wall: the rectangle
    /// shrunk by d_low less the one shrunk by d_high.
    double shell_area(double d_low, double d_high) const;

    /// \return the points at least d >= 0 from every face: the box shrunk by d on each side
    /// (a segment or a point at the middle when d reaches the depth).
    Box shrunk(double d) const;

    /// Exact volume of the sphere (c, r) inside the box between z_low and z_high
    /// (sphere_volume_in_box; 0 when the box has no area).
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;

    /// The same as sphere_volume (there is no faster routine for a box).
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
        return sphere_volume(c, r, z_low, z_high);
    }

    /// "box:LX,LY" (9 significant digits; `exact`: the shortest text of each double); a box not
    /// at the origin adds "@X,Y", its corner.
    std::string spec(bool exact = false) const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// --container's word for the shape, "box:LX,LY" its SPEC.
    static constexpr std::string_view kind = "box";
    /// The SPEC in letters, as messages list it.
    static constexpr std::string_view form = "box:LX,LY";
    /// The hydraulic diameter 4 A / P in the SPEC's letters ("": none).
    static constexpr std::string_view hydraulic_formula = "2 LX LY / (LX + LY)";
    std::string_view name() const { return kind; }
    PACKBED_SHAPE_ANSWERS(Box);
    PACKBED_PRISM_HEIGHTS
    std::string_view axis() const { return ""; }
    Rectangle bounds() const { return {m_x_low, m_x_high, m_y_low, m_y_high}; }
    /// The wall profiles' first column: the distance from the nearest face itself.
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

    /// \return how far the sphere (c, r) reaches beyond the nearest face, r - d (<= 0 inside).
    double sticks_out(const Vec3& c, double r) const { return -wall_distances(c, r).first; }

private:
    double m_x_low, m_x_high, m_y_low, m_y_high;
};

} // namespace packbed
