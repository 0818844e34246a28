#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The tunnel below a water table: convergence, joint slip and inflow, dry, one way and two way.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_tunnel_below_water_table.py [--output DIR] [--quick]

The scene (demos/scenes/tunnel_below_water_table.yaml): the 8 m tunnel of the tunnel demo, 300 m
deep in granite (σ_v = 7.95 MPa, K0 = 0.5, plane strain, an 80 m section), cut by bedding (3 m
apart) and a cross set dipping 60° (8 m apart), both Barton-Bandis with a Coulomb strength (φ = 30°,
c = 0) and Barton's JRC transmissivity of their mechanical aperture; the water table 100 m above
the axis (its hydrostatic head, 140 m in the section's coordinates, kept on the far boundaries).
The same scene three ways (docs/flow.md, "Water in scenes"):

- dry: no water anywhere (the scene without its `water:` section);
- one way: the table's hydrostatic water p0 = ρ g (z_table - z) in the joints from the in-situ
  stage on (joints pre-closed at the effective stress σ_n - p0) and kept there; after excavation the
  flow along the joints into the drained opening at the excavated closures, which does not act back;
- two way: after every stage the coupled steady state: the network's pressure, drained to p = 0 at
  the opening's wall, acts on the joints (σ'_n = σ_n - p) and their closures set the network's
  transmissivity (rockjoint.fem.water.coupled).

A fourth run, one way with a lined opening (no flow through its wall), shows the water standing
still: no flow anywhere. Each run is jointed beside intact on the same mesh (the intact rock holds
no water: its answer is the same in every run). Outputs (in DIR): <run>/ (the scene's outputs:
summary.txt, scene.png with the joints' water, jointed_flow.xdmf with head_m and pressure_Pa),
tunnel_water.txt (the side-by-side table) and tunnel_water.json (its numbers, and the joint
network of every wet run: nodes, head and pressure after each stage). Units in print: mm, L/min per
metre of tunnel, MPa.
"""
import argparse
import copy
import dataclasses
import json
import os
import time

import numpy as np
from mpi4py import MPI

from rockjoint.console import quiet_compiler_logging, say
from rockjoint.scenes import load_scene, make_plan, run_scene

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command

# %% The scene and its three (four) runs -------------------------------------------------------
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes",
                                "tunnel_below_water_table.yaml"))
RUNS = {"dry": None, "one way": ("one_way", "drained"), "two way": ("two_way", "drained"),
        "one way, lined": ("one_way", "lined")}
LMIN = 6e4   # m²/s -> L/min per metre of tunnel


def variant(scene, water):
    """The scene dry (water None) or with its water's (coupling, opening) replaced."""
    data = copy.deepcopy(scene.data)
    if water is None:
        data.pop("water")
    else:
        data["water"]["coupling"], data["water"]["opening"] = water
    return dataclasses.replace(scene, data=data)


def numbers(result) -> dict:
    """The excavation's answers of one run: per model the opening's convergence (mean inward wall
    displacement, u·n with n out of the rock, into the opening) [mm], the joint points at their
    strength at the end and the largest slip [mm];
    the jointed model's inflow into the tunnel [L/min/m], largest joint pressure [MPa], joint points
    opened by water, coupled iterations; and its network after every stage."""
    out = {}
    for model in ("jointed", "intact"):
        row = result.row(model, "excavation")
        out[model] = {"convergence_mm": float(row.monitors["opening"][-1] * 1e3), "slipping": row.slipping,
                      "max_slip_mm": row.max_slip * 1e3}
    rows = [r for r in result.rows if r.model == "jointed"]
    j = rows[-1].water
    rates = j.flow_rates or {}
    out["jointed"].update(inflow=abs(min(0.0, rates.get("opening", 0.0))) * LMIN, max_pressure_MPa=j.max_pressure * 1e-6,
                          opened_by_water=j.opened_by_water, iterations=j.iterations,
                          flow_rates={b: q * LMIN for b, q in rates.items()})
    out["networks"] = {r.stage: {"nodes": r.network.nodes.tolist(), "head": r.network.head.tolist(),
                                 "pressure": r.network.pressure.tolist(),
                                 "flow_rates": {b: q * LMIN for b, q in r.network.flow_rates.items()}}
                       for r in rows if r.network is not None}
    return out


def table(answers: dict) -> list:
    """The three answers side by side (and the lined run), jointed and intact."""
    names = list(answers)
    lines = [f"{'after excavation':44}" + "".join(f"{n:>16}" for n in names)]

    def row(label, get, fmt="{:16.4f}"):
        lines.append(f"{label:44}" + "".join(fmt.format(get(answers[n])) for n in names))

    row("convergence jointed [mm]", lambda a: a["jointed"]["convergence_mm"])
    row("convergence intact [mm]", lambda a: a["intact"]["convergence_mm"])
    row("joint points at their strength (slipping)", lambda a: a["jointed"]["slipping"], "{:16d}")
    row("largest joint slip [mm]", lambda a: a["jointed"]["max_slip_mm"])
    row("inflow into the tunnel [L/min per m]", lambda a: a["jointed"]["inflow"], "{:16.4g}")
    row("largest joint water pressure [MPa]", lambda a: a["jointed"]["max_pressure_MPa"])
    row("joint points opened by water", lambda a: a["jointed"]["opened_by_water"], "{:16d}")
    row("coupled iterations (excavation)", lambda a: a["jointed"]["iterations"], "{:16d}")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--quick", action="store_true", help="the scene at its reduced size (mesh 8 m, 2 load steps)")
    args = ap.parse_args()
    t_start = time.perf_counter()
    os.makedirs(args.output, exist_ok=True)
    answers = {}
    for name, water in RUNS.items():
        scene = variant(SCENE.at_reduced_size() if args.quick else SCENE, water)
        plan = make_plan(scene)
        t0 = time.perf_counter()
        result = run_scene(scene, plan, os.path.join(args.output, name.replace(", ", "_").replace(" ", "_")), COMM)
        answers[name] = numbers(result)
        say(f"{name}: {time.perf_counter() - t0:.1f} s")
    lines = table(answers)
    elapsed = COMM.allreduce(time.perf_counter() - t_start, op=MPI.MAX)
    lines.append(f"demo wall time [s]: {elapsed:.1f} on {COMM.size} rank(s)")
    say("\n" + "\n".join(lines))
    if COMM.rank == 0:
        with open(os.path.join(args.output, "tunnel_water.txt"), "w", encoding="utf-8") as f:
            f.write("# rockjoint: the tunnel below a water table (demos/scenes/tunnel_below_water_table.yaml"
                    + (", reduced" if args.quick else "") + ")\n" + "\n".join(lines) + "\n")
        with open(os.path.join(args.output, "tunnel_water.json"), "w", encoding="utf-8") as f:
            json.dump({"table_m": SCENE["water"]["table"], "answers": answers}, f)


if __name__ == "__main__":
    main()
