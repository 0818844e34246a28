#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
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
echo "== FE coupling"; /usr/bin/python3 bench/bench_fem.py --build "$build" --repeat 5 --ranks 1 2 \
    --ratio-size 0.0235 --scaling-sizes 0.0174 0.0135 --scaling-repeat 3 --scaling-ranks 1
echo "== FE coupling at 1M dofs (about 25 min)"; /usr/bin/python3 bench/bench_fem.py --build "$build" --repeat 3 \
    --ranks 1 2 --ratio-size 0.0137 --scaling-sizes --no-variants --mesh-dir .scratch/fem_1m --output bench/results/fem_1m.md
echo "== levers on the jointed Newton"; /usr/bin/python3 bench/bench_newton_levers.py --build "$build"
echo "== largest model (4M dofs, 2 ranks, ~15 GiB, about 25 min with the mesh)"
/usr/bin/python3 bench/bench_fem_large.py --build "$build" --mesh-size 0.0083 --ranks 2 --mesh-dir .scratch/fem_4m
/usr/bin/python3 bench/bench_fem_large.py --build "$build" --mesh-size 0.0137 --ranks 2 --mesh-dir .scratch/fem_1m \
    --output bench/results/fem_large_1m.md
echo "== direct vs iterative"; /usr/bin/python3 bench/bench_direct_vs_iterative.py
echo "== Kirsch"; /usr/bin/python3 bench/bench_kirsch.py
echo "== FE speed against error"; /usr/bin/python3 bench/bench_fe_speed_vs_error.py
echo "== exact contact (BEM)"; /usr/bin/python3 bench/bench_contact.py --repeat 5
echo "== flow along the joint"; /usr/bin/python3 bench/bench_flow.py --repeat 3
echo "== accuracy ladder"; /usr/bin/python3 bench/bench_accuracy_ladder.py
echo "== equivalent continuum"; /usr/bin/python3 bench/bench_continuum.py
echo "== slipping-joint profile"; /usr/bin/python3 bench/bench_tunnel_profile.py --repeat 3
echo "== coupled water"; /usr/bin/python3 bench/bench_coupled_water.py --repeat 3
