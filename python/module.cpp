// packbed._core: the library for Python (pybind11). A thin caller of the library's pipeline
// (packbed/pipeline.hpp), as the command line is; python/packbed/__init__.py re-exports it.
// Arrays: a Bed's centres and radii are numpy views of its own memory (no copy); everything
// else is copied into new arrays.
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "packbed/analysis.hpp"
#include "packbed/analysis_files.hpp"
#include "packbed/bed_checks.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/lattice.hpp"
#include "packbed/limits.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/output.hpp"
#include "packbed/periodic.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/random_array.hpp"
#include "packbed/read.hpp"
#include "packbed/version.hpp"
#include "packbed/volume.hpp"
#include "packbed/voxel.hpp"

namespace py = pybind11;
using namespace packbed;

namespace {

/// A bed: spheres with their own radii, the container they are in (when known) and the record
/// of how it was made or read (summary.json's content).
struct Bed {
    Packing packing;
    std::optional<Container> container;
    nlohmann::json summary = nlohmann::json::object();
};

/// The period along z of a bed's cell periodic on all six faces (a random array's: its
/// summary's period_z), or nothing.
std::optional<double> period_z_of(const Bed& bed) {
    if (bed.summary.is_object() && bed.summary.contains("period_z") &&
        bed.summary["period_z"].is_number())
        return bed.summary["period_z"].get<double>();
    return std::nullopt;
}

/// One profile of an analysis as numpy arrays: each bin's interval [low, high] and its value.
struct Profile {
    py::array_t<double> low, high, value;
};

Profile profile(const std::vector<ProfileBin>& bins) {
    Profile p{py::array_t<double>(static_cast<py::ssize_t>(bins.size())),
              py::array_t<double>(static_cast<py::ssize_t>(bins.size())),
              py::array_t<double>(static_cast<py::ssize_t>(bins.size()))};
    auto low = p.low.mutable_unchecked<1>(), high = p.high.mutable_unchecked<1>(),
         value = p.value.mutable_unchecked<1>();
    for (std::size_t i = 0; i < bins.size(); ++i) {
        const auto k = static_cast<py::ssize_t>(i);
        low(k) = bins[i].low;
        high(k) = bins[i].high;
        value(k) = bins[i].value;
    }
    return p;
}

/// Counts (a coordination histogram) as a numpy array of int64.
template <class T> py::array_t<std::int64_t> counts(const std::vector<T>& h) {
    py::array_t<std::int64_t> out(static_cast<py::ssize_t>(h.size()));
    for (std::size_t k = 0; k < h.size(); ++k)
        out.mutable_at(static_cast<py::ssize_t>(k)) = static_cast<std::int64_t>(h[k]);
    return out;
}

/// An analysis as Python sees it: the library's BedAnalysis, its numbers as summary.json has
/// them, and the container it was measured in.
struct Analysis {
    BedAnalysis analysis;
    nlohmann::json summary;
    Container container;
};

/// The properties an Analysis and a PelletAnalysis share (R's `analysis` has them): the void
/// fraction, the band, the reference diameter and the radial and axial profiles, each with its
/// docstring.
template <class R>
py::class_<R>& def_measured(py::class_<R>& c, const char* void_fraction, const char* diameter,
                            const char* radial, const char* axial) {
    return c
        .def_property_readonly(
            "void_fraction", [](const R& a) { return a.analysis.void_fraction; }, void_fraction)
        .def_property_readonly(
            "band",
            [](const R& a) {
                return std::make_pair(a.analysis.band.z_low, a.analysis.band.z_high);
            },
            "The band (z_low, z_high) the numbers refer to (length).")
        .def_property_readonly(
            "diameter", [](const R& a) { return a.analysis.diameter; }, diameter)
        .def_property_readonly(
            "radial_void_fraction",
            [](const R& a) { return profile(a.analysis.radial_void_fraction); }, radial)
        .def_property_readonly(
            "axial_void_fraction",
            [](const R& a) { return profile(a.analysis.axial_void_fraction); }, axial);
}

/// A pellet bed's analysis as Python sees it: analyze_pellet_bed's numbers, summary.json's
/// record of them, and the container.
struct PelletAnalysisResult {
    PelletAnalysis analysis;
    nlohmann::ordered_json summary;
    Container container;
};

/// JSON to Python objects, through Python's own json module (exact for every double: both
/// write and read shortest round-trip text).
py::object to_python(const nlohmann::json& value) {
    return py::module_::import("json").attr("loads")(
        value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

/// Each of `warnings` as a Python UserWarning (the command line prints them on stderr).
void warn(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings)
        if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0)
            throw py::error_already_set();
}

/// A flat record (progress_json) as a dict, in its order, each number as it is (a NaN stays a
/// float: JSON text would make it None).
py::dict flat_dict(const nlohmann::ordered_json& record) {
    py::dict out;
    for (const auto& [key, value] : record.items()) {
        const py::str name(key);
        if (value.is_string())
            out[name] = value.get<std::string>();
        else if (value.is_number_unsigned())
            out[name] = value.get<std::uint64_t>();
        else if (value.is_number_integer())
            out[name] = value.get<std::int64_t>();
        else
            out[name] = value.get<double>();
    }
    return out;
}

/// Run `work` without the GIL, checking for Ctrl-C (Python's SIGINT flag) from the calling
/// thread through `control.should_stop`, which the library calls every mc_period iterations.
/// A signal turns into KeyboardInterrupt; a progress callback's exception goes through.
template <class Work>
auto run_interruptible(RunControl& control, const py::object& progress, Work&& work) {
    if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
        throw InvalidInput(fmt::format("progress: {} is not allowed; allowed: None or a function "
                                       "called with one dict",
                                       printable(std::string(py::repr(progress)).substr(0, 80))));
    std::optional<py::error_already_set> callback_error;
    bool interrupted = false;
    control.should_stop = [&] {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
            PyErr_Clear();
            interrupted = true;
        }
        return interrupted || callback_error.has_value();
    };
    if (!progress.is_none())
        control.on_progress = [&](const Progress& p) {
            py::gil_scoped_acquire gil;
            if (callback_error)
                return;
            try {
                progress(flat_dict(progress_json(p)));
            } catch (py::error_already_set& e) {
                callback_error.emplace(std::move(e));
            }
        };
    try {
        py::gil_scoped_release released;
        return work();
    } catch (const Cancelled&) {
        if (callback_error)
            throw std::move(*callback_error);
        if (interrupted) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
            throw py::error_already_set();
        }
        throw;
    }
}

/// threads=N as the command line's --threads (packbed::use_threads); None: OpenMP's default.
void set_threads(const std::optional<long long>& threads) {
    if (threads)
        use_threads(check_option("threads", *threads, option_range::threads));
}

/// A vector's bytes, and a vector of T from bytes (pickling a Bed: its numbers exactly).
template <class T> py::bytes bytes_of(const std::vector<T>& v) {
    return py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}
template <class T> std::vector<T> vector_of(const py::bytes& b, std::size_t count) {
    const std::string text = b;
    if (text.size() != count * sizeof(T))
        throw InvalidInput("Bed: a pickled state of the wrong size is not allowed; allowed: the "
                           "state a Bed's pickling gives");
    std::vector<T> v(count);
    std::memcpy(v.data(), text.data(), text.size());
    return v;
}

/// A Bed's pickled state: its count, centres, radii, orientations and types as bytes (exact),
/// the container's record and the summary as JSON text (doubles printed to round-trip).
py::tuple bed_state(const Bed& bed) {
    const Packing& p = bed.packing;
    return py::make_tuple(p.size(), bytes_of(p.centers), bytes_of(p.radii),
                          bytes_of(p.orientations), bytes_of(p.types),
                          bed.container ? py::object(py::str(bed.container->summary_json().dump()))
                                        : py::none(),
                          bed.summary.dump());
}

Bed bed_from_state(const py::tuple& state) {
    if (state.size() != 7)
        throw InvalidInput("Bed: a pickled state of the wrong size is not allowed; allowed: the "
                           "state a Bed's pickling gives");
    const auto n = state[0].cast<std::size_t>();
    if (n > limits::max_spheres)
        throw InvalidInput(fmt::format("Bed: a pickled state of {} spheres is not allowed; "
                                       "allowed: at most {}",
                                       n, limits::max_spheres));
    Bed bed;
    bed.packing.centers = vector_of<Vec3>(state[1], n);
    bed.packing.radii = vector_of<double>(state[2], n);
    const std::size_t turned = py::len(state[3]) == 0 ? 0 : n;
    bed.packing.orientations = vector_of<Quaternion>(state[3], turned);
    const std::size_t typed = py::len(state[4]) == 0 ? 0 : n;
    bed.packing.types = vector_of<std::uint32_t>(state[4], typed);
    if (!state[5].is_none()) {
        const ContainerRecord record =
            container_from_record(nlohmann::json::parse(state[5].cast<std::string>()));
        if (!record.container)
            throw InvalidInput("Bed: a pickled container is not allowed: " + record.allowed);
        bed.container = record.container;
    }
    bed.summary = nlohmann::json::parse(state[6].cast<std::string>());
    return bed;
}

/// `array` made read-only: a bed's arrays view its memory, which was checked when the bed was
/// made (finite, in range, inside its container) and which every call trusts.
py::array read_only(py::array array) {
    array.attr("setflags")(py::arg("write") = false);
    return array;
}

/// The container `container` names, else the bed's own. A container given is checked to hold
/// the bed, as `packbed analyze --container` checks it (spheres 0.01 of their mean diameter,
/// pellets 0.01 d_v by their exact shapes). \throws InvalidInput when neither is there, or
/// when the bed does not fit the container given
Container container_for(const Bed& bed, const std::optional<std::string>& container,
                        const PelletSpec* pellet) {
    if (container) {
        const Container given = container_from_spec("--container", *container);
        if (pellet)
            check_pellets_inside(bed.packing, {}, "centers", given, *pellet, 0.01);
        else if (bed.packing.size() > 0)
            check_inside(bed.packing, {}, "centers", given, 0.01 * bed.packing.mean_diameter(),
                         false);
        return given;
    }
    if (!bed.container)
        throw InvalidInput(fmt::format("--container is needed: this bed has no container (give "
                                       "container='SPEC', SPEC one of {})",
                                       forms_but("")));
    return *bed.container;
}

/// A whole number given to the module as a Python object, checked with the command line's
/// words (check_whole): an int of any size (a seed up to 2^64 - 1) or a numpy integer (what
/// np.arange gives), never a bool (Python's or numpy's), a float or a string (which numpy or
/// pybind11 would convert).
std::uint64_t whole(const py::handle& value, std::string_view option, const WholeRange& range) {
    const bool boolean = PyBool_Check(value.ptr()) ||
                         py::isinstance(value, py::module_::import("numpy").attr("bool_"));
    if (boolean || !PyIndex_Check(value.ptr()))
        throw InvalidInput(fmt::format("--{}: '{}' is not allowed; allowed: {}", option,
                                       printable(std::string(py::str(value)).substr(0, 80)),
                                       range.allowed()));
    const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    if (!index)
        throw py::error_already_set();
    return check_whole(option, std::string(py::str(index)), range);
}

/// generate(shape=...): a bed of pellets (docs/generate.md, "Pellets"), as `packbed generate
/// --shape` makes it; `sphere_only` names each sphere option and whether it was given another
/// value than its default (refused, as the command line refuses it).
Bed generate_pellets(std::optional<double> aspect_ratio,
                     const std::optional<std::string>& container, const py::object& particles,
                     const py::object& seed, double band_clearance,
                     std::optional<long long> threads, const py::object& progress,
                     const std::optional<std::filesystem::path>& out, bool force,
                     const std::string& shape, double friction, double wall_friction,
                     std::optional<long long> max_iterations, const std::string& sizes,
                     const std::string& fractions, std::optional<double> layer_height,
                     const std::optional<std::filesystem::path>& checkpoint,
                     const std::vector<std::pair<std::string, bool>>& sphere_only) {
    namespace range = option_range;
    for (const auto& [name, given] : sphere_only)
        if (given)
            throw InvalidInput(fmt::format(
                "{} is not allowed with shape='{}'; allowed with a pellet: aspect_ratio, "
                "container, particles, seed, sizes, fractions, layer_height, checkpoint, "
                "band_clearance, friction, wall_friction, max_iterations, threads, progress, "
                "out, force "
                "(docs/generate.md, \"Pellets\")",
                name, printable(std::string_view(shape).substr(0, 80))));
    if (aspect_ratio && container)
        throw InvalidInput(fmt::format("--aspect-ratio {} and --container {} are both given; "
                                       "allowed: one of the two",
                                       *aspect_ratio, printable(container->substr(0, 80))));
    PelletRequest request;
    request.shape = shape;
    request.particles = whole(particles, "particles", range::particles);
    request.seed = whole(seed, "seed", range::seed);
    if (aspect_ratio)
        request.aspect_ratio = check_option("aspect-ratio", *aspect_ratio, range::aspect_ratio);
    request.container = container.value_or("");
    request.band_clearance = check_option("band-clearance", band_clearance, range::band_clearance);
    request.friction = check_option("friction", friction, range::friction);
    request.wall_friction = check_option("wall-friction", wall_friction, range::friction);
    if (max_iterations)
        request.max_steps = check_option("max-iterations", *max_iterations, range::max_iterations);
    request.sizes = sizes;
    request.fractions = fraction_bases().at(fractions);
    if (layer_height)
        request.layer_height =
            check_option("layer-height", *layer_height, option_range::layer_height);
    request.checkpoint = checkpoint ? checkpoint->string() : std::string();
    const PreparedPellets prepared = prepare_pellets(request);
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(*out, "--out", OutputKind::directory, force);
    set_threads(threads);
    RunControl control;
    GeneratedPellets pellets = run_interruptible(
        control, progress, [&] { return run_pellets(prepared, control, threads_in_use()); });
    if (directory) {
        stage_pellet_bed(*directory, pellets);
        directory->commit();
    }
    return Bed{std::move(pellets.packing), pellets.container, std::move(pellets.summary)};
}

/// Raise ValueError for a bed with orientations whose summary names no pellet shape.
void refuse_pellets(const Bed& bed, std::string_view what) {
    if (bed.packing.orientations.empty())
        return;
    throw InvalidInput(fmt::format(
        "{} of a bed with orientations but no pellet shape in its summary is not allowed; "
        "allowed: a bed of spheres, or of pellets from generate(shape=...) or read()",
        what));
}

/// What the bed's summary records (read_bed_summary: its friction and wall friction, checked
/// as packbed export checks a summary.json).
BedSummary recorded(const Bed& bed) {
    return read_bed_summary(bed.summary, "the bed's summary");
}

/// The pellet of a bed with orientations (its summary's shape.spec: generate(shape=...) and
/// read() of a pellet bed record it); nothing for a bed of spheres. Raises ValueError for
/// orientations without a shape that `what` can read.
std::optional<PelletSpec> bed_pellet(const Bed& bed, std::string_view what) {
    if (bed.packing.orientations.empty())
        return std::nullopt;
    std::optional<PelletSpec> pellet;
    const auto spec = bed.summary.find("shape");
    if (spec != bed.summary.end() && spec->is_object() && spec->contains("spec") &&
        (*spec)["spec"].is_string())
        pellet = parse_pellet_shape((*spec)["spec"].get<std::string>());
    if (!pellet)
        refuse_pellets(bed, what);
    // A bed with sizes: its pellets' D from the smallest to the largest drawn.
    if (const auto range = recorded(bed).size_range)
        pellet->scales = {range->first / pellet->diameter, range->second / pellet->diameter};
    return pellet;
}

Bed generate(std::optional<double> aspect_ratio, const std::optional<std::string>& container,
             const py::object& particles, const py::object& seed, double diameter,
             const std::string& sizes, const std::string& fractions, double e0, double ck,
             double cg_step, std::optional<double> overlap_low, std::optional<double> overlap_high,
             double tolerance, long long mc_period, long long mc_window,
             std::optional<double> mc_tolerance, const std::string& update,
             const std::string& solver, std::optional<double> skin,
             std::optional<double> layer_height, double friction, double wall_friction,
             std::optional<double> target_void_fraction,
             const std::optional<std::filesystem::path>& checkpoint,
             std::optional<long long> max_iterations, double band_clearance,
             std::optional<long long> threads, const py::object& progress,
             const std::optional<std::filesystem::path>& out, bool force, const std::string& engine,
             long long ranks, const std::optional<std::string>& mpi_command, const std::string& lmp,
             const std::string& shape) {
    // The spheres' options a pellet bed refuses when given other values than their defaults.
    const SoftSphereParameters defaults;
    if (shape != "sphere")
        return generate_pellets(aspect_ratio, container, particles, seed, band_clearance, threads,
                                progress, out, force, shape, friction, wall_friction,
                                max_iterations, sizes, fractions, layer_height, checkpoint,
                                {{"diameter", diameter != defaults.diameter},
                                 {"e0", e0 != defaults.e0},
                                 {"ck", ck != defaults.ck},
                                 {"cg_step", cg_step != defaults.cg_step},
                                 {"overlap_low", overlap_low.has_value()},
                                 {"overlap_high", overlap_high.has_value()},
                                 {"tolerance", tolerance != defaults.tolerance},
                                 {"mc_period", mc_period != defaults.mc_period},
                                 {"mc_window", mc_window != defaults.mc_window},
                                 {"mc_tolerance", mc_tolerance.has_value()},
                                 {"update", update != to_string(defaults.update)},
                                 {"solver", solver != to_string(defaults.solver)},
                                 {"skin", skin.has_value()},
                                 {"target_void_fraction", target_void_fraction.has_value()},
                                 {"engine", engine != to_string(Engine::packbed)},
                                 {"ranks", ranks != 1},
                                 {"mpi_command", mpi_command.has_value()},
                                 {"lmp", lmp != "lmp"}});
    GenerateRequest request;
    SoftSphereParameters& p = request.params;
    namespace range = option_range;
    if (aspect_ratio && container) // the command line's words (CLI11's excludes)
        throw InvalidInput(fmt::format("--aspect-ratio {} and --container {} are both given; "
                                       "allowed: one of the two",
                                       *aspect_ratio, printable(container->substr(0, 80))));
    if (aspect_ratio)
        request.aspect_ratio = check_option("aspect-ratio", *aspect_ratio, range::aspect_ratio);
    p.particles = whole(particles, "particles", range::particles);
    p.seed = whole(seed, "seed", range::seed);
    p.diameter = check_option("diameter", diameter, range::diameter);
    p.e0 = check_option("e0", e0, range::e0);
    p.ck = check_option("ck", ck, range::ck);
    p.cg_step = check_option("cg-step", cg_step, range::cg_step);
    if (overlap_low)
        p.overlap_low = check_option("overlap-low", *overlap_low, range::overlap_bound);
    if (overlap_high)
        p.overlap_high = check_option("overlap-high", *overlap_high, range::overlap_bound);
    p.tolerance = check_option("tolerance", tolerance, range::tolerance);
    p.mc_period =
        static_cast<std::uint32_t>(check_option("mc-period", mc_period, range::mc_period));
    p.mc_window =
        static_cast<std::uint32_t>(check_option("mc-window", mc_window, range::mc_window));
    if (mc_tolerance)
        p.mc_tolerance = check_option("mc-tolerance", *mc_tolerance, range::mc_tolerance);
    p.update = update_orders().at(update);
    p.solver = solvers().at(solver);
    if (skin)
        p.skin = check_option("skin", *skin, range::skin);
    if (layer_height)
        p.layer_height = check_option("layer-height", *layer_height, range::layer_height);
    p.friction = check_option("friction", friction, range::friction);
    p.wall_friction = check_option("wall-friction", wall_friction, range::friction);
    if (target_void_fraction)
        request.target_void_fraction = check_option("target-void-fraction", *target_void_fraction,
                                                    range::void_fraction_target);
    if (max_iterations)
        p.max_iterations = check_option("max-iterations", *max_iterations, range::max_iterations);
    request.sizes = sizes;
    request.fractions = fraction_bases().at(fractions);
    request.container = container.value_or("");
    request.checkpoint = checkpoint ? checkpoint->string() : std::string();
    request.band_clearance = check_option("band-clearance", band_clearance, range::band_clearance);
    request.engine = engines().at(engine);
    request.launcher.ranks =
        static_cast<std::uint32_t>(check_option("ranks", ranks, range::lammps_ranks));
    request.launcher.mpi_command = mpi_command.value_or("");
    request.launcher.lmp = lmp;
    const PreparedGeneration prepared = prepare_generation(request);
    // The LAMMPS engine runs in a folder: `out`'s staging folder, or a temporary one removed
    // with what LAMMPS wrote there (the directory is never committed).
    std::filesystem::path scratch;
    struct RemoveScratch {
        const std::filesystem::path& path;
        ~RemoveScratch() {
            std::error_code ignored;
            if (!path.empty())
                std::filesystem::remove_all(path, ignored);
        }
    } remove_scratch{scratch};
    std::optional<OutputDirectory> directory; // destroyed (its staging removed) before scratch
    if (out) {
        directory.emplace(*out, "--out", OutputKind::directory, force);
    } else if (request.engine == Engine::lammps) {
        std::string name =
            (std::filesystem::temp_directory_path() / "packbed-lammps-XXXXXX").string();
        if (::mkdtemp(name.data()) == nullptr)
            throw std::runtime_error("cannot create a temporary folder for LAMMPS in " +
                                     std::filesystem::temp_directory_path().string());
        scratch = name;
        directory.emplace(scratch, "--out", OutputKind::directory, false);
    }
    set_threads(threads);
    RunControl control;
    GeneratedBed generated = run_interruptible(control, progress, [&] {
        return generate_bed(prepared, control, threads_in_use(), directory ? &*directory : nullptr);
    });
    Bed bed{std::move(generated.result.packing), generated.result.container,
            std::move(generated.summary)};
    if (out) {
        stage_bed(*directory, bed.packing, *bed.container, band_clearance,
                  bed.summary["void_fraction"].is_number(), bed.summary);
        directory->commit();
    }
    return bed;
}

/// The reading options of `read` and `analyze_frames`, every value checked as the command line
/// checks --format, --frame, --axis, --floor, --diameter, --outside-tolerance and --container.
ReadOptions read_options_of(const std::filesystem::path& path, const std::string& format,
                            long long frame, std::optional<std::pair<double, double>> axis,
                            double floor, std::optional<double> diameter,
                            const std::optional<std::string>& container, double outside_tolerance) {
    check_path("path", path);
    ReadOptions options;
    options.format = particle_formats().at(format);
    if (frame == 0)
        throw InvalidInput("--frame: 0 is not allowed; allowed: a whole number other than 0: 1 "
                           "the first frame, -1 the last");
    options.frame = frame;
    if (axis)
        options.axis = {axis->first, axis->second};
    options.floor = check_option("floor", floor, option_range::floor_height);
    if (diameter)
        options.radius = 0.5 * check_option("diameter", *diameter, option_range::diameter);
    check_option("outside-tolerance", outside_tolerance, option_range::outside_tolerance);
    if (container)
        container_from_spec("--container", *container); // its own message for a bad spec
    return options;
}

/// A bed read from the file `path` (one frame of it) in its container, with its record.
Bed file_bed(const std::filesystem::path& path, ParticleFile&& file,
             std::optional<Container> container) {
    Bed bed{std::move(file.packing), std::move(container), nlohmann::json::object()};
    bed.summary["particles_file"] = path.string();
    bed.summary["particles"] = bed.packing.size();
    bed.summary["frame"] = file.frame;
    if (bed.container)
        bed.summary["container"] = bed.container->summary_json();
    // A random array's cube, periodic along z too: voxelize and export take its period.
    if (const std::optional<double> period_z = period_z_beside(path))
        bed.summary["period_z"] = *period_z;
    return bed;
}

Bed read_bed(const std::filesystem::path& path, const std::string& format, long long frame,
             std::optional<std::pair<double, double>> axis, double floor,
             std::optional<double> diameter, const std::optional<std::string>& container,
             double outside_tolerance) {
    const ReadOptions options =
        read_options_of(path, format, frame, axis, floor, diameter, container, outside_tolerance);
    BedInContainer read =
        read_bed_or_pellets(path, options, container.value_or(""), 0.0, outside_tolerance);
    Bed bed = file_bed(path, std::move(read.file), std::move(read.container));
    if (read.pellet) {
        bed.summary["shape"] = pellet_shape_summary(*read.pellet);
        if (read.pellet->scales != std::pair{1.0, 1.0}) // the sizes recorded beside the file
            bed.summary["sizes"] = {
                {"statistics",
                 {{"smallest", read.pellet->scales.first * read.pellet->diameter},
                  {"largest", read.pellet->scales.second * read.pellet->diameter}}}};
    }
    return bed;
}

/// The band's clearance from the ends (None: AnalysisOptions's 1 Dp), refused beside a fixed
/// band as the command line refuses --band-clearance with --band.
double band_clearance_of(std::optional<double> band_clearance,
                         const std::optional<std::pair<double, double>>& band) {
    if (band && band_clearance)
        throw InvalidInput(fmt::format("band_clearance {} and band ({}, {}) are both given; "
                                       "allowed: one of the two",
                                       *band_clearance, band->first, band->second));
    return check_option("band-clearance", band_clearance.value_or(AnalysisOptions{}.band_clearance),
                        option_range::band_clearance);
}

py::dict analyze_frames(const std::filesystem::path& path, const std::string& format,
                        std::optional<std::pair<double, double>> axis, double floor,
                        std::optional<double> diameter, const std::optional<std::string>& container,
                        double outside_tolerance, std::optional<std::pair<double, double>> band,
                        std::optional<double> band_clearance, std::optional<long long> threads) {
    const ReadOptions options =
        read_options_of(path, format, -1, axis, floor, diameter, container, outside_tolerance);
    AnalysisOptions analysis;
    if (diameter)
        analysis.diameter = *diameter;
    if (band)
        analysis.band = Band{band->first, band->second};
    analysis.band_clearance = band_clearance_of(band_clearance, band);
    const std::optional<Container> found = find_container(path, container.value_or(""));
    if (!found)
        throw InvalidInput(fmt::format("--container is needed: no summary.json with a container "
                                       "next to {}",
                                       printable(path.native())));
    set_threads(threads);
    FrameSeries series;
    {
        py::gil_scoped_release released;
        series = void_fraction_series(path, options, *found, analysis, outside_tolerance);
    }
    const auto n = static_cast<py::ssize_t>(series.frames.size());
    py::array_t<std::int64_t> frame(n), particles(n);
    py::array_t<double> timestep(n), void_fraction(n);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (py::ssize_t i = 0; i < n; ++i) {
        const FrameVoidFraction& row = series.frames[static_cast<std::size_t>(i)];
        frame.mutable_at(i) = static_cast<std::int64_t>(row.frame);
        particles.mutable_at(i) = static_cast<std::int64_t>(row.particles);
        timestep.mutable_at(i) = row.timestep ? static_cast<double>(*row.timestep) : nan;
        void_fraction.mutable_at(i) = row.void_fraction.value_or(nan);
    }
    py::dict result;
    result["frame"] = frame;
    result["timestep"] = timestep;
    result["void_fraction"] = void_fraction;
    result["particles"] = particles;
    result["last"] = py::cast(file_bed(path, std::move(series.last), found));
    return result;
}

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `value` as an array of doubles, refused where numpy's conversion would lose or invent part
/// of it: a masked array (the mask would be dropped), complex numbers (the imaginary part),
/// booleans, strings and other objects (not numbers).
Doubles real_numbers(const py::object& value, std::string_view name) {
    if (py::module_::import("numpy.ma").attr("isMaskedArray")(value).cast<bool>())
        throw InvalidInput(fmt::format("{}: a masked array is not allowed; allowed: an array of "
                                       "numbers (fill or remove the masked values first)",
                                       name));
    const py::array array = py::module_::import("numpy").attr("asarray")(value);
    const char kind = array.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw InvalidInput(fmt::format("{}: an array of dtype {} is not allowed; allowed: real "
                                       "numbers (float or int)",
                                       name, std::string(py::str(array.dtype()))));
    return Doubles::ensure(array);
}

/// An array's shape as numpy prints it: (5,), (5, 2), ().
std::string shape_of(const py::array& a) {
    std::vector<py::ssize_t> sizes(a.shape(), a.shape() + a.ndim());
    return a.ndim() == 1 ? fmt::format("({},)", sizes[0])
                         : fmt::format("({})", fmt::join(sizes, ", "));
}

/// A bed of pellets from numpy arrays (from_arrays given `shape`): the radii each pellet's d_v / 2
/// (the shape's, or those given: the shape scaled by each one's over the shape's), the
/// orientations unit quaternions within 1e-3 (normalised as read() takes a file's, those of
/// norm 1 within 1e-15 kept as they are), the summary's shape and sizes as read() records
/// them, the pellets checked inside the container by their exact shapes.
void add_pellets(Bed& bed, PelletSpec pellet, const std::optional<py::object>& given,
                 const std::optional<std::string>& container) {
    const std::size_t n = bed.packing.size();
    if (!given || given->is_none())
        throw InvalidInput(fmt::format("orientations: none for a bed of {} pellets is not allowed; "
                                       "allowed: an array (N, 4) of unit quaternions qw, qx, qy, "
                                       "qz (the pellet's axis its body z axis turned)",
                                       pellet.kind));
    const Doubles q = real_numbers(*given, "orientations");
    if (q.ndim() != 2 || q.shape(1) != 4 || static_cast<std::size_t>(q.shape(0)) != n)
        throw InvalidInput(fmt::format("orientations: an array of shape {} for {} centres is not "
                                       "allowed; allowed: shape ({}, 4)",
                                       shape_of(q), n, n));
    const auto at = q.unchecked<2>();
    bed.packing.orientations.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto k = static_cast<py::ssize_t>(i);
        const Quaternion o{at(k, 0), at(k, 1), at(k, 2), at(k, 3)};
        const double length = std::sqrt(o.w * o.w + o.x * o.x + o.y * o.y + o.z * o.z);
        if (!(std::abs(length - 1.0) <= 1e-3))
            throw InvalidInput(fmt::format("orientations[{}]: ({}, {}, {}, {}) has norm {}; "
                                           "allowed: a unit quaternion (norm 1 within 1e-3)",
                                           i, o.w, o.x, o.y, o.z, length));
        // exactly as given where it is a unit quaternion to rounding (a bed's own, read())
        bed.packing.orientations[i] = std::abs(length - 1.0) <= 1e-15 ? o : normalized(o);
    }
    const double radius = 0.5 * pellet.volume_diameter;
    if (n > 0) {
        const auto [low, high] =
            std::minmax_element(bed.packing.radii.begin(), bed.packing.radii.end());
        pellet.scales = {*low / radius, *high / radius};
    }
    if (pellet.scales != std::pair{1.0, 1.0}) // the sizes as read() records them
        bed.summary["sizes"] = {{"statistics",
                                 {{"smallest", pellet.scales.first * pellet.diameter},
                                  {"largest", pellet.scales.second * pellet.diameter}}}};
    bed.summary["shape"] = pellet_shape_summary(pellet);
    if (container) {
        bed.container = container_from_spec("--container", *container);
        check_pellets_inside(bed.packing, {}, "centers", *bed.container, pellet, 0.01);
        bed.summary["container"] = bed.container->summary_json();
    }
}

/// A bed from numpy arrays: centres (N x 3) and radii (N), or one diameter for all; given a
/// pellet `shape`, its pellets with their orientations (add_pellets); given `period_z`, spheres
/// in a cell periodic along z too (a random array's, summary.json's period_z).
Bed from_arrays(const py::object& centers_given, const std::optional<py::object>& radii_given,
                std::optional<double> diameter, const std::optional<std::string>& container,
                const std::optional<py::object>& orientations, const std::string& shape,
                std::optional<double> period_z) {
    const bool pellets = shape != "sphere";
    if (period_z && (pellets || !container || container->rfind("periodic:", 0) != 0))
        throw InvalidInput(fmt::format(
            "period_z {}: not allowed {}; allowed: with spheres in a periodic container "
            "(container='periodic:LX,LY'), a cell periodic on all six faces",
            *period_z, pellets ? "with a pellet shape" : "without a periodic container"));
    if (period_z)
        check_option("container-height", *period_z, option_range::container_height);
    if (!pellets && orientations && !orientations->is_none())
        throw InvalidInput("orientations: not allowed for a bed of spheres; allowed: with "
                           "shape='cylinder:D,L' (or another pellet) naming the pellets turned");
    if (pellets && diameter)
        throw InvalidInput("diameter: not allowed with a pellet shape; allowed: radii (each "
                           "pellet's d_v / 2) or none (every pellet the shape's size)");
    std::optional<PelletSpec> pellet;
    if (pellets) {
        pellet = parse_pellet_shape(shape);
        if (!pellet)
            throw InvalidInput(fmt::format("--shape: '{}' is not allowed; allowed: {}",
                                           printable(shape.substr(0, 80)), allowed_shapes()));
        diameter = pellet->volume_diameter; // where no radii are given, each pellet's d_v
    }
    const Doubles centers = real_numbers(centers_given, "centers");
    std::optional<Doubles> radii;
    if (radii_given && !radii_given->is_none())
        radii = real_numbers(*radii_given, "radii");
    if (centers.ndim() != 2 || centers.shape(1) != 3)
        throw InvalidInput(fmt::format("centers: an array of shape {} is not allowed; "
                                       "allowed: shape (N, 3)",
                                       shape_of(centers)));
    const auto n = static_cast<std::size_t>(centers.shape(0));
    if (n > limits::max_spheres)
        throw InvalidInput(fmt::format("centers: {} spheres are not allowed; allowed: at most {}",
                                       n, limits::max_spheres));
    if (!pellets && radii.has_value() == diameter.has_value())
        throw InvalidInput("radii and diameter: exactly one is allowed (radii, an array of N "
                           "radii, or diameter, one for every sphere)");
    if (radii && (radii->ndim() != 1 || static_cast<std::size_t>(radii->shape(0)) != n))
        throw InvalidInput(fmt::format("radii: an array of shape {} for {} centres is not "
                                       "allowed; allowed: shape ({},), one radius per centre",
                                       shape_of(*radii), n, n));
    Bed bed;
    bed.packing.centers.resize(n);
    bed.packing.radii.resize(n);
    const auto c = centers.unchecked<2>();
    for (std::size_t i = 0; i < n; ++i) {
        const auto k = static_cast<py::ssize_t>(i);
        const Vec3 v{c(k, 0), c(k, 1), c(k, 2)};
        const double r = radii ? radii->at(k) : 0.5 * *diameter;
        if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
              std::abs(v.x) <= limits::max_length && std::abs(v.y) <= limits::max_length &&
              std::abs(v.z) <= limits::max_length))
            throw InvalidInput(fmt::format("centers[{}]: ({}, {}, {}) is not allowed; allowed: "
                                           "finite numbers within {:g}",
                                           i, v.x, v.y, v.z, limits::max_length));
        if (!(r >= 0.5 * limits::min_diameter && r <= 0.5 * limits::max_diameter))
            throw InvalidInput(fmt::format("radii[{}]: {} is not allowed; allowed: {:g} to {:g}", i,
                                           r, 0.5 * limits::min_diameter,
                                           0.5 * limits::max_diameter));
        bed.packing.centers[i] = v;
        bed.packing.radii[i] = r;
    }
    if (pellets) {
        add_pellets(bed, *pellet, orientations, container);
    } else if (container) {
        bed.container = container_from_spec("--container", *container);
        check_inside(bed.packing, {}, "centers", *bed.container,
                     0.01 * (n > 0 ? bed.packing.mean_diameter() : 0.0), false, period_z);
        bed.summary["container"] = bed.container->summary_json();
        if (period_z) // as read() records a random array's
            bed.summary["period_z"] = *period_z;
    }
    bed.summary["particles"] = n;
    return bed;
}

/// analyze() of a bed of pellets, as `packbed analyze` measures one (analyze_pellet_bed):
/// `options` checked, the spheres' own options refused by the caller.
PelletAnalysisResult analyze_pellets(const Bed& bed, const PelletSpec& pellet,
                                     const Container& given, const AnalysisOptions& options,
                                     std::optional<long long> threads,
                                     const std::optional<std::filesystem::path>& out, bool force) {
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(*out, "--out", OutputKind::directory, force);
    set_threads(threads);
    PelletAnalysisResult result{{}, {}, given};
    {
        py::gil_scoped_release released;
        result.analysis = analyze_pellet_bed(bed.packing, pellet.shape, given, options);
    }
    result.summary = pellet_analysis_summary(result.analysis, pellet.text, bed.packing.size(),
                                             given, options.contact_tolerance);
    if (directory) {
        for (const auto& [name, text] : pellet_analysis_files(result.analysis, given))
            directory->stage(name, text);
        directory->stage("summary.json", json_file_text(result.summary, "summary.json"));
        directory->commit();
    }
    return result;
}

py::object analyze(const Bed& bed, const std::optional<std::string>& container,
                   std::optional<std::pair<double, double>> band,
                   std::optional<double> band_clearance, std::optional<double> diameter,
                   double shell_width, double slab_height, std::optional<double> centre_bin,
                   double contact_tolerance, std::optional<double> rdf_range,
                   std::optional<double> rdf_bin, std::optional<double> friction,
                   std::optional<long long> threads,
                   const std::optional<std::filesystem::path>& out, bool force) {
    const std::optional<PelletSpec> pellet = bed_pellet(bed, "analyze");
    if (pellet) // the spheres' measures that a bed of pellets has no use for
        for (const auto& [name, given] : {std::pair{"diameter", diameter.has_value()},
                                          std::pair{"centre_bin", centre_bin.has_value()},
                                          std::pair{"rdf_range", rdf_range.has_value()},
                                          std::pair{"rdf_bin", rdf_bin.has_value()},
                                          std::pair{"friction", friction.has_value()}})
            if (given)
                throw InvalidInput(fmt::format(
                    "{} is not allowed for a bed of {} pellets; allowed with pellets: container, "
                    "band, band_clearance, shell_width, slab_height, contact_tolerance, threads, "
                    "out and force (lengths in d_v)",
                    name, pellet->text));
    const Container given = container_for(bed, container, pellet ? &*pellet : nullptr);
    namespace range = option_range;
    AnalysisOptions options;
    if (diameter)
        options.diameter = check_option("diameter", *diameter, range::diameter);
    options.band_clearance = band_clearance_of(band_clearance, band);
    if (band)
        options.band = Band{band->first, band->second};
    options.shell_width = check_option("shell-width", shell_width, range::shell_width);
    options.slab_height = check_option("slab-height", slab_height, range::slab_height);
    options.contact_tolerance =
        check_option("contact-tolerance", contact_tolerance, range::contact_tolerance);
    if (pellet)
        return py::cast(analyze_pellets(bed, *pellet, given, options, threads, out, force));
    if (centre_bin)
        options.centre_bin = check_option("centre-bin", *centre_bin, range::centre_bin);
    if (rdf_range)
        options.rdf_range = check_option("rdf-range", *rdf_range, range::rdf_range);
    options.rdf_range_given = rdf_range.has_value();
    if (rdf_bin)
        options.rdf_bin = check_option("rdf-bin", *rdf_bin, range::rdf_bin);
    options.frictional = (friction ? check_option("friction", *friction, range::friction)
                                   : recorded(bed).friction.value_or(0.0)) > 0.0;
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(*out, "--out", OutputKind::directory, force);
    set_threads(threads);
    Analysis result{{}, {}, given};
    {
        py::gil_scoped_release released;
        AnalyzeJob job =
            analyze_job(bed.packing, given, options, directory ? &*directory : nullptr);
        result.analysis = std::move(job.analysis);
        result.summary = std::move(job.summary);
    }
    if (directory) {
        directory->stage("summary.json", json_file_text(result.summary, "summary.json"));
        directory->commit();
    }
    return py::cast(std::move(result));
}

Bed random_array_bed(const py::object& count, double solid_fraction, double diameter, double gap,
                     const py::object& sweeps, const py::object& seed,
                     const std::optional<std::filesystem::path>& out, bool force) {
    RandomArrayParameters p;
    p.count = whole(count, "count", option_range::random_array_count);
    p.solid_fraction = solid_fraction;
    p.diameter = diameter;
    p.gap = gap;
    p.sweeps = whole(sweeps, "sweeps", option_range::random_array_sweeps);
    p.seed = whole(seed, "seed", option_range::seed);
    p.validate();
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(*out, "--out", OutputKind::directory, force);
    RandomArray array;
    {
        py::gil_scoped_release released;
        array = random_array(p);
    }
    Bed bed{std::move(array.packing), Container(Periodic(array.cell, array.cell)),
            nlohmann::json()};
    bed.summary = random_array_summary(p, array);
    if (directory) {
        stage_bed(*directory, bed.packing, *bed.container, 1.0, false, bed.summary);
        directory->commit();
    }
    return bed;
}

Bed lattice(const std::string& type, const std::string& region, double diameter,
            const std::optional<std::string>& origin, const std::string& keep,
            const std::string& rotate, double band_clearance, bool analysis,
            const std::optional<std::filesystem::path>& out, bool force) {
    LatticeParameters p;
    p.type = lattice_types().at(type);
    p.region = parse_lattice_region(region);
    p.diameter = check_option("diameter", diameter, option_range::diameter);
    check_option("band-clearance", band_clearance, option_range::lattice_band_clearance);
    if (origin)
        p.origin = parse_lattice_origin(*origin);
    p.keep = lattice_keeps().at(keep);
    p.rotations = parse_rotations(rotate);
    p.validate();
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(*out, "--out", OutputKind::directory, force);
    Bed bed{fill_lattice(p), p.region.container, nlohmann::json()};
    bed.summary = lattice_summary(p, bed.packing);
    if (directory) {
        stage_lattice(*directory, p, bed.packing, band_clearance, analysis, bed.summary);
        directory->commit();
    }
    return bed;
}

void write_bed(Bed& bed, const std::filesystem::path& out, bool force, bool analysis,
               double band_clearance) {
    const std::optional<PelletSpec> pellet = bed_pellet(bed, "write");
    if (!bed.container)
        throw InvalidInput("write: this bed has no container; allowed: a bed made by generate "
                           "or lattice, or read or built with container=...");
    OutputDirectory directory(out, "--out", OutputKind::directory, force);
    nlohmann::json summary = bed.summary;
    // The written summary is the written particles.csv's: the file a bed was read from is its
    // source, not its particles file.
    if (summary.is_object() && summary.contains("particles_file")) {
        summary["source"] = summary["particles_file"];
        summary.erase("particles_file");
    }
    if (pellet) { // as generate --shape writes it (stage_pellet_bed)
        directory.stage("particles.csv", particles_csv(bed.packing));
        directory.stage("particles.vtu", particles_vtu(bed.packing));
        directory.stage("summary.json", json_file_text(summary, "summary.json"));
        directory.commit();
        return;
    }
    const bool tall = bed.packing.size() > 0 &&
                      bed_top(bed.packing) > 2.0 * band_clearance * bed.packing.mean_diameter();
    stage_bed(directory, bed.packing, *bed.container, band_clearance, analysis && tall, summary);
    directory.commit();
}

py::object hydraulics(std::optional<double> porosity, const std::optional<std::string>& bed,
                      std::optional<double> diameter, double particle_density, double fluid_density,
                      double viscosity, double gravity, std::optional<double> velocity,
                      std::optional<double> aspect_ratio,
                      const std::optional<std::string>& container) {
    namespace range = option_range;
    HydraulicsRequest request;
    FluidAndParticles& f = request.fluid;
    if (porosity)
        request.porosity = check_option("porosity", *porosity, range::porosity);
    if (bed) {
        check_path("--bed", *bed);
        request.bed = *bed;
    }
    request.diameter_given = diameter.has_value();
    if (diameter)
        f.diameter = check_option("diameter", *diameter, range::diameter_m);
    f.particle_density = check_option("particle-density", particle_density, range::density_kg_m3);
    f.fluid_density = check_option("fluid-density", fluid_density, range::density_kg_m3);
    f.viscosity = check_option("viscosity", viscosity, range::viscosity_pa_s);
    f.gravity = check_option("gravity", gravity, range::gravity_m_s2);
    if (velocity)
        request.velocity = check_option("velocity", *velocity, range::velocity_m_s);
    request.aspect_ratio_given = aspect_ratio.has_value();
    if (aspect_ratio && container)
        throw InvalidInput(fmt::format("--aspect-ratio {} and --container {} are both given; "
                                       "allowed: one of the two",
                                       *aspect_ratio, printable(container->substr(0, 80))));
    if (aspect_ratio)
        request.aspect_ratio =
            check_option("aspect-ratio", *aspect_ratio, range::tube_aspect_ratio);
    request.container = container.value_or("");
    const Report report = hydraulics_report(request);
    warn(report.warnings);
    return to_python(report.values);
}

py::object cfd_report_of(const std::filesystem::path& case_dir,
                         const std::optional<std::filesystem::path>& out, bool force) {
    check_cfd_case(case_dir);
    OutputDirectory directory(out ? *out : case_dir / "cfd-report", "--out", OutputKind::directory,
                              force);
    const Report report = cfd_report(case_dir);
    const std::string why = stage_cfd_report(directory, report);
    directory.commit();
    std::vector<std::string> warnings = report.warnings;
    if (!why.empty())
        warnings.push_back(why);
    warn(warnings);
    return to_python(report.values);
}

py::object cfd_series_of(const std::vector<std::filesystem::path>& cases,
                         const std::optional<std::filesystem::path>& out, bool force) {
    if (cases.size() < 3) // before the output is claimed
        throw InvalidInput(fmt::format("{} case(s) given for a mesh series; allowed: 3 or more "
                                       "cases of one bed, meshed at different resolutions",
                                       cases.size()));
    for (const std::filesystem::path& c : cases)
        check_cfd_case(c);
    OutputDirectory directory(out ? *out : cases.back() / "cfd-series", "--out",
                              OutputKind::directory, force);
    const Report report = cfd_series(cases);
    stage_cfd_series(directory, report);
    directory.commit();
    warn(report.warnings);
    return to_python(report.values);
}

py::object correlations(double aspect_ratio, double profile_step, double profile_to) {
    CorrelationsRequest request;
    request.aspect_ratio = check_option("aspect-ratio", aspect_ratio, option_range::aspect_ratio);
    request.profile_step = check_option("profile-step", profile_step, option_range::profile_step);
    request.profile_to = check_option("profile-to", profile_to, option_range::profile_to);
    const Report report = correlations_report(request);
    warn(report.warnings);
    return to_python(report.values);
}

std::string
export_bed_to(const Bed& bed, const std::filesystem::path& out,
              const std::optional<std::string>& format, const std::optional<std::string>& container,
              std::optional<double> container_height, bool no_container, double density,
              const std::optional<std::string>& box, std::optional<double> fluid_velocity,
              const std::string& contacts, long long refine, std::optional<double> edge,
              const std::optional<std::string>& facets, long long cells_per_diameter,
              long long particle_level, long long wall_level, long long ranks, double reynolds,
              const std::string& turbulence, double fluid_density, double viscosity,
              std::optional<double> scale, const std::string& flow, bool force, long long layers) {
    namespace range = option_range;
    check_path("out", out);
    ExportRequest request;
    request.pellet = bed_pellet(bed, "export");
    request.format = format ? *format : export_format_for(out);
    request.out = out;
    request.force = force;
    // the bed's file where it was read from one (the outputs must not replace it)
    const bool from_file = bed.summary.is_object() && bed.summary.contains("particles_file");
    request.source = from_file ? bed.summary["particles_file"].get<std::string>() : "Python";
    if (from_file)
        request.keep = request.source;
    request.container =
        container ? std::optional(container_from_spec("--container", *container)) : bed.container;
    const BedSummary summary = recorded(bed);
    request.friction = summary.friction;
    request.wall_friction = summary.wall_friction;
    if (container_height)
        request.container_height =
            check_option("container-height", *container_height, range::container_height);
    request.no_container = no_container;
    request.density = check_option("density", density, range::density);
    request.box = box.value_or("");
    if (fluid_velocity)
        request.fluid_velocity =
            check_option("fluid-velocity", *fluid_velocity, range::fluid_velocity);
    request.contacts = contacts;
    request.refine = static_cast<int>(check_option("refine", refine, range::refine));
    if (edge)
        request.edge = check_option("edge", *edge, range::edge);
    if (facets) {
        facet_modes().at(*facets);
        request.facets = *facets;
    }
    request.mesh.cells_per_diameter = static_cast<int>(
        check_option("cells-per-diameter", cells_per_diameter, range::cells_per_diameter));
    request.mesh.particle_level =
        static_cast<int>(check_option("particle-level", particle_level, range::refinement_level));
    request.mesh.wall_level =
        static_cast<int>(check_option("wall-level", wall_level, range::refinement_level));
    request.mesh.layers = static_cast<int>(check_option("layers", layers, range::surface_layers));
    request.flow.ranks = static_cast<int>(check_option("ranks", ranks, range::ranks));
    request.flow.reynolds = check_option("reynolds", reynolds, range::reynolds);
    request.turbulence = turbulence;
    if (flow != "inlet" && flow != "periodic")
        throw InvalidInput(fmt::format("flow '{}' is not allowed; allowed: inlet, periodic",
                                       printable(flow.substr(0, 80))));
    request.mesh.periodic_z = flow == "periodic";
    // A random array's cell repeats along z with its own period (summary.json's period_z).
    if (const std::optional<double> period_z = period_z_of(bed);
        request.mesh.periodic_z && !container_height && !container && period_z)
        request.container_height =
            check_option("container-height", *period_z, range::container_height);
    request.flow.fluid_density = check_option("fluid-density", fluid_density, range::density_kg_m3);
    request.flow.viscosity = check_option("viscosity", viscosity, range::viscosity_pa_s);
    if (scale)
        request.flow.scale = check_option("scale", *scale, range::metres_per_unit);
    py::gil_scoped_release released;
    return export_bed(bed.packing, {}, request);
}

/// A vector's memory handed to numpy without a copy: the array owns the vector through a
/// capsule.
template <class T> py::array owned_array(Voxels<T>&& data, const VoxelGrid& grid, py::dtype dtype) {
    auto* owner = new Voxels<T>(std::move(data));
    py::capsule free(owner, [](void* p) { delete static_cast<Voxels<T>*>(p); });
    const auto [nx, ny, nz] = grid.count;
    const auto item = static_cast<py::ssize_t>(sizeof(T));
    return py::array(
        dtype,
        {static_cast<py::ssize_t>(nx), static_cast<py::ssize_t>(ny), static_cast<py::ssize_t>(nz)},
        {static_cast<py::ssize_t>(ny * nz) * item, static_cast<py::ssize_t>(nz) * item, item},
        owner->data(), free);
}

/// numpy's name of a dtype given as numpy takes one ('float32', np.float32, np.dtype('<f4')).
std::string dtype_name(const py::object& dtype) {
    if (py::isinstance<py::str>(dtype))
        return dtype.cast<std::string>();
    try {
        return py::dtype::from_args(dtype).attr("name").cast<std::string>();
    } catch (const py::error_already_set&) {
        throw InvalidInput(fmt::format("--dtype {} is not allowed; allowed: float64, float32 "
                                       "(a name, numpy's type or a numpy dtype)",
                                       printable(std::string(py::repr(dtype)).substr(0, 80))));
    }
}

py::array voxelize_bed(const Bed& bed, double voxel_size,
                       std::optional<std::array<double, 6>> region, const std::string& kind,
                       const py::object& dtype_given, const std::optional<std::string>& container,
                       std::optional<long long> threads,
                       const std::optional<std::filesystem::path>& out) {
    // A bed of pellets from generate(shape=...) is drawn as its pellets (the shape its summary
    // records).
    const std::optional<PelletSpec> pellet = bed_pellet(bed, "voxelize");
    const PelletShape* shape = pellet ? &pellet->shape : nullptr;
    const Container given = container_for(bed, container, pellet ? &*pellet : nullptr);
    const VoxelType type = voxel_type(kind, dtype_name(dtype_given));
    std::optional<ImageFormat> format;
    if (out) {
        format = image_format(*out);
        if (!format)
            throw InvalidInput(fmt::format("--out {}: the extension is not allowed; allowed: "
                                           ".npy, .tif (or .tiff) or .raw (with a .raw.json "
                                           "header)",
                                           printable(out->native())));
    }
    // A random array's cube is periodic along z too (its summary's period_z).
    const std::optional<double> period_z = shape ? std::nullopt : period_z_of(bed);
    // every check before the work
    voxelize_grid(bed.packing, given, voxel_size, region, type, shape, period_z);
    std::optional<OutputDirectory> directory;
    if (out)
        directory.emplace(out->parent_path().empty() ? "." : out->parent_path(), "--out",
                          OutputKind::files);
    set_threads(threads);
    VoxelImage image;
    {
        py::gil_scoped_release released;
        image = voxelize(bed.packing, given, voxel_size, region, type, shape, period_z);
    }
    if (directory) {
        stage_image(*directory, out->filename().string(), *format, image);
        directory->commit();
    }
    if (const std::string w = untiled_cell_warning(image.grid, given, region.has_value(), period_z);
        !w.empty())
        warn({w});
    const py::dtype numpy_type(voxel_type_name(type));
    if (type == VoxelType::boolean)
        return owned_array(std::move(image.pore), image.grid, numpy_type);
    if (type == VoxelType::float64)
        return owned_array(std::move(image.fraction), image.grid, numpy_type);
    return owned_array(std::move(image.fraction32), image.grid, numpy_type);
}

} // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "packbed's library: packed beds of spheres generated, read, measured and written";
    m.attr("__version__") = std::string(version);

    static py::exception<ConvergenceError> convergence(m, "ConvergenceError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const UnopenableFile& e) {
            // OSError(errno, strerror, filename) is FileNotFoundError for ENOENT,
            // PermissionError for EACCES, as Python's own open() raises them.
            const py::object error = py::reinterpret_borrow<py::object>(PyExc_OSError)(
                e.error(), std::strerror(e.error()),
                py::reinterpret_steal<py::object>(PyUnicode_DecodeFSDefaultAndSize(
                    e.path().data(), static_cast<Py_ssize_t>(e.path().size()))));
            PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(error.ptr())), error.ptr());
        } catch (const InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, as_given(e.what()).c_str());
        } catch (const ConvergenceError& e) {
            convergence(e.what());
        } catch (const Cancelled&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        } catch (const py::builtin_exception& e) { // pybind11's own: as it translates them
            e.set_error();
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory; nothing was written");
        } catch (const std::exception& e) { // a staged file's name as the user gave it
            PyErr_SetString(PyExc_RuntimeError, as_given(e.what()).c_str());
        }
    });

    py::class_<Bed>(m, "Bed", R"(A bed of spheres: centres, radii, its container and its record.

Build one from arrays: Bed(centers, radii=None, diameter=None, container=None), with centers
of shape (N, 3), and either radii (N) or one diameter for every sphere; container a spec
string ('cylinder:D', 'box:LX,LY', 'cone:DB,DT,H', ...: docs/containers.md), the floor at
z = 0. period_z: a 'periodic:LX,LY' cell periodic along z too, of this period (a random
array's; centres in [0, period_z], spheres across the floor and the top as its images).

A bed of pellets: shape a pellet spec as generate's ('cylinder:D,L', 'ring:D,DI,L', ...) and
orientations (N, 4) unit quaternions qw, qx, qy, qz (the pellet's axis its body z axis
turned; norm 1 within 1e-3, normalised); radii each pellet's volume-equivalent d_v / 2 (None:
every pellet the shape's size), no diameter. A container given is checked to hold the pellets
by their exact shapes.)")
        .def(py::init(&from_arrays), py::arg("centers"), py::arg("radii") = py::none(),
             py::kw_only(), py::arg("diameter") = py::none(), py::arg("container") = py::none(),
             py::arg("orientations") = py::none(), py::arg("shape") = "sphere",
             py::arg("period_z") = py::none())
        .def_property_readonly(
            "centers",
            [](py::object self) {
                Bed& bed = self.cast<Bed&>();
                static_assert(sizeof(Vec3) == 3 * sizeof(double));
                return read_only(py::array_t<double>(
                    {static_cast<py::ssize_t>(bed.packing.size()), py::ssize_t{3}},
                    {static_cast<py::ssize_t>(sizeof(Vec3)),
                     static_cast<py::ssize_t>(sizeof(double))},
                    reinterpret_cast<double*>(bed.packing.centers.data()), self));
            },
            "The centres, a read-only numpy array (N, 3) viewing the bed's own memory (no "
            "copy); a changed bed is a new one: Bed(bed.centers + shift, bed.radii, ...).")
        .def_property_readonly(
            "radii",
            [](py::object self) {
                Bed& bed = self.cast<Bed&>();
                return read_only(py::array_t<double>(static_cast<py::ssize_t>(bed.packing.size()),
                                                     bed.packing.radii.data(), self));
            },
            "The radii, a read-only numpy array (N) viewing the bed's own memory (no copy).")
        .def_property_readonly(
            "orientations",
            [](py::object self) -> py::object {
                Bed& bed = self.cast<Bed&>();
                if (bed.packing.orientations.empty())
                    return py::none();
                static_assert(sizeof(Quaternion) == 4 * sizeof(double));
                return read_only(py::array_t<double>(
                    {static_cast<py::ssize_t>(bed.packing.size()), py::ssize_t{4}},
                    {static_cast<py::ssize_t>(sizeof(Quaternion)),
                     static_cast<py::ssize_t>(sizeof(double))},
                    reinterpret_cast<double*>(bed.packing.orientations.data()), self));
            },
            "A pellet bed's orientations, a read-only numpy array (N, 4) of unit quaternions qw, "
            "qx, qy, qz (the pellet's axis is its body z axis turned) viewing the bed's own "
            "memory; None for spheres.")
        .def_property_readonly(
            "period_z", &period_z_of,
            "The period along z of a cell periodic on all six faces (a random array's), or None: "
            "Bed(..., container=bed.container, period_z=bed.period_z) is the same cell.")
        .def_property_readonly(
            "container",
            [](const Bed& bed) -> std::optional<std::string> {
                if (!bed.container)
                    return std::nullopt;
                return bed.container->exact_spec();
            },
            "The container as a spec string ('cylinder:D', ...; each length the shortest text "
            "that reads back as the same float: Bed(..., container=bed.container) is in the "
            "same container), or None when unknown.")
        .def_property_readonly(
            "summary", [](const Bed& bed) { return to_python(bed.summary); },
            "The bed's record as a dict: what summary.json holds (for a generated bed the "
            "parameters, the stages, the void fraction, the largest overlaps).")
        .def("__len__", [](const Bed& bed) { return bed.packing.size(); })
        // pickle, copy.copy and copy.deepcopy (multiprocessing returns beds by pickling them)
        .def(py::pickle(&bed_state, &bed_from_state))
        .def("write", &write_bed, py::call_guard<JobScope>(), py::arg("out"), py::kw_only(),
             py::arg("force") = false, py::arg("analysis") = true, py::arg("band_clearance") = 1.0,
             R"(Write the bed as `packbed generate` does: particles.csv, particles.vtu, the
analysis (tables and plots, when the bed is taller than twice band_clearance) and summary.json
in the directory `out` (new or empty; force=True replaces a non-empty one whole). A bed of
pellets: particles.csv (with the quaternions), particles.vtu and its summary, as `packbed
generate --shape` writes them.)");

    py::class_<Profile>(m, "Profile", "A profile: each bin's interval [low, high] and its value.")
        .def_readonly("low", &Profile::low, "The bins' lower ends (length), numpy array.")
        .def_readonly("high", &Profile::high, "The bins' upper ends (length), numpy array.")
        .def_readonly("value", &Profile::value, "The bins' values, numpy array.")
        .def_property_readonly(
            "middle",
            [](const Profile& p) -> py::array_t<double> {
                return py::array_t<double>(
                    py::module_::import("numpy").attr("add")(p.low, p.high).attr("__mul__")(0.5));
            },
            "The bins' middles (length), numpy array.");

    py::class_<Analysis> analysis(m, "Analysis", "What analyze measured.");
    def_measured(analysis, "The overall void fraction in the band, exact.",
                 "The reference diameter Dp (length).",
                 "e(d) against the distance from the wall (a container of one wall; see walls).",
                 "e(z) over slabs from the floor to the top.")
        .def_property_readonly(
            "centre_distribution",
            [](const Analysis& a) { return profile(a.analysis.centre_distribution); },
            "The density of centres against the distance from the wall over its mean.")
        .def_property_readonly(
            "pair_correlation",
            [](const Analysis& a) { return profile(a.analysis.pair_correlation); },
            "g(r) against the centre distance, corrected for the container.")
        .def_property_readonly(
            "walls",
            [](const Analysis& a) {
                py::dict walls;
                for (const WallAnalysis& w : a.analysis.walls) {
                    py::dict wall;
                    wall["void_fraction"] = profile(w.void_fraction);
                    wall["centre_distribution"] = profile(w.centre_distribution);
                    wall["wall_contacts"] = w.wall_contacts;
                    walls[py::str(w.name)] = wall;
                }
                return walls;
            },
            "Each profile wall's name ('wall', or 'outer' and 'inner' in an annulus) to its "
            "void_fraction and centre_distribution profiles and wall_contacts.")
        .def_property_readonly(
            "coordination_histogram",
            [](const Analysis& a) { return counts(a.analysis.coordination.histogram); },
            "histogram[k]: spheres (centre in the band) with k sphere-sphere contacts.")
        .def_property_readonly(
            "summary", [](const Analysis& a) { return to_python(a.summary); },
            "The numbers as `packbed analyze` writes them in summary.json (band, void fraction, "
            "coordination, rattlers, wall contacts, options, warnings).");

    py::class_<PelletAnalysisResult> pellets(m, "PelletAnalysis",
                                             "What analyze measured in a bed of pellets.");
    def_measured(pellets, "The overall void fraction in the band, from the pellets' exact volumes.",
                 "The pellets' volume-equivalent diameter d_v (length).",
                 "e(d) against the distance from the wall, exact (empty without one wall).",
                 "e(z) over slabs from the floor to the top, exact.")
        .def_property_readonly(
            "orientation",
            [](const PelletAnalysisResult& a) {
                const std::vector<OrientationBin>& bins = a.analysis.orientation;
                const auto n = static_cast<py::ssize_t>(bins.size());
                py::array_t<double> low(n), high(n), cos2(n), order(n), cos2_wall(n);
                py::array_t<std::int64_t> count(n);
                for (py::ssize_t k = 0; k < n; ++k) {
                    const OrientationBin& b = bins[static_cast<std::size_t>(k)];
                    low.mutable_at(k) = b.low;
                    high.mutable_at(k) = b.high;
                    count.mutable_at(k) = static_cast<std::int64_t>(b.pellets);
                    cos2.mutable_at(k) = b.mean_cos2;
                    order.mutable_at(k) = b.order;
                    cos2_wall.mutable_at(k) = b.mean_cos2_wall;
                }
                py::dict out;
                out["low"] = low;
                out["high"] = high;
                out["pellets"] = count;
                out["mean_cos2"] = cos2;
                out["order"] = order;
                out["mean_cos2_wall"] = cos2_wall;
                return out;
            },
            "The axes' orientation against the centroid's distance from the wall (bins of 0.1 "
            "d_v; empty without one wall): a dict of numpy arrays low, high (length), pellets, "
            "mean_cos2 (<cos^2 theta>, theta from the container's z axis), order (S = "
            "(3 <cos^2> - 1) / 2) and mean_cos2_wall (<cos^2 psi>, psi from the wall's normal "
            "at the centroid: 1 pointing at the wall, 0 parallel to it, 1/3 at random).")
        .def_property_readonly(
            "order", [](const PelletAnalysisResult& a) { return a.analysis.overall.order; },
            "S over every pellet with its centroid in the band: 1 upright, -1/2 lying, 0 random.")
        .def_property_readonly(
            "mean_cos2", [](const PelletAnalysisResult& a) { return a.analysis.overall.mean_cos2; },
            "<cos^2 theta> over every pellet with its centroid in the band (1/3 at random).")
        .def_property_readonly(
            "mean_cos2_wall",
            [](const PelletAnalysisResult& a) { return a.analysis.overall.mean_cos2_wall; },
            "<cos^2 psi> over every pellet with its centroid in the band, psi between its axis "
            "and the wall's normal at its centroid (1/3 at random; 0 without one wall).")
        .def_property_readonly(
            "coordination_histogram",
            [](const PelletAnalysisResult& a) { return counts(a.analysis.coordination.histogram); },
            "histogram[k]: pellets (centroid in the band) with k pellet-pellet contacts.")
        .def_property_readonly(
            "summary", [](const PelletAnalysisResult& a) { return to_python(a.summary); },
            "The numbers as `packbed analyze` writes them in summary.json (band, void fraction, "
            "orientation, coordination, wall contacts).");

    m.def("generate", &generate, py::call_guard<JobScope>(), py::kw_only(),
          py::arg("aspect_ratio") = py::none(), py::arg("container") = py::none(),
          py::arg("particles") = SoftSphereParameters{}.particles,
          py::arg("seed") = SoftSphereParameters{}.seed,
          py::arg("diameter") = SoftSphereParameters{}.diameter, py::arg("sizes") = "mono",
          py::arg("fractions") = "volume", py::arg("e0") = SoftSphereParameters{}.e0,
          py::arg("ck") = SoftSphereParameters{}.ck,
          py::arg("cg_step") = SoftSphereParameters{}.cg_step, py::arg("overlap_low") = py::none(),
          py::arg("overlap_high") = py::none(),
          py::arg("tolerance") = SoftSphereParameters{}.tolerance,
          py::arg("mc_period") = SoftSphereParameters{}.mc_period,
          py::arg("mc_window") = SoftSphereParameters{}.mc_window,
          py::arg("mc_tolerance") = py::none(),
          py::arg("update") = to_string(SoftSphereParameters{}.update),
          py::arg("solver") = to_string(SoftSphereParameters{}.solver),
          py::arg("skin") = py::none(), py::arg("layer_height") = py::none(),
          py::arg("friction") = SoftSphereParameters{}.friction,
          py::arg("wall_friction") = SoftSphereParameters{}.wall_friction,
          py::arg("target_void_fraction") = py::none(), py::arg("checkpoint") = py::none(),
          py::arg("max_iterations") = py::none(), py::arg("band_clearance") = 1.0,
          py::arg("threads") = py::none(), py::arg("progress") = py::none(),
          py::arg("out") = py::none(), py::arg("force") = false,
          py::arg("engine") = to_string(Engine::packbed), py::arg("ranks") = 1,
          py::arg("mpi_command") = py::none(), py::arg("lmp") = "lmp", py::arg("shape") = "sphere",
          R"(Pack spheres in a container with the soft-sphere algorithm of Salvat et al. (2005).

The keyword arguments are `packbed generate`'s options in snake_case, with the same defaults
(`packbed generate --help`, docs/generate.md): aspect_ratio a = D/Dp (None: 5) or container
(not both; a spec string such as 'cylinder:0.05', 'box:LX,LY' or 'cone:DB,DT,H' in the
unit of diameter, docs/containers.md), particles Np, seed, diameter Dp, sizes (a --sizes spec, docs/sizes.md), fractions
('volume' or 'number'), e0, ck, cg_step, overlap_low, overlap_high, tolerance, mc_period,
mc_window, mc_tolerance (None: the solver's schedule), update ('in-place' or 'simultaneous'),
solver ('fire' or 'paper'), skin, layer_height (None: 30 Dp for spheres, one piece for pellets), friction, wall_friction, target_void_fraction
(None: none), checkpoint (a file), max_iterations, band_clearance. threads: at most this many threads (None: all; the result does not depend on
it). progress: called as progress(report) every mc_period iterations with a dict (stage,
iteration, cg, max_overlap_pair, max_overlap_wall, mass_centre_z, layer, layers). out: a
directory to write what `packbed generate` writes there (None: nothing is written); force:
replace a non-empty one. engine: 'packbed' (here, threads) or 'lammps' (the same relaxation run
by LAMMPS, docs/lammps.md) with ranks (mpirun -np ranks), mpi_command (a launcher's words
instead) and lmp (the LAMMPS program); with out, LAMMPS's files are kept in out/lammps/.
shape: 'sphere', or a pellet ('cylinder:D,L', 'ring:D,DI,L', 'trilobe:DL,DC,L',
'multilobe:N,DL,DC,L', 'spherocylinder:D,L') for a bed of pellets as `packbed generate --shape` makes it (docs/generate.md, "Pellets"): with aspect_ratio (over the pellet's volume-equivalent
diameter) or container (in the unit of D and L), particles, seed, sizes, fractions,
layer_height, checkpoint (a bed in layers), band_clearance, friction, wall_friction,
max_iterations, threads, progress, out and force; the Bed's orientations hold each pellet's quaternion, and
Bed.write, analyze, export and voxelize take it as they take a bed that read() gives.

Returns a Bed (same seed and options: the same bits as the command line). Raises ValueError
for a bad value (the message names the option, the value and what is allowed),
ConvergenceError when the run does not converge, KeyboardInterrupt on Ctrl-C (nothing is
written). The GIL is released while it runs.)");

    m.def("read", &read_bed, py::call_guard<JobScope>(), py::arg("path"), py::kw_only(),
          py::arg("format") = "auto", py::arg("frame") = -1, py::arg("axis") = py::none(),
          py::arg("floor") = 0.0, py::arg("diameter") = py::none(),
          py::arg("container") = py::none(), py::arg("outside_tolerance") = 0.01,
          R"(Read a bed from a file, as `packbed analyze` does: CSV/TSV tables, XYZ, LAMMPS and
LIGGGHTS dumps and data files, each gzip-compressed or not (format 'auto' detects it).

frame: 1 the first, -1 the last. axis (X, Y) and floor: the container's axis and floor,
subtracted from every centre. diameter: of spheres in files without a size column. container: a
spec string; None: the one summary.json beside the file records, if any. Spheres sticking out of
the container by more than outside_tolerance Dp raise ValueError, as every bad input does.
A bed of pellets (the shape in the summary.json beside the file, as `packbed generate --shape`
writes it) keeps its orientations and has the shape in its summary['shape'].)");

    m.def("analyze_frames", &analyze_frames, py::call_guard<JobScope>(), py::arg("path"),
          py::kw_only(), py::arg("format") = "auto", py::arg("axis") = py::none(),
          py::arg("floor") = 0.0, py::arg("diameter") = py::none(),
          py::arg("container") = py::none(), py::arg("outside_tolerance") = 0.01,
          py::arg("band") = py::none(), py::arg("band_clearance") = py::none(),
          py::arg("threads") = py::none(),
          R"(The void fraction of every frame of a trajectory (a LAMMPS or LIGGGHTS dump), as
`packbed analyze --frames all` writes it in void_fraction_series.csv: a dict of numpy arrays
frame, timestep (NaN where the file has none), void_fraction (NaN where the frame has no
spheres or is not taller than the band) and particles, and 'last', the last frame with spheres
as a Bed (analyze it for the rest). The band: band = (z_low, z_high), fixed, or band_clearance
Dp clear of each frame's ends (None: 1; not both). Reading options and container as read();
every frame is checked inside the container.)");

    m.def("analyze", &analyze, py::call_guard<JobScope>(), py::arg("bed"), py::kw_only(),
          py::arg("container") = py::none(), py::arg("band") = py::none(),
          py::arg("band_clearance") = py::none(), py::arg("diameter") = py::none(),
          py::arg("shell_width") = AnalysisOptions{}.shell_width,
          py::arg("slab_height") = AnalysisOptions{}.slab_height,
          py::arg("centre_bin") = py::none(),
          py::arg("contact_tolerance") = AnalysisOptions{}.contact_tolerance,
          py::arg("rdf_range") = py::none(), py::arg("rdf_bin") = py::none(),
          py::arg("friction") = py::none(), py::arg("threads") = py::none(),
          py::arg("out") = py::none(), py::arg("force") = false,
          R"(Measure a bed as `packbed analyze` does: the overall void fraction (exact), the
radial (wall) and axial void fraction profiles, the centre distribution, contacts and
coordination, and g(r), in the band band_clearance Dp clear of the floor and the top (None: 1)
or band = (z_low, z_high), not both. container: a spec string; None: the bed's own. Lengths in
Dp are in units of diameter (None: the mean sphere diameter). centre_bin, rdf_range, rdf_bin:
None, 0.02, 3 and 0.02 Dp. friction: between the spheres, above 0 a rattler has fewer than 2 contacts, not 4
(None: the one the bed's summary records, else 0). out: a directory to write the tables, plots
and summary.json to (None: nothing is written). Returns an Analysis with numpy arrays.

A bed of pellets (from generate(shape=...) or read() of one) is measured as `packbed analyze`
measures it: the exact void fractions, the axes' orientation against the distance from the
wall and the contacts per pellet, lengths in d_v; it takes container, band, band_clearance,
shell_width, slab_height, contact_tolerance, threads, out and force, refuses the spheres' other
options, and returns a PelletAnalysis.)");

    m.def("voxelize", &voxelize_bed, py::call_guard<JobScope>(), py::arg("bed"), py::kw_only(),
          py::arg("voxel_size"), py::arg("region") = py::none(), py::arg("kind") = "binary",
          py::arg("dtype") = "float64", py::arg("container") = py::none(),
          py::arg("threads") = py::none(), py::arg("out") = py::none(),
          R"(A bed as a voxel image, as `packbed voxelize`: a numpy array of shape (nx, ny, nz),
im[i, j, k] the voxel [x0 + i h, x0 + (i + 1) h] x ... (h = voxel_size).

kind 'binary': bool, True where the voxel's centre is pore space (inside the container and in
no sphere), False where it is solid (a sphere, or outside the container), as PoreSpy expects.
kind 'fraction': float64, each voxel's solid fraction computed exactly from the spheres (closed
form); its sum times h^3 is the spheres' volume in the grid's box. dtype 'float32' (or
np.float32; kind 'fraction' only): the same fractions each rounded once to single precision,
half the memory.
region: (xlow, ylow, zlow,
xhigh, yhigh, zhigh); None: the container across and the floor to the bed's top. out: also write
it to a .npy, .tif or .raw (+ .raw.json) file. The array owns its memory (no copy is made).)");

    m.def("export", &export_bed_to, py::call_guard<JobScope>(), py::arg("bed"), py::arg("out"),
          py::kw_only(), py::arg("format") = py::none(), py::arg("container") = py::none(),
          py::arg("container_height") = py::none(), py::arg("no_container") = false,
          py::arg("density") = ExportRequest{}.density, py::arg("box") = py::none(),
          py::arg("fluid_velocity") = py::none(), py::arg("contacts") = ExportRequest{}.contacts,
          py::arg("refine") = ExportRequest{}.refine, py::arg("edge") = py::none(),
          py::arg("facets") = py::none(),
          py::arg("cells_per_diameter") = ExportRequest{}.mesh.cells_per_diameter,
          py::arg("particle_level") = ExportRequest{}.mesh.particle_level,
          py::arg("wall_level") = ExportRequest{}.mesh.wall_level,
          py::arg("ranks") = OpenFoamFlowOptions{}.ranks,
          py::arg("reynolds") = OpenFoamFlowOptions{}.reynolds,
          py::arg("turbulence") = ExportRequest{}.turbulence,
          py::arg("fluid_density") = OpenFoamFlowOptions{}.fluid_density,
          py::arg("viscosity") = OpenFoamFlowOptions{}.viscosity, py::arg("scale") = py::none(),
          py::arg("flow") = "inlet", py::arg("force") = false,
          py::arg("layers") = ExportRequest{}.mesh.layers,
          R"(Write a bed as `packbed export` does, to the file (or, for 'openfoam', the case
directory) `out`: format 'lammps-data' (atom_style sphere), 'liggghts-data' (atom_style
granular), 'stl', 'stl-ascii', 'obj' or 'openfoam' (docs/dem.md, docs/surfaces.md).

container: a spec string; None: the bed's own (none: no wall treatment and no example DEM
input). container_height: None, the bed's top + 1 Dp. no_container: surfaces without the
container's solids, data files in the spheres' bounding box. Data files: density, box
('xlo,xhi,ylo,yhi,zlo,zhi'), fluid_velocity. Surfaces: contacts ('none', 'shrink:F',
'enlarge:F', 'caps:H', 'bridges:D'), refine (icosphere level) or edge, facets ('inscribed';
'volume': each sphere's polyhedron scaled to hold its volume; 'auto': volume where every gap
allows it; None: auto for 'openfoam', inscribed otherwise), and for 'openfoam'
cells_per_diameter, particle_level, wall_level, layers (snappyHexMesh's prism layers on the
particles and the wall, 0 to 10); the flow of its Allrun: ranks, reynolds (or
fluid_velocity, m/s), turbulence ('laminar', 'kEpsilon', 'kOmegaSST'), fluid_density
(kg/m^3), viscosity (Pa s), scale (metres per unit of the bed's lengths; None: particles of
1 mm), flow ('inlet', or 'periodic': a periodic cell repeating along z with container_height
its period, a random array's own by default, the mean velocity held by a uniform pressure
gradient). force: replace a
non-empty case directory. A bed of pellets is written as its pellets (surfaces of the exact
shapes; data files of rigid clumps of spheres), as `packbed export` writes one.
Returns the command line's report line. Raises ValueError for a bad value.)");

    m.def("hydraulics", &hydraulics, py::call_guard<JobScope>(), py::kw_only(),
          py::arg("porosity") = py::none(), py::arg("bed") = py::none(),
          py::arg("diameter") = py::none(),
          py::arg("particle_density") = HydraulicsRequest{}.fluid.particle_density,
          py::arg("fluid_density") = HydraulicsRequest{}.fluid.fluid_density,
          py::arg("viscosity") = HydraulicsRequest{}.fluid.viscosity,
          py::arg("gravity") = HydraulicsRequest{}.fluid.gravity, py::arg("velocity") = py::none(),
          py::arg("aspect_ratio") = py::none(), py::arg("container") = py::none(),
          R"(The onset of fluidization and the fluid velocity for a DEM start (Tsayger 2013, eq.
(1)), Wen & Yu, Ergun's and Eisfeld & Schnitzlein's pressure gradients, permeabilities and the
regular packings, as `packbed hydraulics --json`; SI units.

porosity, or bed (a summary.json or its directory: a lattice's exact porosity or a generated
bed's void fraction, its diameter read as metres unless diameter is given, its tube's aspect
ratio unless aspect_ratio is given). diameter (m; None: the bed's, else 1 mm), particle_density
and fluid_density (kg/m^3; glass in water by default), viscosity (Pa s), gravity (m/s^2),
velocity (m/s; None: the critical one of eq. (1)), aspect_ratio a = D/d or container (a spec in
metres; a = D_h / d) for the wall-corrected pressure drop. Returns a dict; a correlation used
outside its range gives a UserWarning. Raises ValueError for a bad value.)");

    m.def("cfd_report", &cfd_report_of, py::call_guard<JobScope>(), py::arg("case"), py::kw_only(),
          py::arg("out") = py::none(), py::arg("force") = false,
          R"(The pressure drop of a case written by export(..., format='openfoam') and run by its
Allrun, as `packbed cfd-report CASE --json`: the planes' area-averaged pressures (Pa), the
gradient of the straight line fitted to them, Ergun's and Eisfeld & Schnitzlein's gradients at
the bed's own void fraction between the planes, the fluxes, whether simpleFoam converged (and
which stop ended it: solver['stopped_by'], 'residuals', 'steady pressure drop' or 'endTime')
and the mesh's void fraction. Writes pressure.csv, cfd_report.json and the plot pressure.svg/.png
to out (None: CASE/cfd-report; force replaces a non-empty one). Returns a dict; a correlation
outside its range, or no plot, gives a UserWarning. A case of export(..., flow='periodic'):
the pressure gradient that held its mean velocity, the drag per sphere, K = F / (6 pi mu a
U_s) beside Zick & Homsy's simple cubic arrays and (1 - phi) K beside van der Hoef et al.'s
random ones, no planes and no plot. Raises ValueError for a case that is not a run one.)");

    m.def("cfd_series", &cfd_series_of, py::call_guard<JobScope>(), py::arg("cases"), py::kw_only(),
          py::arg("out") = py::none(), py::arg("force") = false,
          R"(A mesh series of one bed, as `packbed cfd-report CASE CASE CASE ...  --json`: three
or more cases meshed at different resolutions and run by their Allrun, coarse to fine by their
cells; each level's cells, representative size h / d, the mesh's void fraction and its answer
(a periodic cell's K, else the pressure gradient), and Celik et al.'s (2008) apparent order,
Richardson extrapolation and grid convergence index of the three finest. Writes series.csv and
series.json to out (None: the last case's cfd-series/). Returns a dict; an apparent order far
from 2 gives a UserWarning. Raises ValueError for fewer than 3 cases or cases of two kinds.)");

    m.def(
        "mesh_preset",
        [](const std::string& name) {
            const OpenFoamMeshOptions mesh = mesh_presets().at(name);
            return py::dict(py::arg("cells_per_diameter") = mesh.cells_per_diameter,
                            py::arg("particle_level") = mesh.particle_level,
                            py::arg("wall_level") = mesh.wall_level,
                            py::arg("layers") = mesh.layers);
        },
        py::arg("name"),
        R"(The mesh options of `packbed export --mesh NAME` ('quick' or 'accurate',
docs/validation.md) as a dict of export's keywords: export(bed, out, format='openfoam',
**mesh_preset('accurate')). Raises ValueError for another name.)");

    m.def("correlations", &correlations, py::kw_only(),
          py::arg("aspect_ratio") = CorrelationsRequest{}.aspect_ratio,
          py::arg("profile_step") = CorrelationsRequest{}.profile_step,
          py::arg("profile_to") = CorrelationsRequest{}.profile_to,
          R"(The published void-fraction correlations at the aspect ratio a = D/d, as `packbed
correlations --json`: a dict with the mean void fractions and the radial profiles (x from the
wall in d, from 0 to profile_to in steps of profile_step), each with its formula, source and
validity range. A correlation used outside its range gives a UserWarning.)");

    m.def("random_array", &random_array_bed, py::call_guard<JobScope>(), py::kw_only(),
          py::arg("count"), py::arg("solid_fraction") = RandomArrayParameters{}.solid_fraction,
          py::arg("diameter") = 1.0, py::arg("gap") = 0.0,
          py::arg("sweeps") = py::int_(RandomArrayParameters{}.sweeps), py::arg("seed") = 1,
          py::arg("out") = py::none(), py::arg("force") = false,
          R"(Equal spheres at random in a cube periodic on all six faces, as `packbed
random-array`: count spheres at solid_fraction (which sets the cube's edge), hard spheres of
diameter (1 + gap) d in equilibrium (Monte Carlo, sweeps after they have grown to their size),
at most 0.49 of the cube for those. The bed's summary has the cell (container periodic:L,L,
period_z L); export(bed, ..., format='openfoam', flow='periodic') makes its CFD case. out: a
directory to write what the command writes.)");

    m.def("lattice", &lattice, py::call_guard<JobScope>(), py::kw_only(),
          py::arg("type") = "diamond", py::arg("region") = "box:10,10,10",
          py::arg("diameter") = 1.0, py::arg("origin") = py::none(), py::arg("keep") = "whole",
          py::arg("rotate") = "", py::arg("band_clearance") = 1.0, py::arg("analysis") = true,
          py::arg("out") = py::none(), py::arg("force") = false,
          R"(A regular packing of touching balls filling a region, as `packbed lattice`: type
'diamond' (tetrahedral, Tsayger 2013), 'sc', 'bcc', 'fcc' or 'hcp'; region 'box:LX,LY,LZ',
'cylinder:D,H', 'cone:DB,DT,H,HEIGHT' (a container's spec and the height); origin 'x,y,z'; keep 'whole' or
'centres'; rotate 'AXIS:DEGREES,...'. out: a directory to write what the command writes.)");
}
