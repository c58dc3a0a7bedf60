#!/usr/bin/env python3
"""A cell periodic along z, end to end: `packbed export --flow periodic` of a simple cubic
array, its Allrun (blockMesh, snappyHexMesh on 2 ranks, simpleFoam with meanVelocityForce) and
`packbed cfd-report`, against Zick & Homsy (1982).

The 2 x 2 x 2 simple cubic lattice of Dp = 1 (`lattice --region periodic:2,2,2`), its spheres
shrunk to the solid fraction 0.216 (`--contacts shrink:F`, F = 1 - (6 0.216 / pi)^(1/3)), Stokes
flow (Re_p = 0.01) along z. packbed.json must give the cell (volume 8, 8 spheres of radius
(6 0.216 / pi)^(1/3) / 2, solid fraction 0.216, the mean velocity in the fluid the superficial
one over 0.784), blockMeshDict six cyclic patches and no inlet, fvOptions meanVelocityForce at
that velocity. After the run, cfd-report's K = F / (6 pi mu a U_s) must be Zick & Homsy's 7.442
times 0.933 +- 0.01: the mesh of this test (--cells-per-diameter 12, level 1, icosphere level
5 with the default facets, volume: cells of d / 17.9 at the spheres, d the shrunk diameter)
gives 6.942, 6.7 % low, where the
mesh series of docs/validation.md ("CFD: periodic arrays") converges to within 0.1 % of it.
Also: the drag per sphere is rho G times the cell's volume over 8, and the mesh's void fraction
is within 0.003 of the exact 0.784. About 15 s on the 2-core machine.

Usage: check_openfoam_periodic_flow.py PACKBED. Exit 77 (skipped) when OpenFOAM or MPI is
missing."""
import json
import math
import os
import shutil
import sys
import tempfile

from openfoam_env import MESHING, openfoam_or_skip, runner

exe = sys.argv[1]
env = openfoam_or_skip(MESHING + ("simpleFoam", "decomposePar", "mpirun"))
work = tempfile.mkdtemp(prefix="packbed-foam-periodic-flow-")
run = runner(env, work)

phi = 0.216
shrink = 1.0 - (6.0 * phi / math.pi) ** (1.0 / 3.0)
run(exe, "lattice", "--type", "sc", "--region", "periodic:2,2,2", "--origin", "0.5,0.5,0.5",
    "--no-analysis", "--quiet", "--out", "cell")
case = os.path.join(work, "case")
run(exe, "export", "cell/particles.csv", "--format", "openfoam", "--flow", "periodic",
    "--container-height", "2", "--contacts", f"shrink:{shrink!r}", "--cells-per-diameter", "12",
    "--particle-level", "1", "--refine", "5", "--reynolds", "0.01", "--quiet", "--out", case)

report = json.load(open(os.path.join(case, "packbed.json")))
flow = report["openfoam"]["flow"]
cell = flow["periodic"]
radius = 0.5 * (6.0 * phi / math.pi) ** (1.0 / 3.0)
assert cell["spheres"] == 8 and cell["period_z"] == 2 and cell["cell_volume"] == 8, cell
assert abs(cell["sphere_radius"] / radius - 1) < 1e-14, (cell, radius)
assert abs(cell["solid_fraction"] - phi) < 1e-12, cell
assert abs(cell["interstitial_velocity"] / (flow["velocity"] / (1 - phi)) - 1) < 1e-14, flow
assert flow["pressure_planes"] == [], flow
block = open(os.path.join(case, "system", "blockMeshDict")).read()
for name in ("x_low", "x_high", "y_low", "y_high", "z_low", "z_high"):
    assert f"    {name}\n    {{\n        type cyclic;" in block, (name, block)
assert "inlet" not in block and "outlet" not in block, block
options = open(os.path.join(case, "constant", "fvOptions")).read()
assert "type meanVelocityForce;" in options, options
assert f"Ubar (0 0 {cell['interstitial_velocity']!r});" in options, options
for field in ("U", "p"):
    text = open(os.path.join(case, "0.orig", field)).read()
    assert "inlet" not in text and "outlet" not in text, text

run(os.path.join(case, "Allrun"))
out = json.loads(run(exe, "cfd-report", case, "--json", "--quiet"))
p = out["periodic"]
assert out["solver"]["converged"], out["solver"]
k = p["K"]
ratio = p["references"]["K_over_zick_homsy"]
assert p["references"]["zick_homsy_simple_cubic_K"] == 7.442, p
assert abs(ratio - k / 7.442) < 1e-12, p
assert abs(ratio - 0.933) < 0.01, (k, ratio)
volume = 8 * (1e-3) ** 3  # the cell in m^3 (Dp = 1 mm)
assert abs(p["drag_per_sphere_N"] / (p["pressure_gradient_Pa_m"] * volume / 8) - 1) < 1e-12, p
assert abs(out["void_fraction"]["mesh"] - 0.784) < 0.003, out["void_fraction"]
assert abs(p["F"] / ((1 - phi) * k) - 1) < 1e-12, p
print(f"K = {k:.4f}, {ratio:.4f} of Zick & Homsy's 7.442; mesh void fraction "
      f"{out['void_fraction']['mesh']:.5f}")
shutil.rmtree(work)
