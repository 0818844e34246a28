#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What the levers on the jointed Newton's Krylov iterations buy (issue 43, item 1).

The cases of bench_fem.py (column, blocky) on one mesh, one rank, one run per setting; Krylov
iterations, Newton iterations and GAMG set-ups are deterministic for a given mesh and partition,
the times are not (read them only beside each other, from one run):
- default: the project's settings (lagged GAMG, Eisenstat-Walker from η0 = 0.1);
- forcing_initial 0.3 / 0.5: a looser first step (the first step overshoots anyway);
- line_search: Armijo backtracking after the closure limit;
- galerkin_refresh: GAMG keeps its aggregates and prolongators (pc_gamg_reuse_interpolation)
  and only its Galerkin coarse operators and smoothers are rebuilt before every solve tighter
  than η = 1e-3 (the last Newton steps, where the lagged hierarchy of the first Jacobian costs
  iterations);
- fresh_every_step: the hierarchy rebuilt (Galerkin only) before every solve: the floor of what
  a better preconditioner can save;
- own / deflated PCG: a Krylov space carried across the Newton steps (deflated_cg.py: Ritz
  vectors of the earlier solves deflated from the later ones), against the same PCG without
  deflation (the lagged GAMG in both; PETSc's CG gives the default row).

Usage: /usr/bin/python3 bench/bench_newton_levers.py [--mesh-size 0.0235] [--mesh-dir .scratch/fem_200k]
(runs itself under `mpirun -n 1`); writes bench/results/newton_levers.md.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_fem as bf  # noqa: E402
from deflated_cg import use_deflated_cg  # noqa: E402

#: name -> (NewtonOptions overrides, Galerkin refresh below this η (None: off; 1.0: every solve),
#: deflated CG (kept, new Ritz vectors per solve; None: PETSc's CG))
SETTINGS = {
    "default": ({}, None, None),
    "forcing_initial 0.3": ({"forcing_initial": 0.3}, None, None),
    "forcing_initial 0.5": ({"forcing_initial": 0.5}, None, None),
    "line_search": ({"line_search": True}, None, None),
    "galerkin_refresh (η < 1e-3)": ({}, 1e-3, None),
    "fresh_every_step (Galerkin)": ({}, 1.0, None),
    "own PCG, lagged GAMG (reference of the next rows)": ({}, None, (0, 0)),
    "deflated PCG, 5 Ritz vectors per solve, 10 kept": ({}, None, (10, 5)),
    "deflated PCG, 10 Ritz vectors per solve, 30 kept": ({}, None, (30, 10)),
}


def _refresh_below(model, tight: float) -> None:
    """Make the lagged GAMG rebuild (Galerkin operators only, its prolongators kept) before every
    solve with rtol below `tight`: that solve runs with reuse_preconditioner off."""
    from petsc4py import PETSc
    ls = model.linear_solver
    key = ls.ksp.getOptionsPrefix() + "pc_gamg_reuse_interpolation"
    PETSc.Options()[key] = 1
    ls.ksp.setFromOptions()
    PETSc.Options().delValue(key)
    solve = ls.solve

    def refreshing(A, b, x, rtol=None):
        ls.reuse_preconditioner = not (ls.setups and (rtol is None or rtol < tight))
        try:
            return solve(A, b, x, rtol=rtol)
        finally:
            ls.reuse_preconditioner = True
    ls.solve = refreshing


def worker(args) -> None:
    from mpi4py import MPI
    from rockjoint.fem import NewtonOptions
    comm = MPI.COMM_WORLD
    rows = []
    for case in ("column", "blocky"):
        cache = os.path.join(args.mesh_dir, f"{case}_{args.mesh_size}.pkl")
        jm = bf.cached_mesh(case, args.mesh_size, cache)[0] if comm.rank == 0 else None
        corner = comm.bcast(bf.corner_block(jm) if comm.rank == 0 else None)
        dmesh = bf.distribute_cached({"jointed": jm}, comm, cache)["jointed"]
        for name, (newton, tight, deflation) in SETTINGS.items():
            model, law = bf.build_model(case, dmesh, corner, "default")
            model.newton_options = NewtonOptions(verbose=False, **newton)
            if tight is not None:
                _refresh_below(model, tight)
            if deflation is not None:
                use_deflated_cg(model, *deflation)
            t0 = time.perf_counter()
            sol = model.solve(load_steps=1)
            dt = time.perf_counter() - t0
            its = list(model.linear_solver.iterations)
            rows.append({"case": case, "setting": name, "time": dt, "newton": sol.newton_iterations,
                         "krylov": its, "setups": model.linear_solver.setups, "dofs": model.num_dofs,
                         "error": bf.closed_form_error(case, "jointed", model, sol, law)})
            if comm.rank == 0:
                print(f"{case:7s} {name:30s} {dt:6.2f} s  Newton {sol.newton_iterations}  Krylov {its} "
                      f"(sum {sum(its)})  set-ups {model.linear_solver.setups}", flush=True)
    if comm.rank == 0:
        with open(args.json, "w") as fh:
            json.dump(rows, fh)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh-size", type=float, default=0.0235)
    ap.add_argument("--mesh-dir", default=None, help="meshes kept (and reused) here")
    ap.add_argument("--build", default=None)
    ap.add_argument("--output", default=os.path.join(HERE, "results", "newton_levers.md"))
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--json", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        worker(args)
        return
    env = bf.worker_env(args.build)
    with tempfile.TemporaryDirectory() as tmp:
        args.mesh_dir = args.mesh_dir or tmp
        os.makedirs(args.mesh_dir, exist_ok=True)
        out = os.path.join(tmp, "rows.json")
        subprocess.run(["mpirun", "-n", "1", "/usr/bin/python3", os.path.abspath(__file__), "--worker",
                        "--mesh-size", str(args.mesh_size), "--mesh-dir", args.mesh_dir, "--json", out],
                       check=True, env=env)
        with open(out) as fh:
            rows = json.load(fh)
    cmd = f"/usr/bin/python3 bench/bench_newton_levers.py --mesh-size {args.mesh_size}"
    L = [f"# What the levers on the jointed Newton buy (DOLFINx {bf.stack_versions()}, 3D, 1 rank)", "",
         f"Produced by `{cmd}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; load average "
         f"{os.getloadavg()[0]:.2f} at the end. One run per setting: the iterations and set-ups are "
         "deterministic, the times are one run's (noisy). Settings: module docstring.", "",
         "| case | dofs | setting | Newton its | Krylov its | Krylov total | GAMG set-ups | time [s] | error vs closed form |",
         "|---|---:|---|---:|---|---:|---:|---:|---|"]
    for r in rows:
        L.append(f"| {r['case']} | {r['dofs']} | {r['setting']} | {r['newton']} | {','.join(map(str, r['krylov']))} | "
                 f"{sum(r['krylov'])} | {r['setups']} | {r['time']:.2f} | {r['error']:.1e} |")
    text = "\n".join(L) + "\n"
    bf.write_report(text, args.output)


if __name__ == "__main__":
    main()
