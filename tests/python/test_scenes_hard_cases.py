# SPDX-License-Identifier: MIT
"""Hard cases of `rockjoint run` (issue 30, item 2): each scene in tests/scenes/hard_cases ends in
a correct answer or a message that names the set, the block and the numbers; never an internal
error. The CLI runs in its own process (scene_cases.cli), as a user runs it."""
import math
import os

import pytest

from scene_cases import cli

HARD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "hard_cases")
E, NU = 50e9, 0.25


def run(name, tmp_path):
    code, out, err = cli("run", os.path.join(HARD, name + ".yaml"), "--output", tmp_path / "out")
    return code, out, err


def test_tension_names_the_open_set_and_the_block_it_frees(tmp_path):
    code, out, err = run("tension", tmp_path)
    assert code == 1, out + err
    assert "maximum_stress" not in err and "TabulatedLaw" not in err  # no internal error
    assert "no static equilibrium in stage 'pull'" in err
    assert "joint set joint opens" in err and "3 MPa tension" in err
    assert "it frees block_2" in err and "residual_stiffness" in err
    assert "nothing was written" in err and not (tmp_path / "out").exists()
    # the plan's table covers the tension's magnitude x 1.25 instead of 0 MPa
    assert "normal stress 0 - 3.75 MPa" in out + err


def test_tension_with_residual_stiffness_is_solved_with_the_joint_open(tmp_path):
    code, out, err = run("tension_residual", tmp_path)
    assert code == 0, out + err
    sigma, height, kr = 3e6, 1.0, 10e9
    rock = sigma * height * (1 - NU**2) / E          # plane strain, uniaxial σ_yy
    rows = summary(tmp_path / "out" / "summary.txt")
    assert rows["mean u_y top [mm]"][0] == pytest.approx((rock + sigma / kr) * 1e3, rel=1e-6)
    assert rows["joint: max closure [mm]"][0] == pytest.approx(-sigma / kr * 1e3, rel=1e-6)  # opening
    assert rows["joint: max σ_n [MPa]"][0] == pytest.approx(-3.0, rel=1e-6)


def test_sliding_block_names_the_set_and_its_mobilised_friction(tmp_path):
    code, out, err = run("sliding_block", tmp_path)
    assert code == 1, out + err
    assert "no static equilibrium in stage 'load'" in err
    # vertical stress on a 35° plane: τ/σ_n = tan 35° against tan 20°
    assert f"joint set slope slides: stage 'load' mobilises τ/σ_n = {math.tan(math.radians(35)):.3f} (tan 35.0°)" in err
    assert f"its strength allows {math.tan(math.radians(20)):.3f} (tan φ = tan 20.0°)" in err
    assert "it frees block_2" in err and "singular" not in err


def test_a_joint_past_its_table_is_named_with_its_stress(tmp_path):
    code, out, err = run("past_table", tmp_path)
    assert code == 0, out + err
    # the model's own check (rockjoint.fem.mechanics.law_range), then the scene's remedy
    assert ("joint 'joint_1': 12 of 12 points past the range of its law; σ_n reaches 10 MPa where its "
            "table covers σ_n 0 - 5 MPa") in out + err
    # said once, as one line (not again as a log record, nor with the raising code's source line)
    said = [line for line in (out + err).splitlines() if "joint law driven past its range" in line]
    assert len(said) == 1 and said[0].startswith("warning: "), said
    assert ("warning: joint set joint: past its table in stage 'load' (the model's warning above names "
            "the points and σ_n); raise plan: {table_max_stress: ...}") in out + err


def test_supports_that_leave_a_rotation_free_are_a_bad_scene(tmp_path):
    code, out, err = run("rotation_free", tmp_path)
    assert code == 2, out + err
    assert "line 11: supports:" in err
    assert "free to move as a rigid body (rotation about the point (0 m, 0 m))" in err


def test_a_joint_without_shear_stiffness_or_strength_names_the_block_it_frees(tmp_path):
    code, out, err = run("no_shear", tmp_path)
    assert code == 1, out + err
    assert ("joint set joint carries no shear: shear_stiffness_ratio 0 and no strength, under 1 MPa "
            "shear in stage 'load'") in err
    assert "it frees block_2" in err and "no static equilibrium" in err


def test_a_load_on_a_wall_excavated_later_is_a_bad_scene(tmp_path):
    code, out, err = run("load_before_excavation", tmp_path)
    assert code == 2, out + err
    assert ("line 21: stages[0].loads.opening: a load on 'opening' in stage 'lining', before stage "
            "'excavation' excavates it") in err


def test_an_excavation_without_in_situ_stress_is_a_bad_scene(tmp_path):
    code, out, err = run("excavation_without_in_situ", tmp_path)
    assert code == 2, out + err
    assert "stages[0].excavate: excavating 'opening' releases the in-situ stress" in err


def summary(path) -> dict:
    """summary.txt as {quantity: [numbers]} (stage column dropped; one stage per scene here)."""
    out = {}
    for line in open(path, encoding="utf-8").read().splitlines()[1:]:
        words = line.split()
        numbers = []
        while words:
            try:
                numbers.insert(0, float(words[-1]))
            except ValueError:
                break
            words.pop()
        out[" ".join(words[1:])] = numbers
    return out


def test_sliding_block_on_two_ranks_says_it_once(tmp_path):
    code, out, err = cli("run", os.path.join(HARD, "sliding_block.yaml"), "--output", tmp_path / "out", ranks=2)
    assert code != 0
    assert err.count("no static equilibrium in stage 'load': joint set slope slides") == 1, err
    assert not (tmp_path / "out").exists()


def _motions(tmp_path, text):
    from scene_cases import write
    from rockjoint.scenes import load_scene
    from rockjoint.scenes.statics import free_rigid_motions
    return free_rigid_motions(load_scene(write(tmp_path, text)))


def test_free_rigid_motions_of_supports(tmp_path):
    from scene_cases import COLUMN, SCENES
    from rockjoint.scenes import load_scene
    from rockjoint.scenes.statics import free_rigid_motions
    for name in sorted(os.listdir(SCENES)):  # every demo scene is supported
        assert free_rigid_motions(load_scene(os.path.join(SCENES, name))) == [], name
    assert _motions(tmp_path, COLUMN) == []
    assert _motions(tmp_path, COLUMN.replace("{bottom: y, left: x}", "{bottom: y}")) == ["translation along x"]
    # rollers on the bottom of a 3D column: x, y and the turn about the vertical axis are free
    text = COLUMN.replace("kind: column,", "kind: column, dimension: 3,").replace(
        "{bottom: y, left: x}", "{bottom: z}").replace("[0 MPa, -10 MPa]", "[0 MPa, 0 MPa, -10 MPa]")
    free = _motions(tmp_path, text)
    assert sorted(free[:2]) == ["translation along x", "translation along y"]
    assert free[2:] == ["rotation about an axis along z"]
