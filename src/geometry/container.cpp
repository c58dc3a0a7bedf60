#include "packbed/container.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/text.hpp"
#include "packbed/volume.hpp"

namespace packbed {

double Cylinder::cross_section_area() const {
    return std::numbers::pi * m_radius * m_radius;
}

double Cylinder::shell_area(double d_low, double d_high) const {
    const double a = std::max(m_radius - d_low, 0.0), b = std::max(m_radius - d_high, 0.0);
    return std::numbers::pi * (a * a - b * b);
}

double Cylinder::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return m_radius > 0.0 ? sphere_volume_in_cylinder_slab(c, r, m_radius, z_low, z_high) : 0.0;
}

double Cylinder::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(r > 0.0 && m_radius > 0.0))
        return 0.0;
    if (r <= c.z - z_low && r <= z_high - c.z)
        return ball_volume_in_cylinder(std::hypot(c.x, c.y), r, m_radius);
    return sphere_volume_in_cylinder_slab(c, r, m_radius, z_low, z_high);
}

std::vector<WallPlane> Cylinder::walls_within(const Vec3& c, double r, double gap) const {
    const double rho = std::hypot(c.x, c.y);
    if (m_radius - rho - r < gap && rho > 0.0)
        return {WallPlane{{c.x / rho, c.y / rho, 0.0}, m_radius}};
    return {};
}

std::string Cylinder::spec() const {
    return fmt::format("cylinder:{:.9g}", 2.0 * m_radius);
}

std::string Cylinder::describe() const {
    return fmt::format("a cylinder of radius {}", radius());
}

double Box::cross_section_area() const {
    return (m_x_high - m_x_low) * (m_y_high - m_y_low);
}

double Box::shell_area(double d_low, double d_high) const {
    const Box outer = shrunk(d_low), inner = shrunk(d_high);
    return outer.cross_section_area() - inner.cross_section_area();
}

Box Box::shrunk(double d) const {
    const double x_mid = 0.5 * (m_x_low + m_x_high), y_mid = 0.5 * (m_y_low + m_y_high);
    return Box(std::min(m_x_low + d, x_mid), std::max(m_x_high - d, x_mid),
               std::min(m_y_low + d, y_mid), std::max(m_y_high - d, y_mid));
}

double Box::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(m_x_high > m_x_low && m_y_high > m_y_low && z_high > z_low))
        return 0.0;
    return sphere_volume_in_box(c, r, {m_x_low, m_y_low, z_low}, {m_x_high, m_y_high, z_high});
}

std::vector<WallPlane> Box::walls_within(const Vec3& c, double r, double gap) const {
    std::vector<WallPlane> planes;
    if (c.x - m_x_low - r < gap)
        planes.push_back({{-1.0, 0.0, 0.0}, -m_x_low});
    if (m_x_high - c.x - r < gap)
        planes.push_back({{1.0, 0.0, 0.0}, m_x_high});
    if (c.y - m_y_low - r < gap)
        planes.push_back({{0.0, -1.0, 0.0}, -m_y_low});
    if (m_y_high - c.y - r < gap)
        planes.push_back({{0.0, 1.0, 0.0}, m_y_high});
    return planes;
}

std::string Box::spec() const {
    std::string out = fmt::format("box:{:.9g},{:.9g}", m_x_high - m_x_low, m_y_high - m_y_low);
    if (m_x_low != 0.0 || m_y_low != 0.0)
        out += fmt::format("@{:.9g},{:.9g}", m_x_low, m_y_low);
    return out;
}

std::string Box::describe() const {
    return fmt::format("a box ({})", spec());
}

double Annulus::cross_section_area() const {
    return std::numbers::pi * (m_outer * m_outer - m_inner * m_inner);
}

Annulus Annulus::shrunk(double d) const {
    const double mid = 0.5 * (m_outer + m_inner);
    return Annulus(std::max(m_outer - d, mid), std::min(m_inner + d, mid));
}

double Annulus::shell_area(double d_low, double d_high) const {
    return shrunk(d_low).cross_section_area() - shrunk(d_high).cross_section_area();
}

double Annulus::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(m_outer > m_inner))
        return 0.0;
    const double rod =
        m_inner > 0.0 ? sphere_volume_in_cylinder_slab(c, r, m_inner, z_low, z_high) : 0.0;
    return sphere_volume_in_cylinder_slab(c, r, m_outer, z_low, z_high) - rod;
}

double Annulus::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(r > 0.0 && m_outer > m_inner))
        return 0.0;
    if (!(r <= c.z - z_low && r <= z_high - c.z))
        return sphere_volume(c, r, z_low, z_high);
    const double rho = std::hypot(c.x, c.y);
    const double rod = m_inner > 0.0 ? ball_volume_in_cylinder(rho, r, m_inner) : 0.0;
    return ball_volume_in_cylinder(rho, r, m_outer) - rod;
}

std::vector<WallPlane> Annulus::walls_within(const Vec3& c, double r, double gap) const {
    const double rho = std::hypot(c.x, c.y);
    std::vector<WallPlane> planes;
    if (!(rho > 0.0))
        return planes;
    const Vec3 out{c.x / rho, c.y / rho, 0.0};
    if (m_outer - rho - r < gap)
        planes.push_back({out, m_outer});
    if (rho - r - m_inner < gap)
        planes.push_back({out * -1.0, -m_inner});
    return planes;
}

Annulus Annulus::shrunk_from(std::size_t wall, double d) const {
    const double mid = 0.5 * (m_outer + m_inner);
    if (wall == 0)
        return Annulus(std::max(m_outer - d, mid), m_inner);
    return Annulus(m_outer, std::min(m_inner + d, mid));
}

double Annulus::shell_area_from(std::size_t wall, double d_low, double d_high) const {
    return shrunk_from(wall, d_low).cross_section_area() -
           shrunk_from(wall, d_high).cross_section_area();
}

std::string Annulus::spec() const {
    return fmt::format("annulus:{:.9g},{:.9g}", 2.0 * m_outer, 2.0 * m_inner);
}

std::string Annulus::describe() const {
    return spec();
}

double Periodic::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return sphere_slab_volume(c.z, r, z_low, z_high);
}

std::string Periodic::spec() const {
    return fmt::format("periodic:{:.9g},{:.9g}", m_lx, m_ly);
}

std::string Periodic::describe() const {
    return spec();
}

// Every question to the shape: the one place a container's kind is looked at.
namespace {
template <class F> decltype(auto) ask(const Container::Shape& shape, F&& f) {
    return std::visit(std::forward<F>(f), shape);
}
} // namespace

std::string_view Container::name() const {
    return ask(m_shape, [](const auto& s) { return s.name(); });
}

std::string Container::spec() const {
    return ask(m_shape, [](const auto& s) { return s.spec(); });
}

std::string Container::describe() const {
    return ask(m_shape, [](const auto& s) { return s.describe(); });
}

Container Container::scaled(double factor) const {
    return ask(m_shape, [&](const auto& s) -> Container {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Cylinder>)
            return Cylinder(s.radius() * factor);
        else if constexpr (std::is_same_v<S, Box>)
            return Box(s.x_low() * factor, s.x_high() * factor, s.y_low() * factor,
                       s.y_high() * factor);
        else if constexpr (std::is_same_v<S, Annulus>)
            return Annulus(s.outer_radius() * factor, s.inner_radius() * factor);
        else
            return Periodic(s.lx() * factor, s.ly() * factor);
    });
}

bool Container::contains(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.contains(p); });
}

double Container::wall_distance(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distance(p); });
}

std::pair<double, double> Container::wall_distances(const Vec3& c, double r) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distances(c, r); });
}

double Container::depth() const {
    return ask(m_shape, [](const auto& s) { return s.depth(); });
}

std::vector<WallPlane> Container::walls_within(const Vec3& c, double r, double gap) const {
    return ask(m_shape, [&](const auto& s) { return s.walls_within(c, r, gap); });
}

double Container::cross_section_area() const {
    return ask(m_shape, [](const auto& s) { return s.cross_section_area(); });
}

double Container::shell_area(double d_low, double d_high) const {
    return ask(m_shape, [&](const auto& s) { return s.shell_area(d_low, d_high); });
}

Container Container::shrunk(double d) const {
    return ask(m_shape, [&](const auto& s) { return Container(s.shrunk(d)); });
}

double Container::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.sphere_volume(c, r, z_low, z_high); });
}

double Container::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.ball_volume(c, r, z_low, z_high); });
}

Rectangle Container::bounds() const {
    return ask(m_shape, [](const auto& s) { return s.bounds(); });
}

std::string_view Container::profile_position_name() const {
    return ask(m_shape, [](const auto& s) { return s.profile_position_name(); });
}

double Container::profile_position(double d) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position(d); });
}

std::span<const std::string_view> Container::profile_walls() const {
    return ask(m_shape, [](const auto& s) { return s.profile_walls(); });
}

double Container::wall_distance_from(std::size_t wall, const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distance_from(wall, p); });
}

std::pair<double, double> Container::wall_distances_from(std::size_t wall, const Vec3& c,
                                                         double r) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distances_from(wall, c, r); });
}

Container Container::shrunk_from(std::size_t wall, double d) const {
    return ask(m_shape, [&](const auto& s) { return Container(s.shrunk_from(wall, d)); });
}

double Container::shell_area_from(std::size_t wall, double d_low, double d_high) const {
    return ask(m_shape, [&](const auto& s) { return s.shell_area_from(wall, d_low, d_high); });
}

std::size_t Container::nearest_wall(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.nearest_wall(p); });
}

std::string_view Container::profile_position_name_from(std::size_t wall) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position_name_from(wall); });
}

double Container::profile_position_from(std::size_t wall, double d) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position_from(wall, d); });
}

double Container::sticks_out(const Vec3& c, double r) const {
    return ask(m_shape, [&](const auto& s) { return s.sticks_out(c, r); });
}

Container ContainerSpec::container() const {
    if (shape == "box")
        return Box(lx, ly);
    if (shape == "annulus")
        return Annulus(0.5 * diameter, 0.5 * inner);
    if (shape == "periodic")
        return Periodic(lx, ly);
    return Cylinder(0.5 * diameter);
}

std::optional<ContainerSpec> parse_container(std::string_view text) {
    const KindSpec parts = split_kind(text);
    const std::string_view shape = parts.kind;
    if (!parts.parameters)
        return std::nullopt;
    const auto known = std::find(all_shapes.begin(), all_shapes.end(), shape);
    const auto v = parse_finite_list(*parts.parameters);
    if (known == all_shapes.end() || !v || v->size() != (shape == "cylinder" ? 1u : 2u))
        return std::nullopt;
    // Every side within max_length of the origin, as the analysis allows.
    const bool round = shape == "cylinder" || shape == "annulus";
    const double largest = round ? 2.0 * limits::max_length : limits::max_length;
    for (const double x : *v)
        if (!(x > 0.0 && x <= largest))
            return std::nullopt;
    ContainerSpec spec{std::string(shape)};
    if (shape == "annulus" && !((*v)[1] < (*v)[0]))
        return std::nullopt;
    if (round) {
        spec.diameter = (*v)[0];
        spec.inner = v->size() > 1 ? (*v)[1] : 0.0;
    } else {
        spec.lx = (*v)[0];
        spec.ly = (*v)[1];
    }
    return spec;
}

std::string describe(const Container& container) {
    if (const Cylinder* c = container.cylinder())
        return fmt::format("radius {}", c->radius());
    return container.spec();
}

std::string allowed_containers(std::span<const std::string_view> shapes) {
    const auto takes = [&](std::string_view s) {
        return std::find(shapes.begin(), shapes.end(), s) != shapes.end();
    };
    std::vector<std::string> forms;
    const double round = 2.0 * limits::max_length, flat = limits::max_length;
    if (takes("cylinder"))
        forms.push_back(
            fmt::format("cylinder:D, a tube of inner diameter D, a number in (0, {:g}]", round));
    if (takes("box"))
        forms.push_back(
            fmt::format("box:LX,LY, walls at x = 0, LX and y = 0, LY, each in (0, {:g}]", flat));
    if (takes("annulus"))
        forms.push_back(fmt::format("annulus:D,DI, between a tube of diameter D and a coaxial "
                                    "rod of diameter DI, 0 < DI < D <= {:g}",
                                    round));
    if (takes("periodic"))
        forms.push_back(
            fmt::format("periodic:LX,LY, a cell periodic in x and y, each in (0, {:g}]", flat));
    return fmt::format("{}", fmt::join(forms, "; or "));
}

std::string container_not_allowed(std::string_view option, std::string_view spec) {
    return fmt::format("{}: '{}' is not allowed; allowed: {}", option,
                       printable(spec.substr(0, 80)), allowed_containers(all_shapes));
}

} // namespace packbed
