#!/usr/bin/env bash
# Install the Debian 12 packages rockjoint needs (only the missing ones). Needs root or sudo.
set -euo pipefail
packages=(
  build-essential cmake pkg-config libgtest-dev
  libeigen3-dev libgsl-dev libfftw3-dev pybind11-dev
  python3-dev python3-numpy python3-scipy python3-matplotlib python3-pytest python3-h5py python3-meshio
  python3-dolfinx libdolfinx-dev python3-gmsh python3-mpi4py python3-petsc4py
  openmpi-bin
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
