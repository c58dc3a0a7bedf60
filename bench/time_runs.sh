#!/usr/bin/env bash
# Time whole `packbed generate` runs and print a Markdown table:
# seed, update order, threads, iterations, void fraction, largest overlaps, seconds.
# Usage: bench/time_runs.sh [PACKBED] [ASPECT_RATIO] [PARTICLES] [SEEDS] [CONFIGS]
#   CONFIGS: space-separated "update:threads" pairs for the paper's solver (--solver paper),
#            e.g. "in-place:1 simultaneous:2", "fire:THREADS" for --solver fire, or "default"
#            for the plain command (the default solver, fire), with no --update and no --threads
# Example (the paper's case with the paper's solver, seeds 1-5, both update orders):
#   bench/time_runs.sh build/packbed 5 500 "1 2 3 4 5" "in-place:1 simultaneous:1 simultaneous:2"
set -euo pipefail
exe=${1:-build/packbed}
a=${2:-5}
n=${3:-500}
seeds=${4:-"1 2 3 4 5"}
configs=${5:-"in-place:1 simultaneous:1 simultaneous:2"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| a | Np | seed | solver / update | --threads | iterations | void fraction | max overlap pair (Dp) | max overlap wall (Dp) | both < 1e-4 Dp | seconds |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for seed in $seeds; do
  for config in $configs; do
    extra=()
    if [[ $config == fire:* ]]; then
      extra=(--solver fire --threads "${config##*:}")
    elif [[ $config != default ]]; then
      extra=(--solver paper --update "${config%%:*}" --threads "${config##*:}")
    fi
    "$exe" generate --aspect-ratio "$a" --particles "$n" --seed "$seed" "${extra[@]}" \
      --quiet --force --out "$out/run"
    python3 - "$out/run/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
p = s["parameters"]
how = "fire" if p.get("solver") == "fire" else f"paper / {p['update']}"
print(f"| {s['aspect_ratio']:g} | {s['particles']} | {s['seed']} | {how} | {p['threads']} "
      f"| {s['iterations']} | {s['void_fraction']:.4f} | {s['max_overlap_pair']:.3e} "
      f"| {s['max_overlap_wall']:.3e} "
      f"| {'yes' if max(s['max_overlap_pair'], s['max_overlap_wall']) < 1e-4 else 'NO'} "
      f"| {s['seconds']:.2f} |")
PY
  done
done
