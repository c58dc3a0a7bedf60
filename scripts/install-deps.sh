#!/usr/bin/env bash
# Install what packbed needs on Debian 12, from Debian's packages only; nothing when everything
# is already there. Usage: scripts/install-deps.sh [--cfd] [--lammps] [--test]
#   --cfd   also what runs an exported OpenFOAM case and draws its flow (OpenFOAM, Open MPI,
#           ParaView and its Python, xvfb)
#   --lammps also what `packbed generate --engine lammps` runs (LAMMPS, Open MPI)
#   --test  also what the test suite needs beyond the build (the --cfd packages, LAMMPS,
#           LIGGGHTS and admesh to check the files packbed writes; clang for the sanitizers)
# It never removes a package: apt-get runs with --no-remove, and a package that conflicts with
# one already installed is left out, saying so.
set -euo pipefail

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

packages=(
  g++ cmake make            # C++20 compiler (GCC 12, with OpenMP) and the build
  libcli11-dev              # command-line parsing
  libtomlplusplus-dev       # TOML config files
  nlohmann-json3-dev        # summary.json
  libfmt-dev                # formatting, shortest round-trip doubles
  libboost-dev              # Boost.Math tanh-sinh quadrature (header-only)
  libcgal-dev               # mesh unions (packbed export --contacts enlarge/bridges)
  zlib1g-dev                # gzip-compressed bed files (.dump.gz, .csv.gz)
  libccd-dev                # GJK/EPA overlap of convex pellets
  libgtest-dev              # tests
  libbenchmark-dev          # benchmarks
  python3                   # bench/ scripts, examples/validate.py
  gnuplot-nox               # plots of examples/validate.py
  python3-dev pybind11-dev  # the Python module (import packbed)
  python3-numpy             # its arrays
  python3-matplotlib        # the README's Python example plots with it
)
cfd=0 lammps=0 test=0
for option in "$@"; do
  case $option in
    --cfd) cfd=1 ;;
    --lammps) lammps=1 ;;
    --test) cfd=1 lammps=1 test=1 ;;
    *)
      echo "install-deps: unknown option '$option'; allowed: --cfd, --lammps, --test" >&2
      exit 2
      ;;
  esac
done
if ((cfd)); then
  # ParaView reads particles.vtu and renders it headless (pvbatch under xvfb-run). In Debian 12
  # its Python (python3-paraview) conflicts with python3-vtk9: a user who has python3-vtk9
  # keeps it, the VTU test reads with it, and the ParaView test reports skipped.
  if installed python3-vtk9 && ! installed python3-paraview; then
    echo "install-deps: python3-vtk9 is installed and conflicts with python3-paraview in" \
      "Debian 12: ParaView is not installed (its test will report skipped); VTU files are" \
      "checked with python3-vtk9"
  else
    packages+=(paraview python3-paraview xvfb)
  fi
  packages+=(openfoam)      # blockMesh, snappyHexMesh, simpleFoam: the exported case's Allrun
  packages+=(openmpi-bin)   # mpirun: Allrun on --ranks N
fi
if ((lammps)); then
  packages+=(lammps)        # lmp: generate --engine lammps; it reads packbed export's data files
  packages+=(openmpi-bin)   # mpirun: --engine lammps --ranks N
fi
if ((test)); then
  packages+=(python3-pytest python3-tifffile)  # the Python module's tests (TIFF read back)
  packages+=(liggghts)      # and LIGGGHTS reads them too
  packages+=(admesh)        # checks the STL surfaces of packbed export
  packages+=(clang)               # scripts/test-sanitize.sh and scripts/fuzz.sh: clang 14,
  packages+=(libclang-rt-14-dev)  # its ASan/UBSan/libFuzzer runtimes,
  packages+=(libomp-dev)          # and OpenMP for clang (libomp)
fi

missing=()
for p in "${packages[@]}"; do
  [[ $p == \#* ]] && continue
  installed "$p" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: everything is installed"
  exit 0
fi
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends --no-remove \
  "${missing[@]}"
