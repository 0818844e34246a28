#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The intact tunnel against Kirsch: error against mesh size (observed order) and domain size.

A circular hole of radius a = 1 m centred in a W x W plane-strain section (rockjoint.meshes.
tunnel_section, refined toward the opening), E = 20 GPa, ν = 0.25, far field p = σ_v = 10 MPa
(compression), σ_h = K0 p with K0 = 0.5. The FE stresses are compared with Kirsch's
(rockjoint.reference.kirsch) at sample points: the circle r = 1.1 a (360 points) and the radial
lines θ = 0 (sidewall) and θ = 90° (crown) at 40 radii from 1.1 a to 5 a.

Three set-ups (``solve_case(..., loading=...)``):
- exact: a quarter section (rockjoint.meshes.tunnel_section(quarter=True); rollers on the symmetry
  planes are exact for Kirsch), in-situ stress σ0 then excavation with the outer sides loaded by
  Kirsch's own traction: no domain truncation, the error is the discretisation error alone. This is
  the mesh-convergence study: h_wall = a / n at the opening, growing linearly over 4 a to 8 h_wall
  (every size scales with h: a uniform refinement of a graded mesh).
- excavation: the full W x W section with rollers on its four sides, in-situ stress then
  excavation (the demo's set-up): the displacement relative to the in-situ state is Kirsch's
  excavation displacement up to the domain truncation.
- traction: the far-field tractions on the top and right sides, rollers on the left and bottom
  (stresses only: the displacement then includes the far-field uniform strain).
The domain-size study runs the last two at W/a = 10, 20, 40, 80 with P2 at a/h = 16.

Errors, relative to p (stresses) and to p a / (2G) (displacements): max norm over the sample points
("max") and root mean square over them ("rms", an L2-type norm). Observed order from the two finest
meshes of each family: log(e_coarse / e_fine) / log(h_coarse / h_fine).

Usage:  /usr/bin/python3 bench/bench_kirsch.py [--quick]
Writes bench/results/kirsch.md and bench/results/kirsch.png.
"""
from __future__ import annotations

import argparse
import logging
import math
import os
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
E, NU, P, K0, A = 20e9, 0.25, 10e6, 0.5, 1.0
log = logging.getLogger("bench_kirsch")


def sample_points(radius: float, centre, quarter: bool = False) -> np.ndarray:
    """The circle r = 1.1 a (360 points; 90 in the first quadrant for a quarter model) and the radial
    lines θ = 0, 90° (1.1 a .. 5 a, 40 points each; nudged 1e-6 rad inside a quarter model)."""
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
    lines = (0.0, 0.5 * math.pi)
    if quarter:
        th = th[th < 0.5 * math.pi] + 0.25 * math.pi / 90
        lines = (1e-6, 0.5 * math.pi - 1e-6)
    r_line = np.linspace(1.1 * radius, 5.0 * radius, 40)
    r = np.concatenate([np.full(th.size, 1.1 * radius), r_line, r_line])
    t = np.concatenate([th, np.full(40, lines[0]), np.full(40, lines[1])])
    return np.stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)], axis=1)


LOADINGS = ("traction", "excavation", "exact")


def solve_case(width_ratio: float, wall_divisions: int, degree: int = 1, loading: str = "exact", comm=None,
               growth: float = 8.0) -> dict:
    """One intact tunnel solved with JointedRockModel; returns errors against Kirsch and mesh figures.

    loading: "traction" (far-field tractions on the full section, rollers left/bottom; stresses
    only), "excavation" (full section, rollers on the four sides, in-situ stress then excavation) or
    "exact" (a quarter section, rollers on the symmetry planes, in-situ stress then excavation with
    the outer sides loaded by Kirsch's own traction: no domain truncation, the discretisation error
    alone).
    """
    from mpi4py import MPI

    from rockjoint import meshes
    from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
    from rockjoint.fem.output.probe import probe, stress_function
    from rockjoint.reference import KirschSolution

    if loading not in LOADINGS:
        raise ValueError(f"loading must be one of {LOADINGS}, got {loading!r}")
    comm = comm or MPI.COMM_WORLD
    quarter = loading == "exact"
    W = width_ratio * A
    centre = (0.0, 0.0) if quarter else (0.5 * W, 0.5 * W)
    side = 0.5 * W if quarter else W
    h = A / wall_divisions
    far = min(growth * h, W / 8)
    t0 = time.perf_counter()
    jm = meshes.tunnel_section(side, side, meshes.CircularOpening(centre, A), mesh_size=far, opening_mesh_size=h,
                               opening_refine_distance=4 * A, quarter=quarter, comm=comm)
    dmesh = distribute(jm, comm)
    model = JointedRockModel(dmesh, element_degree=degree, rock=(E, NU), joints={}, plane="strain",
                             newton=NewtonOptions(verbose=False))
    kirsch = KirschSolution(A, P, K0, E, NU, centre)
    sigma0 = np.array([[-K0 * P, 0.0], [0.0, -P]])
    if loading == "traction":
        model.fix("left", "x")
        model.fix("bottom", "y")
        model.add_traction("top", (0.0, -P))
        model.add_traction("right", (-K0 * P, 0.0))
        model.solve(load_steps=1)
    else:
        from rockjoint.fem import InSituStress
        supports = (("left", "x"), ("bottom", "y")) if quarter else \
            (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y"))
        for name, comp in supports:
            model.fix(name, comp)
        model.set_in_situ_stress(InSituStress.uniform(sigma0))
        model.solve(name="in-situ")
        model.excavate(meshes.OPENING)
        if quarter:  # the outer sides carry Kirsch's traction: σ0·n (in situ) + (σ_K - σ0)·n
            for name, normal in (("right", (1.0, 0.0)), ("top", (0.0, 1.0))):
                model.add_traction(name, _kirsch_traction_change(kirsch, sigma0, np.array(normal)))
        model.solve(load_steps=1, name="excavation")
    pts = sample_points(A, centre, quarter)
    stress = stress_function(model) if loading == "traction" else model.total_stress()
    sigma = probe(stress, pts).reshape(-1, 2, 2)
    exact = kirsch.cartesian_stress(pts[:, 0], pts[:, 1])
    ds = np.abs(sigma - exact).reshape(-1, 4)[:, [0, 1, 3]] / P
    out = {"W/a": width_ratio, "a/h": wall_divisions, "h": h, "degree": degree,
           "dofs": model.num_dofs, "stress_max": float(ds.max()), "stress_rms": float(np.sqrt(np.mean(ds ** 2)))}
    if loading != "traction":
        u = probe(model.u, pts)
        du = np.abs(u - kirsch.excavation_displacement_xy(pts[:, 0], pts[:, 1])) / (P * A / (2 * kirsch.shear_modulus))
        out.update(displacement_max=float(du.max()), displacement_rms=float(np.sqrt(np.mean(du ** 2))))
    out["seconds"] = time.perf_counter() - t0
    return out


def _kirsch_traction_change(kirsch, sigma0, normal):
    """x (3, n) -> (2, n): (σ_Kirsch(x) - σ0)·n on a straight outer side of outward normal n [Pa]."""
    def traction(x):
        # called at every interpolation point of the mesh (some P2 nodes lie inside the circle,
        # on the polygon's chords): zero there, the traction is used on the outer sides only
        out = np.zeros((2, x.shape[1]))
        rock = np.hypot(x[0] - kirsch.centre[0], x[1] - kirsch.centre[1]) >= kirsch.radius
        s = kirsch.cartesian_stress(x[0][rock], x[1][rock]) - sigma0
        out[:, rock] = np.einsum("nij,j->in", s, normal)
        return out
    return traction


def order(rows, key):
    (h0, e0), (h1, e1) = [(r["h"], r[key]) for r in rows[-2:]]
    return math.log(e0 / e1) / math.log(h0 / h1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer, coarser meshes (a smoke run)")
    ap.add_argument("--output", default=os.path.join(HERE, "results"))
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    logging.getLogger().handlers[0].setLevel(logging.INFO)
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
    divisions = {1: [4, 8, 16] if args.quick else [4, 8, 16, 32, 64],
                 2: [4, 8] if args.quick else [4, 8, 16, 32]}
    families = {}
    for degree, ns in divisions.items():
        families[degree] = []
        for n in ns:
            families[degree].append(solve_case(EXACT_RATIO, n, degree, "exact", comm))
            log.info("P%d a/h = %d: %s", degree, n, _short(families[degree][-1]))
    domain = {}
    ratios = (10, 20) if args.quick else (10, 20, 40, 80)
    n_domain = 8 if args.quick else 16
    for loading in ("excavation", "traction"):
        domain[loading] = []
        for r in ratios:
            domain[loading].append(solve_case(r, n_domain, 2, loading, comm))
            log.info("%s W/a = %g: %s", loading, r, _short(domain[loading][-1]))
    if comm.rank == 0:
        write_report(families, domain, n_domain, args.output)


EXACT_RATIO = 20  # the quarter model's side is 10 a; with Kirsch's traction on it, its size does not matter


def _short(row):
    return {k: f"{v:.3g}" for k, v in row.items() if isinstance(v, float)}


KEYS = ("stress_max", "stress_rms", "displacement_max", "displacement_rms")


def _stack() -> str:
    """The versions that decide these numbers: DOLFINx and gmsh (the meshes differ between gmsh
    releases, so the errors change in their third digit)."""
    import gmsh
    from rockjoint.fem.compat import DOLFINX_RELEASE
    return f"DOLFINx {DOLFINX_RELEASE}, gmsh {gmsh.__version__}"


def write_report(families, domain, n_domain, output):
    os.makedirs(output, exist_ok=True)
    lines = ["# Intact tunnel against Kirsch (plane strain, biaxial far field)", "",
             f"a = {A} m, E = {E * 1e-9:g} GPa, ν = {NU}, p = σ_v = {P * 1e-6:g} MPa, K0 = {K0}. Errors relative "
             "to p (stresses, all three components) and to p a/(2G) (displacements, both components), at the "
             "circle r = 1.1 a and along the radial lines θ = 0 (sidewall) and θ = 90° (crown) from 1.1 a to 5 a: "
             "max = max norm over those points, rms = their root mean square (an L2-type norm). "
             f"Produced by `bash scripts/run.sh python3 bench/bench_kirsch.py` ({_stack()}).", "",
             "## Error against mesh size", "",
             "Quarter model (rollers on the symmetry planes), in-situ stress then excavation, the outer sides "
             "(10 a from the centre) loaded by Kirsch's own traction: the exact solution of the discrete "
             "problem's continuous counterpart is Kirsch's, so these errors are the discretisation error alone. "
             "h = element size at the wall; the mesh grows linearly to 8 h over 4 a (every size scales with h).",
             "", "| element | a/h | dofs | " + " | ".join(KEYS) + " | time [s] |",
             "|---|---|---|" + "---|" * len(KEYS) + "---|"]
    for degree, rows in families.items():
        for r in rows:
            lines.append(f"| P{degree} | {r['a/h']} | {r['dofs']} | " + " | ".join(f"{r[k]:.2e}" for k in KEYS)
                         + f" | {r['seconds']:.1f} |")
        lines.append(f"| P{degree} order (two finest) | | | " + " | ".join(f"{order(rows, k):.2f}" for k in KEYS)
                     + " | |")
    lines += ["", f"## Domain size (full section W x W, P2, a/h = {n_domain})", "",
              "excavation: rollers on the four outer sides, in-situ stress then excavation (the demo's set-up); "
              "traction: the far-field tractions on the top and right sides, rollers on the left and bottom "
              "(stresses only: its displacement includes the far-field strain).", "",
              "| loading | W/a | dofs | " + " | ".join(KEYS) + " |", "|---|---|---|" + "---|" * len(KEYS)]
    for loading, rows in domain.items():
        for r in rows:
            lines.append(f"| {loading} | {r['W/a']:g} | {r['dofs']} | "
                         + " | ".join(f"{r[k]:.2e}" if k in r else "" for k in KEYS) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(output, "kirsch.md"), "w") as f:
        f.write(text)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    ax = axes[0]
    for degree, rows in families.items():
        h = np.array([r["h"] for r in rows])
        for k, marker in zip(KEYS, "os^v"):
            ax.loglog(h, [r[k] for r in rows], marker + ("-" if degree == 1 else "--"), label=f"P{degree} {k}")
    h = np.array([r["h"] for r in families[1]])
    ax.loglog(h, 0.5 * families[1][0]["stress_rms"] * h / h[0], "k:", label="O(h)")
    ax.loglog(h, 0.5 * families[1][0]["displacement_rms"] * (h / h[0]) ** 2, "k-.", label="O(h²)")
    ax.set_xlabel("element size at the wall h [m] (a = 1 m)")
    ax.set_ylabel("relative error [-]")
    ax.set_title("error against mesh size (quarter model, Kirsch's traction outside)")
    ax.legend(fontsize=6, ncol=2)
    ax = axes[1]
    for loading, style in (("excavation", "-"), ("traction", "--")):
        rows = domain[loading]
        for k, marker in zip(KEYS, "os^v"):
            if k in rows[0]:
                ax.loglog([r["W/a"] for r in rows], [r[k] for r in rows], marker + style, label=f"{loading} {k}")
    w = np.array([r["W/a"] for r in domain["excavation"]], dtype=float)
    ax.loglog(w, domain["excavation"][0]["displacement_max"] * (w[0] / w) ** 2, "k:", label="O((a/W)²)")
    ax.set_xlabel("section size W/a [-]")
    ax.set_title(f"domain size (full section, P2, a/h = {n_domain})")
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(output, "kirsch.png"), dpi=110)


if __name__ == "__main__":
    main()
