#!/usr/bin/env bash
# Fuzz the readers: build the libFuzzer targets of fuzz/ with clang, ASan and UBSan
# if needed, then run each for SECONDS on a fresh copy of its seed corpus, one after another,
# one process each. Prints executions, exec/s, coverage and findings; exits 1 on any finding.
#
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
#   SECONDS  per target (default 600)
#   TARGET   csv xyz dump data toml checkpoint pellet_checkpoint summary lammps_log job (or
#            fuzz_csv, ...); default: all
# Environment:
#   PACKBED_FUZZ_BUILD  build folder (default build-fuzz)
#   PACKBED_FUZZ_OUT    output folder (default BUILD/fuzz-out, ignored by git):
#                       OUT/TARGET/corpus (the seeds and what the run added),
#                       OUT/TARGET/findings (crash, leak, timeout and oom inputs: kept from run
#                       to run), OUT/TARGET/fuzz.log (libFuzzer's output)
#   FUZZ_SEED           libFuzzer's -seed (default: a random one, printed)
#   JOBS                build jobs (default 2)
# Reproduce a finding: BUILD/fuzz/fuzz_TARGET OUT/TARGET/findings/crash-...
set -euo pipefail
cd "$(dirname "$0")/.."

all=(csv xyz dump data toml checkpoint pellet_checkpoint summary lammps_log job)
seconds=600
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then
  seconds=$1
  shift
fi
targets=()
for t in "${@:-${all[@]}}"; do
  t=${t#fuzz_}
  if [[ ! " ${all[*]} " =~ " $t " ]]; then
    echo "fuzz.sh: unknown target '$t'; allowed: ${all[*]}" >&2
    exit 2
  fi
  targets+=("$t")
done

build=${PACKBED_FUZZ_BUILD:-build-fuzz}
out=${PACKBED_FUZZ_OUT:-$build/fuzz-out}
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPACKBED_SANITIZE=ON -DPACKBED_SANITIZE_COLD=OFF -DPACKBED_BUILD_FUZZ=ON \
  -DPACKBED_BUILD_TESTS=OFF \
  -DPACKBED_BUILD_BENCH=OFF -DPACKBED_BUILD_EXAMPLES=OFF >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]/#/fuzz_}"

# UBSan prints no stack unless asked; every finding stops the process (-fno-sanitize-recover).
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}

status=0
summary=()
for t in "${targets[@]}"; do
  name=fuzz_$t
  dir=$out/$name
  rm -rf "$dir/corpus"
  mkdir -p "$dir/findings"
  cp -r "fuzz/corpus/$name" "$dir/corpus"
  touch "$dir/.start"
  args=(-max_total_time="$seconds" -timeout=10 -print_final_stats=1
        -artifact_prefix="$dir/findings/")
  [[ -f fuzz/dict/$t.dict ]] && args+=(-dict="fuzz/dict/$t.dict")
  [[ -n ${FUZZ_SEED:-} ]] && args+=(-seed="$FUZZ_SEED")
  echo "fuzz.sh: $name for $seconds s (log: $dir/fuzz.log)"
  rc=0
  "$build/fuzz/$name" "${args[@]}" "$dir/corpus" >"$dir/fuzz.log" 2>&1 || rc=$?
  seed=$(grep -m1 -o 'Seed: [0-9]*' "$dir/fuzz.log" | cut -d' ' -f2 || true)
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$dir/fuzz.log" | grep -o '[0-9]*$' || true)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$dir/fuzz.log" | grep -o '[0-9]*$' || true)
  last=$(grep -E '^#[0-9]+.*cov: ' "$dir/fuzz.log" | tail -1 || true)
  cov=$(grep -o 'cov: [0-9]*' <<<"$last" | cut -d' ' -f2 || true)
  ft=$(grep -o 'ft: [0-9]*' <<<"$last" | cut -d' ' -f2 || true)
  corp=$(grep -o 'corp: [0-9]*/[0-9a-zA-Z]*' <<<"$last" | cut -d' ' -f2 || true)
  new=$(find "$dir/findings" -type f -newer "$dir/.start" | sort)
  found=$(grep -c . <<<"$new" || true)
  line=$(printf '%-16s %10s runs %7s exec/s  cov %5s  ft %6s  corpus %-12s seed %-10s findings %s' \
    "$name" "${runs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "${seed:-?}" "$found")
  echo "$line"
  summary+=("$line")
  if ((rc != 0 || found > 0)); then
    status=1
    echo "fuzz.sh: $name FAILED (exit $rc); findings in $dir/findings/:" >&2
    [[ -n $new ]] && echo "$new" | sed 's/^/  /' >&2
    grep -E 'FINDING|ERROR: |runtime error|SUMMARY' "$dir/fuzz.log" | head -5 | sed 's/^/  /' >&2
  fi
done
echo
echo "fuzz.sh: $seconds s per target, build $build, outputs $out/"
printf '%s\n' "${summary[@]}"
if ((status != 0)); then
  echo "fuzz.sh: FINDINGS (inputs under $out/*/findings/, logs $out/*/fuzz.log)" >&2
fi
exit $status
