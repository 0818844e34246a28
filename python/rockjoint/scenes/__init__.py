# SPDX-License-Identifier: MIT
"""rockjoint.scenes: scene files (YAML), the planner and the scene runner.

    from rockjoint.scenes import load_scene, make_plan, run_scene
    scene = load_scene("demos/scenes/tunnel.yaml")      # checked whole, SI inside
    plan = make_plan(scene)                             # what to model, with cost and error
    result = run_scene(scene, plan, "out/tunnel")       # jointed beside intact, pictures, XDMF

Schema and planner rules: docs/scenes.md.
"""
from .planner import Plan, make_plan  # noqa: F401
from .schema import Scene, load_scene  # noqa: F401
from .yamlnodes import SceneError  # noqa: F401


def run_scene(scene, plan, output, comm=None):
    """Run `scene` as `plan` says (rockjoint.scenes.runner.run_scene; needs the FE stack); a
    scene at its reduced size is `scene.at_reduced_size()`, planned and run as any scene."""
    from .runner import run_scene as run  # the FE stack is optional: planning works without it
    return run(scene, plan, output, comm)
