#!/usr/bin/env python3
"""A bed of pellets from `packbed generate --shape` to a CFD result, as a user would run it:
12 cylinders (D = L = 3 in the bed's unit) poured into a tube of a = 4 (one layer), exported
with `--format openfoam --contacts shrink:0.02` and run by ./Allrun on 2 MPI ranks (blockMesh,
snappyHexMesh, simpleFoam), then `packbed cfd-report`. Asserts
- checkMesh's "Mesh OK." and the patches inlet, outlet, wall and particles with faces;
- the mesh's volume within 3 % of the exact fluid volume of the shrunk pellets in the
  container (packbed.json; measured 1.4 % less: the gaps of 2 % about each pellet are
  narrower than the default cells);
- simpleFoam converged (every last initial residual below 1e-6), the inlet's and the outlet's
  fluxes within 1e-6 of each other, the inlet's the superficial velocity times the tube's
  cross-section;
- the pressure gradient over the planes (a line fitted to their pressures) 0.282 of Ergun's at
  the planes' void fraction and d = 6 V / S (676.7 Pa/m against 2401 Pa/m), within 18 %. One
  layer of pellets is no bed, and no correlation holds for it: the number guards the units,
  the fluid and the boundary conditions, which move it by orders of magnitude; the run is
  deterministic, and the band is for another OpenFOAM build or rank count.

Usage: check_openfoam_pellets.py PACKBED. Exit 77 (skipped) when OpenFOAM or mpirun is missing
(scripts/install-deps.sh --test installs both)."""
import json
import math
import os
import shutil
import sys
import tempfile

from openfoam_env import RUNNING, check_patches, openfoam_or_skip, patch_faces, runner

exe = sys.argv[1]
env = openfoam_or_skip(RUNNING + ("checkMesh",))
work = tempfile.mkdtemp(prefix="packbed-pellets-")
run = runner(env, work)

case = os.path.join(work, "case")
run(exe, "generate", "--shape", "cylinder:3,3", "--aspect-ratio", "4", "--particles", "12",
    "--seed", "3", "--quiet", "--out", "bed")
run(exe, "export", "bed/particles.csv", "--format", "openfoam", "--contacts", "shrink:0.02",
    "--ranks", "2", "--out", case, "--quiet")
record = json.load(open(os.path.join(case, "packbed.json")))
assert record["pellets"] == 12 and record["shape"] == "cylinder:3,3", record
assert math.isclose(record["diameter"], 3.0, rel_tol=1e-12), record  # 6 V / S = D when L = D
run(os.path.join(case, "Allrun"), cwd=case)

check = open(os.path.join(case, "log.checkMesh")).read()
assert "Mesh OK." in check, check[-3000:]
check_patches(patch_faces(check), ("inlet", "outlet", "wall", "particles"))

run(exe, "cfd-report", case, "--quiet")
report = json.load(open(os.path.join(case, "cfd-report", "cfd_report.json")))
solver = report["solver"]
assert solver["converged"], solver
assert all(v < 1e-6 for v in solver["last_initial_residuals"].values()), solver
fluxes = report["fluxes_m3_s"]
assert abs(fluxes["inlet"] + fluxes["outlet"]) <= 1e-6 * fluxes["outlet"], fluxes
flow = record["openfoam"]["flow"]
scale = flow["metres_per_unit"]
area = math.pi * record["container"]["radius"] ** 2 * scale**2
assert math.isclose(-fluxes["inlet"], flow["velocity"] * area, rel_tol=1e-3), (fluxes, flow)
fluid = record["volumes"]["fluid"] * scale**3
mesh = report["mesh"]["volume_m3"]
assert abs(mesh / fluid - 1.0) <= 0.03, (mesh, fluid)
ergun = next(c for c in report["correlations"]["band"] if c["name"] == "ergun-1952")
assert 0.282 / 1.18 <= ergun["cfd_over"] <= 0.282 * 1.18, ergun
print(f"12 pellets: Mesh OK, mesh volume {mesh / fluid:.4f} of the exact fluid, converged in "
      f"{solver['iterations']} iterations, gradient {report['pressure_gradient_Pa_m']['cfd']:.1f}"
      f" Pa/m = {ergun['cfd_over']:.3f} of Ergun's")
shutil.rmtree(work)
