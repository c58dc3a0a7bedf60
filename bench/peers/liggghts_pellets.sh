#!/usr/bin/env bash
# LIGGGHTS's pour-and-settle of N cylinder pellets (L = D = 1 mm) into a tube of diameter
# A d_v, d_v = (3 D^2 L / 2)^(1/3) = 1.1447 mm, each pellet a rigid clump of spheres
# (bench/peers/liggghts_pellets.in: fix particletemplate/multisphere, fix multisphere): the
# peer of `packbed generate --shape cylinder:1,1 -a A -n N`. The clump is packbed's
# (CylinderShape::for_each_clump_sphere): equal spheres of radius s = min(R, L/2) / 2, centres
# on rings of radius 0 .. R - s (steps of at most s; ceil(2 pi r / s), at least 3, about a
# ring) at z = -(L/2 - s) .. L/2 - s (steps of at most s): 24 spheres at L = D.
# Writes OUTDIR/clump.txt, OUTDIR/bodies.dump (each body's centre of mass, principal moments
# and axes), OUTDIR/bodies.dump.spheres, OUTDIR/log.liggghts, and prints one line:
#   pellets P spheres_per_clump S steps T wall_s W loop_s X void_fraction E
# P the pellets in the settled bed (of N asked for), T the steps run, W the wall time of the
# LIGGGHTS run (start-up and the clump's Monte Carlo mass and inertia, ntry 1e6, included), X
# the part of it in the time steps (the sum of the log's "Loop time"), E = 1 - P V / (pi RT^2 H),
# V = pi D^2 L / 4 (the cylinder's, not the clump's), H the top of the highest cylinder
# (centre of mass plus its support along z, the axis being the principal axis whose moment
# differs most from the other two): over the whole bed, floor to top (packbed's void_fraction
# is over a band 1 d_v clear of the floor and the top, which beds this small do not have).
# Usage: bench/peers/liggghts_pellets.sh N A OUTDIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [[ $# -ne 3 ]]; then
  echo "usage: bench/peers/liggghts_pellets.sh N A OUTDIR (N pellets, tube diameter A d_v)" >&2
  exit 2
fi
n=$1 a=$2 out=$3
if ! command -v liggghts >/dev/null 2>&1; then
  echo "bench/peers/liggghts_pellets.sh: liggghts not found; install Debian's liggghts" \
       "(bench/peers/install.sh)" >&2
  exit 1
fi
if ! command -v python3 >/dev/null 2>&1; then
  echo "bench/peers/liggghts_pellets.sh: python3 not found (writes the clump, reads the dump)" >&2
  exit 1
fi
if ! [[ $n =~ ^[1-9][0-9]*$ ]] ||
   ! python3 -c "import sys; sys.exit(not float(sys.argv[1]) > 1.5)" "$a" 2>/dev/null; then
  echo "bench/peers/liggghts_pellets.sh: N must be a positive integer and A a number > 1.5" \
       "(got N = $n, A = $a)" >&2
  exit 2
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
d=1e-3 l=1e-3

# The clump (lines x y z r, m) and its number of spheres; the tube radius.
read -r ns rt < <(python3 - "$d" "$l" "$a" "$out/clump.txt" <<'EOF'
import math, sys
d, l, a, path = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
R, h = d / 2, l / 2
s = 0.5 * min(R, h)
steps = lambda span: math.ceil(span / s - 1e-9) if span > 0 else 0
axial, rings = steps(2 * (h - s)), steps(R - s)
spheres = []
for i in range(axial + 1):
    z = 0.0 if axial == 0 else -(h - s) + 2 * (h - s) * i / axial
    for j in range(rings + 1):
        r = 0.0 if rings == 0 else (R - s) * j / rings
        around = max(3, math.ceil(2 * math.pi * r / s)) if r > 0 else 1
        for k in range(around):
            phi = 2 * math.pi * k / around
            spheres.append((r * math.cos(phi), r * math.sin(phi), z))
with open(path, "w") as f:
    for x, y, z in spheres:
        f.write(f"{x:.12g} {y:.12g} {z:.12g} {s:.12g}\n")
dv = (1.5 * d * d * l) ** (1 / 3)
print(len(spheres), repr(a * dv / 2))
EOF
)

# The screen goes to /dev/null, not `-screen none`: insert/pack prints to the screen unchecked
# and LIGGGHTS 3.8 crashes without one (a segmentation fault in Region::reset_random).
cd "$out"  # LIGGGHTS writes its default log where it runs
start=$(date +%s.%N)
if ! liggghts -in "$here/liggghts_pellets.in" -var N "$n" -var NS "$ns" -var RT "$rt" \
     -var D "$d" -var L "$l" -var CLUMP "$out/clump.txt" -var OUT "$out/bodies.dump" \
     -log "$out/log.liggghts" -screen /dev/null; then
  echo "bench/peers/liggghts_pellets.sh: liggghts failed; see $out/log.liggghts:" >&2
  tail -n 5 "$out/log.liggghts" >&2
  exit 1
fi
end=$(date +%s.%N)

python3 - "$out/bodies.dump" "$out/log.liggghts" "$n" "$ns" "$rt" "$d" "$l" "$start" "$end" <<'EOF'
import math, re, sys
dump, log, n, ns, rt, d, l, start, end = sys.argv[1:]
n, ns, rt, d, l = int(n), int(ns), float(rt), float(d), float(l)
steps, loop = None, 0.0
for line in open(log):
    m = re.match(r"settled: step (\d+) pellets (\S+)", line)
    if m:
        steps = int(m.group(1))
    m = re.match(r"Loop time of (\S+) on", line)
    if m:
        loop += float(m.group(1))
lines = open(dump).read().splitlines()
head = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ENTRIES"))
bodies = [[float(v) for v in line.split()] for line in lines[head + 1:] if line.strip()]
top = 0.0
for b in bodies:
    z, moments, axes = b[2], b[3:6], (b[6:9], b[9:12], b[12:15])
    # the pellet's axis: the principal axis whose moment differs most from the other two
    k = max(range(3), key=lambda i: min(abs(moments[i] - moments[j]) for j in range(3) if j != i))
    c = abs(axes[k][2]) / math.sqrt(sum(v * v for v in axes[k]))
    top = max(top, z + c * l / 2 + math.sqrt(max(0.0, 1 - c * c)) * d / 2)
if len(bodies) != n:
    print(f"bench/peers/liggghts_pellets.sh: {len(bodies)} pellets in the bed, {n} asked for "
          "(insert/pack placed fewer)", file=sys.stderr)
void = "none"
if bodies and top > 0:
    void = f"{1 - len(bodies) * math.pi * d * d * l / 4 / (math.pi * rt * rt * top):.4f}"
print(f"pellets {len(bodies)} spheres_per_clump {ns} steps {steps} "
      f"wall_s {float(end) - float(start):.2f} loop_s {loop:.2f} void_fraction {void}")
EOF
