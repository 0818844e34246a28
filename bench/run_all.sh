#!/usr/bin/env bash
# Run every benchmark one after the other (they time themselves; run on an idle machine) and
# write bench/results/*.md (+ PNGs). Usage: bash bench/run_all.sh [build dir, default ./build]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
export PYTHONPATH="$root/python:$build/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$root"
echo "== closure laws"; "$build/bench/bench_closure_laws" bench/results/closure_laws.md
echo "== interaction cell"; /usr/bin/python3 bench/bench_interaction_cell.py --build "$build"
echo "== tabulation"; /usr/bin/python3 bench/bench_tabulation.py --build "$build"
echo "== topography"; /usr/bin/python3 bench/bench_topography.py
echo "== FE coupling"; /usr/bin/python3 bench/bench_fem.py --build "$build" --ranks 1 2
