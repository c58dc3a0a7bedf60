// The periodic cell: no side wall, periodic in x and y.
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/shape.hpp"
#include <algorithm>
#include <limits>

namespace packbed {

/// A cell periodic in x and y, [0, LX) x [0, LY), with no side walls: a sphere leaving one
/// side comes back through the opposite one, and two spheres touch through the sides by the
/// minimum image (their nearest copies). The floor is z = 0 and it is open at the top. For
/// bulk statistics: the analysis measures it along z only. Every question about walls gets
/// "none": wall_distance is +infinity, depth 0 (no wall profile), no wall contacts. A sphere
/// cut by a side of the cell has its missing part inside through the opposite side, so its
/// volume in the cell is its whole volume between the heights. Immutable after construction.
class Periodic : public Periods {
public:
    /// \param lx,ly the cell's periods (length, > 0)
    Periodic(double lx, double ly)
        : Periods(lx, ly) {}

    /// \return true for every point above the floor: each is a copy of one in the cell.
    bool contains(const Vec3& p) const { return p.z >= 0.0; }
    /// No wall: f is never called.
    template <class F> void wall_contacts(const Vec3&, double, F&&) const {}

    double wall_distance(const Vec3&) const { return std::numeric_limits<double>::infinity(); }
    std::pair<double, double> wall_distances(const Vec3&, double) const {
        return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
    /// 0: there is no wall to measure a profile from.
    double depth() const { return 0.0; }
    std::vector<WallPlane> walls_within(const Vec3&, double, double) const { return {}; }
    /// \return the cross-section, LX LY.
    double cross_section_area() const { return lx() * ly(); }
    double shell_area(double, double) const { return 0.0; }
    Periodic shrunk(double) const { return *this; }
    /// The whole sphere between z_low and z_high (spherical segments): the parts beyond a
    /// side are inside through the opposite one. Exact for spheres narrower than the cell.
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
        return sphere_volume(c, r, z_low, z_high);
    }

    /// "periodic:LX,LY" (9 significant digits; `exact`: the shortest text of each double).
    std::string spec(bool exact = false) const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;
    /// --container's word for the shape, "periodic:LX,LY" its SPEC.
    static constexpr std::string_view kind = "periodic";
    /// The SPEC in letters, as messages list it.
    static constexpr std::string_view form = "periodic:LX,LY";
    /// The hydraulic diameter 4 A / P in the SPEC's letters ("": none).
    static constexpr std::string_view hydraulic_formula = "";
    std::string_view name() const { return kind; }
    PACKBED_SHAPE_ANSWERS(Periodic);
    PACKBED_PRISM_HEIGHTS
    std::string_view axis() const { return ""; }
    Rectangle bounds() const { return {0.0, lx(), 0.0, ly()}; }
    std::string_view profile_position_name() const { return "wall_distance"; }
    double profile_position(double d) const { return d; }

    /// No wall to measure a profile from: profile_walls is empty, and the questions about
    /// one wall (never asked) answer as for no wall.
    std::span<const std::string_view> profile_walls() const { return {}; }
    double wall_distance_from(std::size_t, const Vec3& p) const { return wall_distance(p); }
    std::pair<double, double> wall_distances_from(std::size_t, const Vec3& c, double r) const {
        return wall_distances(c, r);
    }
    Periodic shrunk_from(std::size_t, double) const { return *this; }
    double shell_area_from(std::size_t, double, double, double, double) const { return 0.0; }
    std::size_t nearest_wall(const Vec3&) const { return 0; }
    std::string_view profile_position_name_from(std::size_t) const { return "wall_distance"; }
    double profile_position_from(std::size_t, double d) const { return d; }
    /// \return how far the centre of the sphere lies outside the cell [0, LX] x [0, LY] (0
    /// inside; the radius does not count: a sphere across a side is inside through the other).
    double sticks_out(const Vec3& c, double) const {
        return std::max({0.0, -c.x, c.x - lx(), -c.y, c.y - ly()});
    }
};

} // namespace packbed
