#!/usr/bin/env bash
# Cylinder beds (L = D) poured into tubes with friction between pellets and at the walls, for
# docs/validation.md ("Pellets: cylinder beds in tubes"): each bed A:N:SEED:MU:THREADS runs as
#   packbed generate --shape cylinder:1,1 -a A -n N -s SEED --friction MU --wall-friction MU
# at most JOBS (default: the cores) at once, each stopped after LIMIT seconds (default 3600);
# then one line per bed: a, pellets, seed, mu, void fraction (summary.json's band), steps,
# seconds, pairs and walls whose friction was let go, the exact depths over the tolerance.
# usage: bench/pellet_friction_tubes.sh PACKBED OUT A:N:SEED:MU:THREADS ...
set -euo pipefail
bin=$(realpath "$1")
out=$2
shift 2
mkdir -p "$out"
export bin out limit=${LIMIT:-3600}
one() {
    IFS=: read -r a n s mu t <<<"$1"
    d="$out/a$a-mu$mu-s$s"
    timeout "$limit" "$bin" generate --shape cylinder:1,1 -a "$a" -n "$n" -s "$s" \
        --friction "$mu" --wall-friction "$mu" --threads "$t" -o "$d" --force -q \
        >"$d.log" 2>&1 || echo "exit $?" >>"$d.log"
}
export -f one
printf '%s\n' "$@" | xargs -P "${JOBS:-$(nproc)}" -I{} bash -c 'one {}'
python3 - "$out" <<'PY'
import json, pathlib, sys
print("a pellets seed mu e steps seconds let_go_pairs let_go_walls pair/tol wall/tol")
for d in sorted(pathlib.Path(sys.argv[1]).glob("a*-mu*-s*")):
    if d.suffix == ".log":
        continue
    f = d / "summary.json"
    if not f.exists():
        print(d.name, "did not end:", (d.parent / (d.name + ".log")).read_text().strip()[-200:])
        continue
    s = json.loads(f.read_text())
    g = s.get("friction_let_go", {})
    print(f'{s["aspect_ratio"]:g} {s["particles"]} {s["seed"]} {s["friction"]:g} '
          f'{s.get("void_fraction", float("nan")):.4f} {s["steps"]} {s["seconds"]:.0f} '
          f'{g.get("pairs", 0)} {g.get("walls", 0)}{" all" if g.get("everywhere") else ""} '
          f'{s["max_penetration_pair"] / s["tolerance"]:.2f} '
          f'{s["max_penetration_wall"] / s["tolerance"]:.2f}')
PY
