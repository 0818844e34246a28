#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A build without CHOLMOD's GPL-2+ supernodal module (ROCKJOINT_CHOLMOD=OFF; docs/install.md):
# the flow library and its C++ tests configured and built on their own, linked without CHOLMOD,
# and every flow test passing with Eigen's simplicial LLᵀ as the `cholesky` solver.
# Usage: bash tests/install/without_cholmod.sh <source dir>   (ctest runs it as flow_without_cholmod)
set -euo pipefail
src="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/../..}" && pwd)"
build="$(mktemp -d)"
trap 'rm -rf "$build"' EXIT
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DROCKJOINT_CHOLMOD=OFF -DROCKJOINT_PYTHON=OFF \
      -DROCKJOINT_FEM=OFF -DROCKJOINT_BENCH=OFF > "$build/configure.log"
cmake --build "$build" -j "${CMAKE_BUILD_PARALLEL_LEVEL:-2}" --target test_flow_reynolds test_flow_transmissivity_table \
      > "$build/build.log"
if grep -qi cholmod "$build"/tests/CMakeFiles/test_flow_*.dir/link.txt; then
  echo "without_cholmod: a flow test still links CHOLMOD" >&2; exit 1
fi
"$build/tests/test_flow_reynolds" --gtest_brief=1
"$build/tests/test_flow_transmissivity_table" --gtest_brief=1
echo "flow without CHOLMOD: built and passed"
