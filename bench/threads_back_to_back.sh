#!/usr/bin/env bash
# Does a run get the cores it is given when it starts right after another? Runs the same bed
# ROUNDS times back to back (the one-minute load average raised by the runs before), alternating
# the default command with OMP_DYNAMIC=false (OpenMP's count fixed, as only that gave while
# packbed turned OpenMP's dynamic adjustment on), then the Python module's generate in a loop of
# three, each way. Prints wall and user seconds of every run and the ratio of the means. Noisy
# machines: compare the ratios of one run of this script.
#
# Usage: bench/threads_back_to_back.sh [PACKBED] [ROUNDS]   (default build/packbed, 3)
#   PYTHONPATH must reach the module (default build/python) for the Python loop.
set -euo pipefail
cd "$(dirname "$0")/.."
packbed=${1:-build/packbed}
rounds=${2:-3}
work=$(mktemp -d "${TMPDIR:-/tmp}/packbed-threads.XXXXXX")
trap 'rm -rf "$work"' EXIT
bed=(generate -a 20 -n 10000 -s 1 --no-analysis -q)

run() { # LABEL ENV...: one run, "LABEL wall user"
  local label=$1
  shift
  rm -rf "$work/out"
  /usr/bin/time -f "$label %e %U" env "$@" "$packbed" "${bed[@]}" -o "$work/out" 2>&1 >/dev/null
}
{
  for ((k = 0; k < rounds; ++k)); do
    run default
    run fixed OMP_DYNAMIC=false
  done
  for mode in default fixed; do
    extra=()
    [[ $mode == fixed ]] && extra=(OMP_DYNAMIC=false)
    env "${extra[@]}" PYTHONPATH="${PYTHONPATH:-build/python}" /usr/bin/python3 - "$mode" <<'EOF'
import os, resource, sys, time
import packbed
for k in range(3):
    t0, u0 = time.time(), resource.getrusage(resource.RUSAGE_SELF).ru_utime
    packbed.generate(aspect_ratio=20, particles=10000, seed=1)
    print(f"python-{sys.argv[1]} {time.time() - t0:.2f} "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_utime - u0:.2f}")
EOF
  done
} | tee "$work/times"
python3 - "$work/times" <<'EOF'
import sys
rows = [line.split() for line in open(sys.argv[1]) if line.strip()]
mean = lambda label, col: sum(float(r[col]) for r in rows if r[0] == label) / sum(r[0] == label for r in rows)
for a, b in (("default", "fixed"), ("python-default", "python-fixed")):
    print(f"{a}: wall {mean(a, 1):.2f} s, user {mean(a, 2):.2f} s; {b}: wall {mean(b, 1):.2f} s, "
          f"user {mean(b, 2):.2f} s; wall ratio {mean(a, 1) / mean(b, 1):.3f}")
EOF
