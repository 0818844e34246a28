# SPDX-License-Identifier: MIT
"""The rock slope demo's scene (demos/scenes/rock_slope.yaml) through `rockjoint run`: its factor
of safety by strength reduction, dry, against the limit equilibrium of a block sliding on its
cohesionless bedding (F = tan φ / tan ψ: the back-release set and the crack open behind a sliding
block and carry nothing), at two joint mesh sizes that must agree; the search's trial count against
the planner's rule; the summary's rows and the mechanism picture. And on 2 ranks = serial."""
import copy
import dataclasses
import math
import os

import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from mpi_ranks import two_ranks  # noqa: E402
from rockjoint.scenes import load_scene, make_plan, run_scene  # noqa: E402
from rockjoint.scenes.runner import NoEquilibrium, summary_table  # noqa: E402
from rockjoint.scenes.slope_plan import trial_count  # noqa: E402
from scene_cases import SCENES  # noqa: E402


def dry_scene(joint_size=None):
    """The demo's scene at its reduced size (3 m elements), dry; joint_size [m] on the joints."""
    scene = load_scene(os.path.join(SCENES, "rock_slope.yaml")).at_reduced_size()
    data = copy.deepcopy(scene.data)
    data.pop("water")
    if joint_size is not None:
        data["mesh"]["joint_size"] = joint_size
    return dataclasses.replace(scene, data=data)


def limit_equilibrium(scene) -> float:
    g, joints = scene.data["geometry"], scene.data["joints"]
    dip = next(s["dip"] for s in g["joint_sets"] if s["name"] == "bedding")
    return math.tan(joints["bedding"]["strength"]["friction_angle"]) / math.tan(dip)


def test_the_slope_scene_factor_converges_and_is_the_limit_equilibrium(tmp_path):
    found = {}
    for size in (1.5, 0.75):
        scene = dry_scene(size)
        result = run_scene(scene, make_plan(scene), str(tmp_path / f"joints_{size}"))
        found[size] = result.safety.found
        print(f"joints at {size} m: F = {found[size].factor:.4f}, {len(found[size].trials)} trials, "
              f"{result.safety.seconds:.1f} s; moving {result.safety.moving}")
    expected = limit_equilibrium(scene)
    for f in found.values():
        assert f.bounded
        assert f.factor == pytest.approx(expected, rel=0.03)           # limit equilibrium, 3 %
        assert abs(len(f.trials) - trial_count(f.factor, f.tolerance)) <= 1   # the planner's count
    assert found[1.5].factor == pytest.approx(found[0.75].factor, rel=0.02)   # two meshes, 2 %
    text = summary_table(result)
    assert f"{found[0.75].factor:.4g}" in text and "bracket (stable, failed)" in text
    assert "never fails: no factor of safety" in text
    assert all(b in text for b in result.safety.moving) and result.safety.moving
    assert {"mechanism.png", "scene.png", "jointed.xdmf", "summary.txt"} <= set(result.files)


@pytest.mark.mpi
def test_the_slope_scene_on_two_ranks_is_serial(tmp_path_factory):
    comm = two_ranks()
    scene = dry_scene(1.5)
    out = comm.bcast(str(tmp_path_factory.mktemp("slope")) if comm.rank == 0 else None)
    parallel = run_scene(scene, make_plan(scene), os.path.join(out, "two"), comm).safety
    serial = run_scene(scene, make_plan(scene), os.path.join(out, f"one_{comm.rank}"), MPI.COMM_SELF).safety
    assert [(f, held) for f, held, _ in parallel.found.trials] == [(f, held) for f, held, _ in serial.found.trials]
    assert parallel.found.factor == serial.found.factor
    assert parallel.moving == serial.moving


def test_water_that_jacks_the_back_joints_open_is_named(tmp_path):
    """The demo's slope with the table 40 m up behind the crest (5 m below the ground): on the
    steep back-release joints the water reaches ρ_w g × 35 m ≈ 0.34 MPa while the rock's horizontal
    stress there is about ν/(1 - ν) ρ g z (a third of the vertical): the water opens them (jacking),
    nothing holds what it opens whatever the strength, and the run says so by name."""
    scene = load_scene(os.path.join(SCENES, "rock_slope.yaml")).at_reduced_size()
    data = copy.deepcopy(scene.data)
    data["water"]["table"] = 40.0
    scene = dataclasses.replace(scene, data=data)
    with pytest.raises(NoEquilibrium) as err:
        run_scene(scene, make_plan(scene), str(tmp_path / "jacked"))
    words = str(err.value)
    assert "no equilibrium even with its joints' strength multiplied by 20" in words
    assert "hydraulic jacking" in words and "back_1" in words, words
