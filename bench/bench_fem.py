#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A jointed analysis at the cost of an intact linear solve: time, memory and scaling in DOLFINx.

Headline: jointed analysis time / ONE intact linear solve on the same mesh (target <= 2).
- jointed analysis = JointedRockModel.solve() wall time: every Newton iteration's joint residual
  and Jacobian, the linear solves (GAMG set-up included), one load step, Newton rtol 1e-10 on
  ||r|| / ||f||; the bulk assembly (K, f: once, the same for the intact model) is reported apart.
- intact linear solve = the same mesh with the split nodes glued (no joints), the same solver
  (CG + GAMG, same options) to the same relative residual 1e-10 (CG stops on the true residual,
  so one solve meets it): the KSP set-up and solve of that one solve.
Each run builds fresh models (fresh KSP, so every GAMG set-up is a first one); intact and jointed
alternate in the same process, `--repeat` times; the table gives the minimum over the runs and
the ratio of the minima (and the median of the per-run ratios, to show the noise).

Cases (unit cube, rock E 20 GPa, ν 0.25, Barton-Bandis joints K_ni 10 MPa/mm, V_m 1 mm, constant
k_s 1 MPa/mm, P1, nodal joint quadrature):
- column: 2 horizontal joints (z = 1/3, 2/3), rollers bottom/left/front, 5 MPa on top; closed
  form u_top = -(σ H / E + 2 Δ(σ)) (jointed), -σ H / E (intact).
- blocky: 2 intersecting inclined joints (dip 60° toward +x and 30° toward -x through the
  centre: 4 blocks), principal stresses (2, 2, 5) MPa applied as tractions on all six faces,
  rollers on the corner block only (bottom z, left x, front y): the exact solution is the uniform
  stress in every block plus a constant jump per joint, so every joint point carries
  σ_n = n·σn, |τ| = |σn - σ_n n| and closes Δ(σ_n) (error = max over points); intact: u_top =
  ε_zz H with ε_zz = (-σ_z + ν(σ_x + σ_y)) / E.

Memory: peak resident set (resource.getrusage ru_maxrss, per rank, summed over ranks) of one model
set-up + solve, the peak reset (/proc/self/clear_refs) before it, so the baseline of the process
(Python, DOLFINx, both distributed meshes) is included but not the other model.

Usage:
  /usr/bin/python3 bench/bench_fem.py                      # full: ratios 1 and 2 ranks, scaling
  /usr/bin/python3 bench/bench_fem.py --quick              # ~50k dofs, 2 runs, no scaling
  /usr/bin/python3 bench/bench_fem.py --repeat 3 --ratio-size 0.0137 --scaling-sizes --no-variants \
      --mesh-dir .scratch/fem_1m --output bench/results/fem_1m.md   # ~1M dofs (issue 31)
Options: --ratio-size H (column mesh size, 0.0235 = 203k dofs), --scaling-sizes H..., --repeat N,
--ranks 1 2, --scaling-repeat N (3), --scaling-ranks k (1), --build DIR. Every worker runs under `mpirun -n k --bind-to core`.
Writes bench/results/fem.md and bench/results/fem_scaling.png.
"""
from __future__ import annotations

import argparse
import json
import logging
import os
import pickle
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

E, NU, KNI, VM, KS = 20e9, 0.25, 1e10, 1e-3, 1e9
COLUMN_STRESS = 5e6
BLOCKY_STRESS = (2e6, 2e6, 5e6)   #: principal stresses (compression) along x, y, z [Pa]
#: blocky mesh size for about the same dofs as the column at the same size (4 joint faces less)
BLOCKY_SIZE_FACTOR = 1.0


def stack_versions() -> str:
    """'0.11.0.post0, PETSc 3.25.5' of the DOLFINx and PETSc the workers import."""
    from petsc4py import PETSc
    from rockjoint.fem.compat import DOLFINX_RELEASE
    return f"{DOLFINX_RELEASE}, PETSc {'.'.join(map(str, PETSc.Sys.getVersion()))}"


# ---------------------------------------------------------------------------------------------
# worker (inside mpirun)
def make_mesh(case: str, h: float):
    from rockjoint import meshes
    if case == "column":
        return meshes.column(1.0, 1.0, [1 / 3, 2 / 3], dim=3, mesh_size=h)
    joints = [meshes.Joint((0.5, 0.5, 0.5), 60.0, 90.0, "steep"),
              meshes.Joint((0.5, 0.5, 0.5), 30.0, 270.0, "flat")]
    return meshes.jointed_block((1.0, 1.0, 1.0), joints, dim=3, mesh_size=h * BLOCKY_SIZE_FACTOR)


def cached_mesh(case: str, h: float, cache: str | None) -> tuple:
    """(JointedMesh, seconds gmsh took) of `case` at size h: read from the pickle `cache` if it
    exists, else made (make_mesh) and kept there (cache None: made, not kept). One process."""
    if cache and os.path.exists(cache):
        with open(cache, "rb") as fh:
            return pickle.load(fh)
    t0 = time.perf_counter()
    jm = make_mesh(case, h)
    made = (jm, time.perf_counter() - t0)
    if cache:
        with open(cache, "wb") as fh:
            pickle.dump(made, fh)
    return made


def reset_peak_rss() -> None:
    """Reset this process's peak resident set (VmHWM, which ru_maxrss reads) to its current value (Linux)."""
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")


def peak_rss(comm) -> int:
    """The peak resident set [B] since reset_peak_rss(), summed over the ranks of comm (collective)."""
    import resource
    from mpi4py import MPI
    return comm.allreduce(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, op=MPI.SUM)


def glued(jm):
    """The intact mesh: the jointed one with its split nodes glued back (no joints)."""
    from rockjoint.scenes.geometry import glued as glue
    return glue(jm)


def corner_block(jm) -> str:
    """Name of the block holding the corner (0, 0, 0)."""
    import numpy as np
    node = int(np.argmin(np.linalg.norm(jm.points, axis=1)))
    cell = int(np.flatnonzero((jm.cells == node).any(axis=1))[0])
    return jm.names["blocks"][int(jm.cell_blocks[cell])]


def build_model(case, dmesh, corner, variant, law=None, **model_options):
    """The case's model, prepared (K, f, linear solver). law: the joints' (default: the Barton-Bandis
    law of the module docstring); model_options: further JointedRockModel arguments (element_degree,
    quadrature; used by bench_fe_speed_vs_error.py)."""
    import numpy as np
    import rockjoint
    from rockjoint.fem import JointedRockModel, NewtonOptions
    law = rockjoint.BartonBandis(KNI, VM) if law is None else law
    newton = NewtonOptions(verbose=True, forcing="fixed" if variant == "fixed_forcing" else "eisenstat_walker")
    petsc = {"pc_gamg_agg_nsmooths": 1} if variant == "smoothed_aggregation" else None
    model = JointedRockModel(dmesh, rock=(E, NU), joints={n: law for n in dmesh.names["joints"].values()},
                             shear_stiffness=KS, plane=None, linear_solver="iterative", newton=newton,
                             petsc_options=petsc, **model_options)
    if case == "column":
        model.fix("bottom", "z")
        model.fix("left", "x")
        model.fix("front", "y")
        model.add_traction("top", (0.0, 0.0, -COLUMN_STRESS))
    else:
        model.fix("bottom", "z", block=corner)
        model.fix("left", "x", block=corner)
        model.fix("front", "y", block=corner)
        for name, axis, outward in (("left", 0, -1), ("right", 0, 1), ("front", 1, -1), ("back", 1, 1),
                                    ("bottom", 2, -1), ("top", 2, 1)):
            t = np.zeros(3)
            t[axis] = -BLOCKY_STRESS[axis] * outward   # σ m with σ = -diag(stress)
            model.add_traction(name, t)
    model.prepare()   # function space, K, f, linear solver (fresh KSP)
    if variant == "no_reuse":
        model.linear_solver.reuse_preconditioner = False
    return model, law


def closed_form_error(case, label, model, sol, law) -> float:
    """Relative error of the answer against the closed form (module docstring)."""
    import numpy as np
    comm = model.comm
    if label == "intact" or case == "column":
        u_top = model.boundary_mean_displacement("top")[2]
        if case == "column":
            ref = -COLUMN_STRESS / E - (2 * law.closure_at_stress(COLUMN_STRESS) if label == "jointed" else 0.0)
        else:
            sx, sy, sz = BLOCKY_STRESS
            ref = (-sz + NU * (sx + sy)) / E
        return abs(u_top - ref) / abs(ref)
    j = sol.joints
    n = np.asarray(j["normal"])
    p = np.asarray(BLOCKY_STRESS)
    sn = (n**2 * p).sum(axis=1)
    tau = np.linalg.norm(-(p * n) + sn[:, None] * n, axis=1)
    clos = np.array([law.closure_at_stress(s) for s in sn])
    err = max(np.max(np.abs(np.asarray(j["normal_stress"]) - sn) / sn, initial=0.0),
              np.max(np.abs(np.asarray(j["closure"]) - clos) / clos, initial=0.0),
              np.max(np.abs(np.linalg.norm(j["shear_traction"], axis=1) - tau), initial=0.0) / max(p))
    return comm.allreduce(float(err), op=_max())


def _max():
    from mpi4py import MPI
    return MPI.MAX


def run_one(case, label, dmesh, corner, variant="default") -> dict:
    import gc
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
    gc.collect()
    reset_peak_rss()
    comm.barrier()
    t0 = time.perf_counter()
    model, law = build_model(case, dmesh, corner, variant)
    solver, ls_cpu = model.linear_solver, [0.0]
    solve_linear = solver.solve

    def timed_linear_solve(*a, **kw):   # CPU time of the linear solves (process_time)
        c = time.process_time()
        try:
            return solve_linear(*a, **kw)
        finally:
            ls_cpu[0] += time.process_time() - c

    solver.solve = timed_linear_solve
    comm.barrier()
    t1, c1 = time.perf_counter(), time.process_time()
    sol = model.solve(load_steps=1)
    c2 = time.process_time()
    comm.barrier()
    t2 = time.perf_counter()
    peak = peak_rss(comm)
    tm = {k: comm.allreduce(v, op=MPI.MAX) for k, v in model.timings.items()}
    krylov = list(model.linear_solver.iterations)
    out = {
        "dofs": model.num_dofs, "pairs": comm.allreduce(model.interface.num_pairs),
        "setup": t1 - t0, "bulk_assembly": tm["bulk_assembly"], "solve": t2 - t1,
        "solve_cpu": comm.allreduce(c2 - c1, op=MPI.MAX), "linear_solve_cpu": comm.allreduce(ls_cpu[0], op=MPI.MAX),
        "linear_solve": tm["linear_solve"], "interface": tm["interface_residual"] + tm["interface_jacobian"]
        + tm["matrix_copy"], "newton_iterations": sol.newton_iterations, "krylov": krylov,
        "pc_setups": model.linear_solver.setups, "peak_rss": peak,
        "error": closed_form_error(case, label, model, sol, law),
        "residual_norms": [r.residual_norms for r in sol.reports],
        "forcing": [r.forcing for r in sol.reports],
    }
    if label == "intact" and sol.newton_iterations != 1:
        raise RuntimeError(f"intact model needed {sol.newton_iterations} linear solves, expected 1")
    del model, sol
    gc.collect()
    return out


def worker(args) -> None:
    logging.basicConfig(level=logging.INFO, format="%(message)s")  # Newton progress (rank 0)
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
    load0 = os.getloadavg()
    jm, t_mesh = None, 0.0
    if comm.rank == 0:
        jm, t_mesh = cached_mesh(args.case, args.mesh_size, args.mesh_cache)
    corner = comm.bcast(corner_block(jm) if comm.rank == 0 else None)
    meshes = distribute_cached({"intact": glued(jm) if comm.rank == 0 else None, "jointed": jm}, comm,
                               args.mesh_cache)
    del jm
    runs = {"intact": [], "jointed": []}
    for k in range(args.repeat):
        for label in ("intact", "jointed"):
            if comm.rank == 0:
                print(f"--- {args.case} {label} run {k + 1}/{args.repeat} ({comm.size} rank(s))", flush=True)
            runs[label].append(run_one(args.case, label, meshes[label], corner))
    variants = {}
    for variant in args.variants:
        if comm.rank == 0:
            print(f"--- {args.case} jointed, variant {variant}", flush=True)
        variants[variant] = run_one(args.case, "jointed", meshes["jointed"], corner, variant)
    if comm.rank == 0:
        with open(args.json, "w") as fh:
            json.dump({"case": args.case, "ranks": comm.size, "mesh_size": args.mesh_size,
                       "mesh_generation": t_mesh, "runs": runs, "variants": variants,
                       "load": [load0, os.getloadavg()]}, fh)


def distribute_cached(jointed_meshes: dict, comm, cache: str | None) -> dict:
    """{label: DistributedJointMesh}. With a mesh cache, the partition is cached beside it
    (<cache>.owners<ranks>.npz) and reused: a run on another DOLFINx version (another partitioner
    build) then solves on the same mesh *and* the same partition."""
    import numpy as np
    from rockjoint.fem.mesh.distributed_mesh import distribute
    path = f"{cache}.owners{comm.size}.npz" if cache else None
    have = comm.bcast(bool(path) and os.path.exists(path) if comm.rank == 0 else None)
    owners = dict(np.load(path)) if have and comm.rank == 0 else {}
    meshes = {label: distribute(jm, comm, owners=owners.get(label)) for label, jm in jointed_meshes.items()}
    if path and not have:
        found = {label: d.cell_owners() for label, d in meshes.items()}
        if comm.rank == 0:
            np.savez(path, **found)
    return meshes


# ---------------------------------------------------------------------------------------------
# driver
def find_build(build: str | None) -> str:
    cands = [build] if build else [os.environ.get("ROCKJOINT_BUILD_DIR", ""), "build-fem", "build",
                                   "/work/main/build"]
    for c in cands:
        if c:
            path = c if os.path.isabs(c) else os.path.join(ROOT, c)
            lib = os.path.join(path, "python", "rockjoint")
            if os.path.isdir(lib) and any(f.startswith("_rockjoint_fem_coupling") for f in os.listdir(lib)):
                return path
    sys.exit("no build with rockjoint._rockjoint_fem_coupling found: build with -DROCKJOINT_FEM=ON and pass --build")


def worker_env(build: str | None) -> dict:
    """The environment of the workers that mpirun starts: this repository's Python package and the
    build's compiled modules on PYTHONPATH (find_build), Open MPI allowed to run as root."""
    build = find_build(build)
    return dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.join(ROOT, "python"), os.path.join(build, "python")]),
                OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def write_report(text: str, path: str) -> None:
    """Print a report and write it to `path` (its folder made if needed)."""
    print(text)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as fh:
        fh.write(text)
    print(f"wrote {path}")


def launch(env, ranks, case, h, repeat, out, cache, variants=()) -> dict:
    cmd = ["mpirun", "-n", str(ranks), "--bind-to", "core", "/usr/bin/python3", os.path.abspath(__file__),
           "--worker", "--case", case, "--mesh-size", str(h), "--repeat", str(repeat), "--json", out,
           "--mesh-cache", cache] + (["--variants", *variants] if variants else [])
    print(f"== {' '.join(cmd)}", flush=True)
    subprocess.run(cmd, check=True, env=env)
    with open(out) as fh:
        return json.load(fh)


def summary(res: dict) -> dict:
    """Minima over the runs and the ratios."""
    import statistics
    i, j = res["runs"]["intact"], res["runs"]["jointed"]
    ls = min(r["linear_solve"] for r in i)
    solve = min(r["solve"] for r in j)
    out = {
        "ranks": res["ranks"], "case": res["case"], "dofs_intact": i[0]["dofs"], "dofs": j[0]["dofs"],
        "pairs": j[0]["pairs"], "intact_ls": ls, "jointed": solve, "ratio": solve / ls,
        "ratio_median": statistics.median(b["solve"] / a["linear_solve"] for a, b in zip(i, j)),
        "interface": min(r["interface"] for r in j), "bulk": min(r["bulk_assembly"] for r in j),
        "newton": j[0]["newton_iterations"], "krylov_jointed": j[0]["krylov"], "krylov_intact": i[0]["krylov"],
        "setups": j[0]["pc_setups"], "err_jointed": max(r["error"] for r in j),
        "err_intact": max(r["error"] for r in i), "rss_intact": max(r["peak_rss"] for r in i),
        "rss_jointed": max(r["peak_rss"] for r in j), "runs": len(j),
        "intact_solve_max": max(r["linear_solve"] for r in i), "jointed_max": max(r["solve"] for r in j),
        "intact_ls_cpu": min(r["linear_solve_cpu"] for r in i), "jointed_cpu": min(r["solve_cpu"] for r in j),
        "load": res["load"], "mesh_generation": res["mesh_generation"],
    }
    out["ratio_cpu"] = out["jointed_cpu"] / out["intact_ls_cpu"]
    return out


def fmt(x, digits=3):
    return f"{x:.{digits}g}"


def report(ratio_results, scaling_results, args, wall, load_start) -> str:
    load_end = os.getloadavg()
    cmd = "/usr/bin/python3 bench/bench_fem.py" + (" --quick" if args.quick else "") + \
        ("" if args.quick else f" --repeat {args.repeat} --ranks {' '.join(map(str, args.ranks))} "
         f"--ratio-size {args.ratio_size} --scaling-sizes {' '.join(map(str, args.scaling_sizes))} "
         f"--scaling-repeat {args.scaling_repeat} --scaling-ranks {args.scaling_ranks}") + \
        (f" --mesh-dir {args.mesh_dir}" if args.mesh_dir else "")
    reused = [case for case, r in _REUSED.items() if r]
    meshes = (f"Meshes and partitions of the ratio rows: {', '.join(reused)} read from `{args.mesh_dir}` "
              "(made by an earlier run, e.g. on the other DOLFINx version: same mesh, same partition), "
              "the others made here and kept there." if args.mesh_dir and reused else
              "Meshes made by gmsh and partitioned by DOLFINx's partitioner in this run.")
    L = [
        f"# A jointed analysis at the cost of an intact linear solve (DOLFINx {stack_versions()}, 3D)",
        "",
        f"Produced by `bench/bench_fem.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{platform.machine()}, {os.cpu_count()} CPUs; whole run {wall:.0f} s. Machine load average "
        f"(1, 5, 15 min) at the start {', '.join(f'{x:.2f}' for x in load_start)} and at the end "
        f"{', '.join(f'{x:.2f}' for x in load_end)}: the machine was shared with other jobs, so wall "
        "times are inflated and noisy; intact and jointed alternate in the same process, so their "
        "ratio is less affected than the times.",
        "",
        f"Reproduce: `{cmd}` (workers run under `mpirun -n k --bind-to core`). {meshes}",
        "",
        "Definitions (module docstring of the script): *jointed* = `JointedRockModel.solve()` wall "
        "time (all Newton iterations: joint residuals and Jacobians, linear solves with their GAMG "
        "set-ups); *intact LS* = one linear solve of the intact model on the same mesh (glued "
        "nodes), same solver, same tolerance (relative true residual 1e-10, the jointed model's "
        "final accuracy), set-up included; min over runs; *ratio* = min jointed / min intact LS "
        "(median of the per-run ratios in brackets). *interface* = joint residual + Jacobian "
        "assembly (incl. the K → J copy) of the whole jointed solve. Solver: CG + GAMG (plain "
        "aggregation, per-block rigid-body near-nullspace), preconditioner lagged across Newton "
        "iterations, Eisenstat-Walker forcing; Newton rtol 1e-10, one load step. *CPU* = "
        "process time (time.process_time, max over ranks) of the same quantities: on a shared, "
        "loaded machine wall time also counts the time other jobs held the core, CPU time does "
        "not, so the CPU ratio is the headline whenever the load average exceeds the cores (on 2 "
        "ranks, MPI waits busy-poll and count as CPU).",
        "",
        "## Jointed analysis / one intact linear solve (target <= 2)",
        "",
        "| case | ranks | dofs (jointed / intact) | joint pairs | runs | intact LS [s] | jointed [s] | ratio (wall) | "
        "intact LS CPU [s] | jointed CPU [s] | ratio (CPU) | "
        "interface share | Newton its | Krylov its per Newton it (intact) | GAMG set-ups | error vs closed form (jointed / intact) | bulk assembly [s] |",
        "|---|---:|---|---:|---:|---:|---:|---|---:|---:|---|---:|---:|---|---:|---|---:|",
    ]
    for s in ratio_results:
        L.append(f"| {s['case']} | {s['ranks']} | {s['dofs']} / {s['dofs_intact']} | {s['pairs']} | {s['runs']} | "
                 f"{fmt(s['intact_ls'])} | {fmt(s['jointed'])} | {s['ratio']:.2f} ({s['ratio_median']:.2f}) | "
                 f"{fmt(s['intact_ls_cpu'])} | {fmt(s['jointed_cpu'])} | **{s['ratio_cpu']:.2f}** | "
                 f"{100 * s['interface'] / s['jointed']:.0f} % | {s['newton']} | "
                 f"{','.join(map(str, s['krylov_jointed']))} ({','.join(map(str, s['krylov_intact']))}) | "
                 f"{s['setups']} | {s['err_jointed']:.1e} / {s['err_intact']:.1e} | {fmt(s['bulk'])} |")
    by = {(s["case"], s["ranks"]): s for s in ratio_results}
    speed = []
    for case in ("column", "blocky"):
        if (case, 1) in by and (case, 2) in by:
            a, b = by[(case, 1)], by[(case, 2)]
            speed.append(f"{case}: jointed {a['jointed'] / b['jointed']:.2f}x, intact linear solve "
                         f"{a['intact_ls'] / b['intact_ls']:.2f}x")
    if speed:
        L += ["", "2-rank speed-up (1-rank time / 2-rank time): " + "; ".join(speed) + "."]
    variants = [(s, v, r) for s, res in ratio_results_variants(ratio_results) for v, r in res.items()]
    if variants:
        L += ["", "## What each measure buys (column case, 1 rank, one run each, jointed solve)", "",
              "| settings | jointed [s] | jointed CPU [s] | ratio (CPU) to the min intact LS | Newton its | Krylov its | GAMG set-ups |",
              "|---|---:|---:|---:|---:|---|---:|"]
        s0 = by.get(("column", 1))
        if s0:
            L.append(f"| default: lagged PC + Eisenstat-Walker + plain aggregation (min of {s0['runs']}) | "
                     f"{fmt(s0['jointed'])} | {fmt(s0['jointed_cpu'])} | {s0['ratio_cpu']:.2f} | {s0['newton']} | "
                     f"{sum(s0['krylov_jointed'])} | {s0['setups']} |")
        names = {"fixed_forcing": "every Newton step to rtol 1e-10 (no Eisenstat-Walker)",
                 "no_reuse": "GAMG rebuilt every Newton iteration (no lagging)",
                 "smoothed_aggregation": "smoothed aggregation (pc_gamg_agg_nsmooths 1, the old default)"}
        for s, v, r in variants:
            L.append(f"| {names.get(v, v)} | {fmt(r['solve'])} | {fmt(r['solve_cpu'])} | "
                     f"{r['solve_cpu'] / s['intact_ls_cpu']:.2f} | "
                     f"{r['newton_iterations']} | {sum(r['krylov'])} | {r['pc_setups']} |")
    if scaling_results:
        L += ["", f"## Scaling ({scaling_results[0]['ranks']} rank(s), column case, min of the runs)", "",
              "| dofs (jointed) | runs | intact LS [s] | jointed [s] | ratio (wall) | intact LS CPU [s] | jointed CPU [s] "
              "| ratio (CPU) | Newton its | Krylov its (jointed total / intact) "
              "| peak RSS intact [GiB] | peak RSS jointed [GiB] | mesh generation [s] |",
              "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|"]
        for s in scaling_results:
            L.append(f"| {s['dofs']} | {s['runs']} | {fmt(s['intact_ls'])} | {fmt(s['jointed'])} | {s['ratio']:.2f} | "
                     f"{fmt(s['intact_ls_cpu'])} | {fmt(s['jointed_cpu'])} | {s['ratio_cpu']:.2f} | "
                     f"{s['newton']} | {sum(s['krylov_jointed'])} / {sum(s['krylov_intact'])} | "
                     f"{s['rss_intact'] / 2**30:.2f} | {s['rss_jointed'] / 2**30:.2f} | {fmt(s['mesh_generation'])} |")
        L += ["", "Peak RSS: ru_maxrss of one model set-up + solve per rank, summed over ranks (the "
              "process baseline with Python, DOLFINx and both distributed meshes included). "
              "![scaling](fem_scaling.png)"]
    L += ["", "Newton residual norms ||r|| [N] and forcing terms η of the jointed runs (first run):", ""]
    for s in ratio_results:
        L.append(f"- {s['case']}, {s['ranks']} rank(s): " + ", ".join(
            f"{x:.2e}" for x in s["norms"]) + "; η = " + ", ".join(
            "–" if e is None else f"{e:.1e}" for e in s["forcing"]))
    return "\n".join(L) + "\n"


_VARIANTS = {}
_REUSED = {}   # case -> whether its ratio-row mesh came from --mesh-dir


def ratio_results_variants(ratio_results):
    return [(s, _VARIANTS[(s["case"], s["ranks"])]) for s in ratio_results if _VARIANTS.get((s["case"], s["ranks"]))]


def plot(scaling_results, path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d = [s["dofs"] for s in scaling_results]
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.loglog(d, [s["intact_ls"] for s in scaling_results], "o-", label="intact: one linear solve")
    a.loglog(d, [s["jointed"] for s in scaling_results], "s-", label="jointed: whole Newton solve")
    a.loglog(d, [2 * s["intact_ls"] for s in scaling_results], "k:", label="2 × intact (wall)")
    if all("jointed_cpu" in s for s in scaling_results):
        a.loglog(d, [s["intact_ls_cpu"] for s in scaling_results], "o--", color="C0", alpha=0.6,
                 label="intact, CPU time")
        a.loglog(d, [s["jointed_cpu"] for s in scaling_results], "s--", color="C1", alpha=0.6,
                 label="jointed, CPU time")
    a.set_xlabel("dofs")
    a.set_ylabel("time [s] (wall: solid, CPU: dashed)")
    a.legend(fontsize=8)
    a.set_title(f"time, {scaling_results[0]['ranks']} rank(s), min of the runs")
    b.loglog(d, [s["rss_intact"] / 2**30 for s in scaling_results], "o-", label="intact")
    b.loglog(d, [s["rss_jointed"] / 2**30 for s in scaling_results], "s-", label="jointed")
    b.set_xlabel("dofs")
    b.set_ylabel("peak RSS, summed over ranks [GiB]")
    b.legend()
    b.set_title("memory")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=None)
    ap.add_argument("--ratio-size", type=float, default=0.0235, help="mesh size of the ratio rows [m]")
    ap.add_argument("--scaling-sizes", type=float, nargs="*", default=[0.0174, 0.0135],
                    help="further mesh sizes of the scaling table (the ratio size is its first row)")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--scaling-repeat", type=int, default=3, help="runs per size of the scaling table")
    ap.add_argument("--scaling-ranks", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help="~50k dofs, 2 runs, no scaling, no variants")
    ap.add_argument("--no-variants", action="store_true",
                    help="leave out the 'what each measure buys' runs (at 1M dofs the one without "
                         "Eisenstat-Walker alone takes minutes)")
    ap.add_argument("--output", default=os.path.join(HERE, "results", "fem.md"))
    ap.add_argument("--mesh-dir", default=None,
                    help="keep the ratio rows' meshes and partitions here and reuse them: a run on "
                         "the other DOLFINx version then compares on the same mesh and partition")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--case", default="column", help=argparse.SUPPRESS)
    ap.add_argument("--mesh-size", type=float, default=0.0235, help=argparse.SUPPRESS)
    ap.add_argument("--mesh-cache", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--variants", nargs="*", default=[], help=argparse.SUPPRESS)
    ap.add_argument("--json", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        worker(args)
        return
    if args.quick:
        args.ratio_size, args.scaling_sizes, args.repeat = 0.037, [], 2
    env = worker_env(args.build)
    load_start = os.getloadavg()
    t0 = time.perf_counter()
    ratio_results, scaling_results = [], []
    with tempfile.TemporaryDirectory() as tmp:
        mesh_dir = args.mesh_dir or tmp
        os.makedirs(mesh_dir, exist_ok=True)
        for case in ("column", "blocky"):
            cache = os.path.join(mesh_dir, f"{case}_{args.ratio_size}.pkl")
            _REUSED[case] = os.path.exists(cache)
            for n in args.ranks:
                variants = ("fixed_forcing", "no_reuse", "smoothed_aggregation") \
                    if (case == "column" and n == 1 and not (args.quick or args.no_variants)) else ()
                res = launch(env, n, case, args.ratio_size, args.repeat, os.path.join(tmp, "out.json"), cache,
                             variants)
                s = summary(res)
                s["norms"] = res["runs"]["jointed"][0]["residual_norms"][-1]
                s["forcing"] = res["runs"]["jointed"][0]["forcing"][-1]
                _VARIANTS[(case, n)] = res["variants"]
                ratio_results.append(s)
                if case == "column" and n == args.scaling_ranks and args.scaling_sizes:
                    scaling_results.append(s)
        for h in args.scaling_sizes:
            n = args.scaling_ranks
            res = launch(env, n, "column", h, args.scaling_repeat, os.path.join(tmp, "out.json"),
                         os.path.join(tmp, f"column_{h}.pkl"))
            scaling_results.append(summary(res))
            os.remove(os.path.join(tmp, f"column_{h}.pkl"))
    with open(os.path.join(tempfile.gettempdir(), "bench_fem_results.json"), "w") as fh:
        json.dump({"ratio": ratio_results, "scaling": scaling_results, "variants": {
            f"{c}_{n}": v for (c, n), v in _VARIANTS.items()}}, fh)   # raw numbers, if the report fails
    text = report(ratio_results, scaling_results, args, time.perf_counter() - t0, load_start)
    write_report(text, args.output)
    if scaling_results:
        plot(scaling_results, os.path.join(os.path.dirname(args.output), "fem_scaling.png"))


if __name__ == "__main__":
    main()
