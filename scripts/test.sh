#!/usr/bin/env bash
# Build (installing what is missing) and run every test: C++ (GoogleTest), Python (pytest),
# and the MPI suites (mpirun -n 2), all driven by ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ROCKJOINT_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$build"
ctest --output-on-failure -j 2 "$@"
