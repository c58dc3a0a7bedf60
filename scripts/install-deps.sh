#!/usr/bin/env bash
# Install what packbed needs on Debian 12, from Debian's packages only; nothing when everything
# is already there. Usage: scripts/install-deps.sh [--test]
#   --test  also what the test suite needs beyond the build (VTK's Python reader, LAMMPS, LIGGGHTS,
#           admesh and OpenFOAM to check the surfaces and cases packbed export writes)
set -euo pipefail

packages=(
  g++ cmake make            # C++20 compiler (GCC 12, with OpenMP) and the build
  libcli11-dev              # command-line parsing
  libtomlplusplus-dev       # TOML config files
  nlohmann-json3-dev        # summary.json
  libfmt-dev                # formatting, shortest round-trip doubles
  libboost-dev              # Boost.Math tanh-sinh quadrature (header-only)
  libcgal-dev               # mesh unions (packbed export --contacts enlarge/bridges)
  libgtest-dev              # tests
  libbenchmark-dev          # benchmarks
  python3                   # bench/ scripts, examples/validate.py
  gnuplot-nox               # plots of examples/validate.py
)
if [[ ${1:-} == --test ]]; then
  packages+=(python3-vtk9)  # reads particles.vtu as ParaView does
  packages+=(lammps)        # reads the data files of packbed export (lmp)
  packages+=(liggghts)      # and LIGGGHTS reads them too
  packages+=(admesh)        # checks the STL surfaces of packbed export
  packages+=(openfoam)      # surfaceCheck, blockMesh, snappyHexMesh, checkMesh on them
  packages+=(clang)               # scripts/test-sanitize.sh and scripts/fuzz.sh: clang 14,
  packages+=(libclang-rt-14-dev)  # its ASan/UBSan/libFuzzer runtimes,
  packages+=(libomp-dev)          # and OpenMP for clang (libomp)
fi

missing=()
for p in "${packages[@]}"; do
  [[ $p == \#* ]] && continue
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: everything is installed"
  exit 0
fi
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
