#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Run any command in rockjoint's Debian 13 userland with the development paths set, e.g.
#   bash scripts/run.sh python3 demos/demo_tunnel.py --output out
#   bash scripts/run.sh mpirun -n 2 python3 -m pytest tests/python/test_fem_column_mpi.py
# (natively on Debian 13; inside the root of scripts/host.sh on Debian 12). Build first.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
build="$rj_build_dir"
rj_setup
export PYTHONPATH="$rj_repo/python:$build/python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
rj_run "$@"
