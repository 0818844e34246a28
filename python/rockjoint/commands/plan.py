# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint plan SCENE`: what the planner would model, each choice with its cost and error."""
from __future__ import annotations

import sys

from ..scenes import SceneError, load_scene, make_plan


def add_parser(sub) -> None:
    """Register the 'plan' command and its options."""
    p = sub.add_parser("plan", help="print what a scene needs to model, with cost and error",
                       description=__doc__)
    p.add_argument("scene", help="scene file (YAML, docs/scenes.md)")
    p.add_argument("--reduced", action="store_true", help="the scene's reduced size")
    p.set_defaults(func=main)


def checked_plan(args):
    """(scene, plan) or None after printing the scene's mistake (exit code 2)."""
    try:
        scene = load_scene(args.scene)
        if args.reduced:
            scene = scene.at_reduced_size()
        return scene, make_plan(scene)
    except SceneError as err:
        print(f"rockjoint {args.command}: bad scene: {err}", file=sys.stderr)
        return None


def main(args) -> int:
    """Print the plan of the scene in args.scene (cost, error); returns the exit code."""
    checked = checked_plan(args)
    if checked is None:
        return 2
    scene, plan = checked
    print(f"plan for scene {scene.data['name']!r} ({args.scene}), error budget "
          f"{scene.data['error_budget']:.0%}:")
    print(plan.text())
    return 0
