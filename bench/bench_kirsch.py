#!/usr/bin/env python3
"""The intact tunnel against Kirsch: error against mesh size (observed order) and domain size.

A circular hole of radius a = 1 m centred in a W x W plane-strain section (rockjoint.meshes.
tunnel_section, refined toward the opening), E = 20 GPa, ν = 0.25, far field p = σ_v = 10 MPa
(compression), σ_h = K0 p with K0 = 0.5. The FE stresses are compared with Kirsch's
(rockjoint.reference.kirsch) at sample points: the circle r = 1.1 a (360 points) and the radial
lines θ = 0 (sidewall) and θ = 90° (crown) at 40 radii from 1.1 a to 5 a.

Loading (``--loading``):
- traction: the far-field tractions on the outer sides (top: p, right: K0 p; rollers on the left and
  bottom sides). Stresses only: the displacement then includes the far-field uniform strain.
- excavation (needs the staged API): in-situ stress σ0 (uniform, σ_v = p, σ_h = K0 p), rollers on
  the four outer sides, then the opening excavated; the displacement relative to the in-situ state
  is Kirsch's excavation displacement, compared as well (u_r, u_θ on the same points).

Errors, relative to p (stresses) and to p a / (2G) (displacements): max norm over the sample points
("max") and root mean square over them ("rms", an L2-type norm). Mesh family: h_wall = a / n at the
opening, growing linearly over 4 a to 8 h_wall (all sizes scale with h_wall: a uniform refinement of
a graded mesh), W/a = 80. Domain-size study: W/a = 10, 20, 40, 80 with P2 at the finest P2 mesh. Observed order from the
two finest meshes of each family: log(e_coarse / e_fine) / log(h_coarse / h_fine).

Usage:  /usr/bin/python3 bench/bench_kirsch.py [--quick] [--loading traction|excavation]
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


def sample_points(radius: float, centre) -> np.ndarray:
    """The circle r = 1.1 a (360 points) and the radial lines θ = 0, 90° (1.1 a .. 5 a, 40 points each)."""
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
    r_circle = np.full(th.size, 1.1 * radius)
    r_line = np.linspace(1.1 * radius, 5.0 * radius, 40)
    r = np.concatenate([r_circle, r_line, r_line])
    t = np.concatenate([th, np.zeros(40), np.full(40, 0.5 * math.pi)])
    return np.stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)], axis=1)


def solve_case(width_ratio: float, wall_divisions: int, degree: int = 1, loading: str = "traction", comm=None,
               growth: float = 8.0) -> dict:
    """One intact tunnel solved with JointedRockModel; returns errors against Kirsch and mesh figures."""
    from mpi4py import MPI

    from rockjoint import meshes
    from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
    from rockjoint.fem.probe import probe, stress_function
    from rockjoint.reference import KirschSolution

    comm = comm or MPI.COMM_WORLD
    W = width_ratio * A
    centre = (0.5 * W, 0.5 * W)
    h = A / wall_divisions
    far = min(growth * h, W / 8)
    t0 = time.perf_counter()
    jm = meshes.tunnel_section(W, W, meshes.CircularOpening(centre, A), mesh_size=far, opening_mesh_size=h,
                               opening_refine_distance=4 * A, comm=comm)
    dmesh = distribute(jm, comm)
    model = JointedRockModel(dmesh, element_degree=degree, rock=(E, NU), joints={}, plane="strain",
                             newton=NewtonOptions(verbose=False))
    kirsch = KirschSolution(A, P, K0, E, NU, centre)
    if loading == "traction":
        model.fix("left", "x")
        model.fix("bottom", "y")
        model.add_traction("top", (0.0, -P))
        model.add_traction("right", (-K0 * P, 0.0))
        model.solve(load_steps=1)
    elif loading == "excavation":
        from rockjoint.fem import InSituStress
        for side, comp in (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y")):
            model.fix(side, comp)
        model.set_in_situ_stress(InSituStress.uniform([[-K0 * P, 0.0], [0.0, -P]]))
        model.solve(name="in-situ")
        model.excavate(meshes.OPENING)
        model.solve(load_steps=1, name="excavation")
    else:
        raise ValueError(f"loading must be 'traction' or 'excavation', got {loading!r}")
    pts = sample_points(A, centre)
    if loading == "traction":
        sigma = probe(stress_function(model), pts).reshape(-1, 2, 2)
    else:
        sigma = probe(model.total_stress(), pts).reshape(-1, 2, 2)
    exact = kirsch.cartesian_stress(pts[:, 0], pts[:, 1])
    ds = np.abs(sigma - exact).reshape(-1, 4)[:, [0, 1, 3]] / P
    out = {"W/a": width_ratio, "a/h": wall_divisions, "h": h, "degree": degree,
           "dofs": model.num_dofs, "stress_max": float(ds.max()), "stress_rms": float(np.sqrt(np.mean(ds ** 2))),
           "seconds": time.perf_counter() - t0}
    if loading == "excavation":
        u = probe(model.u, pts)
        du = np.abs(u - kirsch.excavation_displacement_xy(pts[:, 0], pts[:, 1])) / (P * A / (2 * kirsch.shear_modulus))
        out.update(displacement_max=float(du.max()), displacement_rms=float(np.sqrt(np.mean(du ** 2))))
    return out


def order(rows, key):
    (h0, e0), (h1, e1) = [(r["h"], r[key]) for r in rows[-2:]]
    return math.log(e0 / e1) / math.log(h0 / h1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer, coarser meshes (a smoke run)")
    ap.add_argument("--loading", choices=("traction", "excavation"), default="traction")
    ap.add_argument("--output", default=os.path.join(HERE, "results"))
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    logging.getLogger().handlers[0].setLevel(logging.INFO)
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
    divisions = {1: [4, 8, 16] if args.quick else [4, 8, 16, 32], 2: [4, 8] if args.quick else [4, 8, 16]}
    ratio = 20 if args.quick else 80
    families = {}
    for degree, ns in divisions.items():
        rows = []
        for n in ns:
            rows.append(solve_case(ratio, n, degree, args.loading, comm))
            log.info("P%d a/h = %d: %s", degree, n, {k: f"{v:.3g}" for k, v in rows[-1].items()
                                                        if isinstance(v, float)})
        families[degree] = rows
    domain = [solve_case(r, divisions[2][-1], 2, args.loading, comm) for r in (10, 20, 40, 80)]
    for d in domain:
        log.info("W/a = %g: %s", d["W/a"], d)
    if comm.rank == 0:
        write_report(families, domain, ratio, args)


def write_report(families, domain, ratio, args):
    os.makedirs(args.output, exist_ok=True)
    keys = ["stress_max", "stress_rms"] + (["displacement_max", "displacement_rms"]
                                           if "displacement_max" in families[1][0] else [])
    lines = ["# Intact tunnel against Kirsch (plane strain, biaxial far field)", "",
             f"a = {A} m, E = {E * 1e-9:g} GPa, ν = {NU}, p = σ_v = {P * 1e-6:g} MPa, K0 = {K0}, "
             f"loading: {args.loading}. Errors relative to p (stresses) and p a/(2G) (displacements), "
             "at the circle r = 1.1 a and the radial lines θ = 0, 90° (1.1 a .. 5 a): max = max norm, "
             "rms = root mean square (L2-type).", "",
             f"## Error against mesh size (W/a = {ratio})", "",
             "| element | a/h_wall | dofs | " + " | ".join(keys) + " | time [s] |",
             "|---|---|---|" + "---|" * len(keys) + "---|"]
    for degree, rows in families.items():
        for r in rows:
            lines.append(f"| P{degree} | {r['a/h']} | {r['dofs']} | " + " | ".join(f"{r[k]:.3e}" for k in keys)
                         + f" | {r['seconds']:.1f} |")
        lines.append(f"| P{degree} observed order | | | " + " | ".join(f"{order(rows, k):.2f}" for k in keys)
                     + " | |")
    lines += ["", f"## Domain size (P2, a/h_wall = {domain[0]['a/h']})", "",
              "| W/a | dofs | " + " | ".join(keys) + " |", "|---|---|" + "---|" * len(keys)]
    for r in domain:
        lines.append(f"| {r['W/a']:g} | {r['dofs']} | " + " | ".join(f"{r[k]:.3e}" for k in keys) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(args.output, "kirsch.md"), "w") as f:
        f.write(text)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for degree, rows in families.items():
        h = np.array([r["h"] for r in rows])
        for k, style in zip(keys, ("o-", "s--", "^-", "v--")):
            axes[0].loglog(h, [r[k] for r in rows], style, label=f"P{degree} {k}")
    h = np.array([r["h"] for r in families[1]])
    axes[0].loglog(h, families[1][0]["stress_max"] * h / h[0], "k:", label="O(h)")
    axes[0].loglog(h, families[1][0]["stress_max"] * (h / h[0]) ** 2, "k-.", label="O(h²)")
    axes[0].set_xlabel("h at the wall [m] (a = 1 m)")
    axes[0].set_ylabel("relative error [-]")
    axes[0].set_title(f"error against mesh size, W/a = {ratio}")
    axes[0].legend(fontsize=7)
    axes[1].loglog([r["W/a"] for r in domain], [r["stress_max"] for r in domain], "o-", label="stress max")
    axes[1].loglog([r["W/a"] for r in domain], [r["stress_rms"] for r in domain], "s--", label="stress rms")
    axes[1].set_xlabel("W/a [-]")
    axes[1].set_title(f"domain size (P2, a/h = {domain[0]['a/h']})")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "kirsch.png"), dpi=110)


if __name__ == "__main__":
    main()
