#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Where the time of a slipping-joint analysis goes: the continuum bench's discrete tunnel, and the
tunnel and blocky demos, split by phase.

Cases:
  discrete tunnel  bench/bench_continuum.py's discrete model at s = 0.25 m (40 m x 40 m section,
                   a = 4 m, bedding every 0.25 m and a cross set dipping 60° every 0.5 m, all
                   slipping, Coulomb φ = 30°; far-field element 1.5 m): in situ, then excavation in
                   5 load steps. Beside it, in the same run, the intact model on the same
                   triangles (tunnel_section(..., intact=True): one block, the joint traces kept as
                   mesh lines): its linear solves are the yardstick of the Newton iterations.
  demos            demos/demo_tunnel.py and demos/demo_blocky_rock_mass.py at their default sizes
                   (every model each demo solves, summed).
Phases (CPU seconds of this process, and wall seconds): geometry (the 2D section's crossings and
outline split, gmsh's synchronize and embedding; OCC cut, fragment, synchronize where used), gmsh mesh generation, node splitting (meshes.build_jointed_mesh), the rest of
tunnel_section / jointed_block (entity queries, element extraction), distribution (DOLFINx mesh,
joint pairing), table building (rockjoint.tabulate), model set-up (forms, the joint coupling, the
linear solver), bulk assembly, joint residual, Jacobian (bulk copy + joint tangent), linear solves
(with PETSc's own event log: symbolic and numeric factorisations, triangular solves, Krylov
iterations), and the Python overhead of Newton (its time minus residual, Jacobian and solves).
Load-step cuts are the failed load steps the adaptive stepping halved.
Linear solver of the discrete tunnel: the same analysis (meshing left out) at s = 1, 0.5 and
0.25 m with the direct solver (a MUMPS LU every Newton iteration) and the lagged one (an LU kept
as FGMRES's preconditioner while it serves), the evidence for linear_solver.LAGGED_DOF_RANGE,
LAGGED_REBUILD_FACTOR and the lagged solver's FGMRES.

Usage:  bash scripts/run.sh python3 bench/bench_tunnel_profile.py [--repeat N] [--no-demos] [--no-solvers]
Writes bench/results/tunnel_profile.md (and prints it).
"""
from __future__ import annotations

import argparse
import contextlib
import logging
import os
import sys
import tempfile
import time
from collections import defaultdict

import numpy as np
from petsc4py import PETSc

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "demos"))

import bench_continuum as bc  # noqa: E402
import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import InSituStress, JointedRockModel, distribute  # noqa: E402
from rockjoint.fem.output.probe import probe  # noqa: E402

#: Before issue 31 (main at dbd35c6: joint pieces inside the opening removed after the fragment,
#: GMRES + GAMG for the 90k-dof slip Jacobian), measured with this bench on 2026-11-27 03:37 UTC
#: (one run, load average 5.9): phase -> (wall, CPU) [s]; CPU None where not timed
BEFORE = {"geometry (OCC cut, fragment, synchronize, remove)": (21.98, 17.00),
          "gmsh mesh generation": (11.12, 5.54), "rest of meshing": (4.99, 2.58),
          "distribution": (1.37, 0.68), "linear solves (31, GMRES + GAMG, 1180 Krylov iterations)": (64.67, None),
          "Jacobian + residual + Newton overhead": (1.83, None), "total (set-up + solve)": (106.99, 60.74)}
BEFORE_ANSWER = (24.6708, 17.0147, 31)   # crown, sidewall [mm], Newton iterations (main, same day)

#: the geometry phase: the 2D section's crossings and outline (meshes.planar_section) and the
#: built-in kernel's synchronize and embedding; OCC's cut, fragment and synchronize (3D, and
#: the OCC builders of the demos' blocks)
GEOMETRY = "geometry (crossings, outline, synchronize; OCC booleans)"

#: PETSc events of the linear solves (their time is inside the model's linear_solve timing)
EVENTS = ("MatLUFactorSym", "MatLUFactorNum", "MatCholFctrSym", "MatCholFctrNum", "MatSolve", "KSPSolve",
          "KSPGMRESOrthog", "MatMult")


class Phases:
    """CPU and wall seconds per phase, from timers wrapped around library calls while active."""

    def __init__(self):
        self.cpu, self.wall, self.calls = defaultdict(float), defaultdict(float), defaultdict(int)
        self.models = []   # every JointedRockModel made while active
        self._depth = defaultdict(int)

    def _timed(self, f, label):
        def timed(*args, **kwargs):
            self._depth[label] += 1
            c, w = time.process_time(), time.perf_counter()
            try:
                return f(*args, **kwargs)
            finally:
                self._depth[label] -= 1
                if self._depth[label] == 0:   # recursion (e.g. a wrapper calling itself) counted once
                    self.cpu[label] += time.process_time() - c
                    self.wall[label] += time.perf_counter() - w
                    self.calls[label] += 1
        return timed

    @contextlib.contextmanager
    def active(self):
        import gmsh
        from rockjoint.meshes import builders
        from rockjoint.fem.mechanics import model as model_module
        from rockjoint.meshes import planar_section
        targets = [(gmsh.model.occ, n, "geometry") for n in ("cut", "fragment", "synchronize", "remove")]
        targets += [(gmsh.model.geo, "synchronize", "geometry"), (gmsh.model.mesh, "embed", "geometry"),
                    (planar_section, "arrange", "geometry"), (planar_section, "split_outline", "geometry")]
        targets += [(gmsh.model.mesh, "generate", "gmsh generate"),
                    (builders, "build_jointed_mesh", "node splitting"),
                    (meshes, "tunnel_section", "meshing total"), (meshes, "jointed_block", "meshing total"),
                    (rockjoint, "tabulate", "table building")]
        for module in (bc, sys.modules.get("demo_tunnel"), sys.modules.get("demo_blocky_rock_mass")):
            if module is not None:
                for name, label in (("distribute", "distribution"), ("tabulate", "table building")):
                    if hasattr(module, name):
                        targets.append((module, name, label))
        saved = [(obj, name, getattr(obj, name)) for obj, name, _ in targets]
        for obj, name, label in targets:
            setattr(obj, name, self._timed(getattr(obj, name), label))
        init = model_module.JointedRockModel.__init__

        def register(model, *args, **kwargs):
            init(model, *args, **kwargs)
            self.models.append(model)
        model_module.JointedRockModel.__init__ = register
        try:
            yield self
        finally:
            model_module.JointedRockModel.__init__ = init
            for obj, name, f in saved:
                setattr(obj, name, f)

    def model_split(self):
        """{phase: wall seconds} summed over the models made while active, and the counts."""
        t, n = defaultdict(float), defaultdict(int)
        for m in self.models:
            for k, v in m.timings.items():
                t[k] += v
            for k, v in m.counts.items():
                n[k] += v
            reports = [r for s in m.stages for r in s.reports]
            n["newton_iterations"] += sum(r.iterations for r in reports)
            n["load_step_cuts"] += sum(not r.converged for r in reports)
            n["krylov"] += sum(i for r in reports for i in r.linear_iterations if i is not None)
        return t, n


def petsc_events():
    """{event: (count, seconds)} of PETSc's log so far."""
    return {e: (int(p["count"]), float(p["time"])) for e in EVENTS
            for p in [PETSc.Log.Event(e).getPerfInfo()]}


def tunnel_model(dmesh, **options):
    """bench_continuum's tunnel model (discrete joints, or none on an intact mesh), in situ applied;
    options: more JointedRockModel arguments (linear_solver, petsc_options)."""
    model = bc.jointed_model(dmesh, None, **options)
    for side, component in (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y")):
        model.fix(side, component)
    model.set_in_situ_stress(InSituStress.uniform([[-bc.K0 * bc.SIGMA_V, 0.0], [0.0, -bc.SIGMA_V]]))
    return model


def discrete_tunnel(spacing=bc.SPACING, mesh_size=1.5, **options):
    """Set-up + solve of the discrete tunnel with the phase split, and the intact model on the
    same triangles solved in the same run. Returns a dict of the numbers."""
    comm = bc.COMM
    joints = bc.discrete_sets(spacing, ("bedding", "cross"))
    opening = meshes.CircularOpening(bc.CENTRE, bc.RADIUS)
    sizes = dict(mesh_size=mesh_size, opening_mesh_size=mesh_size / 4, opening_refine_distance=2 * bc.RADIUS)
    phases = Phases()
    before = petsc_events()
    c0, w0 = time.process_time(), time.perf_counter()
    with phases.active():
        jm = meshes.tunnel_section(bc.WIDTH, bc.WIDTH, opening, joints, comm=comm, **sizes)
        model = tunnel_model(bc.distribute(jm, comm), **options)
        model.solve(name="in-situ")
        model.excavate(meshes.OPENING, fraction_left=bc.SUPPORT)
        t_exc = time.perf_counter()
        res = model.solve(load_steps=5, name="excavation")
        exc_wall = time.perf_counter() - t_exc
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    after = petsc_events()
    events = {e: (after[e][0] - before[e][0], after[e][1] - before[e][1]) for e in EVENTS}
    h = mesh_size / 4
    r = bc.RADIUS + h * h / (4 * bc.RADIUS)
    u = probe(model.u, np.array([[bc.CENTRE[0], bc.CENTRE[1] + r], [bc.CENTRE[0] + r, bc.CENTRE[1]]]))
    # The yardstick: one linear solve of the intact model on the same triangles (Cholesky of K).
    intact = tunnel_model(distribute(meshes.tunnel_section(bc.WIDTH, bc.WIDTH, opening, joints, intact=True,
                                                           comm=comm, **sizes), comm))
    # Each of its linear solves timed: the first is one intact linear solve as a user's intact
    # analysis pays it (MUMPS's analysis, factorisation, triangular solves: bench_fem.py's "intact
    # LS, set-up included"); the later ones reuse the analysis (factorisation and solves only).
    solve_times = []
    solver = intact.prepare().linear_solver
    def timed_solve(*args, _solve=solver.solve, **kwargs):
        t0 = time.perf_counter()
        try:
            return _solve(*args, **kwargs)
        finally:
            solve_times.append(time.perf_counter() - t0)
    solver.solve = timed_solve
    intact.solve(name="in-situ")
    intact.excavate(meshes.OPENING, fraction_left=bc.SUPPORT)
    intact.solve(load_steps=5, name="excavation")
    if len(solve_times) < 2:
        raise RuntimeError(f"intact tunnel: {len(solve_times)} linear solve(s), expected more than 1")
    return dict(kind=model.linear_solver.kind, factor_entries=(factor_entries(model), factor_entries(intact)),crown=-u[0, 1], sidewall=-u[1, 0], cpu=cpu, wall=wall, phases=phases, events=events,
                cells=comm.allreduce(model.mesh.topology.index_map(2).size_local), dofs=model.num_dofs,
                excavation_wall=exc_wall, excavation_iterations=res.newton_iterations,
                newton_iterations=sum(s.newton_iterations for s in model.stages),
                intact_fresh=solve_times[0], intact_solve=float(np.mean(solve_times[1:])),
                intact_solves=len(solve_times) - 1,
                intact_dofs=intact.num_dofs)


def factor_entries(model):
    """Entries in the model's last LU / Cholesky factors (MUMPS INFOG(29)), None if iterative."""
    solver = model.linear_solver
    return None if solver.kind == "iterative" else solver.ksp.getPC().getFactorMatrix().getMumpsInfog(29)


def solver_comparison(spacings=(1.0, 0.5, 0.25), mesh_size=1.5):
    """Rows (spacing, dofs, solver, LU factorisations, triangular solves, Newton iterations,
    linear solves [s], set-up + solve [s], crown, sidewall [m]) of the discrete tunnel solved with
    each linear solver on one mesh per spacing (meshing not timed)."""
    from rockjoint.fem.solvers.linear_solver import LAGGED_REBUILD_FACTOR
    comm = bc.COMM
    opening = meshes.CircularOpening(bc.CENTRE, bc.RADIUS)
    sizes = dict(mesh_size=mesh_size, opening_mesh_size=mesh_size / 4, opening_refine_distance=2 * bc.RADIUS)
    h = mesh_size / 4
    r = bc.RADIUS + h * h / (4 * bc.RADIUS)
    points = np.array([[bc.CENTRE[0], bc.CENTRE[1] + r], [bc.CENTRE[0] + r, bc.CENTRE[1]]])
    rows = []
    for spacing in spacings:
        jm = meshes.tunnel_section(bc.WIDTH, bc.WIDTH, opening, bc.discrete_sets(spacing, ("bedding", "cross")),
                                   comm=comm, **sizes)
        variants = [("direct", "direct", None, None), ("lagged", "lagged", None, None)]
        if spacing == min(spacings):
            variants.append((f"lagged, rebuild_factor 2 (not {LAGGED_REBUILD_FACTOR:g})", "lagged", 2.0, None))
            # MUMPS's approximate minimum fill ordering instead of its automatic choice: the same
            # factors here (13.8M against 14.0M entries on the matrix alone), a shorter analysis
            # on that matrix alone (0.08 against 0.4 s), no gain inside the analysis (this row)
            # right-preconditioned GMRES instead of FGMRES: one more triangular solve per linear solve
            variants.append(("lagged, GMRES (not FGMRES)", "lagged", None, {"ksp_type": "gmres"}))
            variants.append(("lagged, MUMPS ordering AMF (ICNTL(7) = 2, not MUMPS's choice)", "lagged", None,
                             {"mat_mumps_icntl_7": 2}))
        for label, kind, rebuild, options in variants:
            before = petsc_events()
            t0 = time.perf_counter()
            model = tunnel_model(distribute(jm, comm), linear_solver=kind,
                                 **({} if options is None else {"petsc_options": options}))
            if rebuild is not None:
                model.prepare()
                model.linear_solver.rebuild_factor = rebuild
            model.solve(name="in-situ")
            model.excavate(meshes.OPENING, fraction_left=bc.SUPPORT)
            model.solve(load_steps=5, name="excavation")
            wall = time.perf_counter() - t0
            after = petsc_events()
            u = probe(model.u, points)
            rows.append((spacing, model.num_dofs, label, after["MatLUFactorNum"][0] - before["MatLUFactorNum"][0],
                         after["MatLUFactorSym"][1] - before["MatLUFactorSym"][1],
                         after["MatSolve"][0] - before["MatSolve"][0],
                         sum(s.newton_iterations for s in model.stages), model.timings["linear_solve"], wall,
                         -u[0, 1], -u[1, 0]))
            print(f"solvers: s = {spacing} m, {label}: {wall:.2f} s", flush=True)
    return rows


def run_demo(module_name, argv):
    """Run a demo's main() with the phase timers; returns (Phases, cpu, wall)."""
    import importlib
    demo = importlib.import_module(module_name)
    phases = Phases()
    saved = sys.argv
    sys.argv = [module_name + ".py"] + argv
    c0, w0 = time.process_time(), time.perf_counter()
    try:
        with phases.active():
            demo.main()
    finally:
        sys.argv = saved
    return phases, time.process_time() - c0, time.perf_counter() - w0


def split_rows(phases, cpu, wall):
    """Markdown rows of the phase split (wall seconds; CPU seconds where this process timed them)."""
    t, n = phases.model_split()
    mesh_total = phases.wall["meshing total"]
    inner = sum(phases.wall[k] for k in ("geometry", "gmsh generate", "node splitting"))
    newton_parts = t["interface_residual"] + t["interface_jacobian"] + t["matrix_copy"] + t["linear_solve"]
    its = max(n["newton_iterations"], 1)
    rows = [(GEOMETRY, phases.wall["geometry"], phases.cpu["geometry"],
             phases.calls["geometry"]),
            ("gmsh mesh generation", phases.wall["gmsh generate"], phases.cpu["gmsh generate"],
             phases.calls["gmsh generate"]),
            ("node splitting", phases.wall["node splitting"], phases.cpu["node splitting"],
             phases.calls["node splitting"]),
            ("rest of meshing (entity queries, elements)", mesh_total - inner,
             phases.cpu["meshing total"] - sum(phases.cpu[k] for k in ("geometry", "gmsh generate",
                                                                       "node splitting")), ""),
            ("distribution (DOLFINx mesh, joint pairs)", phases.wall["distribution"], phases.cpu["distribution"],
             phases.calls["distribution"]),
            ("table building (rockjoint.tabulate)", phases.wall["table building"], phases.cpu["table building"],
             phases.calls["table building"]),
            ("model set-up (forms, coupling, solver)", t["setup"], None, len(phases.models)),
            ("bulk assembly", t["bulk_assembly"], None, ""),
            ("joint residual", t["interface_residual"], None, n["interface_residual"]),
            ("Jacobian (bulk copy + joint tangent)", t["interface_jacobian"] + t["matrix_copy"], None,
             n["interface_jacobian"]),
            ("linear solves", t["linear_solve"], None, n["linear_solve"]),
            ("Newton's Python overhead", t["newton"] - newton_parts, None,
             f"{1e3 * (t['newton'] - newton_parts) / its:.1f} ms/iteration"),
            ("total (set-up + solve)", wall, cpu, "")]
    lines = ["| phase | wall [s] | CPU [s] | calls / note |", "|---|---|---|---|"]
    for name, w, c, k in rows:
        lines.append(f"| {name} | {w:.2f} | {'' if c is None else f'{c:.2f}'} | {k} |")
    lines.append(f"\nNewton iterations {n['newton_iterations']}, load-step cuts {n['load_step_cuts']}, "
                 f"Krylov iterations {n['krylov']}, non-finite residuals {n['nonfinite_residuals']}.")
    return "\n".join(lines)


def events_rows(events):
    lines = ["| PETSc event | count | seconds |", "|---|---|---|"]
    for e, (count, seconds) in events.items():
        if count:
            lines.append(f"| {e} | {count} | {seconds:.2f} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of the discrete tunnel (the minimum is kept)")
    parser.add_argument("--no-demos", action="store_true")
    parser.add_argument("--no-solvers", action="store_true", help="leave out the linear solver comparison")
    args = parser.parse_args()
    logging.basicConfig(level=logging.WARNING)
    PETSc.Log.begin()
    runs = []
    for k in range(args.repeat):
        out = discrete_tunnel()
        runs.append(out)
        print(f"discrete tunnel run {k + 1}: {out['wall']:.2f} s wall, {out['cpu']:.2f} s CPU, crown "
              f"{out['crown'] * 1e3:.4f} mm, sidewall {out['sidewall'] * 1e3:.4f} mm, "
              f"{out['newton_iterations']} Newton iterations", flush=True)
    best = min(runs, key=lambda r: r["wall"])
    per_iteration = best["excavation_wall"] / best["excavation_iterations"]
    load = os.getloadavg()
    text = ["# Where the time of a slipping-joint analysis goes\n", __doc__.split("Usage:")[0],
            f"Reproduce: `bash scripts/run.sh python3 bench/bench_tunnel_profile.py --repeat {args.repeat}`. "
            f"Produced {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, 1 rank, {os.cpu_count()} CPUs "
            f"shared with other jobs: load average {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} (1/5/15 min) at "
            "the end. Wall times are inflated by that load; CPU times are this process's own.\n",
            f"## Discrete tunnel (s = {bc.SPACING} m): {best['cells']} cells, {best['dofs']} dofs\n",
            f"Runs (wall / CPU [s]): " + ", ".join(f"{r['wall']:.2f} / {r['cpu']:.2f}" for r in runs)
            + f"; the fastest is split below. Crown {best['crown'] * 1e3:.4f} mm, sidewall "
            f"{best['sidewall'] * 1e3:.4f} mm, {best['newton_iterations']} Newton iterations.\n",
            split_rows(best["phases"], best["cpu"], best["wall"]), "", events_rows(best["events"]), "",
            f"Newton iteration against one intact linear solve on the same triangles (same run): the "
            f"excavation's {best['excavation_iterations']} iterations took {best['excavation_wall']:.2f} s, "
            f"{per_iteration:.3f} s each. The intact model ({best['intact_dofs']} dofs, MUMPS Cholesky): "
            f"one linear solve with its set-up (its first: analysis, factorisation, triangular solves; "
            f"what an intact analysis costs, and bench_fem.py's yardstick) {best['intact_fresh']:.3f} s, "
            f"ratio **{per_iteration / best['intact_fresh']:.2f}**; a later one reusing the analysis "
            f"(factorisation and triangular solves, mean of {best['intact_solves']}) "
            f"{best['intact_solve']:.3f} s, ratio **{per_iteration / best['intact_solve']:.2f}**. Entries "
            f"in the factors (MUMPS INFOG(29)): jointed {best['factor_entries'][0]}, intact "
            f"{best['factor_entries'][1]}.\n"]
    t, n = best["phases"].model_split()
    after = {"geometry (OCC cut, fragment, synchronize, remove)": "geometry",
             "gmsh mesh generation": "gmsh generate"}
    rows = ["| phase | before: wall / CPU [s] | after: wall / CPU [s] |", "|---|---|---|"]
    ph = best["phases"]
    rest = (ph.wall["meshing total"] - ph.wall["geometry"] - ph.wall["gmsh generate"],
            ph.cpu["meshing total"] - ph.cpu["geometry"] - ph.cpu["gmsh generate"])
    now = [(ph.wall[after[k]], ph.cpu[after[k]]) for k in after] + \
          [rest, (ph.wall["distribution"], ph.cpu["distribution"]), (t["linear_solve"], None),
           (t["newton"] - t["linear_solve"], None), (best["wall"], best["cpu"])]
    def fmt(w, c):
        return f"{w:.2f} / {'-' if c is None else f'{c:.2f}'}"
    for (name, before), now_ in zip(BEFORE.items(), now):
        rows.append(f"| {name} | {fmt(*before)} | {fmt(*now_)} |")
    text += ["### Before and after issue 31\n",
             f"Before: main at dbd35c6 through this bench (one run, load average 5.9), crown "
             f"{BEFORE_ANSWER[0]:.4f} mm, sidewall {BEFORE_ANSWER[1]:.4f} mm, {BEFORE_ANSWER[2]} Newton iterations "
             f"(bench/results/continuum.md, 2026-11-26: 64.71 s on a quieter machine). After: the fastest run above, "
             f"{n['linear_solve']} linear solves ({best['kind']}: {best['events']['MatLUFactorNum'][0]} MUMPS LU "
             f"factorisations); crown {100 * (best['crown'] * 1e3 / BEFORE_ANSWER[0] - 1):+.3f} %, "
             f"sidewall {100 * (best['sidewall'] * 1e3 / BEFORE_ANSWER[1] - 1):+.3f} % against before.\n",
             "\n".join(rows), ""]
    if not args.no_solvers:
        table = ["| s [m] | dofs | linear solver | LU factorisations | LU analyses [s] | triangular solves | "
                 "Newton iterations | linear solves [s] | set-up + solve [s] | crown [mm] | sidewall [mm] |",
                 "|---|---|---|---|---|---|---|---|---|---|---|"]
        for sp, dofs, label, lu, sym, tri, its, solve, wall, crown, side in solver_comparison():
            table.append(f"| {sp:g} | {dofs} | {label} | {lu} | {sym:.2f} | {tri} | {its} | {solve:.2f} | {wall:.2f} | "
                         f"{crown * 1e3:.4f} | {side * 1e3:.4f} |")
        text += ["### Linear solver of the discrete tunnel\n",
                 "The analysis above without its meshing, one run each, with each linear solver (\"auto\" picks "
                 "\"lagged\" for a non-symmetric 2D Jacobian from 60k to 250k dofs, \"direct\" below: "
                 "linear_solver.LAGGED_DOF_RANGE). Wall seconds.\n", "\n".join(table), ""]
    if not args.no_demos:
        for module, argv in (("demo_tunnel", []), ("demo_blocky_rock_mass", [])):
            with tempfile.TemporaryDirectory() as tmp:
                phases, cpu, wall = run_demo(module, argv + ["--output", tmp])
            text += [f"## demos/{module}.py (default sizes, every model it solves)\n", split_rows(phases, cpu, wall), ""]
    report = "\n".join(text)
    print(report)
    with open(os.path.join(HERE, "results", "tunnel_profile.md"), "w") as f:
        f.write(report + "\n")


if __name__ == "__main__":
    main()
