#include "packbed/openfoam.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <type_traits>

#include <fmt/format.h>

#include "base/require.hpp"
#include "geometry/shape_text.hpp"
#include "packbed/error.hpp"
#include "packbed/hydraulics.hpp"
#include "packbed/option_ranges.hpp"

namespace packbed {

namespace {

/// The FoamFile header of a dictionary, or of a field of class `type`.
std::string header(const std::string& object, const std::string& location,
                   const std::string& type = "dictionary") {
    return fmt::format("/*--- written by packbed export --format openfoam ---*/\n"
                       "FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {};\n"
                       "    location \"{}\";\n    object {};\n}}\n\n",
                       type, location, object);
}

/// The fluid point farthest from every surface among candidates on the container's eight
/// vertical search lines (Container::search_lines: off every cell face), every 0.05 Dp in
/// height. Distances to a body are
/// taken to its sphere (bodies lie inside their spheres, so the clearance is never
/// overstated), to the wall by Container::wall_distance.
std::pair<Vec3, double> farthest_fluid_point(const std::vector<TreatedBody>& bodies,
                                             const SurfaceContainer& container, double dp) {
    std::vector<std::size_t> by_z(bodies.size());
    for (std::size_t i = 0; i < by_z.size(); ++i)
        by_z[i] = i;
    std::sort(by_z.begin(), by_z.end(), [&](std::size_t a, std::size_t b) {
        return bodies[a].center.z < bodies[b].center.z;
    });
    double largest = 0.0;
    for (const TreatedBody& b : bodies)
        largest = std::max(largest, b.radius);
    const std::vector<std::pair<double, double>> lines = container.container.search_lines();
    Vec3 best{};
    double best_clearance = -1.0;
    const double step = 0.05 * dp;
    for (double z = 0.01237 * dp; z < container.height; z += step)
        for (const auto& [x, y] : lines) {
            const Vec3 p{x, y, z};
            double clearance =
                std::min({container.container.wall_distance(p), p.z, container.height - p.z});
            if (clearance <= best_clearance)
                continue;
            // Bodies whose centre is within clearance + largest radius in height.
            const auto low =
                std::lower_bound(by_z.begin(), by_z.end(), z - clearance - largest,
                                 [&](std::size_t i, double v) { return bodies[i].center.z < v; });
            for (auto it = low; it != by_z.end() && bodies[*it].center.z <= z + clearance + largest;
                 ++it) {
                const TreatedBody& b = bodies[*it];
                clearance = std::min(clearance, norm(p - b.center) - b.radius);
                if (clearance <= best_clearance)
                    break;
            }
            if (clearance > best_clearance) {
                best_clearance = clearance;
                best = p;
            }
        }
    return {best, best_clearance};
}

/// The RANS fields of a case (model k-epsilon or k-omega SST), in SI units: at the inlet a
/// turbulence intensity I = 5 % of the local velocity (k = 3/2 (I u)^2) and a mixing length
/// l = 0.1 d (epsilon = C_mu^{3/4} k^{3/2} / l, omega = k^{1/2} / (C_mu^{1/4} l), C_mu = 0.09:
/// OpenFOAM's turbulentIntensityKineticEnergyInlet and turbulentMixingLength*Inlet); the same
/// values inside at the start; wall functions on `walls` (kqRWallFunction, epsilon- or
/// omegaWallFunction, nutkWallFunction); inletOutlet at the outlet.
void add_rans_fields(OpenFoamCase& c, const std::vector<std::string>& walls, Turbulence model,
                     double d) {
    constexpr double intensity = 0.05, cmu = 0.09;
    const double length = 0.1 * d;
    const double k = 1.5 * (intensity * c.velocity) * (intensity * c.velocity);
    const double epsilon = std::pow(cmu, 0.75) * std::pow(k, 1.5) / length;
    const double omega = std::sqrt(k) / (std::pow(cmu, 0.25) * length);
    const auto field = [&](const std::string& name, const char* dimensions, double value,
                           const std::string& inlet, const std::string& wall) {
        std::string on_walls;
        for (const std::string& w : walls)
            on_walls += fmt::format("    {} {{ type {}; value uniform {}; }}\n", w, wall, value);
        c.files.emplace_back(
            "0.orig/" + name,
            header(name, "0", "volScalarField") +
                fmt::format("dimensions {};\n\ninternalField uniform {};\n\nboundaryField\n{{\n"
                            "    #includeEtc \"caseDicts/setConstraintTypes\"\n"
                            "    inlet {{ {} value uniform {}; }}\n"
                            "    outlet {{ type inletOutlet; inletValue uniform {}; value uniform "
                            "{}; }}\n{}}}\n",
                            dimensions, value, inlet, value, value, value, on_walls));
    };
    field("k", "[0 2 -2 0 0 0 0]", k,
          fmt::format("type turbulentIntensityKineticEnergyInlet; intensity {};", intensity),
          "kqRWallFunction");
    if (model == Turbulence::k_epsilon)
        field(
            "epsilon", "[0 2 -3 0 0 0 0]", epsilon,
            fmt::format("type turbulentMixingLengthDissipationRateInlet; mixingLength {};", length),
            "epsilonWallFunction");
    else
        field("omega", "[0 0 -1 0 0 0 0]", omega,
              fmt::format("type turbulentMixingLengthFrequencyInlet; mixingLength {};", length),
              "omegaWallFunction");
    std::string nut_walls;
    for (const std::string& w : walls)
        nut_walls += fmt::format("    {} {{ type nutkWallFunction; value uniform 0; }}\n", w);
    c.files.emplace_back(
        "0.orig/nut",
        header("nut", "0", "volScalarField") +
            "dimensions [0 2 -1 0 0 0 0];\n\ninternalField uniform 0;\n\nboundaryField\n{\n"
            "    #includeEtc \"caseDicts/setConstraintTypes\"\n"
            "    inlet { type calculated; value uniform 0; }\n"
            "    outlet { type calculated; value uniform 0; }\n" +
            nut_walls + "}\n");
}

/// A plane of `planes` as surfaceFieldValue's area average of p (the dictionary's body).
std::string plane_average(const std::vector<double>& planes, std::size_t n, int interval,
                          const std::string& indent) {
    return fmt::format(
        "{i}type surfaceFieldValue;\n{i}libs (\"libfieldFunctionObjects.so\");\n"
        "{i}writeControl timeStep;\n{i}writeInterval {every};\n{i}log false;\n"
        "{i}writeFields false;\n{i}writeArea true;\n"
        "{i}regionType sampledSurface;\n{i}name p{n};\n"
        "{i}sampledSurfaceDict {{ type plane; planeType pointAndNormal; "
        "pointAndNormalDict {{ point (0 0 {z}); normal (0 0 1); }} interpolate false; }}\n"
        "{i}operation areaAverage;\n{i}fields (p);\n",
        fmt::arg("i", indent), fmt::arg("every", interval), fmt::arg("n", n),
        fmt::arg("z", planes[n]));
}

/// snappyHexMeshDict's addLayersControls: `count` prism layers on the particles and on the
/// container's surfaces that snappyHexMesh cuts (a tube's wall, an annulus' rod); none for the
/// background's own faces (a box's sides, a periodic cell's cyclic pairs). With
/// finalLayerThickness 0.5 of the cell beside it and an expansion of 1.2, three layers span
/// about 1.3 cells where snappyHexMesh can extrude them in full; carried over every edge (the
/// caps' rims included, featureAngle 180) and thinned only where they would pass the medial
/// axis (maxThicknessToMedialRatio 1), the levels keep their layers alike enough for the a = 5
/// series to converge at order 2.1 (docs/validation.md, "Prism layers"). Without layers the
/// block is snappyHexMesh's usual one, unused.
std::string add_layers_controls(int count, const OpenFoamBackground& back) {
    check_option("layers", count, option_range::surface_layers);
    const bool on = count > 0;
    std::string layers = "    layers {}\n";
    if (on) {
        layers =
            fmt::format("    layers\n    {{\n        particles {{ nSurfaceLayers {}; }}\n", count);
        if (back.wall_surface)
            layers += fmt::format("        wall {{ nSurfaceLayers {}; }}\n", count);
        if (back.rod_surface)
            layers += fmt::format("        rod {{ nSurfaceLayers {}; }}\n", count);
        layers += "    }\n";
    }
    return fmt::format(
        "addLayersControls\n{{\n    relativeSizes true;\n{layers}"
        "    expansionRatio {expansion};\n    finalLayerThickness {final_layer};\n"
        "    minThickness 0.1;\n"
        "    nGrow 0;\n    featureAngle {feature_angle};\n    slipFeatureAngle 30;\n"
        "    nRelaxIter 3;\n"
        "    nSmoothSurfaceNormals 1;\n    nSmoothNormals 3;\n    nSmoothThickness 10;\n"
        "    maxFaceThicknessRatio 0.5;\n    maxThicknessToMedialRatio {medial};\n"
        "    minMedialAxisAngle 90;\n    nBufferCellsNoExtrude 0;\n    nLayerIter 50;\n"
        "{relaxed}}}\n\n",
        fmt::arg("layers", layers), fmt::arg("expansion", on ? "1.2" : "1.0"),
        fmt::arg("final_layer", on ? "0.5" : "0.3"), fmt::arg("feature_angle", on ? "180" : "60"),
        fmt::arg("medial", on ? "1.0" : "0.3"),
        fmt::arg("relaxed", on ? "    nRelaxedIter 20;\n" : ""));
}

/// The stop on a steady pressure drop: `pressureDrop` (fieldValueDelta) takes the first plane's
/// area-averaged p less the last one's every iteration, and `steadyPressureDrop`
/// (runTimeControl, from iteration 50) ends the run, writing the fields, once that drop's
/// running mean (weight 1/50 per iteration) is within 1e-5 of Ergun's drop across the planes
/// of the drop itself, and U's initial residual is below 1e-4 (the RANS cases' stop for U):
/// the drop then moves by less than about 2e-7 of itself per iteration. Ergun's drop sets the
/// tolerance because OpenFOAM's `average` condition takes an absolute one; the drops measured
/// are 1.3 and 2.1 times Ergun's at the bed's void fraction below its top (a = 5 and 3). On
/// 30 spheres at a = 3, Re_p 100, it stops at iteration 303, the gradient within 6e-7 of a
/// run to iteration 1 500.
std::string steady_pressure_drop(const std::vector<double>& planes, double void_fraction,
                                 double velocity, double diameter,
                                 const OpenFoamFlowOptions& flow) {
    const double ergun =
        ergun_pressure_gradient(void_fraction, velocity, diameter, flow.fluid_density,
                                flow.viscosity) *
        (planes.back() - planes.front()) / flow.fluid_density; // kinematic, m^2/s^2
    const std::size_t last = planes.size() - 1;
    return fmt::format(
        "    // the drop of p from the first plane to the last, every iteration\n"
        "    pressureDrop\n    {{\n        type fieldValueDelta;\n"
        "        libs (\"libfieldFunctionObjects.so\");\n        operation subtract;\n"
        "        writeControl timeStep;\n        writeInterval 1;\n        log false;\n"
        "        region1\n        {{\n{first}        }}\n"
        "        region2\n        {{\n{last}        }}\n    }}\n"
        "    // the run ends when that drop is steady: its running mean (window 50 iterations)\n"
        "    // within 1e-5 of Ergun's drop across the planes ({ergun:.6g} m^2/s^2) of the drop,\n"
        "    steadyPressureDrop\n    {{\n        type runTimeControl;\n"
        "        libs (\"libutilityFunctionObjects.so\");\n        timeStart 50;\n"
        "        conditions\n        {{\n            pressureDropSteady\n            {{\n"
        "                type average;\n                functionObject pressureDrop;\n"
        "                fields (\"subtract(areaAverage(p0,p),areaAverage(p{n},p))\");\n"
        "                tolerance {tolerance:.6g};\n                window 50;\n"
        "                windowType approximate;\n                groupID 1;\n            }}\n"
        "            // and U's initial residual below 1e-4 (every component), with it\n"
        "            velocityResidual\n            {{\n"
        "                type equationInitialResidual;\n                fields (U);\n"
        "                value 1e-4;\n                mode minimum;\n                groupID 1;\n"
        "            }}\n        }}\n    }}\n",
        fmt::arg("first", plane_average(planes, 0, 1, "            ")),
        fmt::arg("last", plane_average(planes, last, 1, "            ")), fmt::arg("n", last),
        fmt::arg("ergun", ergun), fmt::arg("tolerance", 1e-5 * ergun));
}

/// The files that make the meshed case run (OpenFoamFlowOptions; docs/notes/openfoam-v1912.md
/// has the sources of each setting): `walls` the no-slip patches, `bed_top` the bed's top
/// (bed units), the pressure planes between 1 Dp above the floor and 1 Dp below the top;
/// `section` the container's cross-section (bed units): the inlet's flow rate is the
/// superficial velocity times it, whatever part of the inlet the particles cover. A cell
/// periodic along z (`mesh.periodic_z`; `void_fraction` its exact one) has no inlet, outlet or
/// planes: OpenFOAM's meanVelocityForce holds the mean velocity in the fluid at the superficial
/// velocity over the void fraction with a uniform pressure gradient, which is the result
/// (log.simpleFoam).
/// `bed_void_fraction` (below the bed's top) scales a laminar run's stop on a steady pressure
/// drop above Re_p 10 or with `mesh.layers` (steady_pressure_drop).
void add_flow_files(OpenFoamCase& c, const std::vector<std::string>& walls, double bed_top,
                    double section, double diameter, const OpenFoamFlowOptions& flow,
                    const OpenFoamMeshOptions& mesh, double void_fraction,
                    double bed_void_fraction) {
    const bool periodic = mesh.periodic_z;
    check_option("ranks", flow.ranks, option_range::ranks);
    check_option("fluid-density", flow.fluid_density, option_range::density_kg_m3);
    check_option("viscosity", flow.viscosity, option_range::viscosity_pa_s);
    if (flow.velocity != 0.0)
        check_option("fluid-velocity", flow.velocity, option_range::velocity_m_s);
    else
        check_option("reynolds", flow.reynolds, option_range::reynolds);
    const double d = c.scale * diameter; // m
    // The flow's numbers within the hydraulics' physical ranges (limits.hpp), so that a scale
    // far from any bed cannot ask simpleFoam for a velocity of 1e294 m/s.
    if (!(d >= limits::min_particle_diameter_m && d <= limits::max_particle_diameter_m))
        throw InvalidInput(fmt::format(
            "--scale {:g} is not allowed for spheres of {:g} units: they would be {:g} m; "
            "allowed: a scale that makes them {:g} to {:g} m",
            c.scale, diameter, d, limits::min_particle_diameter_m,
            limits::max_particle_diameter_m));
    const double nu = flow.viscosity / flow.fluid_density;
    c.velocity = flow.velocity > 0.0 ? flow.velocity : flow.reynolds * nu / d;
    c.reynolds = c.velocity * d / nu;
    if (!(c.velocity <= limits::max_velocity_m_s))
        throw InvalidInput(fmt::format(
            "--reynolds {:g} is not allowed with spheres of {:g} m: the inlet's velocity would be "
            "{:g} m/s; allowed: a Reynolds number that gives at most {:g} m/s (or --scale, "
            "--viscosity, --fluid-density)",
            flow.reynolds, d, c.velocity, limits::max_velocity_m_s));
    const double area = section * c.scale * c.scale; // m^2
    if (periodic && flow.turbulence != Turbulence::laminar)
        throw InvalidInput(fmt::format("--turbulence {} is not allowed with --flow periodic; "
                                       "allowed: laminar (a periodic cell has no inlet to set the "
                                       "turbulence at)",
                                       turbulence_models().name(flow.turbulence)));
    // Planes clear of the bed's ends by 1 Dp (or its middle half when it is lower than 3 Dp).
    double low = diameter, high = bed_top - diameter;
    if (high - low < diameter) {
        low = 0.25 * bed_top;
        high = 0.75 * bed_top;
    }
    const int planes = periodic ? 0 : 9;
    for (int n = 0; n < planes; ++n)
        c.planes.push_back(c.scale * (low + (high - low) * n / (planes - 1)));
    c.interstitial_velocity = c.velocity / void_fraction;

    std::string u_walls, p_walls;
    for (const std::string& w : walls) {
        u_walls += fmt::format("    {} {{ type noSlip; }}\n", w);
        p_walls += fmt::format("    {} {{ type zeroGradient; }}\n", w);
    }
    const std::string u_ends =
        periodic ? std::string("    // periodic: constant/fvOptions holds the mean velocity\n")
                 : fmt::format("    // the superficial velocity {u} m/s times the cross-section "
                               "{a} m^2\n"
                               "    inlet {{ type flowRateInletVelocity; volumetricFlowRate {q}; "
                               "value uniform (0 0 0); }}\n"
                               "    outlet {{ type inletOutlet; inletValue uniform (0 0 0); value "
                               "$internalField; }}\n",
                               fmt::arg("u", c.velocity), fmt::arg("a", area),
                               fmt::arg("q", c.velocity * area));
    c.files.emplace_back(
        "0.orig/U",
        header("U", "0", "volVectorField") +
            fmt::format("dimensions [0 1 -1 0 0 0 0];\n\ninternalField uniform (0 0 0);\n\n"
                        "boundaryField\n{{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n"
                        "{ends}{walls}}}\n",
                        fmt::arg("ends", u_ends), fmt::arg("walls", u_walls)));
    c.files.emplace_back(
        "0.orig/p",
        header("p", "0", "volScalarField") +
            fmt::format("// kinematic: p / rho, m^2/s^2\ndimensions [0 2 -2 0 0 0 0];\n\n"
                        "internalField uniform 0;\n\n"
                        "boundaryField\n{{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n"
                        "{ends}{walls}}}\n",
                        fmt::arg("ends", periodic ? ""
                                                  : "    inlet { type zeroGradient; }\n"
                                                    "    outlet { type fixedValue; value uniform "
                                                    "0; }\n"),
                        fmt::arg("walls", p_walls)));
    if (periodic)
        // The momentum source of OpenFOAM's meanVelocityForce: a uniform pressure gradient
        // (kinematic) in every cell, corrected each iteration so that the volume-averaged
        // velocity of the fluid along z is Ubar; it writes the gradient to log.simpleFoam
        // ("pressure gradient = ...") and to TIME/uniform/.
        c.files.emplace_back(
            "constant/fvOptions",
            header("fvOptions", "constant") +
                fmt::format("// the superficial velocity {u} m/s over the cell's exact void "
                            "fraction {e}: the mean velocity in the fluid\n"
                            "momentumSource\n{{\n    type meanVelocityForce;\n"
                            "    selectionMode all;\n    fields (U);\n    Ubar (0 0 {ubar});\n}}\n",
                            fmt::arg("u", c.velocity), fmt::arg("e", void_fraction),
                            fmt::arg("ubar", c.interstitial_velocity)));
    c.files.emplace_back("constant/transportProperties",
                         header("transportProperties", "constant") +
                             fmt::format("// rho = {} kg/m^3, mu = {} Pa s\n"
                                         "transportModel Newtonian;\nnu {};\n",
                                         flow.fluid_density, flow.viscosity, nu));
    const Turbulence model = flow.turbulence;
    const bool rans = model != Turbulence::laminar;
    c.files.emplace_back(
        "constant/turbulenceProperties",
        header("turbulenceProperties", "constant") +
            (rans ? fmt::format("simulationType RAS;\nRAS\n{{\n    RASModel {};\n    turbulence "
                                "on;\n    printCoeffs on;\n}}\n",
                                turbulence_models().name(model))
                  : std::string("simulationType laminar;\n")));
    if (rans)
        add_rans_fields(c, walls, model, d);
    c.files.emplace_back(
        "system/decomposeParDict",
        header("decomposeParDict", "system") +
            fmt::format("numberOfSubdomains {0};\n// slabs along z: hierarchical works in "
                        "parallel snappyHexMesh (Debian's scotch and metis are stubs)\n"
                        "method hierarchical;\ncoeffs {{ n (1 1 {0}); }}\n",
                        flow.ranks) +
            (periodic ? "// both sides of each cyclic pair on one rank: parallel snappyHexMesh "
                        "cannot match a\n// processor boundary through a cyclic one\n"
                        "constraints\n{\n    cyclics\n    {\n        type preservePatches;\n"
                        "        patches (x_low x_high y_low y_high z_low z_high);\n"
                        "        enabled true;\n    }\n}\n"
                      : ""));
    std::string functions;
    for (std::size_t n = 0; n < c.planes.size(); ++n)
        functions += fmt::format("    p{}\n    {{\n{}    }}\n", n,
                                 plane_average(c.planes, n, 10, "        "));
    if (!periodic)
        functions +=
            "    inletFlux\n    {\n        type surfaceFieldValue;\n"
            "        libs (\"libfieldFunctionObjects.so\");\n"
            "        writeControl timeStep;\n        writeInterval 10;\n        log false;\n"
            "        writeFields false;\n        regionType patch;\n        name inlet;\n"
            "        operation sum;\n        fields (phi);\n    }\n"
            "    outletFlux\n    {\n        $inletFlux;\n        name outlet;\n    }\n";
    // A laminar run above Re_p 10, or on a mesh with layers, also stops once the pressure drop
    // across the planes is steady (docs/surfaces.md): its U residual can level off above
    // residualControl's (5.2e-5 on 30 spheres at a = 3, Re_p 100, where it asks 1e-5; 1.6e-6
    // with three layers on 150 spheres at a = 5, Re_p 1, where it asks 1e-6) while the drop has
    // long settled.
    if (!periodic && !rans && (c.reynolds > 10.0 || mesh.layers > 0))
        functions += steady_pressure_drop(c.planes, bed_void_fraction, c.velocity, d, flow);
    c.files.emplace_back(
        "system/controlDict",
        header("controlDict", "system") +
            "application simpleFoam;\nstartFrom latestTime;\nstartTime 0;\nstopAt endTime;\n"
            "endTime 3000;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 3000;\n"
            "purgeWrite 0;\nwriteFormat ascii;\nwritePrecision 10;\nwriteCompression off;\n"
            "timeFormat general;\ntimePrecision 6;\nrunTimeModifiable true;\n\n" +
            (periodic ? "// periodic: the pressure gradient is meanVelocityForce's, in "
                        "log.simpleFoam\n"
                      : "// the area-averaged (kinematic) pressure on planes z = const across the "
                        "bed, clear of its ends, and the volumetric fluxes of the inlet and outlet "
                        "(postProcessing/)\n") +
            "functions\n{\n" + functions + "}\n");
    // RANS: the turbulence quantities upwind (bounded), the wall distance of kOmegaSST, looser
    // residuals (a RANS solution's residuals level off higher) and relaxed k, epsilon, omega.
    c.files.emplace_back(
        "system/fvSchemes",
        header("fvSchemes", "system") +
            "ddtSchemes { default steadyState; }\n"
            "gradSchemes { default Gauss linear; grad(U) cellLimited Gauss linear 1; }\n"
            "divSchemes\n{\n    default none;\n"
            "    div(phi,U) bounded Gauss linearUpwind grad(U);\n" +
            (rans ? "    div(phi,k) bounded Gauss upwind;\n    div(phi,epsilon) bounded Gauss "
                    "upwind;\n    div(phi,omega) bounded Gauss upwind;\n"
                  : "") +
            "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
            "laplacianSchemes { default Gauss linear limited corrected 0.33; }\n"
            "interpolationSchemes { default linear; }\n"
            "snGradSchemes { default limited corrected 0.33; }\n" +
            (rans ? "wallDist { method meshWave; }\n" : ""));
    c.files.emplace_back(
        "system/fvSolution",
        header("fvSolution", "system") +
            "solvers\n{\n"
            "    p { solver GAMG; smoother GaussSeidel; tolerance 1e-9; relTol 0.01; }\n"
            "    \"(U|k|epsilon|omega)\" { solver smoothSolver; smoother symGaussSeidel; "
            "tolerance 1e-10; relTol 0.1; }\n"
            "}\n\n"
            "SIMPLE\n{\n    nNonOrthogonalCorrectors 1;\n    consistent yes;\n" +
            (periodic ? "    // no boundary fixes p: its level at cell 0\n    pRefCell 0;\n"
                        "    pRefValue 0;\n"
                      : "") +
            (rans ? "    residualControl { p 1e-5; U 1e-4; \"(k|epsilon|omega)\" 1e-5; }\n}\n\n"
                    "relaxationFactors { equations { U 0.9; \"(k|epsilon|omega)\" 0.7; } }\n"
                  // A periodic cell: U's residual levels off near 1e-6 in a random array (32
                  // spheres, 0.3: Uy at 1.02e-6 from iteration 300 to 3000, while the pressure
                  // gradient had settled to 1e-6 of itself by 150); 1e-5 stops it there and
                  // changes nothing in the simple cubic array (103 iterations either way).
                  // Laminar through a bed at Re_p 100 (150 spheres, a = 5, d/12): U's residual
                  // levels off at 6.23e-6 from iteration 600 to 3000, the planes' pressures
                  // settled to 1e-8 of themselves by 700; at Re_p 1 it falls below 1e-6 in about
                  // 100 iterations.
                  : std::string(periodic || c.reynolds > 10.0
                                    ? "    residualControl { p 1e-6; U 1e-5; }\n}\n\n"
                                    : "    residualControl { p 1e-6; U 1e-6; }\n}\n\n") +
                        "relaxationFactors { equations { U 0.9; } }\n"));
    c.allrun = fmt::format(
        "#!/bin/bash\n"
        "# Mesh, scale to metres, solve and post-process this case (written by packbed "
        "export).\n# Each step's output is in log.STEP; the first that fails stops the "
        "run.\nset -euo pipefail\ncd \"$(dirname \"$0\")\"\n"
        "# Debian's OpenFOAM finds its etc/ only through WM_PROJECT_DIR\n"
        "if [ -z \"${{WM_PROJECT_DIR:-}}\" ] && [ -d /usr/share/openfoam ]; then\n"
        "    export WM_PROJECT_DIR=/usr/share/openfoam\nfi\n"
        "ranks={ranks}  # decomposeParDict's numberOfSubdomains (export --ranks)\n"
        "mpi_flags=(-np \"$ranks\" -x WM_PROJECT_DIR)\n"
        "if [ \"$(id -u)\" = 0 ]; then mpi_flags+=(--allow-run-as-root); fi\n"
        "step() {{\n    local name=$1\n    shift\n    echo \"$name\"\n"
        "    if ! \"$@\" > \"log.$name\" 2>&1; then\n"
        "        echo \"$name failed (log.$name):\" >&2\n"
        "        tail -n 20 \"log.$name\" >&2\n        exit 1\n    fi\n}}\n"
        "parallel() {{\n    if [ \"$ranks\" -gt 1 ]; then\n"
        "        mpirun \"${{mpi_flags[@]}}\" \"$@\" -parallel\n    else\n        \"$@\"\n"
        "    fi\n}}\n"
        "step blockMesh blockMesh\n"
        "if [ \"$ranks\" -gt 1 ]; then step decomposePar decomposePar -force; fi\n"
        "step snappyHexMesh parallel snappyHexMesh -overwrite\n"
        "# the bed's units to metres: {scale} m per unit (d = {d} m)\n"
        "step transformPoints parallel transformPoints -scale '({scale} {scale} {scale})'\n"
        "if [ \"$ranks\" -gt 1 ]; then\n"
        "    for p in processor*; do rm -rf \"$p/0\"; cp -r 0.orig \"$p/0\"; done\n"
        "else\n    rm -rf 0\n    cp -r 0.orig 0\nfi\n"
        "step checkMesh parallel checkMesh\n"
        "step simpleFoam parallel simpleFoam\n"
        "if [ \"$ranks\" -gt 1 ]; then\n"
        "    step reconstructParMesh reconstructParMesh -constant\n"
        "    step reconstructPar reconstructPar -latestTime\nfi\n"
        "grep -E 'SIMPLE solution converged|pressureDropSteady condition satisfied' log.simpleFoam "
        "|| echo 'simpleFoam did not converge within endTime: see log.simpleFoam' >&2\n",
        fmt::arg("ranks", flow.ranks), fmt::arg("scale", c.scale), fmt::arg("d", d));
}

} // namespace

const Registry<Turbulence>& turbulence_models() {
    static const Registry<Turbulence> models("turbulence",
                                             {{"laminar", Turbulence::laminar},
                                              {"kEpsilon", Turbulence::k_epsilon},
                                              {"kOmegaSST", Turbulence::k_omega_sst}});
    return models;
}

const Registry<OpenFoamMeshOptions>& mesh_presets() {
    static const Registry<OpenFoamMeshOptions> presets(
        "mesh", {{"quick", OpenFoamMeshOptions{}},
                 {"accurate", OpenFoamMeshOptions{.cells_per_diameter = 8, .layers = 3}}});
    return presets;
}

OpenFoamCase openfoam_case(const TreatedBed& bed, const SurfaceContainer& container,
                           const TreatmentVolumes& volumes, const std::string& contacts,
                           double diameter, const SurfaceOptions& surface,
                           const OpenFoamMeshOptions& options, const OpenFoamFlowOptions& flow) {
    CaseParticles particles;
    // In a periodic cell the fluid point keeps clear of the copies across the sides too.
    const std::optional<Periods> cell = container.periods();
    particles.bounds = cell ? periodic_images(bed, *cell).bodies : bed.bodies;
    // A bridge's part outside its spheres lies within about its radius of their contact
    // point, which is on a sphere: it is at most that much closer than the spheres.
    for (const Bridge& b : bed.bridges)
        particles.reach = std::max(particles.reach, 1.01 * b.radius);
    particles.count = bed.bodies.size();
    for (const TreatedBody& b : bed.bodies)
        particles.top = std::max(particles.top, b.center.z + b.radius);
    double largest = 0.0;
    for (const TreatedBody& b : particles.bounds)
        largest = std::max(largest, b.radius);
    particles.wall_edge = largest * icosphere_edge(surface.level);
    SurfaceOptions tessellation = surface;
    tessellation.container = container;
    tessellation.write_container = false;
    tessellation.facets = facets_for(bed, tessellation);
    // Facets grown to hold the volume reach that much beyond the balls.
    if (tessellation.facets == Facets::volume)
        particles.reach =
            std::max(particles.reach, (volume_facets_scale(surface.level) - 1.0) * largest);
    particles.surface = bed_surface(bed, tessellation);
    return openfoam_case(particles, container, volumes, contacts, diameter, options, flow);
}

OpenFoamCase openfoam_case(const CaseParticles& particles, const SurfaceContainer& container,
                           const TreatmentVolumes& volumes, const std::string& contacts,
                           double diameter, const OpenFoamMeshOptions& options,
                           const OpenFoamFlowOptions& flow) {
    detail::require(options.cells_per_diameter >= 1 && options.cells_per_diameter <= 100,
                    "--cells-per-diameter", options.cells_per_diameter, "1 to 100");
    detail::require(options.particle_level >= 0 && options.particle_level <= 8, "--particle-level",
                    options.particle_level, "0 to 8");
    detail::require(options.wall_level >= 0 && options.wall_level <= 8, "--wall-level",
                    options.wall_level, "0 to 8");
    if (options.periodic_z && !container.container.periods())
        throw InvalidInput(fmt::format("--flow periodic is not allowed with --container {}; "
                                       "allowed: a periodic cell (periodic:LX,LY)",
                                       container.container.spec()));
    OpenFoamCase c;
    const double height = container.height;
    c.cell_size = diameter / options.cells_per_diameter;
    c.fluid_volume = volumes.container_volume - volumes.treated_solid;
    const OpenFoamBackground back =
        container.container.openfoam_background(height, c.cell_size, options);
    const double finest = detail::refined(
        c.cell_size, back.wall_surface ? std::max(options.particle_level, options.wall_level)
                                       : options.particle_level);
    const std::optional<Periods> cell = container.periods();
    std::tie(c.location_in_mesh, c.clearance) =
        farthest_fluid_point(particles.bounds, container, diameter);
    c.clearance -= particles.reach;
    if (!(c.clearance > 2.0 * finest))
        throw InvalidInput(fmt::format(
            "no point of the fluid clears every surface by two of the finest cells ({:.4g}): the "
            "largest clearance found is {:.4g}; allowed: a container taller than the bed, or "
            "finer cells",
            finest, c.clearance));

    c.particles = particles.surface;
    if (back.wall_surface) {
        // The wall, open, half a background cell beyond both ends of the box.
        std::vector<Solid> walls =
            container.container.solids(-0.5 * c.cell_size, height + 0.5 * c.cell_size,
                                       std::min(particles.wall_edge, 0.5 * c.cell_size));
        c.wall.push_back(std::move(walls[0]));
        if (back.rod_surface) // an annulus: solids wall, rod, bottom, top
            c.rod.push_back(std::move(walls[1]));
    }
    c.files.emplace_back("system/blockMeshDict",
                         header("blockMeshDict", "system") + back.block_mesh);

    std::string snappy = header("snappyHexMeshDict", "system");
    snappy += fmt::format(
        "castellatedMesh true;\nsnap true;\naddLayers {add_layers};\n\n"
        "geometry\n{{\n"
        "    particles.stl {{ type triSurfaceMesh; name particles; }}\n"
        "{wall_geometry}}}\n\n"
        "castellatedMeshControls\n{{\n"
        "    maxLocalCells 10000000;\n    maxGlobalCells 50000000;\n"
        "    minRefinementCells 0;\n    maxLoadUnbalance 0.10;\n    nCellsBetweenLevels 2;\n"
        "    features ();\n"
        "    // Levels tied to Dp: a cell of level L at a surface is Dp / ({cpd} 2^L).\n"
        "    refinementSurfaces\n    {{\n"
        "        particles {{ level ({lp} {lp}); patchInfo {{ type wall; }} }}\n"
        "{wall_refinement}    }}\n"
        "    resolveFeatureAngle 30;\n    refinementRegions {{}}\n"
        "    // In the fluid, {clear} from the nearest surface.\n"
        "    locationInMesh ({x} {y} {z});\n"
        "    allowFreeStandingZoneFaces true;\n}}\n\n"
        "snapControls\n{{\n    nSmoothPatch 3;\n    tolerance 2.0;\n    nSolveIter 30;\n"
        "    nRelaxIter 5;\n    nFeatureSnapIter 10;\n    implicitFeatureSnap false;\n"
        "    explicitFeatureSnap false;\n    multiRegionFeatureSnap false;\n}}\n\n"
        "{layer_controls}"
        "meshQualityControls\n{{\n    maxNonOrtho 65;\n    maxBoundarySkewness {skew};\n"
        "    maxInternalSkewness 4;\n    maxConcave 80;\n    minVol 1e-30;\n"
        "    minTetQuality 1e-30;\n    minArea -1;\n    minTwist 0.02;\n"
        "    minDeterminant 0.001;\n    minFaceWeight 0.05;\n    minVolRatio 0.01;\n"
        "    minTriangleTwist -1;\n    nSmoothScale 4;\n    errorReduction 0.75;\n"
        "    relaxed {{ maxNonOrtho 75; }}\n}}\n\n"
        "mergeTolerance 1e-6;\n",
        fmt::arg("wall_geometry",
                 std::string(back.wall_surface
                                 ? "    wall.stl { type triSurfaceMesh; name wall; }\n"
                                 : "") +
                     (back.rod_surface ? "    rod.stl { type triSurfaceMesh; name rod; }\n" : "")),
        fmt::arg("wall_refinement",
                 (back.wall_surface ? fmt::format("        wall {{ level ({0} {0}); patchInfo {{ "
                                                  "type wall; }} }}\n",
                                                  options.wall_level)
                                    : std::string()) +
                     (back.rod_surface ? fmt::format("        rod {{ level ({0} {0}); patchInfo "
                                                     "{{ type wall; }} }}\n",
                                                     options.wall_level)
                                       : std::string())),
        fmt::arg("add_layers", options.layers > 0 ? "true" : "false"),
        fmt::arg("layer_controls", add_layers_controls(options.layers, back)),
        fmt::arg("skew", back.boundary_skewness), fmt::arg("cpd", options.cells_per_diameter),
        fmt::arg("lp", options.particle_level), fmt::arg("clear", c.clearance),
        fmt::arg("x", c.location_in_mesh.x), fmt::arg("y", c.location_in_mesh.y),
        fmt::arg("z", c.location_in_mesh.z));
    c.files.emplace_back("system/snappyHexMeshDict", snappy);

    // The flow: scaled to metres by Allrun, d = 1 mm unless a scale is given.
    if (flow.scale != 0.0)
        check_option("scale", flow.scale, option_range::metres_per_unit);
    c.scale = flow.scale > 0.0 ? flow.scale : 1e-3 / diameter;
    std::vector<std::string> walls{"particles"};
    if (!cell)
        walls.push_back("wall");
    if (back.rod_surface)
        walls.push_back("rod");
    if (back.wall_surface)
        walls.push_back("outside"); // no faces after snappyHexMesh; an entry all the same
    const double section = container.container.cross_section_area(0.0, 0.0);
    const double bed_top = std::min(particles.top, height);
    // The bed's void fraction below its top (the stop on a steady pressure drop scales with
    // Ergun's drop at it): the container's may count a clear space above the bed.
    const double void_below_top =
        std::clamp(1.0 - volumes.treated_solid /
                             (container.container.cross_section_area(0.0, bed_top) * bed_top),
                   0.2, 0.95);
    add_flow_files(c, walls, bed_top, section, diameter, flow, options,
                   volumes.treated_void_fraction, void_below_top);
    c.files.emplace_back("case.foam", ""); // what ParaView opens the case by

    const double bed_void = volumes.untouched_void_fraction;
    const std::string drive =
        options.periodic_z
            ? fmt::format("the cell repeats along z with period {} (bed units): no inlet or "
                          "outlet; `constant/fvOptions` (meanVelocityForce) holds the mean "
                          "velocity in the fluid at {} m/s, the superficial velocity over the "
                          "exact void fraction {:.6f}, by a uniform pressure gradient (`p` is "
                          "kinematic, p / rho, and periodic); no slip on the particles.",
                          height, c.interstitial_velocity, volumes.treated_void_fraction)
            : std::string("the inlet's flow rate that velocity times the container's "
                          "cross-section, the outlet at p = 0 (`p` is kinematic, p / rho); no "
                          "slip on the particles and walls.");
    const std::string results =
        options.periodic_z
            ? std::string("`log.simpleFoam`: \"pressure gradient = G\" each iteration, the "
                          "kinematic gradient that drives the flow (rho G in Pa/m); the drag on "
                          "the spheres balances it: G rho times the cell's volume over the "
                          "number of spheres is each one's (`packbed cfd-report`).")
            : fmt::format("`postProcessing/p0` to `p{}`: the area-averaged (kinematic) pressure "
                          "on the planes z = {} to {} m across the bed, 1 Dp clear of its ends, "
                          "with each plane's fluid area; `postProcessing/inletFlux` and "
                          "`outletFlux`: the volumetric fluxes (m^3/s). The pressure gradient is "
                          "-rho times the slope of the planes' pressures against z.",
                          c.planes.size() - 1, c.planes.front(), c.planes.back());
    const std::string ends = options.periodic_z
                                 ? std::string()
                                 : fmt::format("`inlet` (z = 0), `outlet` (z = {}), ", height);
    c.files.emplace_back(
        "README.md",
        fmt::format(
            "# Packed bed for snappyHexMesh and simpleFoam (written by packbed export)\n\n"
            "{n} particles of diameter {dp} in {where}, from z = 0 to {h} "
            "(lengths in the bed's unit; `scale 1`). Contacts: `{contacts}`.\n\n"
            "Run it all, on {ranks} MPI rank(s) (export again with `--ranks N` for another "
            "count):\n\n```sh\n./Allrun\n```\n\n"
            "blockMesh, decomposePar, snappyHexMesh, transformPoints (the bed's units to "
            "metres: "
            "{scale} m per unit, so d = {dm} m), checkMesh, simpleFoam ({model}, steady), "
            "reconstructParMesh and reconstructPar; each step's output in `log.STEP`. The "
            "fluid: rho = {rho} kg/m^3, mu = {mu} Pa s (nu = {nu} m^2/s); {whose}"
            "superficial velocity {u} m/s, the particle Reynolds number rho u d / mu = "
            "{re:.4g}; {drive} Or step by step: `blockMesh`, `snappyHexMesh -overwrite`, "
            "`checkMesh` mesh it in the bed's units.\n\n"
            "{results}\n\n"
            "(Debian's OpenFOAM needs `export WM_PROJECT_DIR=/usr/share/openfoam` first, "
            "where its `etc/` is, as Allrun does; elsewhere source OpenFOAM's `etc/bashrc`.) "
            "Open "
            "`case.foam` in ParaView to see the mesh and the flow.\n\n"
            "- `constant/triSurface/particles.stl`: every particle, closed and separate (patch "
            "`particles`){surfaces}.\n"
            "- Patches after meshing: {ends}`particles`{patches}.\n"
            "- {cells}.\n{layers}"
            "- `locationInMesh` ({x}, {y}, {z}): {clear} from the nearest surface.\n\n"
            "Exact volumes (geometry, not the mesh): container {vc}; solid {vs} after the "
            "treatment; fluid {vf}. Void fraction {e0:.6f} untouched, {e1:.6f} treated. "
            "`checkMesh` prints the mesh's `Total volume`, to compare with the fluid volume: "
            "gaps narrower than the finest cells are lost by the mesh, so refine where that "
            "matters.\n",
            fmt::arg("n", particles.count), fmt::arg("dp", diameter), fmt::arg("where", back.where),
            fmt::arg("h", height), fmt::arg("contacts", contacts),
            fmt::arg("surfaces", back.surfaces), fmt::arg("patches", back.patches),
            fmt::arg("cells", back.cells), fmt::arg("x", c.location_in_mesh.x),
            fmt::arg("y", c.location_in_mesh.y), fmt::arg("z", c.location_in_mesh.z),
            fmt::arg("clear", c.clearance), fmt::arg("vc", volumes.container_volume),
            fmt::arg("vs", volumes.treated_solid), fmt::arg("vf", c.fluid_volume),
            fmt::arg("e0", bed_void), fmt::arg("e1", volumes.treated_void_fraction),
            fmt::arg("model", flow.turbulence == Turbulence::laminar
                                  ? std::string("laminar")
                                  : "RANS, " + turbulence_models().name(flow.turbulence)),
            fmt::arg("ranks", flow.ranks), fmt::arg("scale", c.scale),
            fmt::arg("dm", c.scale * diameter), fmt::arg("rho", flow.fluid_density),
            fmt::arg("mu", flow.viscosity), fmt::arg("nu", flow.viscosity / flow.fluid_density),
            fmt::arg("u", c.velocity), fmt::arg("re", c.reynolds), fmt::arg("drive", drive),
            fmt::arg("results", results), fmt::arg("ends", ends),
            fmt::arg("layers",
                     options.layers > 0
                         ? fmt::format("- {} prism layers asked on the particles{} (the last "
                                       "half the cell beside it, each 1.2 times the one before): "
                                       "snappyHexMesh thins or drops them where surfaces are "
                                       "close; the table at the end of `log.snappyHexMesh` "
                                       "gives how many it added on each patch.\n",
                                       options.layers,
                                       back.rod_surface    ? ", the wall and the rod"
                                       : back.wall_surface ? " and the wall"
                                                           : "")
                         : std::string()),
            fmt::arg("whose", options.periodic_z ? "the " : "the inlet's ")));
    return c;
}

} // namespace packbed
