#!/usr/bin/env bash
# Build (installing what is missing) and run the main demo: a laboratory joint-closure test,
# jointed specimen beside the intact one. Outputs go to ./out/ (PNG, XDMF, text report).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ROCKJOINT_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh"
export PYTHONPATH="$root/python:$build/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
mkdir -p "$root/out"
cd "$root/out"
/usr/bin/python3 "$root/demos/demo_lab_closure_test.py" "$@"
