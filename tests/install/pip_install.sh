#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The pip route (issue 42, item 1; docs/install.md): in the current userland (one that imports
# DOLFINx), a virtual environment with the system site packages, `pip install
# --no-build-isolation <repo>`, then, from a directory outside the checkout and with no
# PYTHONPATH: the version, the CLI, the main demo and a scene run from the installed package.
# Usage: bash tests/install/pip_install.sh [repo]   (ctest runs it as `pip_install`)
set -euo pipefail
repo="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/../..}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
unset PYTHONPATH
export MPLBACKEND=Agg
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"   # the wheel's C++ build
t0=$SECONDS
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
# scikit-build-core builds in a temporary tree of its own (the checkout's build/ is untouched)
"$work/venv/bin/python" -m pip install --no-build-isolation --no-deps --no-index --quiet "$repo"
echo "pip install: $((SECONDS - t0)) s"
mkdir "$work/run" && cd "$work/run"
version="$("$work/venv/bin/python" -c "import rockjoint, os; assert '$repo' not in rockjoint.__file__; print(rockjoint.__version__)")"
test "$("$work/venv/bin/rockjoint" --version)" = "rockjoint $version"
"$work/venv/bin/python" -c "import rockjoint.fem, rockjoint.meshes, rockjoint.scenes"
"$work/venv/bin/python" "$repo/demos/demo_lab_closure_test.py" > demo.txt
grep -q "max relative difference" demo.txt
"$work/venv/bin/rockjoint" run "$repo/demos/scenes/blocky_rock_mass.yaml" --reduced --output scene > scene.txt 2>&1
test -s scene/summary.txt
# the CMake package for C++ users, in the environment's prefix
test -f "$work/venv/lib/cmake/rockjoint/rockjointConfig.cmake"
echo "pip route: installed rockjoint $version, demo and scene run outside the checkout ($((SECONDS - t0)) s)"
