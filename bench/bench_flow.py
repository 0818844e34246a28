#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Benchmark: flow along a joint (rockjoint.flow): time per load of the transmissivity of a gap
field (both gradients), the linear solvers against each other, the error against closed forms,
and the hydraulic / mechanical aperture ratio of the granite-like synthetic joint under load.
Target: a 512² gap field in <= 1 s per load (both gradients) on this machine.

Run:  bash scripts/run.sh python3 bench/bench_flow.py [--repeat 3] [--sizes 128 256 512]
Prints the tables and writes bench/results/flow.md. The joint is the granite-like synthetic mated
pair of bench/bench_contact.py (H 0.8, rms 1 mm, matedness 2.5 mm, h 0.25 mm, E 50 GPa, ν 0.25),
its gap fields from contact.closure_curve(..., keep_fields=True). A time is one call of an
ApertureFlow made once per grid and kernel (as closure_curve(flow=True) does: its symbolic
factorisation is made at the first call, which is timed apart), the minimum of --repeat calls.
"""
import argparse
import os
import platform
import sys
import time

import numpy as np

import rockjoint
from rockjoint import contact, flow
from rockjoint import topography as topo

SOLVERS = ("cholesky", "simplicial_cholesky", "conjugate_gradient")
TARGET = 1.0             # s per load, 512², both gradients
FLOW_LOADS = (0.1e6, 1e6, 10e6)
RATIO_LOADS = np.concatenate([np.geomspace(0.1e6, 10e6, 7), [30e6]])
BARTON_JRC = (5.0, 10.0, 15.0)   # a granite joint's usual range of JRC
E_STAR = rockjoint.composite_modulus(50e9, 0.25)


def joint(n):
    upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (n, n), 0.25e-3, 2.5e-3, seed=1)
    return topo.composite_topography(upper, lower).aperture


def timed(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


# ---- closed forms on an n x n grid ---------------------------------------------------------------
def closed_form_errors(n, solver):
    """Relative errors against: parallel plates (e³/12), layers e(y) (arithmetic mean of e³/12
    along x, harmonic along y), the two-phase checkerboard of 2 x 2 squares per period, contrast
    10 (√(k1 k2): Keller 1964, Dykhne 1971)."""
    rng = np.random.default_rng(n)
    h = 0.25e-3
    f = flow.ApertureFlow((n, n), h, solver=solver, tolerance=1e-12)
    plates = f(np.full((n, n), 2e-4))
    layer = rng.uniform(2e-5, 3e-4, n)
    layered = f(np.tile(layer[:, None], (1, n)))
    k = layer ** 3 / 12
    e1 = 1e-4
    e2 = e1 * 10 ** (1 / 3)
    i, j = np.indices((n, n))
    board = f(np.where((i // (n // 2) + j // (n // 2)) % 2, e2, e1))
    exact = np.sqrt(e1 ** 3 / 12 * e2 ** 3 / 12)
    return dict(plates=abs(plates.tensor[0, 0] / (2e-4 ** 3 / 12) - 1),
                arithmetic=abs(layered.tensor[0, 0] / np.mean(k) - 1),
                harmonic=abs(layered.tensor[1, 1] * np.mean(1 / k) - 1),
                checkerboard=board.tensor[0, 0] / exact - 1)


def solver_table(sizes, repeat):
    rows = []
    for n in sizes:
        curve = contact.closure_curve(joint(n), E_STAR, FLOW_LOADS, keep_fields=True)
        for solver in SOLVERS:
            slow = solver == "conjugate_gradient" and n >= 512
            gaps = curve.gap[-1:] if slow else curve.gap   # CG at 512²: one load, once (10-20 s)
            f = flow.ApertureFlow((n, n), 0.25e-3, solver=solver)
            t0 = time.perf_counter()
            f(gaps[0])
            first = time.perf_counter() - t0
            times, its = [], []
            for g in gaps:
                t, r = timed(lambda: f(g), 1 if slow else repeat)
                times.append(t)
                its.append(sum(r.iterations))
            err = closed_form_errors(n, solver) if n <= 512 and not slow else None
            rows.append(dict(n=n, solver=solver, first=first, per_load=max(times), its=max(its),
                             loads=len(gaps), err=err))
            print(f"{n}² {solver}: first {first:.3f} s, per load {max(times):.3f} s, its {max(its)}",
                  flush=True)
    return rows


def sealed_sides_times(repeat):
    curve = contact.closure_curve(joint(512), E_STAR, FLOW_LOADS, periodic=False, keep_fields=True)
    f = flow.ApertureFlow((512, 512), 0.25e-3, periodic=False)
    f(curve.gap[0])
    return max(timed(lambda: f(g), repeat)[0] for g in curve.gap)


# ---- the synthetic joint under load: e_h / e ------------------------------------------------------
def ratio_table():
    """Per load: the walls' answer and the two closed-form estimates from the gap statistics that
    the literature gives (from memory, docs/flow.md): Renshaw (1995) e_h³ = <e>³ (1 + σ²/<e>²)^-3/2;
    Zimmerman & Bodvarsson (1996) e_h³ ≈ <e>³ (1 - 1.5 σ²/<e>²)(1 - 2c), c the contact fraction;
    and the JRC that Barton's e_h = e²/JRC^2.5 (µm) needs to give the walls' e_h."""
    t0 = time.perf_counter()
    curve = contact.closure_curve(joint(512), E_STAR, RATIO_LOADS, keep_fields=True, flow=True)
    seconds = time.perf_counter() - t0
    rows = []
    for s, g, f, area in zip(curve.stress, curve.gap, curve.flow_results, curve.contact_area_ratio):
        e, var = np.nanmean(g), np.nanvar(g)
        eh = f.hydraulic_aperture
        renshaw = e * (1 + var / e ** 2) ** -0.5
        zb = e * max((1 - 1.5 * var / e ** 2) * (1 - 2 * area), 0.0) ** (1 / 3)
        e_um, eh_um = e * 1e6, eh * 1e6
        jrc = (e_um ** 2 / eh_um) ** (1 / 2.5)
        barton = [flow.transmissivity_law("barton_jrc", initial_aperture=e, jrc=j).hydraulic_aperture(0.0) / e
                  for j in BARTON_JRC]
        rows.append(dict(s=s, area=area, e=e, eh=eh, cv=np.sqrt(var) / e, renshaw=renshaw, zb=zb,
                         jrc=jrc, barton=barton, anis=f.tensor[0, 0] / f.tensor[1, 1],
                         txy=f.tensor[0, 1] / f.mean))
    first = curve.initial_flow
    return rows, first, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 256, 512])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "results", "flow.md"))
    args = ap.parse_args()
    solvers = solver_table(args.sizes, args.repeat)
    sealed = sealed_sides_times(args.repeat) if 512 in args.sizes else None
    ratios, first, curve_seconds = ratio_table()

    def fmt_err(err, key):
        return "-" if err is None else f"{err[key]:.1e}"

    lines = [
        "# Flow along a joint: cost, solvers, closed forms, e_h / e under load", "",
        f"Produced by `bench/bench_flow.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{platform.machine()}, {os.cpu_count()} CPUs (OMP_NUM_THREADS="
        f"{os.environ.get('OMP_NUM_THREADS', 'unset')}), load average "
        f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} at the end (a shared machine).", "",
        f"Reproduce: `{' '.join(['bash scripts/run.sh python3 bench/bench_flow.py'] + sys.argv[1:])}`", "",
        "## Time per load and error against closed forms", "",
        "Gap fields of the granite-like synthetic joint (periodic kernel) at "
        f"{', '.join(f'{s / 1e6:g}' for s in FLOW_LOADS)} MPa. *per load*: the slowest load, each the "
        f"minimum of {args.repeat} calls of one `ApertureFlow` (both gradients: one factorisation, two "
        "solves); *first*: its first call, with the symbolic factorisation. Errors (relative, on the "
        "same n x n grid): parallel plates, layers e(y) along (arithmetic mean of e³) and across "
        "(harmonic), and the two-phase checkerboard (2 x 2 squares of n/2 cells, contrast 10) "
        "against √(k1 k2), whose error is the discretisation's (corner singularities; it falls "
        "with n). CG: incomplete Cholesky, relative residual 1e-10 (at 512² one load, once).", "",
        "| grid | solver | first [s] | per load [s] | target 1 s | CG its (both) | plates | arithmetic | harmonic | checkerboard |",
        "|---|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for r in solvers:
        met = ("yes" if r["per_load"] <= TARGET else "no") if r["n"] == 512 else "-"
        lines.append(f"| {r['n']}² | {r['solver']} | {r['first']:.3f} | {r['per_load']:.3f} | {met} | "
                     f"{r['its'] if r['solver'] == 'conjugate_gradient' else '-'} | "
                     f"{fmt_err(r['err'], 'plates')} | {fmt_err(r['err'], 'arithmetic')} | "
                     f"{fmt_err(r['err'], 'harmonic')} | "
                     f"{'-' if r['err'] is None else format(r['err']['checkerboard'], '+.3f')} |")
    if sealed is not None:
        lines += ["", f"Sealed sides (the zero-padded kernel's gap fields, fixed pressures on the inlet "
                  f"and outlet faces, two factorisations per load), 512², cholesky: {sealed:.3f} s per load."]
    by = {(r["n"], r["solver"]): r for r in solvers}
    n_max = max(args.sizes)
    if all((n_max, s) in by for s in SOLVERS):
        chol = by[(n_max, "cholesky")]["per_load"]
        lines += ["", f"Choice: `cholesky` (CHOLMOD's supernodal factorisation through Eigen) is the "
                  f"default: at {n_max}² Eigen's simplicial LDLᵀ takes "
                  f"{by[(n_max, 'simplicial_cholesky')]['per_load'] / chol:.1f} times as long per load and "
                  f"incomplete-Cholesky CG {by[(n_max, 'conjugate_gradient')]['per_load'] / chol:.0f} times "
                  f"({by[(n_max, 'conjugate_gradient')]['its']} iterations for the two gradients: the "
                  "5-point operator's condition number grows as n², and an incomplete factorisation "
                  "does not change that order)."]
    lines += [
        "",
        "## The synthetic joint under load: hydraulic against mechanical aperture", "",
        f"512² periodic, loads {', '.join(f'{s / 1e6:.3g}' for s in RATIO_LOADS)} MPa: "
        f"`contact.closure_curve(..., flow=True)` in {curve_seconds:.1f} s in all (BEM and flow). "
        f"At first contact: e = {first.mechanical_aperture * 1e6:.1f} µm, "
        f"e_h = {first.hydraulic_aperture * 1e6:.1f} µm (ratio {first.hydraulic_aperture / first.mechanical_aperture:.3f}). "
        "e = mean gap (contact spots as 0), e_h = (12 (T_xx + T_yy)/2)^(1/3); σ_e/e the coefficient of "
        "variation of the gap; estimates of e_h from the gap statistics: Renshaw (1995) and Zimmerman & "
        "Bodvarsson (1996) (formulas in docs/flow.md); JRC_B: the JRC that Barton's conversion "
        "e_h = e²/JRC^2.5 (µm) needs to give the walls' e_h at the walls' e.", "",
        f"| σ [MPa] | A/A0 | e [µm] | e_h [µm] | e_h/e | σ_e/e | Renshaw e_h/e | Z&B e_h/e | JRC_B | "
        f"Barton e_h/e at JRC {' / '.join(f'{j:g}' for j in BARTON_JRC)} | T_xx/T_yy | T_xy/T |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    for r in ratios:
        lines.append(f"| {r['s'] / 1e6:.3g} | {r['area']:.2e} | {r['e'] * 1e6:.1f} | {r['eh'] * 1e6:.1f} | "
                     f"{r['eh'] / r['e']:.3f} | {r['cv']:.3f} | {r['renshaw'] / r['e']:.3f} | "
                     f"{r['zb'] / r['e']:.3f} | {r['jrc']:.2f} | "
                     f"{' / '.join(f'{b:.2f}' for b in r['barton'])} | {r['anis']:.3f} | {r['txy']:+.4f} |")
    at = {round(r["s"] / 1e6, 3): r for r in ratios}
    low, high = at[0.1], at[10.0]
    lines += [
        "", "### Against the published ranges", "",
        "Cited from knowledge (the search tool of this session returned none of these papers' text; "
        "check the numbers against the originals before quoting them):", "",
        "* Barton, Bandis & Bakhtar (1985, Int. J. Rock Mech. Min. Sci. 22(3), 121-140): laboratory "
        "joints under normal load pass less flow than parallel plates at their mechanical aperture E; "
        "their conversion e = E²/JRC^2.5 (µm, for E >= e) gives e/E = E/JRC^2.5, falling in proportion "
        "to E as the joint closes. Olsson & Barton (2001, IJRMMS 38, 317-329) keep it for normal "
        "closure before shear.",
        "* Renshaw (1995, J. Geophys. Res. 100(B12), 24629-24636): e_h/<e> falls as σ_e/<e> grows "
        "under normal stress; his closed form e_h³ = <e>³ (1 + σ_e²/<e>²)^(-3/2) follows laboratory "
        "fractures from e_h/<e> near 1 when open to a few tenths near closure.",
        "* Zimmerman & Bodvarsson (1996, Transport in Porous Media 23, 1-30), reviewing laboratory "
        "and numerical data: e_h < <e> always, e_h³ ≈ <e>³ (1 - 1.5 σ_e²/<e>²)(1 - 2c) for small σ_e/<e> "
        "and contact fraction c; the natural fractures they compile have σ_e/<e> of order 1 under "
        "moderate stress and e_h/<e> well below 1, decreasing with stress.", "",
        f"The walls' ratio falls from {low['eh'] / low['e']:.2f} at 0.1 MPa to {high['eh'] / high['e']:.2f} at "
        f"10 MPa: at the top of the laboratory range and falling slowly. The two closed forms from the "
        f"gap statistics agree with it (Renshaw {low['renshaw'] / low['e']:.3f} / {high['renshaw'] / high['e']:.3f}, "
        f"Zimmerman & Bodvarsson {low['zb'] / low['e']:.3f} / {high['zb'] / high['e']:.3f} at 0.1 / 10 MPa), so "
        f"the difference from the laboratory lies in the geometry, not in the flow solution: the synthetic "
        f"joint's gap varies little (σ_e/<e> = {low['cv']:.2f} to {high['cv']:.2f}) and its elastic walls touch "
        f"on {100 * high['area']:.2f} % of the area at 10 MPa, where natural joints have σ_e/<e> near 1 and "
        f"far larger contact areas (damaged, mismatched, gouge-bearing walls; the local cubic law also "
        f"overestimates flow where the walls are steep, Zimmerman & Bodvarsson 1996). Barton's conversion disagrees in its trend: at a "
        f"fixed JRC it makes e_h/e proportional to e, so over the walls' closure (e from {low['e'] * 1e6:.0f} to "
        f"{high['e'] * 1e6:.0f} µm) JRC 10 takes the ratio from {low['barton'][1]:.2f} to {high['barton'][1]:.2f}, "
        f"and the JRC that reproduces the walls' e_h falls with load ({low['jrc']:.1f} to {high['jrc']:.1f}): "
        f"an empirical JRC is not a property of the aperture field alone."]
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main()
