#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Load cycles on the elastic-plastic contact reference: permanent closure and unloading stiffness
of synthetic granite-like joints (issue 21), beside the laboratory ranges.

    bash scripts/run.sh python3 bench/bench_contact_plastic.py [--grid 256] [--seeds 1 2 3]

Joints: the accuracy ladder's granite-like mated pairs (bench/bench_accuracy_ladder.py: Hurst 0.8,
rms 1 mm, matedness 2.5 mm, E 50 GPa, ν 0.25), periodic BEM (contact/, docs/contact.md) with the
pressure capped at the indentation hardness H. H is not one number for granite: its minerals span
mica (soft) to feldspar and quartz (hardest), so the cycle is run at H = 2, 5 and 10 GPa and
elastic walls (H = inf) beside them. Cycle: load to 10 MPa in steps, unload to 0.1 MPa, reload to
10 MPa. Reported per H (mean over seeds): permanent closure (walls unloaded) / largest closure,
and the unloading/loading stiffness ratio at the top (secant over the last 0.5 MPa each way).
Laboratory (Bandis et al. 1983; the issue's fresh granitic joints to ~10 MPa): 20-30 % permanent
closure, unloading 2-4 times stiffer at the top. Nothing here is tuned to them.
"""
import argparse
import logging
import os
import time

import numpy as np

import rockjoint
from rockjoint import contact
from rockjoint import topography as topo

JOINT = dict(hurst=0.8, rms=1.0e-3, matedness=2.5e-3, young=50e9, poisson=0.25)
HARDNESS = (2e9, 5e9, 10e9, float("inf"))
UP = np.r_[np.linspace(0.5e6, 9.5e6, 10), 10e6]
DOWN = np.array([9.5e6, 5e6, 2e6, 0.5e6, 0.1e6])
RELOAD = np.array([2e6, 5e6, 9.5e6, 10e6])


def cycle(aperture, e_star, hardness):
    path = np.r_[UP, DOWN, RELOAD]
    c = contact.closure_curve(aperture, e_star, path, hardness=hardness)
    top = len(UP) - 1
    loading = (c.closure[top] - c.closure[top - 1]) / (UP[top] - UP[top - 1])      # dΔ/dσ up
    unloading = (c.closure[top] - c.closure[top + 1]) / (UP[top] - DOWN[0])        # dΔ/dσ down
    # permanent closure: the walls unloaded after the first unloading = a second solver run on
    # the loading and unloading part only (the path above reloads)
    first = contact.closure_curve(aperture, e_star, np.r_[UP, DOWN], hardness=hardness)
    return dict(max_closure=c.closure[top], permanent=first.unloaded_closure,
                ratio=loading / unloading, reload_error=abs(c.closure[-1] - c.closure[top]) / c.closure[top],
                plastic=c.plastic_area_ratio[top], area=c.contact_area_ratio[top], closure=c.closure, path=path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", type=int, default=256)
    ap.add_argument("--spacing", type=float, default=0.25e-3, help="grid spacing [m]")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "results"))
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    e_star = rockjoint.composite_modulus(JOINT["young"], JOINT["poisson"])
    rows = {h: [] for h in HARDNESS}
    t0 = time.perf_counter()
    for seed in args.seeds:
        upper, lower = topo.mated_pair(topo.SelfAffineSpec(JOINT["hurst"], JOINT["rms"]), (args.grid, args.grid),
                                       args.spacing, JOINT["matedness"], seed=seed)
        aperture = topo.composite_topography(upper, lower).aperture
        for h in HARDNESS:
            r = cycle(aperture, e_star, h)
            rows[h].append(r)
            logging.info("seed %d, H %s: max closure %.4f mm, permanent %.1f %%, stiffness ratio %.2f",
                         seed, "inf" if not np.isfinite(h) else f"{h * 1e-9:g} GPa", r["max_closure"] * 1e3,
                         100 * r["permanent"] / r["max_closure"], r["ratio"])
    lines = ["# Load cycles on the elastic-plastic contact reference: granite-like joints",
             "",
             f"Produced by `bash scripts/run.sh python3 bench/bench_contact_plastic.py --grid {args.grid}` "
             f"({args.grid}² periodic, h = {args.spacing * 1e3:g} mm, seeds {args.seeds}, "
             f"{time.perf_counter() - t0:.0f} s). Cycle 0.5 → 10 → 0.1 → 10 MPa. Mean (min-max) over seeds.",
             "",
             "| H [GPa] | largest closure [mm] | permanent closure / largest | unloading / loading stiffness at 10 MPa | A/A0 at 10 MPa | at H at 10 MPa (of A0) | reload to 10 MPa vs first [rel.] |",
             "|---:|---:|---:|---:|---:|---:|---:|"]
    for h in HARDNESS:
        r = rows[h]
        perm = np.array([x["permanent"] / x["max_closure"] for x in r])
        ratio = np.array([x["ratio"] for x in r])
        lines.append(f"| {'inf' if not np.isfinite(h) else f'{h * 1e-9:g}'} | "
                     f"{np.mean([x['max_closure'] for x in r]) * 1e3:.4f} | "
                     f"{100 * perm.mean():.1f} % ({100 * perm.min():.1f}-{100 * perm.max():.1f}) | "
                     f"{ratio.mean():.2f} ({ratio.min():.2f}-{ratio.max():.2f}) | "
                     f"{np.mean([x['area'] for x in r]):.4f} | {np.mean([x['plastic'] for x in r]):.2e} | "
                     f"{max(x['reload_error'] for x in r):.1e} |")
    lines += ["", "Laboratory, fresh granitic joints loaded to ~10 MPa (Bandis et al. 1983, as quoted in issue 21): "
              "permanent closure 20-30 % of the largest, unloading 2-4 times stiffer than loading at the top."]
    text = "\n".join(lines) + "\n"
    print(text)
    os.makedirs(args.output, exist_ok=True)
    with open(os.path.join(args.output, "contact_plastic.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
