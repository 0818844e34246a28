#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A jointed rock slope's factor of safety by strength reduction, dry and with water, beside intact rock.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_rock_slope.py [--output DIR] [--quick]

The scene (demos/scenes/rock_slope.yaml): a 30 m face at 65° in granite (E = 20 GPa, ν = 0.25,
ρ = 2650 kg/m³), plane strain, cut by bedding dipping 35° out of the face (6 m apart, daylighting
on the face; Coulomb φ = 40°, c = 0), a steep back-release set dipping 80° into the slope (c = 50
kPa) and a tension crack 8 m behind the crest down to the highest bedding joint (no strength). Every
joint's tan φ and c are divided by a trial F, the slope is loaded by its weight (and then its
water), and F is the largest factor with equilibrium, to 1 % (docs/slopes.md). The same scene
twice:

- dry: the scene without its `water:` section;
- wet: the water table 40 m up behind the crest (5 m below the ground there), drawn down straight to
  the toe under the face: p = ρ_w g (z_w - z) in every joint below it, the crack and the sliding
  planes, set after the weight (the joints carry σ'_n = σ_n - p).

The intact slope (the same mesh, no joints) is elastic and never fails: it has no factor of
safety, and its displacement is given beside. The bedding is cohesionless, so a block sliding on it
alone has the limit-equilibrium factor tan φ / tan ψ (= 1.198 dry): the dry answer is checked
against it (tests/python/test_fem_slope_scene.py, which also runs the scene at two mesh sizes).

Outputs (in DIR): dry/ and wet/ (each the scene's outputs: summary.txt, scene.png, mechanism.png
(the displacement at the largest stable F with the moving blocks hatched, slip and opening along
each joint), jointed.xdmf at that F), rock_slope.txt (the side-by-side numbers). Units in print:
m, mm, s.
"""
import argparse
import copy
import dataclasses
import math
import os
import time

from mpi4py import MPI

from rockjoint.console import quiet_compiler_logging, say
from rockjoint.scenes import load_scene, make_plan, run_scene

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command

# %% The scene, dry and wet --------------------------------------------------------------------
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "rock_slope.yaml"))


def dry(scene):
    """The scene without its water."""
    data = copy.deepcopy(scene.data)
    data.pop("water")
    return dataclasses.replace(scene, data=data)


def numbers(result) -> dict:
    """The search's answer of one run: F, its bracket, the trials, their time, the moving blocks;
    the intact rock's largest displacement [mm]."""
    f = result.safety.found
    if not f.decided_by_strength:   # never print a factor the strength does not decide
        raise RuntimeError(f"the rock slope's search found no factor of safety: {f.reason or 'not bounded'}")
    intact = [r for r in result.rows if r.model == "intact"][-1]
    return {"F": f.factor, "stable": f.stable, "failed": f.failed, "trials": len(f.trials),
            "seconds": result.safety.seconds, "moving": result.safety.moving,
            "intact_mm": intact.max_displacement * 1e3}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default="rock_slope", help="output folder")
    ap.add_argument("--quick", action="store_true", help="the scene at its reduced size (3 m elements)")
    args = ap.parse_args()
    t0 = time.perf_counter()
    scene = SCENE.at_reduced_size() if args.quick else SCENE

    # %% 1. Plan once (the factor of safety's cost in trial solves is one of its choices) ------------
    plan = make_plan(scene)
    say(next(c for c in plan.choices if c.topic == "factor of safety").cost, comm=COMM)

    # %% 2. Strength reduction, dry then wet ---------------------------------------------------------
    found = {}
    for case, variant in (("dry", dry(scene)), ("wet", scene)):
        result = run_scene(variant, make_plan(variant), os.path.join(args.output, case), COMM)
        found[case] = numbers(result)

    # %% 3. The numbers side by side -----------------------------------------------------------------
    g = scene.data["geometry"]
    phi = scene.data["joints"]["bedding"]["strength"]["friction_angle"]
    bedding = next(s for s in g["joint_sets"] if s["name"] == "bedding")
    lines = [f"rock slope: H = {g['height']:g} m at {math.degrees(g['face_angle']):g}°, elements "
             f"{scene.data['mesh']['size']:g} m ({scene.data['mesh']['joint_size']:g} m on the joints)",
             f"limit equilibrium of a block on the bedding alone (c = 0), dry: tan φ / tan ψ = "
             f"{math.tan(phi) / math.tan(bedding['dip']):.4f}"]
    for case, n in found.items():
        lines.append(f"{case}: F = {n['F']:.3f} (stable at {n['stable']:.4g}, none at {n['failed']:.4g}; "
                     f"{n['trials']} trial solves in {n['seconds']:.1f} s); moving: {', '.join(n['moving'])}")
    lines.append(f"intact rock (elastic, no joints): never fails, no factor of safety; max |u| = "
                 f"{found['dry']['intact_mm']:.3f} mm under its weight")
    if COMM.rank == 0:
        with open(os.path.join(args.output, "rock_slope.txt"), "w", encoding="utf-8") as fh:
            fh.write("\n".join(lines) + "\n")
    for line in lines:
        say(line, comm=COMM)
    say(f"done in {time.perf_counter() - t0:.1f} s; outputs in {os.path.abspath(args.output)}", comm=COMM)


if __name__ == "__main__":
    main()
