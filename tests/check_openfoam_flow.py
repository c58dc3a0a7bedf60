#!/usr/bin/env python3
"""`packbed export --format openfoam` run as a user would: ./Allrun on 2 MPI ranks
(blockMesh, decomposePar, snappyHexMesh, transformPoints to metres, checkMesh, simpleFoam,
reconstructPar) on a generated bed of 30 spheres (a = 3, caps:0.02, d = 1 mm, water at
Re_p = 1). Asserts
- simpleFoam converged: "SIMPLE solution converged", every last initial residual of p and U
  below the case's residualControl (1e-6; RANS 1e-5, U 1e-4);
- mass is conserved: the inlet's and the outlet's volumetric fluxes within 0.1 %, and the
  inlet's flux is the superficial velocity times the tube's cross-section;
- the pressure gradient over the bed clear of its ends (a straight line fitted to the 9
  planes' area-averaged pressures) against Eisfeld & Schnitzlein's at the bed's own void
  fraction in the same band (packbed hydraulics): measured 0.567 of it (957.9 Pa/m against
  1689 Pa/m; Ergun 888 Pa/m) with the case's default facets (auto: volume here). The band
  asserted is 0.465 to 0.669, 0.567 +- 18 %: the run is
  deterministic (the same packages give the same digits), so the band is for another
  OpenFOAM build or rank count, and narrow enough to catch what matters. One refinement level
  coarser moved the paper's bed from 0.70 to 1.29 (docs/validation.md, "CFD"); wrong units,
  fluid or boundary conditions move it by orders of magnitude. This is not the validation (the
  bed is a = 3, the edge of Eisfeld & Schnitzlein's data): that is docs/validation.md.

With a RANS model (`check_openfoam_flow.py PACKBED kOmegaSST 100`: --turbulence and
--reynolds), the same bed at Re_p = 100: simpleFoam ran the model (its log names it, nut is
not zero), converged to the RANS residuals (1e-5, U 1e-4), conserved mass, and the gradient lies
within 18 % of the measured 0.688 of Eisfeld & Schnitzlein (2.065e5 Pa/m against 3.001e5):
0.564 to 0.812.

Laminar at Re_p = 100 (`check_openfoam_flow.py PACKBED laminar 100`), the same bed: U's
residual levels off near 5e-5, above the case's 1e-5, so residualControl never stops it (it
ran all 3 000 iterations, 210 s, before the stop below). The case's runTimeControl ends it once
the pressure drop across the planes is steady: measured at iteration 303 (a run to 1 500
iterations ends 6e-7 away in the gradient). Asserted: the log says that condition ended the run
and not residualControl (U's last residual above 1e-5), within 1 000 iterations; the drop's last
50 values (postProcessing/pressureDrop) within 1e-5 of the last; cfd-report says converged,
stopped by "steady pressure drop"; the gradient within 18 % of the measured 0.688 of Eisfeld &
Schnitzlein (2.065e5 Pa/m, the kOmegaSST run's to 0.02 %).

With prism layers (`check_openfoam_flow.py PACKBED laminar 1 3`: --layers 3), the same bed
at Re_p = 1: snappyHexMesh added layers on the particles and on the wall (measured 1.04 and
1.86 of the 3 asked, on average; asserted above 0.9), the run converged (measured: on a steady
pressure drop at iteration 119), mass is conserved, and the gradient lies within 3 % of
1 129.75 Pa/m, where the same bed's layered meshes settle (d/24 and d/32 within 0.02 % of each
other; docs/validation.md, "Prism layers"): measured 1 110.0, 1.75 % below, where the same
mesh without layers gives 957.9, 15 % below.

Usage: check_openfoam_flow.py PACKBED [TURBULENCE REYNOLDS [LAYERS]]. Exit 77 (skipped) when OpenFOAM
or mpirun is missing (scripts/install-deps.sh --test installs both)."""
import glob
import json
import math
import os
import re
import shutil
import sys
import tempfile

from openfoam_env import RUNNING, openfoam_or_skip, runner

exe = sys.argv[1]
turbulence, reynolds = (sys.argv[2], float(sys.argv[3])) if len(sys.argv) > 3 else ("laminar", 1.0)
layers = int(sys.argv[4]) if len(sys.argv) > 4 else 0
env = openfoam_or_skip(RUNNING)
work = tempfile.mkdtemp(prefix="packbed-flow-")
run = runner(env, work)


def last_row(name):
    """The last row of postProcessing/NAME/0/surfaceFieldValue.dat, as numbers."""
    rows = [line.split() for line in open(os.path.join(case, "postProcessing", name, "0",
                                                       "surfaceFieldValue.dat"))
            if line.strip() and not line.startswith("#")]
    return [float(v) for v in rows[-1]]


case = os.path.join(work, "case")
run(exe, "generate", "--solver", "fire", "--aspect-ratio", "3", "--particles", "30", "--seed",
    "1", "--quiet", "--out", "bed")
run(exe, "export", "bed/particles.csv", "--format", "openfoam", "--contacts", "caps:0.02",
    "--ranks", "2", "--turbulence", turbulence, "--reynolds", repr(reynolds), "--layers",
    str(layers), "--out", case, "--quiet")
flow = json.load(open(os.path.join(case, "packbed.json")))["openfoam"]["flow"]
assert flow["ranks"] == 2 and flow["reynolds"] == reynolds, flow
assert flow["turbulence"] == turbulence, flow
# Re_p = rho u d / mu for water and d = 1 mm
assert math.isclose(flow["velocity"], reynolds * 1.002e-3 / (998.2 * 1e-3), rel_tol=1e-12), flow
run(os.path.join(case, "Allrun"), cwd=case)

log = open(os.path.join(case, "log.simpleFoam")).read()
last = log[log.rfind("\nTime = "):]
steady_stop = turbulence == "laminar" and reynolds > 10
if layers:
    # snappyHexMesh's table of what it added: every patch asked got layers on average (it
    # thins or drops them near contacts and in narrow gaps), then either stop may end the run.
    table = open(os.path.join(case, "log.snappyHexMesh")).read()
    table = table[table.rfind("patch     faces    layers"):]
    added = {m.group(1): float(m.group(2))
             for m in re.finditer(r"^(particles|wall)\s+\d+\s+([0-9.]+)\s", table, re.M)}
    print(f"layers added on average: {added}")
    assert set(added) == {"particles", "wall"} and min(added.values()) > 0.9, table[:2000]
    steady_stop = "pressureDropSteady condition satisfied" in log
if steady_stop:
    assert "pressureDropSteady condition satisfied" in log, log[-3000:]
    assert "SIMPLE solution converged" not in log, log[-3000:]
    iterations = int(re.search(r"Time = (\d+)", last).group(1))
    ux = float(re.search(r"Solving for Ux, Initial residual = ([0-9.eE+-]+)", last).group(1))
    print(f"stopped on a steady pressure drop at iteration {iterations}, U's residual {ux:.3g}")
    # above residualControl's U (1e-5 above Re_p 10, 1e-6 below), or it would have stopped
    assert iterations < 1000 and ux > (1e-5 if reynolds > 10 else 1e-6), (iterations, ux)
    drop = [float(line.split()[1]) for line in
            open(os.path.join(case, "postProcessing", "pressureDrop", "0",
                              "fieldValueDelta.dat"))
            if line.strip() and not line.startswith("#")]
    spread = (max(drop[-50:]) - min(drop[-50:])) / abs(drop[-1])
    assert spread < 1e-5, spread
else:
    assert "SIMPLE solution converged" in log, log[-3000:]
    # the residualControl of the case's fvSolution: laminar 1e-6; RANS 1e-5, U 1e-4 (the
    # first initial residual of each field in the last iteration)
    tolerances = {"p": 1e-6, "Ux": 1e-6, "Uy": 1e-6, "Uz": 1e-6}
    if turbulence != "laminar":
        assert f"Selecting RAS turbulence model {turbulence}" in log, log[:3000]
        tolerances = {"p": 1e-5, "Ux": 1e-4, "Uy": 1e-4, "Uz": 1e-4, "k": 1e-5}
    for field, tolerance in tolerances.items():
        residual = re.search(rf"Solving for {field}, Initial residual = ([0-9.eE+-]+)", last)
        assert residual and float(residual.group(1)) < tolerance, (field, last)
assert glob.glob(os.path.join(case, "processor*")), "not run in parallel"

inlet, outlet = last_row("inletFlux")[1], last_row("outletFlux")[1]
imbalance = abs(inlet + outlet) / abs(inlet)
print(f"fluxes: inlet {inlet:.6e}, outlet {outlet:.6e} m^3/s: imbalance {imbalance:.2e}")
assert imbalance < 1e-3, imbalance
# the inlet's flux is the superficial velocity times the tube's section (flowRateInletVelocity:
# the spheres on the floor cover 6 % of the inlet, the open part takes the flow)
section = math.pi * (1.5e-3) ** 2
assert math.isclose(-inlet, flow["velocity"] * section, rel_tol=1e-6), (inlet, flow)

z = flow["pressure_planes"]
p = [last_row(f"p{n}")[2] for n in range(len(z))]  # kinematic, m^2/s^2
mean_z, mean_p = sum(z) / len(z), sum(p) / len(p)
slope = sum((a - mean_z) * (b - mean_p) for a, b in zip(z, p)) / sum(
    (a - mean_z) ** 2 for a in z)
gradient = -flow["fluid_density"] * slope  # Pa/m
summary = json.load(open(os.path.join(work, "bed", "summary.json")))
band = summary["void_fraction_band"]
assert math.isclose(z[0], band[0] * 1e-3) and math.isclose(z[-1], band[1] * 1e-3), (z, band)
report = json.loads(run(exe, "hydraulics", "--porosity", repr(summary["void_fraction"]),
                        "--diameter", "1e-3", "--velocity", repr(flow["velocity"]),
                        "--aspect-ratio", "3", "--json"))["pressure_gradient"]
ratio = gradient / report["eisfeld_schnitzlein_Pa_m"]
print(f"pressure gradient {gradient:.4g} Pa/m over z {z[0]:.4g} to {z[-1]:.4g} m; Eisfeld & "
      f"Schnitzlein {report['eisfeld_schnitzlein_Pa_m']:.4g} Pa/m (ratio {ratio:.3f}), Ergun "
      f"{report['ergun_Pa_m']:.4g} Pa/m, at the band's void fraction "
      f"{summary['void_fraction']:.4f}")
measured = 0.567 if reynolds < 10 else 0.688
if layers:
    measured = 0.6572
    # The same bed's layered meshes settle at d/24 and d/32 (1 129.95 and 1 129.75 Pa/m;
    # docs/validation.md), where this mesh gives 1 110.0, 1.75 % below; without layers it
    # gives 957.9, 15 % below. Asserted: within 3 % of the finest.
    assert abs(gradient / 1129.75 - 1) < 0.03, gradient
assert abs(ratio / measured - 1) < 0.18, (ratio, measured)
if turbulence != "laminar":  # the model ran: a turbulent viscosity somewhere in the bed
    times = [d for d in os.listdir(case) if re.fullmatch(r"[0-9]+", d) and d != "0"]
    nut = open(os.path.join(case, max(times, key=int), "nut")).read()
    values = re.search(r"internalField\s+nonuniform\s+List<scalar>\s+\d+\s*\(([^)]*)\)", nut)
    assert values and max(float(v) for v in values.group(1).split()) > 0, nut[:2000]

# packbed cfd-report reads the same case to the same numbers.
r = json.loads(run(exe, "cfd-report", case, "--json"))
assert math.isclose(r["pressure_gradient_Pa_m"]["cfd"], gradient, rel_tol=1e-9), r
assert math.isclose(r["correlations"]["eisfeld_schnitzlein_Pa_m"],
                    report["eisfeld_schnitzlein_Pa_m"], rel_tol=1e-9), r
assert math.isclose(r["correlations"]["ergun_Pa_m"], report["ergun_Pa_m"], rel_tol=1e-9), r
assert math.isclose(r["void_fraction"]["band"], summary["void_fraction"], rel_tol=1e-9), r
assert r["solver"]["converged"] and math.isclose(r["fluxes_m3_s"]["inlet"], inlet), r
assert r["solver"]["stopped_by"] == ("steady pressure drop" if steady_stop else "residuals"), r
# the mesh holds less fluid than the exact treated geometry: the gaps it cannot resolve
assert r["void_fraction"]["mesh"] < r["void_fraction"]["container_treated"], r
print(f"cfd-report: void fraction {r['void_fraction']['container_treated']:.5f} treated, "
      f"{r['void_fraction']['mesh']:.5f} meshed")
shutil.rmtree(work)
