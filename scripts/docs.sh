#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build the documentation site (docs/*.md, the Python docstrings, the C++ headers through doxygen
# and breathe) into docs/_build/html, with every warning an error. Build the package first
# (scripts/build.sh): autodoc imports rockjoint from the build tree.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
rj_setup
export PYTHONPATH="$rj_repo/python:$rj_build_dir/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
cd "$rj_repo"
mkdir -p docs/_doxygen
# Doxygen reads the public headers of the library's components (warnings as errors too).
rj_run bash -c '(cat <<DOXY
PROJECT_NAME = rockjoint
INPUT = constitutive contact flow joint continuum
FILE_PATTERNS = *.hpp *.h
RECURSIVE = YES
EXCLUDE_PATTERNS = */tests/* */detail/*
GENERATE_HTML = NO
GENERATE_LATEX = NO
GENERATE_XML = YES
OUTPUT_DIRECTORY = docs/_doxygen
QUIET = YES
WARN_IF_UNDOCUMENTED = NO
DOXY
) | doxygen -'
rj_run python3 -m sphinx -W --keep-going -n -b html -q docs docs/_build/html
