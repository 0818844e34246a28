# SPDX-License-Identifier: MIT
"""Scene files are checked whole before anything runs: ten malformed scenes, each failing with a
message that names the key path and its line in the file, and `rockjoint plan|run` exiting with 2.

The expected line is found in the malformed text itself (the line holding the marker), not taken
from the code under test.
"""
import re

import pytest

from rockjoint.scenes import SceneError, load_scene
from scene_cases import COLUMN, cli, write


def test_the_valid_column_loads_in_si(tmp_path):
    scene = load_scene(write(tmp_path, COLUMN))
    assert scene["rock"]["young"] == pytest.approx(50e9)
    assert scene["geometry"]["joint_heights"] == [pytest.approx(0.05)]
    law = scene["joints"]["joint"]["law"]["parameters"]
    assert law["initial_normal_stiffness"] == pytest.approx(20e9)      # 20 MPa/mm in Pa/m
    assert scene["joints"]["joint"]["strength"]["friction_angle"] == pytest.approx(0.5235987756)
    assert scene["error_budget"] == pytest.approx(0.05)
    assert scene["geometry"]["dimension"] == 2


# (name, old text, new text, key path the message names, marker of the line it must name)
MALFORMED = [
    ("unknown key", "error_budget: 5 %", "error_budget: 5 %\ncolour: red", "colour", "colour: red"),
    ("missing value", "  young: 50 GPa", "  young:", "rock.young", "  young:"),
    ("wrong unit", "  young: 50 GPa", "  young: 50 mm", "rock.young", "  young: 50 mm"),
    ("no unit", "width: 100 mm", "width: 100", "geometry.width", "width: 100,"),
    ("out of range", "  poisson: 0.25", "  poisson: 0.7", "rock.poisson", "  poisson: 0.7"),
    ("unknown law parameter", "initial_normal_stiffness: 20 MPa/mm",
     "normal_stiffness: 20 MPa/mm", "joints.joint.law.parameters.normal_stiffness", "normal_stiffness"),
    ("unknown law", "model: barton_bandis", "model: hooke", "joints.joint.law.model", "model: hooke"),
    ("unknown boundary", "loads: {top:", "loads: {roof:", "stages[0].loads.roof", "roof"),
    ("traction of the wrong size", "[0 MPa, -10 MPa]", "[0 MPa, 0 MPa, -10 MPa]",
     "stages[0].loads.top.traction", "-10 MPa]"),
    ("budget out of range", "error_budget: 5 %", "error_budget: 150 %", "error_budget", "150 %"),
    ("missing section", "supports: {bottom: y, left: x}\n", "", "missing key 'supports'", "name: column"),
    ("joint without a law", "joints:\n  joint:\n", "joints:\n  other:\n", "joints.other", "  other:"),
    ("monitor of no boundary", "monitor: [top]", "monitor: [roof]", "outputs.monitor[0]", "[roof]"),
]


@pytest.mark.parametrize("name,old,new,key,marker", MALFORMED, ids=[m[0] for m in MALFORMED])
def test_malformed_scene_names_key_and_line(tmp_path, name, old, new, key, marker):
    assert old in COLUMN
    text = COLUMN.replace(old, new, 1)
    line = next(i + 1 for i, t in enumerate(text.splitlines()) if marker in t)
    path = write(tmp_path, text)
    with pytest.raises(SceneError) as err:
        load_scene(path)
    message = str(err.value)
    assert key in message and f"line {line}:" in message, message
    code, out, errors = cli("plan", path)
    assert code == 2, out + errors
    assert key in errors and f"line {line}" in errors and "\n" not in errors.strip(), errors


BLOCK = COLUMN.replace("geometry: {kind: column, width: 100 mm, height: 100 mm, joint_heights: [50 mm]}",
                       "geometry:\n  kind: block\n  size: [100 mm, 100 mm]\n  joint_sets:\n"
                       "    - {name: joint, point: [50 mm, 50 mm], dip: 30 deg}")


@pytest.mark.parametrize("old,new,key", [
    ("point: [50 mm, 50 mm]", "point: [50 mm, 150 mm]", "geometry.joint_sets[0].point"),
    ("dip: 30 deg}", "dip: 30 deg, dip_direction: 45 deg}", "geometry.joint_sets[0].dip_direction"),
    ("dip: 30 deg}", "dip: 100 deg}", "geometry.joint_sets[0].dip")])
def test_joint_sets_are_checked_against_the_geometry(tmp_path, old, new, key):
    load_scene(write(tmp_path, BLOCK, "good.yaml"))
    text = BLOCK.replace(old, new)
    line = next(i + 1 for i, t in enumerate(text.splitlines()) if "point:" in t)
    with pytest.raises(SceneError, match=rf"line {line}: {re.escape(key)}:"):
        load_scene(write(tmp_path, text))


@pytest.mark.parametrize("old,new,limit", [
    ("dip: 30 deg}", "dip: 95 deg}", "must be <= 90 deg"),          # π/2 in the unit written
    ("dip: 30 deg}", "dip: 1.7 rad}", "must be <= 1.5708 rad"),
    ("dip: 30 deg}", "dip: -5 °}", "must be >= 0 °")])
def test_a_limit_is_stated_in_the_unit_the_user_wrote(tmp_path, old, new, limit):
    with pytest.raises(SceneError, match=re.escape(limit)) as err:
        load_scene(write(tmp_path, BLOCK.replace(old, new)))
    assert "(SI)" not in str(err.value)


def test_not_yaml_and_missing_file(tmp_path):
    path = write(tmp_path, COLUMN.replace("rock:\n", "rock: [\n"))
    with pytest.raises(SceneError, match="not valid YAML"):
        load_scene(path)
    code, _, errors = cli("run", tmp_path / "nothing.yaml", "--output", tmp_path / "out")
    assert code == 2 and "cannot read" in errors
    assert not (tmp_path / "out").exists()   # nothing written for a bad scene


def test_each_sets_strength_is_built_once_as_the_joints_own(tmp_path):
    """Scene.strengths holds each set's JointStrength, built once at loading: the object planner,
    statics, model and smeared material all use (its capacity is the closed form c + σ_n tan φ)."""
    import math
    from rockjoint.joint import JointStrength
    scene = load_scene(write(tmp_path, COLUMN))
    strength = scene.strengths["joint"]
    assert isinstance(strength, JointStrength)
    assert strength.shear_strength(2e6) == pytest.approx(2e6 * math.tan(math.radians(30)), rel=1e-12)
    assert scene.at_reduced_size().strengths["joint"] is strength   # not rebuilt
    plain = load_scene(write(tmp_path, COLUMN.replace(
        "    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}\n", "")))
    assert plain.strengths == {"joint": None}


def test_a_strength_the_joint_refuses_is_named_at_its_line(tmp_path):
    """Dilation steeper than friction passes the key-by-key ranges but not the joint's own check
    (joint/joint_strength.cpp): the message names the set's strength and its line."""
    bad = COLUMN.replace("cohesion: 0 MPa}", "cohesion: 0 MPa, dilation_angle: 40 deg}")
    assert bad != COLUMN
    with pytest.raises(SceneError, match=r"joints\.joint\.strength.*dilation") as err:
        load_scene(write(tmp_path, bad))
    assert "line" in str(err.value)
