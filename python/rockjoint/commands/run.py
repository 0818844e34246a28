# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint run SCENE`: run a scene as planned, jointed beside intact; pictures, XDMF, table."""
from __future__ import annotations

import logging
import os
import sys

from ..console import quiet_compiler_logging, say
from ..scenes import SceneError
from .plan import checked_plan


def add_parser(sub) -> None:
    """Register the 'run' command and its options."""
    p = sub.add_parser("run", help="run a scene (YAML): jointed beside intact, pictures and XDMF",
                       description=__doc__)
    p.add_argument("scene", help="scene file (YAML, docs/scenes.md)")
    p.add_argument("--output", help="output folder (default: ./<scene file name>)")
    p.add_argument("--reduced", action="store_true",
                   help="the scene's reduced size (its `reduced:` section: coarse mesh, small scans)")
    p.set_defaults(func=main)


def main(args) -> int:
    """Run the scene in args.scene and write its outputs; returns the exit code."""
    checked = checked_plan(args)
    if checked is None:
        return 2
    scene, plan = checked
    # the FE stack (mpi4py, DOLFINx) is optional: `rockjoint plan` and --help work without it
    from mpi4py import MPI
    from ..fem import ConvergenceError, LinearSolveError  # FE stack, as above
    from ..scenes.runner import NoEquilibrium, run_scene, summary_table  # FE stack, as above
    quiet_compiler_logging()
    log = logging.getLogger("rockjoint.scenes")
    log.propagate = False
    if not log.handlers:
        log.addHandler(logging.StreamHandler())
        log.handlers[0].setFormatter(logging.Formatter("%(message)s"))
    log.setLevel(logging.INFO if MPI.COMM_WORLD.rank == 0 else logging.WARNING)
    output = args.output or os.path.splitext(os.path.basename(args.scene))[0]
    log.info("scene %r: %s", scene.data["name"], "; ".join(f"{c.topic}: {c.choice}" for c in plan.choices))
    try:
        result = run_scene(scene, plan, output)
    except SceneError as err:  # found while building (e.g. a block name the mesh does not have)
        print(f"rockjoint run: bad scene: {err}", file=sys.stderr)
        return 2
    except (NoEquilibrium, ConvergenceError, LinearSolveError) as err:
        # a valid scene the FE model cannot solve (NoEquilibrium: the statics say why); every rank
        # raised it, rank 0 says it once
        if MPI.COMM_WORLD.rank == 0:
            print(f"rockjoint run: the scene could not be solved, nothing was written: {err}",
                  file=sys.stderr)
        return 1
    say(summary_table(result))
    say(f"wrote {', '.join(result.files)} in {output} ({result.seconds:.1f} s)")
    return 0
