# SPDX-License-Identifier: MIT
"""The user-model demo runs as it is, serially and on 2 ranks.

Its own check is printed: the user's forms + JointCoupling solved by SNES against
JointedRockModel's own Newton (E per block); they must agree to solver tolerance, the joints must carry
load, and 2 ranks must print the serial numbers.
"""
import re

import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402

OUTPUTS = ("user_model.txt", "user_model.png", "user_model.xdmf", "user_model_joints.xdmf",
           "sliding_plane.rjt", "bedding.rjt")


def run_demo(out, ranks):
    demo_runner.run_demo("demo_user_model.py", out, ranks, ("--mesh-size", "2.5"))
    for name in OUTPUTS:
        assert (out / name).exists(), name
    text = (out / "user_model.txt").read_text()
    rows = {}
    for line in text.splitlines()[1:]:
        m = re.match(r"^(.*?\S)\s{2,}(\S+)$", line)
        assert m, line
        rows[m.group(1)] = float(m.group(2))
    return rows


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def test_user_model_equals_jointed_rock_model(serial):
    assert serial["relative to max |u|"] <= 1e-8
    user = serial["crest settlement, E per block, user [mm]"]
    assert user == pytest.approx(serial["crest settlement, JointedRockModel [mm]"], rel=1e-8)
    assert serial["SNES iterations (graded E)"] > 2  # the joints make the problem nonlinear
    # The graded model is softer near the crest than the per-block one: it settles more.
    assert serial["crest settlement, graded E [mm]"] > user > 0.0
    # The sliding plane is loaded: closed and sheared.
    assert serial["sliding plane: max closure [mm]"] > 0.0
    assert serial["sliding plane: max |shear traction| [MPa]"] > 0.0


def test_two_ranks_print_the_serial_numbers(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    for key in ("crest settlement, graded E [mm]", "crest horizontal displacement [mm]",
                "sliding plane: max closure [mm]", "sliding plane: max normal stress [MPa]",
                "sliding plane: max |shear traction| [MPa]", "crest settlement, E per block, user [mm]",
                "crest settlement, JointedRockModel [mm]"):
        # printed with 6 decimals
        assert parallel[key] == pytest.approx(serial[key], abs=1.5e-6), key
    assert parallel["relative to max |u|"] <= 1e-8
