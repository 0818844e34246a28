#!/usr/bin/env bash
# Install missing Debian packages, configure and build rockjoint into ./build (or $ROCKJOINT_BUILD_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ROCKJOINT_BUILD_DIR:-$root/build}"
"$root/scripts/install_deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build" -j "$(nproc)"
echo "build: done in $build (Python: PYTHONPATH=$root/python:$build/python)"
