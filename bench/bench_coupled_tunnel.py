#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The coupled steady water on the tunnel (issue 45, item 2: the schemes measured on the tunnel):
the jointed section of demos/demo_tunnel.py (two joint sets, elastic joints) excavated dry, then
the water of a table 300 m above the axis (the far boundaries' head; p = ρ g (h - z)) drained
into the unlined tunnel (p = 0 on the opening), coupled both ways by every scheme of
coupled_steady; against the excavation stage's own mechanical solve (the denominator a user
would pick: one solve of the scene's mechanics) in the same run.

Usage:  python3 bench/bench_coupled_tunnel.py [--mesh-size 4] [--repeat 2]
Prints the table and writes bench/results/coupled_water_tunnel.md.
"""
from __future__ import annotations

import argparse
import datetime
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "demos"))
import demo_tunnel as tunnel  # noqa: E402  (the tunnel's scene, laws and section)

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import InSituStress, JointedRockModel, NewtonOptions, distribute  # noqa: E402
from rockjoint.fem.water.coupled import coupled_steady  # noqa: E402

SCHEMES = (("frozen", "aitken"), ("frozen", "iqn-ils"), ("local", "aitken"), ("local", "iqn-ils"))


def excavated(dmesh, tables):
    """The elastic-joint model after its in-situ stage, with the opening excavated but not solved."""
    joints = {name: tables[s] for name, s in meshes.joint_sets_of(dmesh.names).items()}
    model = JointedRockModel(dmesh, rock=(tunnel.YOUNG, tunnel.POISSON), joints=joints,
                             shear_stiffness_ratio=tunnel.SHEAR_RATIO, residual_stiffness=tunnel.RESIDUAL_STIFFNESS,
                             plane="strain", newton=NewtonOptions(verbose=False))
    for side, component in (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y")):
        model.fix(side, component)
    model.set_in_situ_stress(InSituStress.uniform([[-tunnel.K0 * tunnel.SIGMA_V, 0.0], [0.0, -tunnel.SIGMA_V]]))
    model.solve(name="in-situ")
    model.excavate(meshes.OPENING)
    return model


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh-size", type=float, default=4.0)
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    tables, walls = tunnel.joint_laws()
    laws = tunnel.transmissivity_laws(walls)
    dmesh = distribute(tunnel.section(args.mesh_size, intact=False), tunnel.COMM)
    per_joint = {n: laws[s].transmissivity for n, s in meshes.joint_sets_of(dmesh.names).items()}
    heads = {b: tunnel.DEPTH for b in ("left", "right", "bottom", "top")}
    mech, coupled, iterations, inflow, dofs = [], {s: [] for s in SCHEMES}, {}, {}, 0
    for _ in range(args.repeat):
        for step, acceleration in SCHEMES:
            model = excavated(dmesh, tables)
            t0 = time.perf_counter()
            model.solve(load_steps=2, name="excavation")
            mech.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            water = coupled_steady(model, per_joint, heads, pressures={"opening": 0.0}, network_step=step,
                                   acceleration=acceleration)
            coupled[(step, acceleration)].append(time.perf_counter() - t0)
            iterations[(step, acceleration)] = water.iterations
            inflow[(step, acceleration)] = -water.network.flow_rates["opening"] * 6e4
            dofs = model.num_dofs
    table = ["| scheme | dofs | dry: excavation [s] | the water, coupled [s] | iterations | "
             "wet / dry (excavation + water) / excavation | inflow [L/min per m] |", "|---|---|---|---|---|---|---|"]
    for s in SCHEMES:
        table.append(f"| network step {s[0]}, {s[1]} | {dofs} | {min(mech):.3f} | {min(coupled[s]):.3f} | "
                     f"{iterations[s]} | {(min(mech) + min(coupled[s])) / min(mech):.1f} | {inflow[s]:.4g} |")
    print("\n".join(table))
    if tunnel.COMM.rank == 0:
        text = ["# The coupled steady water on the tunnel: the schemes", "",
                f"`python3 bench/bench_coupled_tunnel.py --mesh-size {args.mesh_size} --repeat {args.repeat}` on "
                f"{datetime.date.today().isoformat()}, {tunnel.COMM.size} rank(s), the minimum of {args.repeat} runs, "
                f"load average {', '.join(f'{x:.2f}' for x in os.getloadavg())} at the end (a shared machine).", "",
                "The jointed section of demos/demo_tunnel.py (elastic joints), excavated dry in 2 load steps (the "
                "denominator), then the water of a table 300 m above the axis drained into the unlined tunnel, "
                "coupled both ways to the default tolerance (1e-8): the wet scene costs the dry excavation and the "
                "coupled water after it. Every scheme reaches the same inflow.", "", *table]
        os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
        with open(os.path.join(HERE, "results", "coupled_water_tunnel.md"), "w", encoding="utf-8") as f:
            f.write("\n".join(text) + "\n")


if __name__ == "__main__":
    main()
