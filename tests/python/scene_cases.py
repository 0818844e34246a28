# SPDX-License-Identifier: MIT
"""Scene texts for the scene tests: a small valid 2D scene and helpers to run the CLI."""
import os
import subprocess
import sys

SOURCE = os.environ.get("ROCKJOINT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(SOURCE, "demos", "scenes")

#: a 2D plane-strain column, one horizontal joint, normal load only (every key of the schema's
#: common path; the malformed scenes are edits of it)
COLUMN = """\
name: column
geometry: {kind: column, width: 100 mm, height: 100 mm, joint_heights: [50 mm]}
rock:
  young: 50 GPa
  poisson: 0.25
joints:
  joint:
    law:
      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}
supports: {bottom: y, left: x}
stages:
  - name: load
    loads: {top: {traction: [0 MPa, -10 MPa]}}
error_budget: 5 %
mesh: {size: 25 mm}
outputs: {monitor: [top]}
"""


def write(tmp_path, text, name="scene.yaml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def cli(*args, ranks=1):
    """python3 -m rockjoint <args> in its own process: (return code, stdout, stderr)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg",
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [sys.executable, "-m", "rockjoint", *map(str, args)]
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    return r.returncode, r.stdout, r.stderr
