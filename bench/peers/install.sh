#!/usr/bin/env bash
# Install the peers packbed is compared with (Debian packages): LAMMPS with MPI, LIGGGHTS.
# Usage: bench/peers/install.sh   (as root, or with sudo available)
set -euo pipefail
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo=sudo; fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
  lammps liggghts openmpi-bin
