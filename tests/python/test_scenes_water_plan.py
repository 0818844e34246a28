# SPDX-License-Identifier: MIT
"""The planner says what the water's coupling costs (docs/scenes.md §planner): one way, a network
solve per stage; two ways, about the measured number of staggered iterations of mechanical solves
per stage, the larger of the numbers bench/results/coupled_water.md and coupled_water_tunnel.md
report for coupled_steady's default scheme (read back here, so that the plan's
figure cannot drift from the measurement). No FE stack needed."""
import os
import re

import pytest

from rockjoint.scenes import defaults, load_scene, make_plan
from scene_cases import COLUMN, SOURCE, write

WATER = """\
in_situ: {vertical: 10 MPa}
water: {table: 500 m, heads: {left: 500 m, right: 440 m}%s}
"""


def scene(tmp_path, coupling=""):
    text = COLUMN.replace("    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}\n",
                          "    flow: {law: cubic_law, initial_aperture: 0.3 mm}\n")
    return load_scene(write(tmp_path, text + WATER % coupling))


def test_the_coupled_iterations_are_the_benchmarks():
    """The larger of the counts measured for coupled_steady's default scheme: the verification
    column (2D, 3D) and the drained tunnel."""
    counts = []
    for name in ("coupled_water.md", "coupled_water_tunnel.md"):
        with open(os.path.join(SOURCE, "bench", "results", name), encoding="utf-8") as f:
            header, rows = None, []
            for line in f:
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                if "iterations" in cells:
                    header = cells
                elif header and "network step local, iqn-ils" in cells:
                    rows.append(int(cells[header.index("iterations")]))
        assert rows, f"no row of coupled_steady's default scheme in bench/results/{name}"
        counts += rows
    assert defaults.COUPLED_ITERATIONS == max(counts)


@pytest.mark.parametrize("coupling, words", [
    ("", "one network solve per stage"),
    (", coupling: two_way", f"about {defaults.COUPLED_ITERATIONS} mechanical stage solves"),
])
def test_the_plan_says_what_the_coupling_costs(tmp_path, coupling, words):
    plan = make_plan(scene(tmp_path, coupling))
    (choice,) = [c for c in plan.choices if c.topic == "water"]
    assert words in choice.cost and "z = 500 m" in choice.choice
    assert plan.water == ("two_way" if coupling else "one_way")
    assert re.search(r"water: (one|two) way", plan.text())


def test_a_dry_scene_plans_no_water(tmp_path):
    plan = make_plan(load_scene(write(tmp_path, COLUMN)))
    assert plan.water is None and not [c for c in plan.choices if c.topic == "water"]
