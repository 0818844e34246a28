# SPDX-License-Identifier: MIT
"""Every demo scene (demos/scenes/*.yaml) runs at its reduced size, serially, and its intact model
matches a closed form; the joints' share (jointed minus intact on the same mesh) matches the
joint law where the joint carries a known stress. `rockjoint run` as a user runs it: exit 0, no
warning, pictures, XDMF and the summary table.

References: intact plane strain / 3D uniaxial and confined states (Hooke's law), Kirsch's mean
wall displacement a (σ_v + σ_h) / (4 G) for the tunnel (tolerance 10 %: an 8 m mesh with 1 m
chords on a W/a = 20 section); the joint law's own closure at the applied stress (the FE model
uses its 1e-6 table: rtol 1e-5).
"""
import os

import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint.scenes import load_scene, make_plan, run_scene  # noqa: E402
from rockjoint.scenes.joint_laws import source_law  # noqa: E402
from scene_cases import SCENES, cli  # noqa: E402

NAMES = ["lab_closure_test", "topography_to_closure", "blocky_rock_mass", "tunnel", "direct_shear",
         "user_model", "tunnel_below_water_table", "injection_test", "rock_slope"]


def run(name, tmp_path):
    scene = load_scene(os.path.join(SCENES, name + ".yaml")).at_reduced_size()
    plan = make_plan(scene)
    return scene, plan, run_scene(scene, plan, str(tmp_path / name))


def test_every_demo_has_a_scene():
    demos = sorted(f[5:-3] for f in os.listdir(os.path.join(SCENES, "..")) if f.startswith("demo_"))
    assert demos == sorted(NAMES)


@pytest.mark.parametrize("name", ["lab_closure_test", "topography_to_closure"])
def test_closure_test_scenes_give_the_law(tmp_path, name):
    scene, plan, result = run(name, tmp_path)
    stage = scene["stages"][-1]["name"]
    j, i = result.row("jointed", stage), result.row("intact", stage)
    stress = -scene["stages"][-1]["loads"]["top"]["traction"][-1]
    rock, height = scene["rock"], scene["geometry"].get("height") or scene["geometry"]["size"][-1]
    e, nu = rock["young"], rock["poisson"]
    uniaxial = stress * height / e * ((1 - nu ** 2) if result.gdim == 2 else 1.0)
    assert i.monitors["top"][-1] == pytest.approx(-uniaxial, rel=1e-8)
    closure = source_law(scene, "joint", plan).closure_at_stress(stress)
    assert j.monitors["top"][-1] - i.monitors["top"][-1] == pytest.approx(-closure, rel=1e-5)
    assert (tmp_path / name / "jointed_joints.xdmf").exists() and (tmp_path / name / "scene.png").exists()


def test_blocky_scene_intact_biaxial_and_slip(tmp_path):
    scene, plan, result = run("blocky_rock_mass", tmp_path)
    i = result.row("intact", "raised vertical load")
    e, nu = 50e9, 0.25
    sxx, syy = -5e6, -20e6   # plane strain: ε_yy = ((1 - ν²) σ_yy - ν (1 + ν) σ_xx) / E
    eyy = ((1 - nu ** 2) * syy - nu * (1 + nu) * sxx) / e
    assert i.monitors["top"][1] == pytest.approx(eyy * 8.0, rel=1e-8)
    assert plan.slip["cross"] and result.row("jointed", "raised vertical load").slipping > 0


def test_tunnel_scene_intact_wall_is_kirsch(tmp_path):
    scene, plan, result = run("tunnel", tmp_path)
    sv, k, a = 7.95e6, 0.5, 4.0
    g = 50e9 / (2 * 1.25)
    kirsch = a * (sv + k * sv) / (4 * g)   # mean inward wall displacement of the excavation
    i, j = result.row("intact", "excavation"), result.row("jointed", "excavation")
    assert i.monitors["opening"][-1] == pytest.approx(kirsch, rel=0.10)
    assert j.monitors["opening"][-1] > i.monitors["opening"][-1]   # the joints add convergence
    assert (tmp_path / "tunnel" / "scene.png").stat().st_size > 10000


def test_tunnel_below_a_water_table_intact_wall_is_kirsch_and_water_drains_in(tmp_path):
    """The water's own checks are the demo's (test_demo_tunnel_below_water_table.py); here the scene
    as `rockjoint run` runs it: the intact rock holds no water, so its wall is Kirsch's as above."""
    scene, plan, result = run("tunnel_below_water_table", tmp_path)
    g = 50e9 / (2 * 1.25)
    kirsch = 4.0 * (7.95e6 + 0.5 * 7.95e6) / (4 * g)
    i, j = result.row("intact", "excavation"), result.row("jointed", "excavation")
    assert i.monitors["opening"][-1] == pytest.approx(kirsch, rel=0.10)
    assert j.monitors["opening"][-1] > i.monitors["opening"][-1]
    assert plan.water == "two_way" and j.water.iterations > 0 and j.flow_rates["opening"] < 0   # water in


def test_direct_shear_and_user_model_scenes(tmp_path):
    _, plan, shear = run("direct_shear", tmp_path)
    assert plan.slip["joint"] and shear.row("jointed", "shear").slipping > 0
    # the upper block slides: the joints' share of the top's horizontal movement is forward
    assert shear.row("jointed", "shear").monitors["top"][0] > 5 * shear.row("intact", "shear").monitors["top"][0]
    _, _, user = run("user_model", tmp_path)
    e, nu, q = 20e9, 0.25, 1e6   # confined (u_x = 0 on both sides), plane strain: ε_yy = q (1+ν)(1-2ν)/((1-ν) E)
    expected = -q * (1 + nu) * (1 - 2 * nu) / ((1 - nu) * e) * 20.0
    assert user.row("intact", "surcharge").monitors["top"][1] == pytest.approx(expected, rel=1e-8)


def test_cli_runs_a_scene_clean(tmp_path):
    code, out, err = cli("run", os.path.join(SCENES, "direct_shear.yaml"), "--reduced", "--output", tmp_path / "o")
    assert code == 0, out + err
    lines = (out + err).splitlines()
    assert not [t for t in lines if "WARNING" in t or "Warning" in t or "warning:" in t]
    assert any(t.startswith("stage") and "jointed" in t and "intact" in t for t in lines)
    for f in ("summary.txt", "scene.png", "jointed.xdmf", "intact.xdmf", "jointed_joints.xdmf"):
        assert (tmp_path / "o" / f).exists(), f
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".rockjoint-run-")]


def test_a_run_that_fails_writes_nothing(tmp_path):
    # 6 MPa shear over 10 MPa normal load on a 30° joint with no lateral support: the upper block
    # slides away (no equilibrium), the solve fails; no output folder, no temporary folder left
    # (supports x and y on the bottom only: {bottom: y, left: y} would leave the whole column free
    # to translate, which the planner now refuses before anything runs)
    from scene_cases import COLUMN, write
    text = COLUMN.replace("[0 MPa, -10 MPa]", "[6 MPa, -10 MPa]").replace("{bottom: y, left: x}", "{bottom: xy}")
    code, out, err = cli("run", write(tmp_path, text), "--output", tmp_path / "out")
    assert code == 1 and "could not be solved, nothing was written" in err, out + err
    assert sorted(os.listdir(tmp_path)) == ["scene.yaml"]
