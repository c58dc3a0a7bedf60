#include "packbed/container.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/text.hpp"
#include "packbed/volume.hpp"

namespace packbed {

// Every question to the shape: the one place a container's kind is looked at.
namespace {
template <class F> decltype(auto) ask(const Container::Shape& shape, F&& f) {
    return std::visit(std::forward<F>(f), shape);
}
} // namespace

std::optional<double> Container::tube_diameter() const {
    return ask(m_shape, [](const auto& s) { return s.tube_diameter(); });
}

std::string_view Container::axis() const {
    return ask(m_shape, [](const auto& s) { return s.axis(); });
}

std::optional<Periods> Container::periods() const {
    return ask(m_shape, [](const auto& s) { return s.periods(); });
}

HydraulicDiameter Container::hydraulic_diameter() const {
    return ask(m_shape, [](const auto& s) { return s.hydraulic_diameter(); });
}

BoxMargin Container::box_margin() const {
    return ask(m_shape, [](const auto& s) { return s.box_margin(); });
}

std::string Container::fit_problem(double largest, const FitWords& words) const {
    return ask(m_shape, [&](const auto& s) { return s.fit_problem(largest, words); });
}

double Container::fill_height(double solid, double e0) const {
    return ask(m_shape, [&](const auto& s) { return s.fill_height(solid, e0); });
}

Vec3 Container::uniform_point(double radius, double u, double v, double z) const {
    return ask(m_shape, [&](const auto& s) { return s.uniform_point(radius, u, v, z); });
}

std::optional<double> Container::top() const {
    return ask(m_shape, [](const auto& s) { return s.top(); });
}

std::vector<std::pair<double, double>> Container::search_lines() const {
    return ask(m_shape, [](const auto& s) { return s.search_lines(); });
}

nlohmann::json Container::summary_json() const {
    return ask(m_shape, [](const auto& s) { return s.summary_json(); });
}

nlohmann::ordered_json Container::export_json(double height) const {
    return ask(m_shape, [&](const auto& s) { return s.export_json(height); });
}

std::vector<Solid> Container::solids(double z_low, double z_high, double edge) const {
    return ask(m_shape, [&](const auto& s) { return s.solids(z_low, z_high, edge); });
}

DemSettleWall Container::settle_wall(double height, std::string_view contact) const {
    return ask(m_shape, [&](const auto& s) { return s.settle_wall(height, contact); });
}

OpenFoamBackground Container::openfoam_background(double height, double cell,
                                                  const OpenFoamMeshOptions& options) const {
    return ask(m_shape,
               [&](const auto& s) { return s.openfoam_background(height, cell, options); });
}

bool Container::well_formed() const {
    return ask(m_shape, [](const auto& s) {
        return std::decay_t<decltype(s)>::from_numbers(s.spec_numbers()).has_value();
    });
}

std::vector<double> Container::spec_numbers() const {
    return ask(m_shape, [](const auto& s) { return s.spec_numbers(); });
}

double Container::prism_volume(double height) const {
    return ask(m_shape, [&](const auto& s) { return s.prism_volume(height); });
}

nlohmann::json Container::region_json(double height) const {
    return ask(m_shape, [&](const auto& s) { return s.region_json(height); });
}

std::string Container::region_allowed() const {
    return ask(m_shape, [](const auto& s) { return s.region_allowed(); });
}

FillWindow Container::fill_window(double margin, double height) const {
    return ask(m_shape, [&](const auto& s) { return s.fill_window(margin, height); });
}

LammpsSide Container::lammps_side(std::span<const double> diameters, double setback) const {
    return ask(m_shape, [&](const auto& s) { return s.lammps_side(diameters, setback); });
}

std::string_view Container::name() const {
    return ask(m_shape, [](const auto& s) { return s.name(); });
}

std::string Container::spec() const {
    return ask(m_shape, [](const auto& s) { return s.spec(); });
}

std::string Container::exact_spec() const {
    return ask(m_shape, [](const auto& s) { return s.spec(true); });
}

std::string Container::describe() const {
    return ask(m_shape, [](const auto& s) { return s.describe(); });
}

Container Container::tube(double diameter) {
    return Cylinder(0.5 * diameter);
}

Container Container::tube_of_radius(double radius) {
    return Cylinder(radius);
}

Container Container::scaled(double factor) const {
    return ask(m_shape, [&](const auto& s) -> Container { return s.scaled(factor); });
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

double Container::depth(double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.depth(z_low, z_high); });
}

std::vector<WallPlane> Container::walls_within(const Vec3& c, double r, double gap) const {
    return ask(m_shape, [&](const auto& s) { return s.walls_within(c, r, gap); });
}

double Container::cross_section_area(double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.cross_section_area(z_low, z_high); });
}

double Container::shell_area(double d_low, double d_high, double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.shell_area(d_low, d_high, z_low, z_high); });
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

double Container::shell_area_from(std::size_t wall, double d_low, double d_high, double z_low,
                                  double z_high) const {
    return ask(m_shape, [&](const auto& s) {
        return s.shell_area_from(wall, d_low, d_high, z_low, z_high);
    });
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

Chord Container::side_chord(const Vec3& p, const Vec3& u) const {
    return ask(m_shape, [&](const auto& s) { return s.side_chord(p, u); });
}

void Container::convex_wall_contacts(const SupportFunction& support, const Vec3& centre,
                                     double reach, const ConvexWallFunction& f) const {
    if (wall_overlap(centre, reach) <= 0.0)
        return;
    ask(m_shape, [&](const auto& s) {
        s.convex_wall_contacts(support, centre, [&](const ConvexWallContact& c) {
            if (c.depth > 0.0)
                f(c);
        });
    });
}

double Container::convex_wall_overlap(const SupportFunction& support, const Vec3& centre,
                                      double reach) const {
    double deepest = 0.0;
    convex_wall_contacts(support, centre, reach,
                         [&](const ConvexWallContact& c) { deepest = std::max(deepest, c.depth); });
    return deepest;
}

double Container::sticks_out(const Vec3& c, double r) const {
    return ask(m_shape, [&](const auto& s) { return s.sticks_out(c, r); });
}

namespace {

/// The shape of kind `kind` among Container::Shape's alternatives from I on, of `numbers`.
template <std::size_t I = 0>
std::optional<Container> parse_shape(std::string_view kind, std::span<const double> numbers) {
    if constexpr (I == std::variant_size_v<Container::Shape>) {
        return std::nullopt;
    } else {
        using S = std::variant_alternative_t<I, Container::Shape>;
        if (kind != S::kind)
            return parse_shape<I + 1>(kind, numbers);
        if (const std::optional<S> shape = S::from_numbers(numbers))
            return Container(*shape);
        return std::nullopt;
    }
}

/// The record of the shape of kind `kind` among Container::Shape's alternatives from I on.
template <std::size_t I = 0>
ContainerRecord record_shape(std::string_view kind, const nlohmann::json& record) {
    if constexpr (I == std::variant_size_v<Container::Shape>) {
        return {std::nullopt, fmt::format("a shape of {}", fmt::join(all_shapes, ", "))};
    } else {
        using S = std::variant_alternative_t<I, Container::Shape>;
        if (kind != S::kind)
            return record_shape<I + 1>(kind, record);
        if (const std::optional<S> shape = S::from_record(record))
            return {Container(*shape), {}};
        return {std::nullopt, fmt::format("{}: {}", S::kind, S::record_allowed())};
    }
}

template <class... S>
std::vector<std::string> allowed_of(const std::variant<S...>*,
                                    std::span<const std::string_view> shapes) {
    std::vector<std::string> forms;
    const auto add = [&](std::string_view kind, auto&& allowed) {
        if (std::find(shapes.begin(), shapes.end(), kind) != shapes.end())
            forms.push_back(allowed());
    };
    (add(S::kind, [] { return S::allowed(); }), ...);
    return forms;
}

} // namespace

std::optional<Container> parse_container(std::string_view text) {
    const KindSpec parts = split_kind(text);
    if (!parts.parameters)
        return std::nullopt;
    const auto numbers = parse_finite_list(*parts.parameters);
    if (!numbers)
        return std::nullopt;
    return parse_shape(parts.kind, *numbers);
}

ContainerRecord container_from_record(const nlohmann::json& record) {
    const auto shape = record.find("shape");
    if (shape == record.end() && record.contains("radius"))
        return record_shape(Cylinder::kind, record);
    if (shape == record.end() || !shape->is_string())
        return {std::nullopt, fmt::format("a shape of {}", fmt::join(all_shapes, ", "))};
    return record_shape(shape->get<std::string>(), record);
}

std::string describe(const Container& container) {
    if (const auto* c = std::get_if<Cylinder>(&container.shape()))
        return fmt::format("radius {}", c->radius());
    return container.spec();
}

std::string allowed_containers(std::span<const std::string_view> shapes) {
    const std::vector<std::string> forms =
        allowed_of(static_cast<const Container::Shape*>(nullptr), shapes);
    return fmt::format("{}", fmt::join(forms, "; or "));
}

std::string hydraulic_formulas() {
    std::vector<std::string> with, none;
    for (const auto& [kind, formula] :
         detail::hydraulic_formulas_of(static_cast<const Container::Shape*>(nullptr))) {
        if (formula.empty())
            none.emplace_back(kind);
        else
            with.push_back(fmt::format("{} {}", kind, formula));
    }
    return fmt::format("{}; none in {}", fmt::join(with, ", "), fmt::join(none, ", "));
}

std::string forms_but(std::string_view kind) {
    std::vector<std::string_view> forms;
    for (std::size_t k = 0; k < all_shapes.size(); ++k)
        if (all_shapes[k] != kind)
            forms.push_back(all_forms[k]);
    if (forms.size() < 2)
        return fmt::format("{}", fmt::join(forms, ""));
    return fmt::format("{} or {}", fmt::join(forms.begin(), forms.end() - 1, ", "), forms.back());
}

std::string container_not_allowed(std::string_view option, std::string_view spec) {
    return fmt::format("{}: '{}' is not allowed; allowed: {}", option,
                       printable(spec.substr(0, 80)), allowed_containers(all_shapes));
}

} // namespace packbed
