# SPDX-License-Identifier: MIT
"""Tables, plots and the JSON of bench/bench_fe_speed_vs_error.py (results dict -> files).

Every number in the report is read from the results; the few sentences of interpretation that do
not depend on the run (why the column's error is at solver tolerance) say so.
"""
from __future__ import annotations

import json
import math
import os

import numpy as np

BUDGETS = (0.1, 0.03, 0.01, 0.003)   #: error budgets (jointed tunnel wall error) for the recommendations


def answer_error(row) -> float:
    """The error a budget is checked on: the larger of the wall error and the joints' share error (the
    question a user asks: how far the wall converges, and how much of that is the joints)."""
    return max(row["wall_error"], row.get("joint_share_error", 0.0))


def jsonable(x):
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items() if not isinstance(v, np.ndarray)}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    return x

NAME = "fe_speed_vs_error"


def _order(rows, hkey, ekey):
    """Observed order log(e_coarse/e_fine)/log(h_coarse/h_fine) of the two finest rows."""
    (h0, e0), (h1, e1) = [(r[hkey], r[ekey]) for r in rows[-2:]]
    if e0 <= 0 or e1 <= 0:
        return float("nan")
    return math.log(e0 / e1) / math.log(h0 / h1)


def _not_falling(rows, hkey, ekey):
    """Pairs (coarse, fine) of consecutive meshes where the error did not fall."""
    return [(a[hkey], b[hkey], a[ekey], b[ekey]) for a, b in zip(rows, rows[1:]) if b[ekey] >= a[ekey]]


def _e(x):
    return "" if x is None else f"{x:.2e}"


def column_section(col):
    L = ["## 1. Jointed column (3D, closed form)", "",
         "bench/bench_fem.py's column (unit cube, joints at z = 1/3, 2/3, Barton-Bandis K_ni 10 MPa/mm, V_m 1 mm, "
         "k_s 1 MPa/mm, 5 MPa on top, CG + GAMG, Newton rtol 1e-10). Error = |u_top - u_exact| / |u_exact| with "
         "u_exact = -(σH/E + 2Δ(σ)), Δ the exact Barton-Bandis inverse. The exact solution (uniform stress, a "
         "constant jump per joint) lies in the P1 space, so this case measures cost, not discretisation error: "
         "every row should sit at solver tolerance whatever h.", "",
         "| h [m] | element | joint quadrature | dofs | joint pairs | error vs closed form | Newton its | time [s] |",
         "|---:|---|---|---:|---:|---:|---:|---:|"]
    for r in col["mesh"]:
        L.append(f"| {r['h']:g} | P{r['degree']} | {r['quadrature']} | {r['dofs']} | {r['pairs']} | {_e(r['error'])} | "
                 f"{r['newton_iterations']} | {r['seconds']:.3f} |")
    return L


def kirsch_section(k):
    L = ["## 2. Intact tunnel against Kirsch (2D plane strain)", "",
         "bench/bench_kirsch.py's exact set-up (quarter model, a = 1 m, Kirsch's traction on the outer sides, in-situ "
         "then excavation): the discretisation error alone. Displacement errors relative to p a/(2G), stresses to p "
         "(definitions in bench/results/kirsch.md); time includes meshing (solve_case times the whole case).", "",
         "| element | a/h | dofs | displacement max | displacement rms | stress max | stress rms | time [s] |",
         "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in k["rows"]:
        L.append(f"| P{r['degree']} | {r['a/h']} | {r['dofs']} | {_e(r['displacement_max'])} | "
                 f"{_e(r['displacement_rms'])} | {_e(r['stress_max'])} | {_e(r['stress_rms'])} | {r['seconds']:.3f} |")
    for d in (1, 2):
        rows = [r for r in k["rows"] if r["degree"] == d]
        L.append(f"| P{d} order (two finest) | | | {_order(rows, 'h', 'displacement_max'):.2f} | "
                 f"{_order(rows, 'h', 'displacement_rms'):.2f} | {_order(rows, 'h', 'stress_max'):.2f} | "
                 f"{_order(rows, 'h', 'stress_rms'):.2f} | |")
    return L


def tunnel_section(t, spacing, radius):
    ref = t["reference"]
    L = ["## 3. Jointed tunnel (2D plane strain, fine-mesh reference)", "",
         f"The section of the module docstring (a = {radius:g} m, W/a = 10, bedding 3 m apart, cross set 60° 5 m apart, "
         "Barton-Bandis tables, k_s = 0.1 k_n). Mesh family n: h_wall = a/n, h_joint = 2a/n, h_far = 8a/n. "
         f"Reference: P2, n = {ref['n']} ({ref['dofs']} dofs, {ref['seconds']:.1f} s, one run). wall error = max over "
         "72 wall points of |u - u_ref| / max |u_ref| (the wall convergence after excavation); stress error = rms "
         "over 72 points on r = 1.5 a of the total stress difference / σ_v; joint share error = the same as the wall "
         "error for the joints' share of the wall displacement (jointed minus intact on the same triangles, against "
         "the reference's). Time: in-situ + excavation solve, model set-up included, meshing excluded (mesh column); "
         "intact = the intact section on the same triangles.", "",
         "| n | h_wall/a | h_joint/spacing | element | joint quadrature | dofs | joint pairs | wall error | "
         "stress error | joint share error | Newton its | time [s] | intact time [s] | meshing [s] |",
         "|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in t["mesh"]:
        L.append(f"| {r['n']} | {1 / r['n']:.4g} | {2 * radius / r['n'] / spacing:.3g} | P{r['degree']} | "
                 f"{r['quadrature']} | {r['dofs']} | {r['pairs']} | {_e(r['wall_error'])} | {_e(r['stress_error'])} | "
                 f"{_e(r['joint_share_error'])} | {r['newton_iterations']} | {r['seconds']:.3f} | "
                 f"{r['intact_seconds']:.3f} | {r['mesh_seconds']:.2f} |")
    for d, q in ((1, "nodal"), (1, "gauss"), (2, "nodal")):
        rows = [r for r in t["mesh"] if r["degree"] == d and r["quadrature"] == q]
        rows = [dict(r, h=1.0 / r["n"]) for r in rows]
        L.append(f"| order (two finest) | | | P{d} | {q} | | | {_order(rows, 'h', 'wall_error'):.2f} | "
                 f"{_order(rows, 'h', 'stress_error'):.2f} | {_order(rows, 'h', 'joint_share_error'):.2f} | | | | |")
    L += ["", "(P2 at the reference's own n is not listed: it is the reference. The two finest P2 rows are "
          "closest to the reference, so their order is optimistic.)"]
    return L


def equal_error_section(t, budgets, answer_error):
    L = ["## 4. P1 against P2, nodal against Gauss, at equal error", "",
         "For each budget on the jointed tunnel's answer error = max(wall error, joint share error): the cheapest row of "
         "section 3 that meets it, per element and joint rule (time = min over runs).", "",
         "| answer error budget | P1 nodal: n, dofs, time [s] | P1 Gauss: n, dofs, time [s] | P2 nodal: n, dofs, time [s] |",
         "|---:|---|---|---|"]
    for b in budgets:
        cells = []
        for d, q in ((1, "nodal"), (1, "gauss"), (2, "nodal")):
            fits = [r for r in t["mesh"] if r["degree"] == d and r["quadrature"] == q and answer_error(r) <= b]
            if fits:
                r = min(fits, key=lambda r: r["seconds"])
                cells.append(f"{r['n']}, {r['dofs']}, {r['seconds']:.3f}")
            else:
                cells.append("not reached")
        L.append(f"| {b:g} | " + " | ".join(cells) + " |")
    return L


def table_section(col, tun):
    ct = {r["tolerance"]: r for r in col["table_tolerance"]}
    L = ["## 5. Table tolerance against FE error", "",
         f"Tables (rockjoint.tabulate) of each case's own Barton-Bandis law at the tolerance given, all else fixed "
         f"(column h = {col['table_tolerance'][0]['h']:g}, P1; tunnel n = {tun['table_tolerance'][0]['n']}, P1 nodal). "
         "Column error: against the closed form of the law itself (the FE error is otherwise at solver tolerance, "
         "section 1), so it is the table's share alone; tunnel error: wall error against the same mesh solved with the "
         "untabulated law.", "",
         "'table error' = the table's largest relative σ error against its law between the knots "
         "(rockjoint.tabulation.table_errors; column / tunnel law): the tolerance is a bound, the actual error is "
         "usually smaller. 'build' = rockjoint.tabulate's time (column / tunnel law).", "",
         "| table tolerance | knots (column / tunnel) | table error (column / tunnel) | build [ms] | column error vs "
         "closed form | tunnel wall error vs the law | tunnel stress error vs the law | column time [s] | tunnel time [s] |",
         "|---:|---|---|---|---:|---:|---:|---:|---:|"]
    for r in tun["table_tolerance"]:
        tol = r["tolerance"]
        c = ct.get(tol)
        if tol is None:
            L.append(f"| untabulated law | - | - | - | | 0 | 0 | | {r['seconds']:.3f} |")
            continue
        L.append(f"| {tol:g} | {c['knots'] if c else ''} / {r['knots']} | "
                 f"{_e(c['table_error']) if c else ''} / {_e(r['table_error'])} | "
                 f"{c['build_seconds'] * 1e3 if c else float('nan'):.2g} / {r['build_seconds'] * 1e3:.2g} | "
                 f"{_e(c['error']) if c else ''} | "
                 f"{_e(r['wall_error'])} | {_e(r['stress_error'])} | {c['seconds']:.3f} | {r['seconds']:.3f} |")
    return L


def steps_section(col, tun):
    L = ["## 6. Load-step size against Newton iterations", "",
         "solve(load_steps=N): N equal steps to start with; the stepping is adaptive (a step that converges in at "
         "most 5 iterations lets the next grow by 1.5), so the steps taken are listed. Column: the whole 5 MPa load; "
         "tunnel: the excavation stage (P1 nodal). 'difference' = wall difference to the 1-step answer (elastic joints "
         "are path-independent, so it measures the Newton tolerance); 'vs reference' = the wall error against the "
         "fine reference.", "",
         "| requested steps | column: steps taken | column Newton its | column time [s] | column error | "
         "tunnel: steps taken | tunnel Newton its | tunnel time [s] | tunnel difference | tunnel wall error vs reference |",
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    cs = {r["steps"]: r for r in col["load_steps"]}
    for r in tun["load_steps"]:
        c = cs.get(r["steps"], {})
        L.append(f"| {r['steps']} | {c.get('load_steps_taken', '')} | {c.get('newton_iterations', '')} | "
                 f"{c.get('seconds', float('nan')):.3f} | {_e(c.get('error'))} | {r['load_steps_taken']} | "
                 f"{r['newton_iterations']} | {r['seconds']:.3f} | {_e(r['wall_error'])} | "
                 f"{_e(r['fine_reference_wall_error'])} |")
    return L


def ranks_section(rk):
    c, t = rk["column"], rk["tunnel"]
    return ["## 7. 1 rank against 2 ranks", "",
            "Sub-runs `mpirun -n 1` and `mpirun -n 2 --bind-to core` of the same script (--ranks-worker), min over the "
            "runs, a warm-up column solve first (form compilation). 'difference' = relative difference of the answers "
            "(column: u_top; tunnel: max wall displacement difference / max wall displacement); the linear solvers "
            "differ with the partition (GAMG aggregates, MUMPS ordering), so it is at Newton/solver tolerance, not "
            "round-off.", "",
            "| case | dofs | 1 rank [s] | 2 ranks [s] | speed-up | Newton its (1 / 2 ranks) | difference 1 vs 2 ranks |",
            "|---|---:|---:|---:|---:|---|---:|",
            f"| column 3D, h = {c['h']:g} (CG + GAMG) | {c['dofs']} | {c['seconds'][0]:.3f} | {c['seconds'][1]:.3f} | "
            f"{c['seconds'][0] / c['seconds'][1]:.2f}x | {c['newton_iterations'][0]} / {c['newton_iterations'][1]} | "
            f"{_e(c['difference'])} |",
            f"| jointed tunnel, n = {t['n']}, P1 | {t['dofs']} | {t['seconds'][0]:.3f} | {t['seconds'][1]:.3f} | "
            f"{t['seconds'][0] / t['seconds'][1]:.2f}x | {t['newton_iterations'][0]} / {t['newton_iterations'][1]} | "
            f"{_e(t['difference'])} |"]


def recommended_section(rec, by_budget):
    L = ["## 8. Recommended settings", "",
         "Rules (applied by the script, nothing chosen by hand): mesh and element = the cheapest row of section 3 "
         "(nodal rule) whose answer error (max of wall error and joint share error) meets the budget on both scenes "
         "(sections 3 and 3b; a row not run on the second scene is not eligible); joint quadrature "
         "= Gauss only if it halves the P1 answer error on that mesh, else nodal (P2 has the nodal rule only); table tolerance = the largest whose FE error is at most "
         "a tenth of the budget on both the column and the tunnel; excavation load steps = the fewest Newton iterations "
         "(ties: fewer steps). The same values are in the JSON under \"recommended\" (budget "
         f"{rec['error_budget']:g}) and \"by_budget\".", "",
         "| answer error budget | element | h_wall / a | h_joint / joint spacing | h_far / a | joint quadrature | "
         "table tolerance | excavation load steps | wall error got | joint share error got | stress error | time [s] | "
         "dofs | intact opening h/a (Kirsch) |",
         "|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in by_budget:
        if not r["met"]:
            L.append(f"| {r['error_budget']:g} | {r['reason']} |" + " |" * 12)
            continue
        intact = r["intact_opening_mesh_size_over_radius"]
        L.append(f"| {r['error_budget']:g} | P{r['element_degree']} | {r['opening_mesh_size_over_radius']:.4g} | "
                 f"{r['joint_mesh_size_over_spacing']:.3g} | {r['far_mesh_size_over_radius']:.3g} | "
                 f"{r['joint_quadrature']} | {r['table_tolerance']:g} | {r['excavation_load_steps']} | "
                 f"{_e(r['wall_error'])} | {_e(r['joint_share_error'])} | {_e(r['stress_error'])} | "
                 f"{r['seconds']:.3f} | {r['dofs']} | "
                 f"{'' if intact is None else f'{intact:.4g}'} |")
    L += ["", "Cheapest row per element and joint rule for each budget on the first scene alone (time [s] / h_wall / a), "
          "to judge how close the choice is (times are noisy on a loaded machine, dofs and errors are not):", ""]
    for r in by_budget:
        if r["met"]:
            L.append(f"- budget {r['error_budget']:g}: " + "; ".join(
                f"{k} {v['seconds']:.3f} s at a/{1 / v['opening_mesh_size_over_radius']:.0f} ({v['dofs']} dofs, "
                f"error {v['answer_error']:.2e})" for k, v in r["cheapest_per_element_and_rule"].items()))
    if "note" in rec:
        L += ["", f"JSON \"recommended\": {rec['note']}."]
    if rec["met"]:
        L += ["", f"Why (JSON \"justification\"): {rec['justification']}."]
        L += ["", f"Default budget {rec['error_budget']:g}: P{rec['element_degree']}, h_wall = "
              f"{rec['opening_mesh_size_over_radius']:.4g} a, h_joint = {rec['joint_mesh_size_over_spacing']:.3g} × "
              f"spacing, {rec['joint_quadrature']} joint rule, table tolerance {rec['table_tolerance']:g} (its FE error: "
              f"tunnel {_e(rec['table_tolerance_error']['tunnel_wall'])}, column "
              f"{_e(rec['table_tolerance_error']['column'])}), {rec['excavation_load_steps']} excavation load step(s) "
              f"({rec['excavation_load_steps_cost']['newton_iterations']} Newton its): wall error "
              f"{_e(rec['wall_error'])} in {rec['seconds']:.3f} s ({rec['dofs']} dofs)."]
    return L


def second_section(sc, first, radius, spacing):
    L = ["## 3b. Second scene: the same mesh ratios, denser joints, K0 = 1.5", ""]
    if "failed" in sc:
        return L + [f"Failed: {sc['failed']}"]
    L += [f"The section of section 3 with bedding planes {sc['bedding_spacing']:g} m apart (twice as dense) and "
          f"K0 = {sc['k0']:g}, tables to 8 σ_v; the family n in the same ratios: h_wall = a/n, h_joint / spacing = "
          f"{2 * radius / spacing:g}/n (as in section 3), h_far = 8a/n. Reference: its own P2 at h_wall = "
          f"a/{round(radius / sc['reference_sizes'][0])}, h_joint = {sc['reference_sizes'][1]:.3g} m "
          f"({sc['reference_dofs']} dofs, MUMPS, {sc['reference_newton_iterations']} Newton its, "
          f"{sc['reference_seconds']:.1f} s): its joint size is the P1 family member n = "
          f"{round(radius / sc['reference_sizes'][0]) // 2}'s, so that row's error is not measured beyond P1 "
          "against P2. One run each, MUMPS. 'first scene' = the same row's answer error in section 3.", "",
          "| n | element | h_wall, h_joint, h_far [m] | dofs | wall error | joint share error | stress error | answer error "
          "| first scene answer error | Newton its | time [s] |", "|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    firsts = {(r["n"], r["degree"]): r for r in first if r["quadrature"] == "nodal"}
    for r in sc["mesh"]:
        f = firsts.get((r["n"], r["degree"]))
        fe = None if f is None else max(f["wall_error"], f["joint_share_error"])
        if "failed" in r:
            L.append(f"| {r['n']} | P{r['degree']} | " + ", ".join(f"{x:.3g}" for x in r["sizes"])
                     + f" | | **failed**: {r['failed']} | | | | {_e(fe)} | | |")
            continue
        L.append(f"| {r['n']} | P{r['degree']} | " + ", ".join(f"{x:.3g}" for x in r["sizes"]) + f" | {r['dofs']} | "
                 f"{_e(r['wall_error'])} | {_e(r['joint_share_error'])} | {_e(r['stress_error'])} | "
                 f"{_e(r['answer_error'])} | {_e(fe)} | {r['newton_iterations']} | {r['seconds']:.3f} |")
    return L


def surprises(res):
    """Observations computed from the tables: errors that do not fall with h, Gauss vs nodal."""
    out = []
    t = res["tunnel"]["mesh"]
    for d, q in ((1, "nodal"), (1, "gauss"), (2, "nodal")):
        rows = [dict(r, h=1.0 / r["n"]) for r in t if r["degree"] == d and r["quadrature"] == q]
        for key in ("wall_error", "stress_error", "joint_share_error"):
            for h0, h1, e0, e1 in _not_falling(rows, "h", key):
                out.append(f"jointed tunnel P{d} {q}: {key} did not fall from h_wall = {h0:.4g} a to {h1:.4g} a "
                           f"({e0:.2e} → {e1:.2e})")
    sc = res.get("second", {}).get("mesh", [])
    for d in (1, 2):
        rows = [dict(r, h=1.0 / r["n"]) for r in sc if r["degree"] == d and "failed" not in r]
        for key in ("wall_error", "joint_share_error"):
            for h0, h1, e0, e1 in _not_falling(rows, "h", key):
                out.append(f"second scene P{d}: {key} did not fall from h_wall = {h0:.4g} a to {h1:.4g} a "
                           f"({e0:.2e} → {e1:.2e})")
    for r in sc:
        if "failed" in r:
            out.append(f"second scene P{r['degree']} n = {r['n']}: the solve failed ({r['failed']})")
    beyond = [(f"second scene P{r['degree']} n = {r['n']}", r["beyond_range"]) for r in sc if r.get("beyond_range")]
    beyond += [(f"first scene P{r['degree']} {r['quadrature']} n = {r['n']}", r["beyond_range"]) for r in t
               if r.get("beyond_range")]
    if res.get("second", {}).get("reference_beyond_range"):
        beyond.append(("second scene reference", res["second"]["reference_beyond_range"]))
    if res["tunnel"]["reference"].get("beyond_range"):
        beyond.append(("first scene reference", res["tunnel"]["reference"]["beyond_range"]))
    for where, count in beyond:
        out.append(f"{where}: {count} joint point(s) past the table's range (answered on the table's linear "
                   "continuation)")
    k = res["kirsch"]["rows"]
    for d in (1, 2):
        rows = [r for r in k if r["degree"] == d]
        for key in ("displacement_max", "stress_max", "stress_rms"):
            for h0, h1, e0, e1 in _not_falling(rows, "h", key):
                out.append(f"Kirsch P{d}: {key} did not fall from h = {h0:.4g} to {h1:.4g} ({e0:.2e} → {e1:.2e})")
    p1 = [dict(r, h=1.0 / r["n"]) for r in t if r["degree"] == 1 and r["quadrature"] == "nodal"]
    k1 = [r for r in k if r["degree"] == 1]
    out.append(f"P1 displacement order (two finest): jointed tunnel wall {_order(p1, 'h', 'wall_error'):.2f}, joints' "
               f"share {_order(p1, 'h', 'joint_share_error'):.2f}, against {_order(k1, 'h', 'displacement_max'):.2f} "
               "for the intact tunnel (Kirsch, max norm)")
    pairs = [(a, b) for a in t for b in t if a["n"] == b["n"] and a["degree"] == b["degree"] == 1
             and a["quadrature"] == "gauss" and b["quadrature"] == "nodal"]
    if pairs:
        ratios = [a["wall_error"] / b["wall_error"] for a, b in pairs]
        its = [f"n = {b['n']}: {b['newton_iterations']} nodal / {a['newton_iterations']} Gauss" for a, b in pairs
               if a["newton_iterations"] != b["newton_iterations"]]
        out.append(f"Gauss / nodal P1 wall error: {min(ratios):.2f} .. {max(ratios):.2f}; Newton iterations differ at "
                   + (", ".join(its) if its else "no mesh"))
    tt = [r for r in res["tunnel"]["table_tolerance"] if r["tolerance"] is not None]
    loose = max(tt, key=lambda r: r["tolerance"])
    secs = [r["seconds"] for r in res["tunnel"]["table_tolerance"]]
    out.append(f"table: at tolerance {loose['tolerance']:g} the tunnel table's actual error is {loose['table_error']:.1e} "
               f"and the FE wall error it causes {loose['wall_error']:.1e}; the tunnel solve takes {min(secs):.3f} .. "
               f"{max(secs):.3f} s whatever the tolerance (untabulated law included)")
    ls = res["tunnel"]["load_steps"]
    out.append(f"load steps: the excavation takes {ls[0]['newton_iterations']} Newton iterations in 1 step and "
               f"{ls[-1]['newton_iterations']} when {ls[-1]['steps']} are requested ({ls[-1]['load_steps_taken']} taken), "
               f"for the same answer (difference <= {max(r['wall_error'] for r in ls):.1e})")
    col = res["column"]["mesh"]
    worst = max(col, key=lambda r: r["error"])
    out.append(f"column: the error does not fall with h (the exact solution is in the FE space); largest "
               f"{worst['error']:.2e} (h = {worst['h']:g}, P{worst['degree']} {worst['quadrature']})")
    return out


def write(res, output, spacing: float, radius: float):
    """The report, its JSON and plots into `output`; `spacing` and `radius` of the tunnel case."""
    os.makedirs(output, exist_ok=True)
    m = res["machine"]
    cmd = "bash scripts/run.sh python3 bench/bench_fe_speed_vs_error.py" + (" --quick" if m["quick"] else "")
    L = ["# FE speed against error (DOLFINx 0.9, Debian 13)", "",
         f"Produced by `{cmd}` on {m['date']}, {m['platform']}, {m['cpus']} CPUs; **whole run {m['wall_seconds']:.0f} s**. "
         f"Load average (1, 5, 15 min) at the start {', '.join(f'{x:.2f}' for x in m['load_start'])}, at the end "
         f"{', '.join(f'{x:.2f}' for x in m['load_end'])}: the machine was shared with other jobs (builds), so times "
         "are minima over the runs and still noisy; the errors, dofs and iteration counts do not depend on the load.",
         "", "Machine-readable: `bench/results/fe_speed_vs_error.json` (every row, plus \"recommended\" and "
         "\"by_budget\"). Plots: `fe_speed_vs_error_mesh.png` (error against mesh size), `fe_speed_vs_error_cost.png` "
         "(error against time), `fe_speed_vs_error_settings.png` (table tolerance, load steps, ranks).", ""]
    L += column_section(res["column"]) + [""] + kirsch_section(res["kirsch"]) + [""]
    L += tunnel_section(res["tunnel"], spacing, radius) + [""]
    if "second" in res:
        L += second_section(res["second"], res["tunnel"]["mesh"], radius, spacing) + [""]
    L += equal_error_section(res["tunnel"], BUDGETS, answer_error)
    L += [""] + table_section(res["column"], res["tunnel"]) + [""] + steps_section(res["column"], res["tunnel"])
    if "ranks" in res:
        L += [""] + ranks_section(res["ranks"])
    L += [""] + recommended_section(res["recommended"], res["by_budget"])
    L += ["", "## 9. Observations computed from the tables", ""] + [f"- {s}" for s in surprises(res)]
    text = "\n".join(L) + "\n"
    print(text, flush=True)
    with open(os.path.join(output, f"{NAME}.md"), "w") as fh:
        fh.write(text)
    with open(os.path.join(output, f"{NAME}.json"), "w") as fh:
        json.dump(jsonable(res), fh, indent=1)
    plots(res, output)


def plots(res, output):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    styles = {(1, "nodal"): "o-", (1, "gauss"): "s--", (2, "nodal"): "^-"}
    t, k, c = res["tunnel"]["mesh"], res["kirsch"]["rows"], res["column"]["mesh"]

    fig, ax = plt.subplots(1, 3, figsize=(16, 4.8))
    for key, st in styles.items():
        rows = [r for r in c if (r["degree"], r["quadrature"]) == key]
        ax[0].loglog([r["h"] for r in rows], [max(r["error"], 1e-16) for r in rows], st, label=f"P{key[0]} {key[1]}")
    ax[0].set(xlabel="element size h [m] (unit cube)", ylabel="|u_top - exact| / |exact| [-]",
              title="jointed column vs closed form\n(exact solution in the P1 space)")
    for d in (1, 2):
        rows = [r for r in k if r["degree"] == d]
        for key, st in (("displacement_max", "o-"), ("stress_rms", "s--")):
            ax[1].loglog([r["h"] for r in rows], [r[key] for r in rows], st, label=f"P{d} {key}")
    ax[1].set(xlabel="h at the wall / a [-]", ylabel="relative error [-]", title="intact tunnel vs Kirsch")
    for key, st in styles.items():
        rows = [r for r in t if (r["degree"], r["quadrature"]) == key]
        ax[2].loglog([1 / r["n"] for r in rows], [r["wall_error"] for r in rows], st, label=f"P{key[0]} {key[1]} wall")
        ax[2].loglog([1 / r["n"] for r in rows], [r["stress_error"] for r in rows], st[0] + ":",
                     alpha=0.6, label=f"P{key[0]} {key[1]} stress")
        ax[2].loglog([1 / r["n"] for r in rows], [r["joint_share_error"] for r in rows], st[0] + "-.",
                     alpha=0.6, label=f"P{key[0]} {key[1]} joint share")
    ax[2].set(xlabel="h at the wall / a [-] (h_joint = 2 h_wall)", ylabel="relative error [-]",
              title="jointed tunnel vs P2 fine mesh")
    for a in ax:
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7)
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(output, f"{NAME}_mesh.png"), dpi=100)
    plt.close(fig)

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
    for key, st in styles.items():
        rows = [r for r in t if (r["degree"], r["quadrature"]) == key]
        err = [answer_error(r) for r in rows]
        ax[0].loglog([r["seconds"] for r in rows], err, st, label=f"P{key[0]} {key[1]}")
        for r, e in zip(rows, err):
            ax[0].annotate(f"n={r['n']}", (r["seconds"], e), fontsize=6)
    for b in BUDGETS:
        ax[0].axhline(b, color="grey", lw=0.5)
    ax[0].set(xlabel="time: in-situ + excavation solve [s] (min over runs)",
              ylabel="max(wall error, joint share error) [-]",
              title="jointed tunnel: error against time")
    for d in (1, 2):
        rows = [r for r in k if r["degree"] == d]
        ax[1].loglog([r["seconds"] for r in rows], [r["displacement_max"] for r in rows], "o-" if d == 1 else "^-",
                     label=f"P{d} displacement max")
    ax[1].set(xlabel="time incl. meshing [s]", ylabel="relative error [-]", title="intact tunnel (Kirsch): error against time")
    for a in ax:
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7)
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(output, f"{NAME}_cost.png"), dpi=100)
    plt.close(fig)

    fig, ax = plt.subplots(1, 3, figsize=(16, 4.8))
    tt = [r for r in res["tunnel"]["table_tolerance"] if r["tolerance"] is not None]
    ct = res["column"]["table_tolerance"]
    ax[0].loglog([r["tolerance"] for r in ct], [max(r["error"], 1e-16) for r in ct], "o-", label="column vs closed form")
    ax[0].loglog([r["tolerance"] for r in tt], [max(r["wall_error"], 1e-16) for r in tt], "s-",
                 label="tunnel wall vs untabulated law")
    ax[0].loglog([r["tolerance"] for r in ct], [r["tolerance"] for r in ct], "k:", label="error = tolerance")
    ax[0].set(xlabel="table tolerance [-]", ylabel="FE error [-]", title="table tolerance against FE error")
    ls_t, ls_c = res["tunnel"]["load_steps"], res["column"]["load_steps"]
    ax[1].plot([r["steps"] for r in ls_c], [r["newton_iterations"] for r in ls_c], "o-", label="column")
    ax[1].plot([r["steps"] for r in ls_t], [r["newton_iterations"] for r in ls_t], "s-", label="tunnel excavation")
    ax[1].set(xlabel="requested load steps", ylabel="Newton iterations (total)", xscale="log",
              title="load steps against Newton iterations")
    ax[1].set_xticks([r["steps"] for r in ls_t], [str(r["steps"]) for r in ls_t])
    if "ranks" in res:
        rk = res["ranks"]
        names = ["column", "tunnel"]
        x = np.arange(2)
        ax[2].bar(x - 0.2, [rk[n]["seconds"][0] for n in names], 0.4, label="1 rank")
        ax[2].bar(x + 0.2, [rk[n]["seconds"][1] for n in names], 0.4, label="2 ranks")
        ax[2].set_xticks(x, [f"column ({rk['column']['dofs']} dofs)", f"tunnel ({rk['tunnel']['dofs']} dofs)"])
        ax[2].set(ylabel="time [s]", title="1 rank against 2 ranks")
    for a in ax:
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7)
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(output, f"{NAME}_settings.png"), dpi=100)
    plt.close(fig)
