#!/usr/bin/env bash
# Run the README's commands as written, in order, and check what they produce.
# Usage: scripts/check-readme.sh [--fresh]
#   (default)  in this checkout. The first command's build then finds build/ already built by
#              the test command, so only its install and run take time. Where results/ exists
#              (the README's first command ran here before), the commands write to an empty
#              folder mounted over it in a mount namespace of their own (`unshare --mount`), so
#              the user's results/ is neither read nor changed; where no such namespace can be
#              made, it runs as --fresh.
#   --fresh    in a fresh clone of HEAD in a temporary folder: the first command builds from
#              nothing (about 5 more minutes on 2 cores).
# Every ```sh block of README.md runs, except the test command (the one that runs this script).
# HOME is a temporary folder, so the install of the first command (~/.local) and everything
# else stays out of the user's files; what the commands wrote to results/ is removed at the
# end.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [[ ${1:-} != --fresh && -n ${1:-} ]]; then
  echo "check-readme: unknown option '$1'; allowed: --fresh" >&2
  exit 2
fi
if [[ ${1:-} != --fresh && -e $root/results && -z ${PACKBED_README_SHADOW:-} ]]; then
  flags=(--mount --propagation private)
  ((EUID == 0)) || flags+=(--map-root-user)
  if [[ -d $root/results && ! -L $root/results ]] && unshare "${flags[@]}" true 2>/dev/null; then
    echo "check-readme: $root/results exists: the README's commands write to an empty folder" \
      "mounted over it, which only they see"
    exec unshare "${flags[@]}" env PACKBED_README_SHADOW=1 "$0" "$@"
  fi
  echo "check-readme: $root/results exists and no mount namespace can be made here (or it is" \
    "not a directory): the commands run in a fresh clone (--fresh)"
  exec "$0" --fresh
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/packbed-readme.XXXXXX")
repo=$root
shadowed=0
cleanup() {
  if ((shadowed)); then umount "$root/results" 2>/dev/null || true; fi
  rm -rf "$work"
  if [[ $repo == "$root" && ${created_results:-0} == 1 ]]; then rm -rf "$root/results"; fi
}
trap cleanup EXIT
if [[ ${1:-} == --fresh ]]; then
  git clone --quiet "$root" "$work/packbed"
  repo=$work/packbed
elif [[ -n ${PACKBED_README_SHADOW:-} ]]; then
  # In this process's own mount namespace: an empty folder over the user's results/.
  mkdir "$work/results"
  mount --bind "$work/results" "$root/results"
  shadowed=1
fi
if [[ -e $repo/results && $shadowed == 0 ]]; then
  echo "check-readme: $repo/results exists; the README's commands write there. Move it away," \
    "or run scripts/check-readme.sh --fresh" >&2
  exit 2
fi
if ((shadowed == 0)); then created_results=1; fi

# The blocks, one script each, the test command left out.
mkdir -p "$work/home" "$work/blocks"
python3 - "$repo/README.md" "$work/blocks" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
blocks = re.findall(r"^```sh\n(.*?)^```", text, flags=re.S | re.M)
kept = [b for b in blocks if "install-deps.sh --test" not in b]
if len(kept) != len(blocks) - 1:
    sys.exit(f"check-readme: expected one test command in README.md, found {len(blocks) - len(kept)}")
for k, b in enumerate(kept, 1):
    open(f"{sys.argv[2]}/block-{k:02d}.sh", "w").write(b)
print(f"check-readme: {len(kept)} blocks of README.md to run")
EOF

export HOME=$work/home CI=1
# One shell for all blocks, as a reader typing them in one terminal (`export` and `cd` carry
# over), stopping at the first command that fails; each block's output in its own log.
{
  echo "set -euo pipefail"
  for block in "$work"/blocks/block-*.sh; do
    name=$(basename "$block" .sh)
    echo "cd '$repo'"
    echo "echo $name >'$work/current'; exec >'$work/$name.log' 2>&1"
    cat "$block"
  done
} >"$work/all.sh"
for block in "$work"/blocks/block-*.sh; do
  echo "check-readme: $(basename "$block" .sh)"
  sed 's/^/    /' "$block"
done
if ! (cd "$repo" && bash "$work/all.sh"); then
  failed=$(cat "$work/current")
  echo "check-readme: $failed failed; its output:" >&2
  cat "$work/$failed.log" >&2
  exit 1
fi

# What the commands produced, checked against numbers from geometry and the papers.
python3 - "$repo" "$work" <<'EOF'
import glob, json, os, subprocess, sys
repo, work = sys.argv[1], sys.argv[2]
home = os.path.join(work, "home")
failures = []
def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        failures.append(what)
def summary(path):
    with open(os.path.join(repo, path, "summary.json")) as f:
        return json.load(f)
def log_of(text):
    """The log of the block whose commands contain `text`."""
    for block in sorted(glob.glob(os.path.join(work, "blocks", "block-*.sh"))):
        if text in open(block).read():
            return open(block.replace("blocks/", "").replace(".sh", ".log")).read()
    return ""

# 1. The first command: installed, and the paper's case packed (a = 5, 500 spheres).
check(os.access(os.path.join(home, ".local/bin/packbed"), os.X_OK), "packbed installed in ~/.local/bin")
s = summary("results/a5-n500")
check(s["particles"] == 500 and s["aspect_ratio"] == 5, "results/a5-n500: 500 spheres at a = 5")
check(0.40 < s["void_fraction"] < 0.46, f"a = 5 void fraction {s['void_fraction']:.4f} in (0.40, 0.46) "
      "(Dixon 1988 gives 0.4265 at a = 5)")
check(max(s["max_overlap_pair"], s["max_overlap_wall"]) <= 1e-4, "overlaps within the 1e-4 Dp tolerance")
check(s["parameters"]["solver"] == "fire", "the default solver is fire")

# The installed CMake package: examples/generate_bed.cpp built against it.
consumer = os.path.join(work, "consumer")
os.makedirs(consumer)
with open(os.path.join(consumer, "CMakeLists.txt"), "w") as f:
    f.write("cmake_minimum_required(VERSION 3.20)\nproject(consumer CXX)\n"
            "find_package(packbed 0.1 REQUIRED)\nadd_executable(generate_bed "
            f"{repo}/examples/generate_bed.cpp)\n"
            "target_link_libraries(generate_bed PRIVATE packbed::packbed)\n")
built = subprocess.run(f"cmake -S {consumer} -B {consumer}/b -DCMAKE_BUILD_TYPE=Release "
                       f"-DCMAKE_PREFIX_PATH={home}/.local >/dev/null && "
                       f"cmake --build {consumer}/b >/dev/null && {consumer}/b/generate_bed",
                       shell=True, capture_output=True, text=True)
check(built.returncode == 0 and built.stdout.startswith("150 spheres"),
      f"find_package(packbed) builds examples/generate_bed.cpp: {built.stdout.strip()}")

# 2. The CFD tour: examples/bed.toml's bed, its hydraulics, its OpenFOAM case.
s = summary("results/bed-a7.99")
check(s["particles"] == 1800 and s["diameter"] == 0.003 and s["aspect_ratio"] == 7.99,
      "results/bed-a7.99: 1 800 spheres of 3 mm at a = 7.99, as examples/bed.toml says")
check(abs(s["container"]["radius"] - 7.99 * 0.003 / 2) < 1e-12, "its tube: Rt = 7.99 x 3 mm / 2")
check(0.38 < s["void_fraction"] < 0.43, f"a = 7.99 void fraction {s['void_fraction']:.4f} in (0.38, 0.43) "
      "(Dixon 1988 gives 0.4127)")
hydraulics = log_of("packbed hydraulics --bed results/bed-a7.99")
check("particle diameter d = 0.003 m (the diameter of results/bed-a7.99/summary.json" in hydraulics,
      "hydraulics takes the bed's 3 mm as its particle diameter")
check("Eisfeld & Schnitzlein (a = 7.99)" in hydraulics, "and the tube's aspect ratio 7.99")
case = os.path.join(repo, "results/bed-a7.99/case")
check(all(os.path.exists(os.path.join(case, p)) for p in
          ("system/blockMeshDict", "system/snappyHexMeshDict", "constant/triSurface")),
      "the OpenFOAM case has its dictionaries and surfaces")

# 2b. From a bed to its pressure drop: the case ran, converged, conserved mass, and the
# gradient lies in the band the test openfoam_case_runs asserts on the same bed
# (tests/check_openfoam_flow.py).
report = os.path.join(repo, "results/small/flow/cfd-report/cfd_report.json")
r = json.load(open(report)) if os.path.exists(report) else {}
check(r.get("solver", {}).get("converged") is True, "simpleFoam converged on the small bed")
check(r.get("fluxes_m3_s", {}).get("imbalance", 1) < 1e-3, "the inlet's and outlet's fluxes agree to 0.1 %")
ratio = r.get("correlations", {}).get("cfd_over_eisfeld_schnitzlein", 0)
check(0.465 < ratio < 0.669, f"its pressure gradient is {ratio:.3f} of Eisfeld & Schnitzlein's (0.465 to "
      "0.669; 0.567 measured)")
printed = log_of("packbed cfd-report results/small/flow")
check("Eisfeld & Schnitzlein (2001) (a = 3)" in printed and "the 6 correlations span" in printed,
      "cfd-report prints the table and the band of correlations")

# 2c. The pipeline against Zick & Homsy: the simple cubic array at 0.216 in its periodic cell.
report = os.path.join(repo, "results/sc/flow/cfd-report/cfd_report.json")
r = json.load(open(report)) if os.path.exists(report) else {}
p = r.get("periodic", {})
check(r.get("solver", {}).get("converged") is True, "simpleFoam converged in the periodic cell")
ratio = p.get("references", {}).get("K_over_zick_homsy", 0)
check(abs(ratio - 0.957) < 0.01, f"its K is {ratio:.4f} of Zick & Homsy's 7.442 (0.957 measured on "
      "this mesh, docs/validation.md)")
check(abs(r.get("void_fraction", {}).get("mesh", 0) - 0.784) < 0.003,
      "the mesh's void fraction is within 0.003 of the exact 0.784")

# 3. The DEM tour: a diamond lattice in a 30 mm tube, its DEM start, a LIGGGHTS settle.
import re
s = summary("results/diamond-tube")
check(abs(s["lattice"]["porosity"] - (1 - 3.141592653589793 * 3 ** 0.5 / 16)) < 1e-12,
      "diamond lattice porosity 1 - pi sqrt(3)/16 = 0.6599 (Tsayger 2013)")
air = re.search(r"superficial velocity w = ([0-9.e+-]+) m/s", log_of("packbed hydraulics --bed results/diamond-tube"))
check(air is not None and abs(float(air.group(1)) - 2.48) < 0.01,
      "air through the 2 mm diamond lattice: critical velocity 2.48 m/s (Tsayger eq. 1), the "
      "value the README passes to export")
data = open(os.path.join(repo, "results/diamond-tube/bed.data")).read()
check(f"{s['balls']} atoms" in data, f"the data file holds the lattice's {s['balls']} balls")
box = [float(v) for v in re.search(r"^(\S+) (\S+) xlo xhi", data, re.M).groups()]
check(box[0] < -0.015 and box[1] > 0.015, f"its box x = {box} holds the 30 mm tube")
settle = log_of("liggghts -in bed.data.liggghts.in")
moved = re.search(r"packbed settle: (\d+) atoms after 2000 steps", settle)
check(moved is not None and int(moved.group(1)) == s["balls"],
      "LIGGGHTS settled every ball for 2 000 steps in the exported walls")
check("lost" not in settle and "WARNING" not in settle, "no mesh element or atom lost")
series = open(os.path.join(repo, "results/settled-analysis/void_fraction_series.csv")).read().split("\n")
check(series[0] == "frame,timestep,void_fraction,particles" and len([l for l in series[1:] if l]) == 2,
      "analyze measured both snapshots of the settle")

# 3b. Poured or dense: the target reached by friction, the dense bed frictionless.
dense, poured = summary("results/dense"), summary("results/poured")
check(dense["parameters"]["friction"] == 0 and 0.385 < dense["void_fraction"] < 0.405,
      f"the dense bed is frictionless, e = {dense['void_fraction']:.4f} in (0.385, 0.405)")
check(abs(poured["void_fraction"] - 0.42) <= 0.005,
      f"the poured bed reached e = {poured['void_fraction']:.4f}, within 0.005 of 0.42")
check(poured["parameters"]["friction"] == poured["target_void_fraction"]["friction"] > 0,
      "its friction is recorded")
check(max(poured["max_overlap_pair"], poured["max_overlap_wall"]) <= 1e-4,
      "its overlaps within the 1e-4 Dp tolerance")
zp, zd = poured["analysis"]["coordination"]["mean"], dense["analysis"]["coordination"]["mean"]
check(zp < zd - 0.2, f"its spheres touch fewer neighbours ({zp:.2f} against {zd:.2f})")

# 4. The analysis tour: analyze gives the void fraction generate measured.
a = summary("results/a5-n500-analysis")
check(abs(a["void_fraction"] - summary("results/a5-n500")["void_fraction"]) < 1e-12,
      "analyze measures the void fraction generate reported")
check(all(os.path.getsize(os.path.join(repo, "results/a5-n500-analysis", f)) > 0 for f in
          ("radial_void_fraction.png", "axial_void_fraction.svg", "pair_correlation.csv")),
      "with its tables and plots")
check("Dixon (1988)" in log_of("packbed correlations --aspect-ratio 5"),
      "correlations names them as cited")
# 5. Mixtures and boxes: the sizes asked, each pair within the tolerance of its smaller sphere.
b = summary("results/binary")
classes = b["sizes"]["statistics"]["classes"]
check([c["count"] for c in classes] == [711, 89],
      "the binary bed holds 711 spheres of 1 mm and 89 of 2 mm (equal volumes, 800 spheres)")
check(abs(classes[1]["volume_fraction"] - 0.5) < 1e-3, "half its volume in the large spheres")
d32 = (711 * 1 + 89 * 8) / (711 * 1 + 89 * 4) * 1e-3
check(abs(b["diameter"] - d32) < 1e-15 and abs(b["aspect_ratio"] - 0.01 / d32) < 1e-9,
      "its reference diameter is d32 and a = D / d32")
rows = [[float(v) for v in line.split(",")] for line in
        open(os.path.join(repo, "results/binary/particles.csv")).read().split("\n")[1:] if line]
worst = 0.0
for i, p in enumerate(rows):
    for q in rows[i + 1:]:
        gap = ((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2) ** 0.5
        worst = max(worst, (p[3] + q[3] - gap) / (2 * min(p[3], q[3])))
check(worst < 1e-4, f"every pair overlaps by less than 1e-4 of its smaller diameter ({worst:.2e})")
check(os.path.getsize(os.path.join(repo, "results/binary/centre_distribution_by_size.svg")) > 0,
      "with the centre distribution of each size drawn")
ln = summary("results/lognormal")["sizes"]["statistics"]
check(ln["count"] == 2000 and ln["size_ratio"] <= 10 and 0.9e-3 < ln["d50"] < 1.1e-3,
      f"the lognormal bed: 2000 spheres, mass median d50 {ln['d50']:.4g} near 1 mm")
box = summary("results/sc-box-analysis")
check(box["container"]["shape"] == "box" and
      open(os.path.join(repo, "results/sc-box-analysis/radial_void_fraction.csv")).readline().strip()
      == "wall_distance,x_from_wall_d,void_fraction",
      "the lattice in a box is analysed against the distance from its nearest wall")
# Whole simple cubic layers from d/2 to 10 balls a side: the band's solid is pi/6 of it.
check(abs(box["void_fraction"] - (1 - 3.141592653589793 / 6)) < 1e-9,
      f"its void fraction is the lattice's, 1 - pi/6 ({box['void_fraction']:.10f})")
# 6. An annulus and a periodic cell: every sphere between the walls, each wall's profile, the
# rod in the OpenFOAM case, the hydraulic diameter; the cell's copies and its LAMMPS box.
ring = summary("results/annulus")
check(ring["container"]["spec"] == "annulus:0.02,0.004" and ring["max_overlap_pair"] < 1e-4
      and ring["max_overlap_wall"] < 1e-4, "the annulus bed ends within the tolerance")
rows = [[float(v) for v in line.split(",")] for line in
        open(os.path.join(repo, "results/annulus/particles.csv")).read().split("\n")[1:] if line]
gaps = [min(0.01 - ((x * x + y * y) ** 0.5 + r), ((x * x + y * y) ** 0.5 - r) - 0.002)
        for x, y, z, r in rows]
check(len(rows) == 1500 and min(gaps) > -1e-4 * 0.002,
      f"its 1500 spheres lie between rod and tube (closest {min(gaps):.2e} m)")
for wall in ("outer", "inner"):
    first = open(os.path.join(repo, f"results/annulus/radial_void_fraction_{wall}.csv")).read()
    e0 = float(first.split("\n")[1].split(",")[2])
    check(0.95 < e0 < 1, f"the {wall} wall's profile starts near e = 1 at its wall ({e0:.3f})")
check(os.path.getsize(os.path.join(repo, "results/annulus/case/constant/triSurface/rod.stl")) > 0,
      "the OpenFOAM case has the rod's surface")
check("D - DI = 0.016 m" in log_of("packbed hydraulics --bed results/annulus"),
      "hydraulics takes the hydraulic diameter D - DI")
bulk = summary("results/bulk")
check(0.34 < bulk["void_fraction"] < 0.38 and bulk["max_overlap_pair"] < 1e-4,
      f"the periodic bed is near random close packing (e = {bulk['void_fraction']:.4f})")
rows = [[float(v) for v in line.split(",")] for line in
        open(os.path.join(repo, "results/bulk/particles.csv")).read().split("\n")[1:] if line]
check(all(0 <= x < 0.016 and 0 <= y < 0.016 for x, y, z, r in rows),
      "its centres are written in the cell")
data = open(os.path.join(repo, "results/bulk/bed.data")).read()
check("0 0.016 xlo xhi" in data and "boundary        p p f" in
      open(os.path.join(repo, "results/bulk/bed.data.lammps.in")).read(),
      "LAMMPS gets the cell as its box, periodic in x and y")
# 7. LAMMPS as the engine: the paper's case relaxed by LAMMPS on 2 ranks, within the tolerance
# and the paper's void fraction; the cluster's job run and brought back by import-lammps.
lmp = summary("results/a5-lammps")
check(lmp["engine"]["name"] == "lammps" and lmp["engine"]["ranks"] == 2
      and lmp["max_overlap_pair"] < 1e-4 and lmp["max_overlap_wall"] < 1e-4,
      "LAMMPS relaxed the paper's case on 2 ranks within the 1e-4 Dp tolerance")
check(0.42 < lmp["void_fraction"] < 0.45,
      f"its void fraction {lmp['void_fraction']:.4f} in (0.42, 0.45) (the paper: 0.43-0.44)")
back = summary("results/cluster-bed")
check(back["particles"] == 1500 and back["engine"]["imported_from"] == "results/cluster-job"
      and max(back["max_overlap_pair"], back["max_overlap_wall"]) < 1e-4,
      "import-lammps brought back the cluster job's 1500 spheres, checked")
check("sbatch job.sh" in open(os.path.join(repo, "results/cluster-job/README.md")).read()
      and "srun lmp -in in.packbed" in open(os.path.join(repo, "results/cluster-job/job.sh")).read(),
      "the job's README says sbatch job.sh, and job.sh is its Slurm script")
# The Python example: the module's bed, its profile plotted, its voxel images; the study.
py = log_of("packbed.voxelize")
m = re.search(r"500 spheres, centres \(500, 3\) void fraction ([0-9.]+)", py)
check(m is not None and abs(float(m.group(1)) - summary("results/a5-n500")["void_fraction"]) < 1e-15,
      "Python: generate(aspect_ratio=5, particles=500, seed=1) is the first command's bed")
m = re.search(r"binary image ([0-9.]+) exact ([0-9.]+)", py)
check(m is not None and abs(float(m.group(1)) - float(m.group(2))) < 0.01 and 0.3 < float(m.group(2)) < 0.5,
      "Python: the box's porosity from the binary and the exact image agree within 0.01")
data = open(os.path.join(repo, "results/python-bed.data")).read()
check("500 atoms" in data and "500 spheres to " in py and
      os.path.exists(os.path.join(repo, "results/python-bed.data.lammps.in")),
      "Python: export writes the LAMMPS data file of the 500 spheres and its example settle")
m = re.search(r"Ergun ([0-9.e+-]+) Pa/m at w = ([0-9.e+-]+) m/s", py)
e = summary("results/a5-n500")["void_fraction"]
if m:  # Ergun (1952) at the velocity of eq. (1), glass (1 mm) in water, the defaults
    u, d, mu, rho = float(m.group(2)), 1e-3, 1.002e-3, 998.2
    ergun = 150 * (1 - e) ** 2 / e ** 3 * mu * u / d ** 2 + 1.75 * (1 - e) / e ** 3 * rho * u ** 2 / d
check(m is not None and abs(float(m.group(1)) / ergun - 1) < 1e-9,
      "Python: hydraulics gives Ergun's pressure gradient at the bed's void fraction")
check(os.path.getsize(os.path.join(repo, "results/python-radial.png")) > 10000 and
      os.path.getsize(os.path.join(repo, "results/void-fraction-study.png")) > 10000,
      "Python: the profile and the study are plotted")

if failures:
    sys.exit(f"check-readme: {len(failures)} check(s) failed")
print("check-readme: every README command ran and its outputs hold")
EOF
