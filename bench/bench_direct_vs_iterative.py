# SPDX-License-Identifier: MIT
"""Direct (MUMPS) against iterative (CG + GAMG) linear solves of an intact elastic block, 2D and 3D.

The evidence behind linear_solver.DIRECT_DOF_LIMIT (the dof count up to which "auto" picks MUMPS).
One linear solve of JointedRockModel's intact column (E = 20 GPa, ν = 0.25, rollers, 5 MPa on top),
set-up and factorisation included, relative residual 1e-10; minimum of --repeat runs. Prints a table
and writes bench/results/direct_vs_iterative.md.

    PYTHONPATH=python:build/python /usr/bin/python3 bench/bench_direct_vs_iterative.py
"""
import argparse
import os
import platform
import time

import numpy as np
from mpi4py import MPI

from rockjoint import meshes
from rockjoint.console import quiet_compiler_logging, say
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
from rockjoint.fem.solvers.linear_solver import DIRECT_DOF_LIMIT

SIZES = {2: (0.02, 0.008, 0.005), 3: (0.12, 0.08, 0.06, 0.045)}  # gmsh mesh sizes [m]


def solve_time(dmesh, dim: int, kind: str, repeat: int) -> tuple:
    best = np.inf
    for _ in range(repeat):
        model = JointedRockModel(dmesh, rock=(20e9, 0.25), joints={}, linear_solver=kind,
                                 newton=NewtonOptions(verbose=False))
        model.fix("bottom", "y" if dim == 2 else "z")
        model.fix("left", "x")
        if dim == 3:
            model.fix("front", "y")
        model.add_traction("top", (0.0, -5e6) if dim == 2 else (0.0, 0.0, -5e6))
        model.solve()
        best = min(best, model.timings["linear_solve"])
    return model.num_dofs, best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "results",
                                                         "direct_vs_iterative.md"))
    args = parser.parse_args()
    quiet_compiler_logging()
    rows = []
    for dim, sizes in SIZES.items():
        for h in sizes:
            dmesh = distribute(meshes.column(1.0, 1.0, [], dim=dim, mesh_size=h, comm=MPI.COMM_WORLD),
                               MPI.COMM_WORLD)
            dofs, direct = solve_time(dmesh, dim, "direct", args.repeat)
            _, iterative = solve_time(dmesh, dim, "iterative", args.repeat)
            rows.append((dim, dofs, direct, iterative))
            say(f"{dim}D {dofs:7d} dofs: MUMPS {direct:.3f} s, CG+GAMG {iterative:.3f} s, "
                f"ratio {direct / iterative:.1f}")
    lines = ["# Direct (MUMPS) against iterative (CG + GAMG) solves of an intact block", "",
             f"Produced by `bench/bench_direct_vs_iterative.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
             f"{platform.machine()}, {os.cpu_count()} CPUs, 1 rank, Debian's reference BLAS; load average "
             f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} at the end. One linear solve (set-up and "
             f"factorisation included), relative residual 1e-10, minimum of {args.repeat} runs.", "",
             "| dim | dofs | MUMPS [s] | CG + GAMG [s] | MUMPS / CG+GAMG |", "|---:|---:|---:|---:|---:|"]
    lines += [f"| {d} | {n} | {a:.3f} | {b:.3f} | {a / b:.1f} |" for d, n, a, b in rows]
    lines += ["", f"Hence `linear_solver=\"auto\"` uses MUMPS up to {DIRECT_DOF_LIMIT[2]} dofs in 2D and "
              f"{DIRECT_DOF_LIMIT[3]} in 3D (`rockjoint.fem.solvers.linear_solver.DIRECT_DOF_LIMIT`)."]
    if MPI.COMM_WORLD.rank == 0:
        with open(args.output, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
        say(f"wrote {args.output}")


if __name__ == "__main__":
    main()
