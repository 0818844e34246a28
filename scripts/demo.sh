#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build (installing what is missing) and run the main demo: a laboratory joint-closure test,
# jointed specimen beside the intact one. Outputs go to ./out/ (PNG, XDMF, text report).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
build="$rj_build_dir"
# The demo needs the Python package's two compiled modules, not the tests and benchmarks.
ROCKJOINT_BUILD_TARGETS="_rockjoint _rockjoint_fem_coupling" bash "$rj_repo/scripts/build.sh"
rj_setup
export PYTHONPATH="$rj_repo/python:$build/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
mkdir -p "$rj_repo/out"
cd "$rj_repo/out"
rj_run "$rj_python" "$rj_repo/demos/demo_lab_closure_test.py" "$@"
