// generate --shape: a bed of pellets, from the request to its files (pipeline.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include <fmt/format.h>

#include "packbed/bed_volume.hpp"
#include "packbed/checkpoint.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/text.hpp"
#include "packbed/version.hpp"

namespace packbed {

namespace {

/// The pellets of one shape as a ShapedBed (a reference to `packing`).
template <class S> ShapedBed<S> shaped_bed(const Packing& packing, const S& shape) {
    return ShapedBed<S>(packing, {shape});
}

constexpr double min_aspect = 0.1, max_aspect = 10.0; // L / D of a cylinder pellet
/// DI / D of a ring: a thinner wall than D / 20 is a tube, not a pellet, and its depth
/// tolerance (1e-3 of the wall) below what the nodes resolve.
constexpr double max_bore = 0.9;

/// The shape `text` names, its lengths each checked (parse_pellet_shape).
std::optional<PelletSpec> parse_lengths(std::string_view text) {
    const KindSpec spec = split_kind(text);
    if (!spec.parameters)
        return std::nullopt;
    const auto numbers = parse_finite_list(*spec.parameters);
    if (!numbers)
        return std::nullopt;
    const auto length_ok = [](double x) { return x > 0.0 && x <= limits::max_length; };
    PelletSpec out;
    out.kind = std::string(spec.kind);
    out.text = std::string(text);
    if (spec.kind == "cylinder") {
        if (numbers->size() != 2)
            return std::nullopt;
        const double d = (*numbers)[0], l = (*numbers)[1];
        if (!(length_ok(d) && length_ok(l)))
            return std::nullopt;
        const double aspect = l / d;
        if (!(aspect >= min_aspect && aspect <= max_aspect))
            return std::nullopt;
        out.shape = MultilobeShape::cylinder(CylinderShape::of_aspect(aspect));
        out.diameter = d;
        out.length = l;
        // pi D^2 L / 4 = pi d_v^3 / 6.
        out.volume_diameter = std::cbrt(1.5 * d * d * l);
        return out;
    }
    if (spec.kind == "ring") {
        if (numbers->size() != 3)
            return std::nullopt;
        const double d = (*numbers)[0], di = (*numbers)[1], l = (*numbers)[2];
        if (!(length_ok(d) && length_ok(di) && length_ok(l) && di < d))
            return std::nullopt;
        if (!(l / d >= min_aspect && l / d <= max_aspect && di / d <= max_bore))
            return std::nullopt;
        out.shape = MultilobeShape::cylinder(CylinderShape::ring(d, di, l));
        out.diameter = d;
        out.inner_diameter = di;
        out.length = l;
        // pi (D^2 - DI^2) L / 4 = pi d_v^3 / 6.
        out.volume_diameter = std::cbrt(1.5 * (d * d - di * di) * l);
        return out;
    }
    if (spec.kind == "spherocylinder") {
        if (numbers->size() != 2)
            return std::nullopt;
        const double d = (*numbers)[0], l = (*numbers)[1];
        if (!(length_ok(d) && (l == 0.0 || length_ok(l)) && l / d <= max_aspect))
            return std::nullopt;
        out.shape = SpherocylinderShape::of_aspect(l / d);
        out.diameter = d;
        out.length = l;
        // pi D^2 L / 4 + pi D^3 / 6 = pi d_v^3 / 6.
        out.volume_diameter = std::cbrt(1.5 * d * d * l + d * d * d);
        return out;
    }
    const bool trilobe = spec.kind == "trilobe";
    if (!trilobe && spec.kind != "multilobe")
        return std::nullopt;
    if (numbers->size() != (trilobe ? 3u : 4u))
        return std::nullopt;
    const double* v = numbers->data() + (trilobe ? 0 : 1);
    const double lobes = trilobe ? 3.0 : (*numbers)[0];
    const double dl = v[0], dc = v[1], l = v[2];
    if (!(lobes >= 2.0 && lobes <= 8.0 && lobes == std::floor(lobes)))
        return std::nullopt;
    if (!(length_ok(dl) && length_ok(dc) && length_ok(l) && dc <= dl))
        return std::nullopt;
    if (!(l / dl >= min_aspect && l / dl <= max_aspect))
        return std::nullopt;
    const int n = static_cast<int>(lobes);
    out.shape = MultilobeShape::of(n, dl, dc, l);
    out.diameter = dl;
    out.circle_diameter = dc;
    out.length = l;
    // The section's area at these lengths times L = pi d_v^3 / 6.
    const MultilobeShape given{{0.5 * dl, 0.5 * l}, n, 0.5 * dc};
    out.volume_diameter = std::cbrt(6.0 * given.section_area() * l / std::numbers::pi);
    return out;
}

} // namespace

std::optional<PelletSpec> parse_pellet_shape(std::string_view text) {
    std::optional<PelletSpec> out = parse_lengths(text);
    // Its size, d_v, in the range of a sphere's diameter: what the readers take back as r.
    if (out && !(out->volume_diameter >= limits::min_diameter &&
                 out->volume_diameter <= limits::max_diameter))
        return std::nullopt;
    return out;
}

bool PelletSpec::same_as(const PelletSpec& other) const {
    const auto near = [](double x, double y) {
        return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y));
    };
    const auto lobes = [](const PelletSpec& p) {
        const auto* lobed = std::get_if<MultilobeShape>(&p.shape);
        return lobed ? lobed->lobes : 0;
    };
    return kind == other.kind && lobes(*this) == lobes(other) && near(diameter, other.diameter) &&
           near(circle_diameter, other.circle_diameter) &&
           near(inner_diameter, other.inner_diameter) && near(length, other.length);
}

std::string allowed_shapes() {
    return fmt::format(
        "sphere (the default); cylinder:D,L (a cylinder of diameter D and length L); "
        "ring:D,DI,L (a hollow cylinder, its bore of diameter DI, 0 < DI <= {:g} D); "
        "trilobe:DL,DC,L (three cylinders of diameter DL, their axes on a circle of diameter "
        "DC, 0 < DC <= DL); multilobe:N,DL,DC,L (N = 2 to 8 such lobes); each length > 0 and "
        "at most {:g}, L / D (L / DL) from {:g} to {:g}; or spherocylinder:D,L (a cylinder of "
        "diameter D and length L capped by two hemispheres, L >= 0, L / D at most {:g}); the "
        "volume-equivalent diameter d_v from {:g} to {:g}",
        max_bore, limits::max_length, min_aspect, max_aspect, max_aspect, limits::min_diameter,
        limits::max_diameter);
}

PreparedPellets prepare_pellets(const PelletRequest& request) {
    PreparedPellets out;
    out.request = request;
    const auto pellet = parse_pellet_shape(request.shape);
    if (!pellet)
        throw InvalidInput(fmt::format("--shape: '{}' is not allowed; allowed: {}",
                                       printable(request.shape), allowed_shapes()));
    out.pellet = *pellet;
    PelletBedParameters& p = out.params;
    // Pellets of many sizes (docs/generate.md, "Sizes of pellets"): D drawn from --sizes as a
    // sphere bed's diameters, the reference pellet the shape at their Sauter mean d32, each
    // pellet's scale its D over d32. `mono` draws nothing: the bed of --shape, bit for bit.
    double dv = pellet->volume_diameter;
    if (request.sizes != "mono") {
        const SizeDistribution distribution = parse_sizes(request.sizes, pellet->diameter);
        const std::vector<double> drawn = draw_diameters(
            distribution, request.particles, request.fractions, sizes_seed(request.seed));
        out.drawn = size_statistics(drawn);
        dv *= out.drawn->sauter_mean / pellet->diameter;
        p.scales.reserve(drawn.size());
        for (const double d : drawn)
            p.scales.push_back(d / out.drawn->sauter_mean);
    }
    out.unit = dv;
    p.particles = request.particles;
    p.seed = request.seed;
    p.shape = pellet->shape;
    p.friction = request.friction;
    p.wall_friction = request.wall_friction;
    p.max_steps = request.max_steps;
    p.layer_height = request.layer_height;
    if (request.container.empty()) {
        p.container = Container::tube(request.aspect_ratio);
    } else {
        const auto c = parse_container(request.container);
        if (!c)
            throw InvalidInput(container_not_allowed("--container", request.container));
        p.container = c->scaled(1.0 / dv);
    }
    // The sizes in the units the container was given in: --container's lengths (those of
    // --shape), or d_v for --aspect-ratio.
    const bool lengths = !request.container.empty();
    const FitWords words{lengths ? dv : 1.0, lengths ? "" : " d_v",
                         out.drawn ? "the largest pellet's bounding diameter"
                                   : "the pellet's bounding diameter"};
    if (const auto problem = p.container.fit_problem(
            2.0 * bounding_radius(p.shape, 0.5 * p.scale_range().second), words);
        !problem.empty())
        throw InvalidInput(
            fmt::format("--shape: '{}' does not fit in {}: {}", printable(request.shape),
                        lengths ? printable(request.container)
                                : fmt::format("a tube of a = {:g}", request.aspect_ratio),
                        problem));
    p.validate();
    if (!request.checkpoint.empty()) {
        check_path("--checkpoint", request.checkpoint);
        out.column = pellet_column(p);
        if (out.column.layers == 1)
            throw InvalidInput(fmt::format(
                "--checkpoint {}: only a pellet bed in layers can be resumed, this one is in "
                "one piece (its column {:.4g} d_v, --layer-height {}); allowed: a column above "
                "twice --layer-height, which is 10 or more",
                printable(request.checkpoint), out.column.height,
                p.layer_height > 0.0 ? fmt::format("{:g}", p.layer_height) : "none"));
    }
    return out;
}

std::optional<std::string> unsettled_pellets_warning(std::size_t touching_nothing,
                                                     std::size_t pellets) {
    // At rest under gravity every pellet rests on something: more than one in a hundred touching
    // nothing (and more than one in a small bed) is a column that was still falling when the
    // settling took it for still.
    if (touching_nothing <= std::max<std::size_t>(1, pellets / 100))
        return std::nullopt;
    return fmt::format("{} of {} pellets touch nothing at the end: the column had not settled (a "
                       "tall bed in one piece; relax it in layers with --layer-height, "
                       "docs/generate.md \"Tall pellet beds in layers\")",
                       touching_nothing, pellets);
}

nlohmann::json pellet_shape_summary(const PelletSpec& pellet) {
    nlohmann::json s;
    const auto* lobed = std::get_if<MultilobeShape>(&pellet.shape);
    if (!lobed)
        s = {{"kind", pellet.kind},
             {"spec", pellet.text},
             {"diameter", pellet.diameter},
             {"length", pellet.length},
             {"length_note", "the cylindrical part's: the caps' centres are L apart, the "
                             "pellet L + D long"}};
    else if (lobed->lobe.bore > 0.0)
        s = {{"kind", pellet.kind},
             {"spec", pellet.text},
             {"diameter", pellet.diameter},
             {"inner_diameter", pellet.inner_diameter},
             {"length", pellet.length}};
    else if (lobed->lobes == 1)
        s = {{"kind", pellet.kind},
             {"spec", pellet.text},
             {"diameter", pellet.diameter},
             {"length", pellet.length}};
    else
        s = {{"kind", pellet.kind},
             {"spec", pellet.text},
             {"lobes", lobed->lobes},
             {"lobe_diameter", pellet.diameter},
             {"circle_diameter", pellet.circle_diameter},
             {"length", pellet.length},
             {"lobe_0", "towards the body x axis, lobe k turned 360 k / lobes degrees "
                        "about the axis"}};
    s["volume_equivalent_diameter"] = pellet.volume_diameter;
    s["axis"] = "the body z axis: particles.csv's quaternion qw, qx, qy, qz turns it "
                "into the pellet's";
    s["r"] = "particles.csv's r is d_v / 2, the pellet's size";
    return s;
}

GeneratedPellets run_pellets(const PreparedPellets& prepared, const RunControl& control,
                             int threads,
                             const std::function<void(std::uint32_t, std::uint32_t)>& on_resume) {
    GeneratedPellets out;
    const auto start = std::chrono::steady_clock::now();
    const std::string& checkpoint = prepared.request.checkpoint;
    PelletLayerHooks hooks;
    std::optional<PelletCheckpoint> resume;
    if (!checkpoint.empty()) {
        // Now, not after the first layer; an output of the job from here on.
        check_writable_file("--checkpoint", checkpoint);
        std::error_code missing;
        if (std::filesystem::exists(std::filesystem::symlink_status(checkpoint, missing))) {
            resume = read_pellet_checkpoint(checkpoint, prepared.params, prepared.column);
            hooks.resume = &*resume;
            if (on_resume)
                on_resume(resume->layers_done, prepared.column.layers);
        }
        hooks.on_layer = [&](const PelletCheckpoint& state) {
            write_pellet_checkpoint(checkpoint, prepared.params, state);
        };
    }
    out.bed = generate_pellet_bed(prepared.params, control, hooks);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double dv = prepared.unit;
    out.packing = out.bed.packing;
    for (Vec3& c : out.packing.centers)
        c = c * dv;
    for (double& r : out.packing.radii)
        r *= dv;
    out.container = prepared.params.container.scaled(dv);

    using nlohmann::json;
    const PelletBedParameters& p = prepared.params;
    const PelletSpec& pellet = prepared.pellet;
    const PelletBed& bed = out.bed;
    json s;
    s["version"] = std::string(version);
    s["generator"] = std::holds_alternative<MultilobeShape>(pellet.shape)
                         ? "pellets: level-set contact and FIRE on positions and rotations "
                           "(docs/design.md, \"A bed of cylinder pellets\")"
                         : "pellets: springs on the exact depths and FIRE on positions and "
                           "rotations (docs/design.md, \"A bed of cylinder pellets\")";
    s["shape"] = pellet_shape_summary(pellet);
    if (prepared.drawn)
        s["sizes"] = {
            {"spec", prepared.request.sizes},
            {"fractions", to_string(prepared.request.fractions)},
            {"of", pellet.kind == "trilobe" || pellet.kind == "multilobe"
                       ? "DL, the lobes' diameter: each pellet is the shape scaled by its DL over "
                         "the shape's"
                       : "D, the pellet's diameter: each pellet is the shape scaled by its D over "
                         "the shape's"},
            {"reference_diameter",
             "d_v of the pellet at the Sauter mean d32 of the drawn sizes: a = D_tube / d_v, and "
             "particles.csv's r is each pellet's own d_v / 2"},
            {"volume_equivalent_diameter", dv},
            {"statistics", size_statistics_summary(*prepared.drawn)}};
    if (const auto a = p.container.tube_diameter())
        s["aspect_ratio"] = *a; // D_tube / d_v
    s["particles"] = p.particles;
    s["seed"] = p.seed;
    s["threads"] = threads;
    s["friction"] = p.friction;
    s["wall_friction"] = p.wall_friction;
    if (p.friction > 0.0 || p.wall_friction > 0.0)
        s["friction_let_go"] = {
            {"pairs", bed.sliding_pairs},
            {"walls", bed.sliding_walls},
            {"everywhere", !bed.friction_kept},
            {"note", "contacts whose overlap above the tolerance friction held at the end: "
                     "their friction was let go for the final relaxation (docs/generate.md, "
                     "\"Friction of pellets\")"}};
    const double top = std::visit(
        [&](const auto& shape) { return bed_top(shaped_bed(out.packing, shape)); }, pellet.shape);
    s["container"] = out.container.summary_json();
    s["container"]["height"] = top;
    s["container"]["bottom"] = 0.0;
    // The smallest pellet's (PelletBedParameters::scales).
    const double tol = p.tolerance * p.smallest_dimension() * p.scale_range().first * dv;
    s["tolerance"] = tol;
    s["max_penetration_pair"] = bed.max_depth_pair * dv;
    s["max_penetration_wall"] = bed.max_depth_wall * dv;
    s["max_node_depth"] = bed.max_depth_nodes * dv;
    s["force_residual"] = bed.residual_force;
    s["torque_residual"] = bed.residual_torque;
    s["residual_unit"] = "a pellet's weight (torque: times its bounding radius)";
    s["pellets_touching_nothing"] = bed.touching_nothing;
    if (auto warning = unsettled_pellets_warning(bed.touching_nothing, bed.packing.size()))
        s["warnings"] = {*warning};
    s["steps"] = bed.steps;
    if (bed.kicks > 0)
        s["kicks"] = {{"taps", bed.kicks},
                      {"note", "a layer locked flat in the final stage was tapped free: its "
                               "pellets tilted, the gravity raised again (docs/generate.md, "
                               "\"A floor layer squeezed flat\")"}};
    if (p.layer_height > 0.0) {
        s["layer_height"] = p.layer_height; // d_v
        s["layers"] = bed.layers;
    }
    s["seconds"] = seconds;
    s["nodes_per_pellet"] = bed.nodes;
    json stages = json::array();
    for (const PelletStage& st : bed.stages) {
        stages.push_back({{"name", st.name},
                          {"steps", st.steps},
                          {"gravity", st.gravity},
                          {"max_node_depth", st.max_depth * dv},
                          {"mass_centre_z", st.mass_centre_z * dv}});
        if (bed.layers > 1)
            stages.back()["layer"] = st.layer;
    }
    s["stages"] = stages;
    const double clearance = prepared.request.band_clearance * dv;
    if (top - clearance <= clearance)
        s["void_fraction_note"] = "the bed is lower than twice the band clearance";
    else {
        s["void_fraction"] = std::visit(
            [&](const auto& shape) {
                return void_fraction(shaped_bed(out.packing, shape), out.container, clearance,
                                     top - clearance);
            },
            pellet.shape);
        s["void_fraction_band"] = {clearance, top - clearance};
    }
    out.summary = s;
    return out;
}

void stage_pellet_bed(OutputDirectory& out, const GeneratedPellets& pellets) {
    out.stage("particles.csv", particles_csv(pellets.packing));
    out.stage("particles.vtu", particles_vtu(pellets.packing));
    out.stage("summary.json", json_file_text(pellets.summary, "summary.json"));
}

} // namespace packbed
