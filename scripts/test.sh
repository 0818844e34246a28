#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build (installing what is missing) and run every test: C++ (GoogleTest), Python (pytest),
# and the MPI suites (mpirun -n 2 and 3), all driven by ctest, in the Debian 13 userland.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
build="$rj_build_dir"
bash "$rj_repo/scripts/build.sh"
rj_setup
cd "$build"
rj_run ctest --output-on-failure -j 2 "$@"
