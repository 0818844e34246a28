#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build the documentation site (docs/*.md, the Python docstrings, the C++ headers through doxygen
# and breathe) into docs/_build/html, with every warning an error (docs/build.sh, which ctest's
# `docs` test runs too). Build the package first (scripts/build.sh): autodoc imports rockjoint
# from the build tree.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
rj_setup
export PYTHONPATH="$rj_repo/python:$rj_build_dir/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
rj_run bash "$rj_repo/docs/build.sh" "$rj_repo/docs/_build"
