#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The largest jointed 3D model this machine solves: memory per dof, time, and a weak-scaling model.

One launch per model (intact, jointed) so that each peak is its own: the column of bench_fem.py
(unit cube, two horizontal Barton-Bandis joints, 5 MPa, closed form u_top) at mesh size H.
1. The mesh is made by gmsh on one process and kept in --mesh-dir (with the partition of each rank
   count, as bench_fem.py keeps them).
2. Each model: `mpirun -n R` distributes the mesh from rank 0, then set-up (K, f, GAMG's
   near-nullspace) and the solve (JointedRockModel.solve, one load step, Newton rtol 1e-10; the
   intact model is one linear solve to the same tolerance). Reported: the resident memory summed
   over ranks after the distribution (the process and the mesh) and its peak during set-up and
   solve (VmHWM, reset before the set-up), their difference per dof (the model's own memory),
   the times (set-up, solve, GAMG set-up, Krylov), the iterations, the error against the closed
   form, and PETSc's message and reduction counts per Krylov iteration and per GAMG set-up
   (PETSc.Log events KSPSolve and PCSetUp, per rank).
3. A weak-scaling projection from those per-rank costs (projection(): an alpha-beta model whose
   assumptions are printed in the report beside its numbers).

Usage (2 ranks, ~4M dofs; about 20 min on the 2-core machine, 11 of them the mesh; ~13 GiB):
  /usr/bin/python3 bench/bench_fem_large.py --mesh-size 0.0083 --ranks 2 --mesh-dir .scratch/fem_4m
A cluster user measures the per-rank costs on the machine to be projected with the same command
(--ranks P, a mesh size giving the dofs per rank of interest) and reads the projection's inputs
from the report; --alpha/--beta/--neighbours set the model's network.
Writes bench/results/fem_large.md.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_fem as bf  # noqa: E402  (the cases, the model, the closed form and the mesh cache)

#: Krylov iterations of one intact linear solve of the column against its dofs, measured by
#: bench_fem.py (bench/results/fem_dolfinx0.5.md, scaling table: 203k 58, 473k 71, 977k 81): the
#: growth exponent of the projection is fitted to these and to this run's own count.
MEASURED_ITERATIONS = ((203250, 58), (472542, 71), (976536, 81))


# ---------------------------------------------------------------------------------------------
# worker (inside mpirun): one model
def _resident() -> int:
    """This process's resident set now [B] (VmRSS)."""
    with open("/proc/self/status") as fh:
        return next(int(line.split()[1]) * 1024 for line in fh if line.startswith("VmRSS"))


def worker(args) -> None:
    import gc
    from mpi4py import MPI
    from petsc4py import PETSc
    comm = MPI.COMM_WORLD
    jm = bf.cached_mesh("column", args.mesh_size, args.mesh_cache)[0] if comm.rank == 0 else None
    corner = comm.bcast(bf.corner_block(jm) if comm.rank == 0 else None)
    source = bf.glued(jm) if (args.label == "intact" and comm.rank == 0) else jm
    t0 = time.perf_counter()
    dmesh = bf.distribute_cached({args.label: source}, comm, args.mesh_cache)[args.label]
    t_distribute = time.perf_counter() - t0
    del jm, source
    gc.collect()
    baseline = comm.allreduce(_resident())
    bf.reset_peak_rss()
    PETSc.Log.begin()
    comm.barrier()
    t1 = time.perf_counter()
    model, law = bf.build_model("column", dmesh, corner, "default")
    comm.barrier()
    t2 = time.perf_counter()
    sol = model.solve(load_steps=1)
    comm.barrier()
    t3 = time.perf_counter()
    peak = bf.peak_rss(comm)
    ranks_max = {k: comm.allreduce(v, op=MPI.MAX) for k, v in model.timings.items()}
    events = {}
    # PETSc does not count the Krylov method's own allreduces in numReductions: they are the
    # calls of VecTDot, VecNorm, VecDot and VecMDot (each one allreduce), counted here
    for name in ("KSPSolve", "PCSetUp", "VecTDot", "VecNorm", "VecDot", "VecMDot"):
        info = PETSc.Log.Event(name).getPerfInfo()
        events[name] = {k: comm.allreduce(float(info[k]), op=MPI.MAX)
                        for k in ("count", "time", "numMessages", "messageLength", "numReductions")}
    out = {
        "label": args.label, "ranks": comm.size, "dofs": model.num_dofs,
        "pairs": comm.allreduce(model.interface.num_pairs), "distribute": t_distribute,
        "setup": t2 - t1, "solve": t3 - t2, "baseline_rss": baseline, "peak_rss": peak,
        "krylov": list(model.linear_solver.iterations), "newton": sol.newton_iterations,
        "pc_setups": model.linear_solver.setups, "interface": ranks_max["interface_residual"]
        + ranks_max["interface_jacobian"] + ranks_max["matrix_copy"],
        "error": bf.closed_form_error("column", args.label, model, sol, law), "events": events,
    }
    if comm.rank == 0:
        with open(args.json, "w") as fh:
            json.dump(out, fh)


# ---------------------------------------------------------------------------------------------
# the weak-scaling model
def reductions_per_iteration(run: dict) -> float:
    """Allreduces per Krylov iteration: the calls of the reducing vector operations of the whole
    solve (the Newton's own norms included: a slight overestimate) / the Krylov iterations."""
    ev = run["events"]
    return sum(ev[k]["count"] for k in ("VecTDot", "VecNorm", "VecDot", "VecMDot")) / sum(run["krylov"])


def projection(run: dict, intact: dict, ranks: list, alpha: float, beta: float, neighbours: int,
               reduction_alpha: float) -> list:
    """Projected solve time of the jointed model with run's dofs per rank on P ranks (weak scaling).

    Per Krylov iteration, per rank (from the run on R ranks): compute t_it = KSPSolve time / its
    (the halo exchange between R ranks on one machine included), messages m, bytes b and
    reductions r. On P > R ranks a subdomain of a 3D partition talks to `neighbours` others
    instead of R - 1, and messages and bytes are both scaled by neighbours / (R - 1) (for the
    bytes an upper bound: a cube-like subdomain of the same volume has about 3.8 times the face
    area of a half cube's cut, and edge and corner neighbours share little). Each message costs
    alpha, each byte 1/beta, each reduction reduction_alpha · log2 P (a tree allreduce). The GAMG
    set-up is projected the same way from its own counts. The Krylov iterations grow with the
    global dofs N = P n as its(N) = its_run (N / N_run)^γ, γ fitted to the intact counts
    (MEASURED_ITERATIONS and the run's intact count). The joints' residuals and Jacobians are
    local (perfect weak scaling). Returns (rows, γ); the first row with P = R is the run itself
    as the model sees it, the denominator of the efficiency."""
    R = run["ranks"]
    ksp, pcs = run["events"]["KSPSolve"], run["events"]["PCSetUp"]
    its = sum(run["krylov"])
    t_it = ksp["time"] / its
    m_it, b_it = ksp["numMessages"] / its, ksp["messageLength"] / its
    r_it = reductions_per_iteration(run)
    points = list(MEASURED_ITERATIONS) + [(intact["dofs"], sum(intact["krylov"]))]
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(k) for _, k in points]
    xm, ym = sum(xs) / len(xs), sum(ys) / len(ys)
    gamma = sum((x - xm) * (y - ym) for x, y in zip(xs, ys)) / sum((x - xm) ** 2 for x in xs)
    rows = []
    for P in sorted(set([R] + [P for P in ranks if P > R])):
        scale = 1.0 if P == R else neighbours / max(R - 1, 1)
        N = run["dofs"] / R * P
        its_P = its * (N / run["dofs"]) ** gamma
        comm_it = scale * (m_it * alpha + b_it / beta) + r_it * reduction_alpha * math.log2(P)
        setup = pcs["time"] + scale * (pcs["numMessages"] * alpha + pcs["messageLength"] / beta) \
            + pcs["numReductions"] * reduction_alpha * math.log2(P)
        total = setup + its_P * (t_it + comm_it) + run["interface"]
        rows.append({"ranks": P, "dofs": N, "its": its_P, "t_it": t_it, "comm_it": comm_it, "setup": setup,
                     "total": total})
    for r in rows:
        r["efficiency"] = rows[0]["total"] / r["total"]
        r["efficiency_it"] = (rows[0]["t_it"] + rows[0]["comm_it"]) / (r["t_it"] + r["comm_it"])
    return rows, gamma


# ---------------------------------------------------------------------------------------------
# driver
def launch(env, ranks, label, h, cache, out) -> dict:
    cmd = ["mpirun", "-n", str(ranks), "--bind-to", "core", "/usr/bin/python3", os.path.abspath(__file__),
           "--worker", "--label", label, "--mesh-size", str(h), "--mesh-cache", cache, "--json", out]
    print(f"== {' '.join(cmd)}", flush=True)
    subprocess.run(cmd, check=True, env=env)
    with open(out) as fh:
        return json.load(fh)


def report(res: dict, proj: list, gamma: float, args, wall: float, t_mesh: float, load, cache: str) -> str:
    GiB = 2.0**30
    i, j = res["intact"], res["jointed"]
    cmd = (f"/usr/bin/python3 bench/bench_fem_large.py --mesh-size {args.mesh_size} --ranks {args.ranks}"
           + (f" --mesh-dir {args.mesh_dir}" if args.mesh_dir else ""))
    L = [f"# The largest jointed model on this machine (DOLFINx {bf.stack_versions()}, 3D column)", "",
         f"Produced by `bench/bench_fem_large.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
         f"{os.cpu_count()} CPUs, {os.sysconf('SC_PAGE_SIZE') * os.sysconf('SC_PHYS_PAGES') / GiB:.1f} GiB; "
         f"whole run {wall:.0f} s; load average at the start {load[0]:.2f}, at the end {load[1]:.2f}.", "",
         f"Reproduce: `{cmd}` (each model its own `mpirun -n {args.ranks} --bind-to core` launch; "
         f"the mesh made by gmsh in one process in {t_mesh:.0f} s, kept in the mesh directory).", "",
         "Memory: resident set summed over ranks; *baseline* = after the distribution (Python, "
         "DOLFINx, PETSc and the distributed mesh), *peak* = VmHWM of set-up + solve (reset after "
         "the distribution), *model* = peak - baseline (matrices, GAMG hierarchy, vectors, the joint "
         "state). Times: wall, max over ranks; *GAMG set-up* and *Krylov* are PETSc's PCSetUp and "
         "KSPSolve events (all Newton iterations), *joints* the joints' residuals and Jacobians with "
         "the K → J copies.", "",
         "| model | ranks | dofs | joint pairs | baseline [GiB] | peak [GiB] | model [GiB] | model per dof [kB] "
         "| peak per dof [kB] | set-up [s] | solve [s] | of it GAMG set-up [s] | Krylov [s] | joints [s] | Newton its "
         "| Krylov its | GAMG set-ups | error vs closed form |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|"]
    for r in (i, j):
        model = r["peak_rss"] - r["baseline_rss"]
        L.append(f"| {r['label']} | {r['ranks']} | {r['dofs']} | {r['pairs']} | {r['baseline_rss'] / GiB:.2f} | "
                 f"{r['peak_rss'] / GiB:.2f} | {model / GiB:.2f} | {model / r['dofs'] / 1e3:.2f} | "
                 f"{r['peak_rss'] / r['dofs'] / 1e3:.2f} | {r['setup']:.1f} | {r['solve']:.1f} | "
                 f"{r['events']['PCSetUp']['time']:.1f} | {r['events']['KSPSolve']['time']:.1f} | {r['interface']:.2f} | "
                 f"{r['newton']} | {','.join(map(str, r['krylov']))} | "
                 f"{r['pc_setups']} | {r['error']:.1e} |")
    mi, mj = i["peak_rss"] - i["baseline_rss"], j["peak_rss"] - j["baseline_rss"]
    L += ["", f"Jointed / intact: model memory per dof {mj / j['dofs'] / (mi / i['dofs']):.2f}, peak per dof "
          f"{j['peak_rss'] / j['dofs'] / (i['peak_rss'] / i['dofs']):.2f}, time (jointed solve / intact "
          f"linear solve) {j['solve'] / i['solve']:.2f}.", ""]
    ksp = j["events"]["KSPSolve"]
    its = sum(j["krylov"])
    L += ["## Weak-scaling projection of the jointed model (a model, not a measurement)", "",
          f"Inputs measured in this run, per rank of the jointed model ({j['dofs'] // j['ranks']} dofs per rank): "
          f"one Krylov iteration {ksp['time'] / its * 1e3:.1f} ms, {ksp['numMessages'] / its:.1f} messages, "
          f"{ksp['messageLength'] / its / 1e3:.1f} kB, {reductions_per_iteration(j):.1f} reductions; one GAMG "
          f"set-up {j['events']['PCSetUp']['time']:.1f} s, {j['events']['PCSetUp']['numMessages']:.0f} messages, "
          f"{j['events']['PCSetUp']['messageLength'] / 1e6:.1f} MB, {j['events']['PCSetUp']['numReductions']:.0f} "
          f"reductions; the joints' residuals and Jacobians {j['interface']:.1f} s.", "",
          f"Assumptions (bench_fem_large.projection): every rank keeps {j['dofs'] // j['ranks']} dofs and its "
          f"compute time per iteration (the same cores, memory bandwidth per core as here); a rank of a 3D "
          f"partition exchanges with {args.neighbours} neighbours (messages and bytes scaled from the "
          f"{j['ranks'] - 1} neighbour(s) here); latency alpha = {args.alpha * 1e6:.1f} µs per message, bandwidth "
          f"beta = {args.beta / 1e9:.1f} GB/s per rank, a reduction {args.reduction_alpha * 1e6:.1f} µs × log2 P; "
          f"Krylov iterations grow as N^{gamma:.2f} (fitted to the intact counts of bench_fem.py's scaling table "
          f"and this run); the Newton iterations stay {j['newton']}; GAMG's coarse levels cost what they cost "
          f"here per iteration (PETSc gathers them on fewer ranks; not modelled). Not modelled: the mesh "
          f"input, which rockjoint reads on rank 0 and distributes (distribute()): rank 0 holds the whole "
          f"JointedMesh, so the global size is capped by one node's memory (the mesh cache here: "
          f"{os.path.getsize(cache) / j['dofs'] * 1e6 / 2**20:.0f} MiB per million dofs).", "",
          "| ranks | dofs | Krylov its | compute per it [ms] | communication per it [ms] | GAMG set-up [s] "
          "| solve [s] | weak-scaling efficiency | of it per Krylov iteration |",
          "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in proj:
        L.append(f"| {r['ranks']} | {r['dofs']:.3g} | {r['its']:.0f} | {r['t_it'] * 1e3:.1f} | "
                 f"{r['comm_it'] * 1e3:.2f} | {r['setup']:.1f} | {r['total']:.1f} | {r['efficiency']:.2f} | "
                 f"{r['efficiency_it']:.2f} |")
    return "\n".join(L) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh-size", type=float, default=0.0083, help="column mesh size [m] (0.0083: ~4M dofs)")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--mesh-dir", default=None, help="keep the mesh (and its partition) here")
    ap.add_argument("--build", default=None)
    ap.add_argument("--alpha", type=float, default=2e-6, help="network latency per message [s]")
    ap.add_argument("--beta", type=float, default=10e9, help="network bandwidth per rank [B/s]")
    ap.add_argument("--reduction-alpha", type=float, default=2e-6, help="cost of one allreduce stage [s]")
    ap.add_argument("--neighbours", type=int, default=13, help="neighbours of a rank in a 3D partition")
    ap.add_argument("--project", type=int, nargs="+", default=[64, 128, 256, 512, 1024])
    ap.add_argument("--output", default=os.path.join(HERE, "results", "fem_large.md"))
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--label", default="jointed", help=argparse.SUPPRESS)
    ap.add_argument("--mesh-cache", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--json", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        worker(args)
        return
    env = bf.worker_env(args.build)
    load0, t0 = os.getloadavg()[0], time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        mesh_dir = args.mesh_dir or tmp
        os.makedirs(mesh_dir, exist_ok=True)
        cache = os.path.join(mesh_dir, f"column_{args.mesh_size}.pkl")
        print(f"== mesh (gmsh, one process) into {cache}", flush=True)
        t_mesh = bf.cached_mesh("column", args.mesh_size, cache)[1]
        res = {label: launch(env, args.ranks, label, args.mesh_size, cache, os.path.join(tmp, f"{label}.json"))
               for label in ("intact", "jointed")}
        proj, gamma = projection(res["jointed"], res["intact"], args.project, args.alpha, args.beta,
                                 args.neighbours, args.reduction_alpha)
        text = report(res, proj, gamma, args, time.perf_counter() - t0, t_mesh, (load0, os.getloadavg()[0]), cache)
    bf.write_report(text, args.output)


if __name__ == "__main__":
    main()
