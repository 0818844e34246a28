# SPDX-License-Identifier: MIT
"""`rockjoint run` on 2 ranks equals serial (issue 30, item 4): the same scene through the CLI,
`mpirun -n 2` and one process, gives the same summary numbers to solver tolerance, the same
output files, each written once (one summary printed, no per-rank copies, no temporary folder
left). Runs from the serial suite: the CLI is started under mpirun as a user starts it."""
import os

import numpy as np
import pytest

from scene_cases import cli, write

# A mixed model (one discrete bedding joint, a smeared cross set), intact beside jointed,
# every output (XDMF, picture): small enough for seconds on 2 ranks.
SCENE = """\
name: two ranks
geometry:
  kind: block
  size: [2 m, 2 m]
  joint_sets:
    - {name: bed, point: [1 m, 1 m], dip: 0 deg, spacing: 1 m, count: 1}
    - {name: cross, point: [1 m, 1 m], dip: 60 deg, dip_direction: 90 deg, spacing: 0.2 m, count: 1}
rock: {young: 50 GPa, poisson: 0.25}
joints:
  bed:
    law:
      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}
  cross:
    law:
      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
    residual_stiffness: 1 MPa/m
supports: {bottom: y, left: x}
stages:
  - name: biaxial
    steps: 2
    loads: {top: {traction: [0 MPa, -10 MPa]}, right: {traction: [-4 MPa, 0 MPa]}}
error_budget: 10 %
mesh: {size: 0.5 m, joint_size: 0.25 m}
plan: {smeared: [cross], slip: true}
outputs: {pictures: true, xdmf: true, monitor: [top, right]}
"""


def numbers(path):
    """summary.txt: {(stage, quantity): [numbers]}."""
    out = {}
    for line in open(path, encoding="utf-8").read().splitlines()[1:]:
        words, values = line.split(), []
        while words:
            try:
                values.insert(0, float(words[-1]))
            except ValueError:
                break
            words.pop()
        out[words[0], " ".join(words[1:])] = values
    return out


def test_run_on_two_ranks_equals_serial(tmp_path):
    scene = write(tmp_path, SCENE)
    code, out1, err1 = cli("run", scene, "--output", tmp_path / "serial")
    assert code == 0, out1 + err1
    code, out2, err2 = cli("run", scene, "--output", tmp_path / "parallel", ranks=2)
    assert code == 0, out2 + err2
    serial, parallel = numbers(tmp_path / "serial" / "summary.txt"), numbers(tmp_path / "parallel" / "summary.txt")
    assert serial.keys() == parallel.keys()
    assert any("cross (smeared)" in q for _, q in serial) and any(q.startswith("bed:") for _, q in serial)
    for key, values in serial.items():
        # the table prints 5 significant digits and the two runs agree to solver tolerance
        # (~1e-8): equal up to one unit in the last printed digit; roundoff values (a share of
        # 1e-16 mm) within 1e-9 mm of each other
        a, b = np.array(values), np.array(parallel[key])
        last = 10.0 ** (np.floor(np.log10(np.maximum(np.abs(a), 1e-300))) - 4)
        assert np.all((np.abs(a - b) <= 1.0001 * last) | (np.abs(a - b) <= 1e-9)), (key, a, b)
    # the same files, each once: no per-rank copies, nothing left in a temporary folder
    files = sorted(os.listdir(tmp_path / "serial"))
    assert files == sorted(os.listdir(tmp_path / "parallel"))
    assert {"summary.txt", "scene.png", "jointed.xdmf", "intact.xdmf", "jointed_joints.xdmf"} <= set(files)
    assert sorted(os.listdir(tmp_path)) == ["parallel", "scene.yaml", "serial"]
    # the summary printed once, the 'wrote' line once (rank 0 speaks)
    assert out2.count("quantity") == 1 and out2.count("wrote ") == 1, out2
