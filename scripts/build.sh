#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install what is missing (Debian 13 packages; on a Debian 12 host, a Debian 13 root first:
# scripts/host.sh), then configure and build rockjoint into its build tree (build/ for DOLFINx 0.11,
# build-0.9/ for 0.9, or $ROCKJOINT_BUILD_DIR).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
build="$rj_build_dir"
rj_setup
rj_build() {
  rj_run cmake -S "$rj_repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$rj_python" >/dev/null
  # ROCKJOINT_BUILD_TARGETS: only these targets (demo.sh: the Python modules); default all.
  local targets=()
  [ -n "${ROCKJOINT_BUILD_TARGETS:-}" ] && read -r -a targets <<<"--target $ROCKJOINT_BUILD_TARGETS"
  rj_run cmake --build "$build" -j "${ROCKJOINT_JOBS:-$(nproc)}" "${targets[@]}"
}
rj_build
echo "build: done in $build (Python: PYTHONPATH=$rj_repo/python:$build/python)"
