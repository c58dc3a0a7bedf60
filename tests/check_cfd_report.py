#!/usr/bin/env python3
"""`packbed cfd-report` on a case whose results are made here, without OpenFOAM: the files
Allrun's run leaves (packbed.json as the export writes it, postProcessing/pN and the fluxes in
OpenFOAM's surfaceFieldValue layout, log.simpleFoam, log.checkMesh) with pressures on a known
line. Asserts
- the fitted gradient is the line's (to 1e-9: the tables hold 11 digits, as OpenFOAM writes
  them), and its standard error that of the least-squares formula when the planes scatter;
- Ergun's and Eisfeld & Schnitzlein's gradients are their formulas (written out here, with their
  sources) at the recorded void fraction, velocity, fluid and aspect ratio (to 1e-12), and so
  is each of the band of correlations (Carman, KTA, Erdim et al., Harrison et al. too), its span
  and whether the CFD lies in it; a bed with no wall gets those without a wall term;
- the flux imbalance, the convergence and iteration count, each field's first initial residual of
  the last iteration, the mesh's void fraction (checkMesh's volume over the container's);
- a restarted run's latest table is read, and the newest table with a row where a run was
  restarted from the same write again (OpenFOAM's surfaceFieldValue_START.dat beside the first)
  or stopped before its first write (an empty table);
- pressure.csv holds the planes; the plot is drawn when gnuplot is there;
- bad cases exit 2 with one line naming CASE, and write nothing (planes whose last rows are of
  different iterations among them).

Usage: check_cfd_report.py PACKBED"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile


RHO, MU, U, SCALE = 998.2, 1.002e-3, 2.5e-3, 1e-3  # water, 2.5 mm/s, bed units of 1 mm
D, E, A = 1.0, 0.42, 5.0  # diameter (bed units), void fraction between the planes, D/d
GRADIENT = 5432.1  # Pa/m, the line the planes lie on
Z = [0.001 + 0.002 * k for k in range(9)]  # m
CONTAINER = 120.0  # bed units^3
MESH = 0.055 * (CONTAINER * SCALE**3)  # checkMesh's "Total volume", m^3: void fraction 0.055


def table(path, region, columns, rows):
    """A surfaceFieldValue.dat as OpenFOAM v1912 writes it."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(f"# Region type :   {region}\n# Faces           : 100\n"
                f"# Area            : 1.0e-06\n# Scale factor    : 1.0000000000e+00\n")
        f.write("# " + "\t".join(["Time            "] + columns) + "\n")
        for row in rows:
            f.write("\t".join(f"{v:.10e}" if i else f"{v:<18g}" for i, v in enumerate(row)) + "\n")


def make_case(work, name, scatter=None, restarted=False):
    """The case NAME under WORK; pressures on the line GRADIENT, plus `scatter` (kinematic).
    `restarted`: the run went on from 20 (True); and "again": from 20 once more, its table
    surfaceFieldValue_20.dat (the first restart's stopped before its first write, empty);
    "stopped": the second restart stopped before its first write too (both tables of 20
    empty)."""
    case = os.path.join(work, name)
    os.makedirs(case)
    json.dump({"diameter": D,
               "volumes": {"container": CONTAINER, "untouched_void_fraction": 0.52,
                           "treated_void_fraction": 0.525},
               "openfoam": {"flow": {"ranks": 2, "metres_per_unit": SCALE, "fluid_density": RHO,
                                     "viscosity": MU, "velocity": U,
                                     "reynolds": RHO * U * D * SCALE / MU, "pressure_planes": Z,
                                     "band_void_fraction": E, "aspect_ratio": A}}},
              open(os.path.join(case, "packbed.json"), "w"), indent=2)
    for k, z in enumerate(Z):
        p = GRADIENT * (0.02 - z) / RHO + (scatter[k] if scatter else 0.0)  # kinematic
        rows = [(10, 1e-6, 7.0), (20, 1e-6, p)]
        table(os.path.join(case, "postProcessing", f"p{k}", "0", "surfaceFieldValue.dat"),
              f"sampledSurface p{k}", ["Area", "areaAverage(p)"], rows)
        later = os.path.join(case, "postProcessing", f"p{k}", "20")
        if restarted is True:  # the run went on from 20: its own table, the one to read
            table(os.path.join(later, "surfaceFieldValue.dat"), f"sampledSurface p{k}",
                  ["Area", "areaAverage(p)"], [(30, 1e-6, p + 1.0 - z)])
        elif restarted:  # from 20 twice, the first stopped before it wrote (empty)
            os.makedirs(later)
            open(os.path.join(later, "surfaceFieldValue.dat"), "w").close()
            again = os.path.join(later, "surfaceFieldValue_20.dat")
            if restarted == "again":
                table(again, f"sampledSurface p{k}", ["Area", "areaAverage(p)"],
                      [(30, 1e-6, p + 2.0 - 2.0 * z)])
            else:
                open(again, "w").close()
    table(os.path.join(case, "postProcessing", "inletFlux", "0", "surfaceFieldValue.dat"),
          "patch inlet", ["sum(phi)"], [(20, -2.0e-9)])
    table(os.path.join(case, "postProcessing", "outletFlux", "0", "surfaceFieldValue.dat"),
          "patch outlet", ["sum(phi)"], [(20, 2.0e-9 * (1 + 3e-4))])
    with open(os.path.join(case, "log.simpleFoam"), "w") as f:
        for t in (1, 2):
            f.write(f"Time = {t}\n\n")
            f.write(f"smoothSolver:  Solving for Ux, Initial residual = {1e-3 / t}, Final "
                    f"residual = 1e-9, No Iterations 1\n")
            f.write(f"GAMG:  Solving for p, Initial residual = {2e-3 / t}, Final residual = "
                    f"1e-9, No Iterations 3\n")
            f.write("GAMG:  Solving for p, Initial residual = 5e-11, Final residual = 5e-11, No "
                    "Iterations 0\n")
        f.write("\nSIMPLE solution converged in 2 iterations\n\nEnd\n")
    with open(os.path.join(case, "log.checkMesh"), "w") as f:
        f.write(f"    Min volume = 1e-14. Max volume = 1e-11.  Total volume = {MESH:.10e}.  "
                "Cell volumes OK.\n")
    return case


PHI, RADIUS, UBAR, CELL = 0.216, 0.372, 1.3e-5, 8.0  # a periodic cell (bed units, m/s)


def make_periodic_case(work, name, k, cells, void=0.79, phi=PHI, ubar=UBAR):
    """A cell periodic along z as export --flow periodic records it and its run logs: the
    meanVelocityForce gradient that gives Zick & Homsy's K = k on a mesh of `cells` cells
    and void fraction `void`."""
    case = os.path.join(work, name)
    os.makedirs(case)
    json.dump({"diameter": D,
               "openfoam": {"flow": {"ranks": 2, "metres_per_unit": SCALE, "fluid_density": RHO,
                                     "viscosity": MU, "velocity": ubar * (1 - phi),
                                     "reynolds": 0.01, "pressure_planes": [],
                                     "band_void_fraction": 1 - phi, "aspect_ratio": None,
                                     "periodic": {"period_z": 2.0, "cell_volume": CELL,
                                                  "spheres": 8, "sphere_radius": RADIUS,
                                                  "solid_fraction": phi,
                                                  "interstitial_velocity": ubar}}}},
              open(os.path.join(case, "packbed.json"), "w"), indent=2)
    volume = CELL * SCALE**3
    force = k * 6 * math.pi * MU * RADIUS * SCALE * ubar * void  # on a sphere, N
    gradient = force * 8 / volume / RHO  # kinematic, m/s^2
    with open(os.path.join(case, "log.simpleFoam"), "w") as f:
        for t, g in ((1, 2 * gradient), (2, gradient)):  # the last line is the one read
            f.write(f"Time = {t}\n\nPressure gradient source: uncorrected Ubar = {ubar}, "
                    f"pressure gradient = {g!r}\n")
        f.write("\nSIMPLE solution converged in 2 iterations\n\nEnd\n")
    with open(os.path.join(case, "log.checkMesh"), "w") as f:
        f.write(f"    cells:            {cells}\n    Min volume = 1e-14. Max volume = 1e-11.  "
                f"Total volume = {void * volume!r}.  Cell volumes OK.\n")
    return case


def periodic_cases(exe, work):
    """cfd-report of a periodic cell, and a mesh series of three (Celik et al. 2008)."""
    # One case: K = rho G V / 8 / (6 pi mu a U_s), U_s = Ubar times the mesh's void fraction;
    # Zick & Homsy's 7.442 at 0.216; van der Hoef's (2005) eq. (9) for (1 - phi) K.
    r = report(exe, make_periodic_case(work, "cell", 7.0, 1000))
    p = r["periodic"]
    assert math.isclose(p["K"], 7.0, rel_tol=1e-12), p
    assert math.isclose(p["F"], (1 - PHI) * 7.0, rel_tol=1e-12), p
    assert math.isclose(r["flow"]["superficial_velocity_m_s"], UBAR * 0.79, rel_tol=1e-12), r
    assert math.isclose(r["void_fraction"]["mesh"], 0.79, rel_tol=1e-12), r
    ref = p["references"]
    assert ref["zick_homsy_simple_cubic_K"] == 7.442 and ref["zick_homsy_solid_fraction"] == 0.216
    assert math.isclose(ref["K_over_zick_homsy"], 7.0 / 7.442, rel_tol=1e-12), ref
    vdh = 10 * PHI / (1 - PHI) ** 2 + (1 - PHI) ** 2 * (1 + 1.5 * math.sqrt(PHI))
    assert math.isclose(ref["van_der_hoef_random_F"], vdh, rel_tol=1e-12), ref
    assert r["mesh"] == {"cells": 1000, "volume_m3": 0.79 * CELL * SCALE**3}, r["mesh"]
    assert sorted(os.listdir(os.path.join(work, "cell", "cfd-report"))) == ["cfd_report.json"]
    # A series whose K follows 7.4 + 30 (h/d)^2 exactly: order 2, extrapolated 7.4, and the
    # GCI of the finest 1.25 |(K1 - K2) / K1| / (r^2 - 1). h/d = (mesh volume / cells)^(1/3)
    # over the spheres' diameter 2 RADIUS.
    volume = 0.79 * CELL
    cases, ks = [], []
    for n, cells in enumerate((27000, 8000, 1000)):  # given fine to coarse: sorted by cells
        h = (volume / cells) ** (1 / 3) / (2 * RADIUS)
        ks.append(7.4 + 30 * h * h)
        cases.append(make_periodic_case(work, f"level{n}", ks[-1], cells))
    out = subprocess.run([exe, "cfd-report", *cases, "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    series = json.loads(out.stdout)
    assert [row["cells"] for row in series["levels"]] == [1000, 8000, 27000], series
    c = series["celik"]
    assert math.isclose(c["order"], 2.0, rel_tol=1e-9) and not c["oscillating"], c
    assert math.isclose(c["extrapolated"], 7.4, rel_tol=1e-9), c
    r21 = 1.5  # (27000 / 8000)^(1/3)
    assert math.isclose(c["gci_fine"], 1.25 * abs((ks[0] - ks[1]) / ks[0]) / (r21**2 - 1),
                        rel_tol=1e-9), c
    assert math.isclose(c["extrapolated_over_reference"], 7.4 / 7.442, rel_tol=1e-9), c
    rows = list(csv.DictReader(open(os.path.join(cases[-1], "cfd-series", "series.csv"))))
    assert [float(row["K"]) for row in rows] == [row["K"] for row in series["levels"]], rows
    print(f"periodic: K {p['K']:.6f}; series order {c['order']:.6f}, extrapolated "
          f"{c['extrapolated']:.9f}, GCI {100 * c['gci_fine']:.4f} %")
    # Refused: two cases (a series needs 3), cases of two kinds, of two beds or two flows, a
    # finer mesh (more cells) with no smaller cells (another bed's volume).
    line = make_case(work, "inlet-level")
    other = make_periodic_case(work, "other-bed", 7.0, 64000, phi=0.3)
    faster = make_periodic_case(work, "other-flow", 7.0, 64000, ubar=2 * UBAR)
    looser = make_periodic_case(work, "other-mesh", 7.0, 64000, void=0.79 * 50)
    for given, words in ((cases[:2], "2 case(s) given for a mesh series"),
                         (cases[:2] + [line], "a inlet case among periodic ones"),
                         (cases[:2] + [other], "allowed: cases of one bed and one flow"),
                         (cases[:2] + [faster], "allowed: cases of one bed and one flow"),
                         (cases + [looser], "but no smaller ones")):
        out = subprocess.run([exe, "cfd-report", *given, "-o", os.path.join(work, "series-bad")],
                             capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
        assert words in out.stderr, out.stderr
        assert not os.path.exists(os.path.join(work, "series-bad"))
    # Re_p above 0.1: the Stokes references are flagged (one warning line on stderr).
    fast = make_periodic_case(work, "fast", 7.0, 1000, ubar=1e-3)
    out = subprocess.run([exe, "cfd-report", fast], capture_output=True, text=True)
    assert out.returncode == 0 and "are for Stokes flow" in out.stderr, out.stderr
    out = subprocess.run([exe, "cfd-report", cases[0]], capture_output=True, text=True)
    assert out.returncode == 0 and "Stokes" not in out.stderr, out.stderr
    # A case exported and never run: no log.
    unrun = make_periodic_case(work, "unrun", 7.0, 1000)
    os.remove(os.path.join(unrun, "log.simpleFoam"))
    out = subprocess.run([exe, "cfd-report", unrun], capture_output=True, text=True)
    assert out.returncode == 2 and "no log.simpleFoam" in out.stderr, out.stderr
    # A mesh that failed checkMesh: with a negative cell checkMesh prints no total volume, and
    # the drag is refused, naming the first failure; a failed check with the volume is warned of.
    negative = make_periodic_case(work, "negative", 7.0, 1000)
    with open(os.path.join(negative, "log.checkMesh"), "w") as f:
        f.write("    cells:            1000\n ***Zero or negative cell volume detected.  Minimum "
                "negative volume: -2.2e-15, Number of negative volume cells: 1\n\n"
                "Failed 2 mesh checks.\n")
    out = subprocess.run([exe, "cfd-report", negative], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert ("the mesh failed 2 of checkMesh's checks (log.checkMesh: \"Zero or negative cell "
            "volume detected.") in out.stderr, out.stderr
    skewed = make_periodic_case(work, "skewed", 7.0, 1000)
    with open(os.path.join(skewed, "log.checkMesh"), "a") as f:
        f.write(" ***Max skewness = 5.2, 1 highly skew faces detected\n\nFailed 1 mesh checks.\n")
    out = subprocess.run([exe, "cfd-report", skewed], capture_output=True, text=True)
    assert out.returncode == 0 and "the mesh failed 1 of checkMesh's checks" in out.stderr, \
        out.stderr


def report(exe, case, *extra):
    out = subprocess.run([exe, "cfd-report", case, "--json", *extra], capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def main(exe):
    work = tempfile.mkdtemp(prefix="packbed-cfd-report-")
    # Eisfeld & Schnitzlein (2001), spheres: K1 = 154, k1 = 1.15, k2 = 0.87 (docs/notes/
    # openfoam-v1912.md, section 7); Ergun (1952).
    d = D * SCALE
    ergun = 150 * MU * U * (1 - E) ** 2 / (E**3 * d**2) + 1.75 * RHO * U**2 * (1 - E) / (E**3 * d)
    aw = 1 + 2 / (3 * A * (1 - E))
    bw = (1.15 / A**2 + 0.87) ** 2
    es = 154 * aw**2 * MU * U * (1 - E) ** 2 / (E**3 * d**2) + aw / bw * RHO * U**2 * (1 - E) / (E**3 * d)

    case = make_case(work, "line")
    r = report(exe, case)
    g = r["pressure_gradient_Pa_m"]
    assert math.isclose(g["cfd"], GRADIENT, rel_tol=1e-9), g
    assert g["standard_error"] < 1e-9 * GRADIENT, g
    assert math.isclose(r["correlations"]["ergun_Pa_m"], ergun, rel_tol=1e-12), (r, ergun)
    assert math.isclose(r["correlations"]["eisfeld_schnitzlein_Pa_m"], es, rel_tol=1e-12), (r, es)
    assert math.isclose(r["correlations"]["cfd_over_eisfeld_schnitzlein"], GRADIENT / es,
                        rel_tol=1e-9)
    assert math.isclose(r["fluxes_m3_s"]["imbalance"], 3e-4, rel_tol=1e-9), r["fluxes_m3_s"]
    assert r["solver"]["converged"] and r["solver"]["iterations"] == 2, r["solver"]
    assert r["solver"]["stopped_by"] == "residuals", r["solver"]
    # The case's runTimeControl ending the run on a steady pressure drop (laminar above
    # Re_p 10) is a converged end too; a log with neither stop is the end time's, warned of.
    log = os.path.join(case, "log.simpleFoam")
    text = open(log).read()
    with open(log, "w") as f:
        f.write(text.replace("SIMPLE solution converged in 2 iterations",
                             "    average: pressureDropSteady condition satisfied\n"
                             "    Stopping calculation"))
    s = report(exe, case, "--force")["solver"]
    assert s["converged"] and s["stopped_by"] == "steady pressure drop", s
    with open(log, "w") as f:
        f.write(text.replace("SIMPLE solution converged in 2 iterations", ""))
    out = subprocess.run([exe, "cfd-report", case, "--json", "--force"], capture_output=True,
                         text=True)
    s = json.loads(out.stdout)["solver"]
    assert not s["converged"] and s["stopped_by"] == "endTime", s
    assert "nor a steady pressure drop" in out.stderr, out.stderr
    with open(log, "w") as f:
        f.write(text)
    # the last iteration's first p residual (1e-3), not its corrector's (5e-11)
    assert r["solver"]["last_initial_residuals"] == {"Ux": 5e-4, "p": 1e-3}, r["solver"]
    assert math.isclose(r["void_fraction"]["mesh"], 0.055, rel_tol=1e-9), r["void_fraction"]
    assert math.isclose(r["flow"]["reynolds"], RHO * U * d / MU, rel_tol=1e-12), r["flow"]
    rows = list(csv.DictReader(open(os.path.join(case, "cfd-report", "pressure.csv"))))
    assert [float(row["z_m"]) for row in rows] == Z, rows
    for row, z in zip(rows, Z):
        assert math.isclose(float(row["pressure_Pa"]), GRADIENT * (0.02 - z), rel_tol=1e-9), row
    if shutil.which("gnuplot"):
        for ext in ("svg", "png"):
            assert os.path.getsize(os.path.join(case, "cfd-report", f"pressure.{ext}")) > 0, ext
    # The band: each correlation's f_v (Erdim et al. 2015's normalisation) written out here,
    # times mu u (1-e)^2 / (d^2 e^3); Ergun's and E&S's the same as above.
    re_m = RHO * U * d / MU / (1 - E)
    wall = (1 + math.pi / (6 * A * (1 - E))) ** 2
    b = 1 - math.pi**2 / (24 * A) * (1 - 1 / (2 * A))
    f_v = {"ergun-1952": 150 + 1.75 * re_m, "carman-1937": 180 + 2.871 * re_m**0.9,
           "kta-1981": 160 + 3 * re_m**0.9, "erdim-2015": 160 + 2.81 * re_m**0.904,
           "harrison-2013": 119.8 * wall + 4.63 * b * re_m ** (5 / 6),
           "eisfeld-schnitzlein-2001": 154 * aw**2 + aw / bw * re_m}
    band = r["correlations"]["band"]
    assert [c["name"] for c in band] == list(f_v), band
    for c in band:
        value = f_v[c["name"]] * MU * U * (1 - E) ** 2 / (d**2 * E**3)
        assert math.isclose(c["Pa_m"], value, rel_tol=1e-12), (c, value)
        assert math.isclose(c["cfd_over"], GRADIENT / value, rel_tol=1e-9), c
    values = [c["Pa_m"] for c in band]
    assert r["correlations"]["band_Pa_m"] == [min(values), max(values)], r["correlations"]
    assert r["correlations"]["cfd_in_band"] == (min(values) <= GRADIENT <= max(values))
    print(f"line: {g['cfd']:.6f} Pa/m (made {GRADIENT}); Ergun {ergun:.6g}, Eisfeld & Schnitzlein "
          f"{es:.6g} Pa/m; the band {min(values):.6g} to {max(values):.6g} Pa/m")

    # Scattered planes: the slope and its standard error of the least-squares formula.
    scatter = [0.1 * math.sin(3.0 * k) / RHO for k in range(9)]
    case = make_case(work, "scatter", scatter)
    g = report(exe, case)["pressure_gradient_Pa_m"]
    p = [GRADIENT * (0.02 - z) + RHO * s for z, s in zip(Z, scatter)]
    mz, mp = sum(Z) / 9, sum(p) / 9
    szz = sum((z - mz) ** 2 for z in Z)
    slope = sum((z - mz) * (q - mp) for z, q in zip(Z, p)) / szz
    rr = sum((q - (mp + slope * (z - mz))) ** 2 for z, q in zip(Z, p))
    assert math.isclose(g["cfd"], -slope, rel_tol=1e-9), (g, slope)
    assert math.isclose(g["standard_error"], math.sqrt(rr / (7 * szz)), rel_tol=1e-6), g
    print(f"scatter: {g['cfd']:.6f} +- {g['standard_error']:.4f} Pa/m")

    periodic_cases(exe, work)

    # A bed periodic across (no wall, aspect_ratio null): Ergun only, and the drag of a sphere
    # beside van der Hoef et al.'s random arrays: F_total = G (pi d^3 / 6) / phi,
    # K = F_total / (3 pi mu d U), F = (1 - phi) K.
    across = make_case(work, "across")
    j = json.load(open(os.path.join(across, "packbed.json")))
    j["openfoam"]["flow"]["aspect_ratio"] = None
    json.dump(j, open(os.path.join(across, "packbed.json"), "w"))
    c = report(exe, across)["correlations"]
    phi = 1 - E
    k = GRADIENT * math.pi * d**3 / 6 / phi / (3 * math.pi * MU * d * U)
    vdh = 10 * phi / (1 - phi) ** 2 + (1 - phi) ** 2 * (1 + 1.5 * math.sqrt(phi))
    assert "eisfeld_schnitzlein_Pa_m" not in c, c
    # No wall: the band holds the correlations without a wall term.
    assert [b["name"] for b in c["band"]] == ["ergun-1952", "carman-1937", "kta-1981",
                                               "erdim-2015"], c["band"]
    assert math.isclose(c["K"], k, rel_tol=1e-9) and math.isclose(c["F"], (1 - phi) * k,
                                                                 rel_tol=1e-9), (c, k)
    assert math.isclose(c["F_over_van_der_hoef"], (1 - phi) * k / vdh, rel_tol=1e-9), c
    print(f"across: F = {c['F']:.6g}, van der Hoef {vdh:.6g}")

    # A restarted run: the table of the latest start time (20) is the one read.
    g = report(exe, make_case(work, "restarted", restarted=True))["pressure_gradient_Pa_m"]
    assert math.isclose(g["cfd"], GRADIENT + RHO, rel_tol=1e-9), g
    # Restarted from 20 again (OpenFOAM's surfaceFieldValue_20.dat beside an empty table):
    # that table's rows; both stopped before their first write: the rows of the run from 0.
    g = report(exe, make_case(work, "again", restarted="again"))["pressure_gradient_Pa_m"]
    assert math.isclose(g["cfd"], GRADIENT + 2.0 * RHO, rel_tol=1e-9), g
    g = report(exe, make_case(work, "stopped", restarted="stopped"))["pressure_gradient_Pa_m"]
    assert math.isclose(g["cfd"], GRADIENT, rel_tol=1e-9), g

    # Bad cases: exit 2, one line naming CASE, nothing written.
    bad = make_case(work, "bad")
    os.remove(os.path.join(bad, "postProcessing", "p3", "0", "surfaceFieldValue.dat"))
    nan = make_case(work, "nan")
    with open(os.path.join(nan, "postProcessing", "p0", "0", "surfaceFieldValue.dat"), "a") as f:
        f.write("30\t1e-06\tnan\n")
    mixed = make_case(work, "mixed")  # p3's table goes on to iteration 30, the others end at 20
    table(os.path.join(mixed, "postProcessing", "p3", "20", "surfaceFieldValue.dat"), "p3",
          ["Area", "areaAverage(p)"], [(30, 1e-6, 1.0)])
    empty = make_case(work, "empty")
    open(os.path.join(empty, "postProcessing", "p5", "0", "surfaceFieldValue.dat"), "w").close()
    old = make_case(work, "old")
    j = json.load(open(os.path.join(old, "packbed.json")))
    del j["openfoam"]["flow"]["band_void_fraction"]
    json.dump(j, open(os.path.join(old, "packbed.json"), "w"))
    planeless = make_case(work, "planeless")
    j = json.load(open(os.path.join(planeless, "packbed.json")))
    del j["openfoam"]["flow"]["pressure_planes"]
    json.dump(j, open(os.path.join(planeless, "packbed.json"), "w"))
    # No NaN or infinity in a report: fluxes of 0 (an imbalance of 0/0), a pressure whose
    # product with the density overflows, a density that makes the Reynolds number overflow.
    still = make_case(work, "still")
    for name in ("inletFlux", "outletFlux"):
        table(os.path.join(still, "postProcessing", name, "0", "surfaceFieldValue.dat"),
              f"patch {name}", ["sum(phi)"], [(20, 0.0)])
    huge = make_case(work, "huge")
    table(os.path.join(huge, "postProcessing", "p4", "0", "surfaceFieldValue.dat"), "p4",
          ["Area", "areaAverage(p)"], [(20, 1e-6, -1e308)])
    dense = make_case(work, "dense")
    j = json.load(open(os.path.join(dense, "packbed.json")))
    j["openfoam"]["flow"]["fluid_density"] = 1e308
    json.dump(j, open(os.path.join(dense, "packbed.json"), "w"))
    # packbed.json nested 1e5 deep: refused where it is read, not a stack overflow.
    deep = make_case(work, "deep")
    with open(os.path.join(deep, "packbed.json"), "w") as f:
        f.write('{"diameter": ' + "[" * 100000 + "]" * 100000 + "}")
    for case, words in ((bad, "postProcessing/p3"), (nan, "not a finite number"),
                        (empty, "p5/0/surfaceFieldValue.dat has no rows"),
                        (mixed, "postProcessing/p3 is of iteration 30, p0's of 20"),
                        (old, "band_void_fraction"), (planeless, "pressure_planes"),
                        (os.path.join(work, "none"), "not a directory"), (work, "packbed.json"),
                        (still, "the inlet's flux sum(phi) is 0"),
                        (huge, "/planes/4/pressure_Pa is not a finite number"),
                        (dense, "packbed.json's flow: fluid-density = 1e+308 is not allowed"), (deep, "not a JSON object")):
        out = subprocess.run([exe, "cfd-report", case], capture_output=True, text=True)
        assert out.returncode == 2, (case, out.returncode, out.stderr)
        assert out.stderr.count("\n") == 1 and "CASE" in out.stderr and words in out.stderr, out.stderr
        assert not os.path.exists(os.path.join(case, "cfd-report")), case
        print(f"refused: {out.stderr.strip()}")
    # The case is an input: an output that is it, or holds it, is refused before anything is
    # read or written, and the case stays as it was.
    before = sorted(os.walk(case := make_case(work, "kept")))
    for out_dir in (case, work):
        out = subprocess.run([exe, "cfd-report", case, "-o", out_dir, "--force"],
                             capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
        assert f"CASE {case} lies in --out {out_dir}" in out.stderr, out.stderr
        print(f"refused: {out.stderr.strip()}")
    assert sorted(os.walk(case)) == before
    shutil.rmtree(work)


if __name__ == "__main__":
    main(sys.argv[1])
