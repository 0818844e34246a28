# SPDX-License-Identifier: MIT
"""Discrete or smeared joint sets in scenes (issue 19 with issue 20's equivalent continuum): the
planner keeps a set discrete where the continuum bench shows smearing neither within the budget
nor cheaper, a scene can smear a set (plan: {smeared: [...]}), and a smeared horizontal set under
a uniform vertical stress gives the discrete answer: the top settles by σH/E' + (H/s) Δ(σ), the
closed form of both (four joints s = H/4 apart in the discrete model)."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from scene_cases import SCENES, cli, write  # noqa: E402

from rockjoint.scenes import load_scene, make_plan  # noqa: E402
from rockjoint.scenes.runner import run_scene  # noqa: E402

E, NU, KNI, VM, SIGMA, H, S = 50e9, 0.25, 20e9, 0.2e-3, 10e6, 1.0, 0.25

BLOCK = f"""\
name: layered block
geometry:
  kind: block
  size: [1 m, 1 m]
  joint_sets:
    - {{name: bed, point: [0.5 m, 0.125 m], dip: 0 deg, spacing: 0.25 m, count: 4}}
    - {{name: vertical, point: [0.5 m, 0.5 m], dip: 90 deg, dip_direction: 90 deg, spacing: 1 m, count: 1}}
rock: {{young: 50 GPa, poisson: 0.25}}
joints:
  bed:
    law:
      model: barton_bandis
      parameters: {{initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}}
    shear_stiffness_ratio: 0.1
  vertical:
    law:
      model: barton_bandis
      parameters: {{initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}}
    shear_stiffness_ratio: 0.1
    residual_stiffness: 1 MPa/m
supports: {{bottom: y, left: x}}
stages:
  - name: load
    loads: {{top: {{traction: [0 MPa, -10 MPa]}}}}
error_budget: 10 %
mesh: {{size: 0.25 m}}
outputs: {{pictures: false, xdmf: false, monitor: [top]}}
"""


def closed_form():
    closure = SIGMA * VM / (KNI * VM + SIGMA)                   # Barton-Bandis inverse
    return -(SIGMA * H * (1 - NU**2) / E + H / S * closure)    # plane strain, uniaxial σ_yy


def test_planner_keeps_sets_discrete_on_the_evidence(tmp_path):
    plan = make_plan(load_scene(write(tmp_path, BLOCK)))
    assert plan.smeared == ()
    text = plan.text()
    assert "joints of bed: discrete" in text and "bench/results/continuum.md" in text


def test_planner_smears_a_dense_set_and_keeps_the_dominant_set_discrete(tmp_path):
    # The demo tunnel with its bedding at 0.25 m (s/a = 0.0625): the bench's mixed model (dominant
    # set discrete, the rest smeared) is within the 10 % budget and cheaper there; the cross set
    # is the dominant one (τ/σ_n = cot 30° under the vertical hoop stress at the sidewall, three
    # times tan 30°; the bedding carries no shear there) and its 5 m spacing has no bench row.
    import os
    text = open(os.path.join(SCENES, "tunnel.yaml"), encoding="utf-8").read()
    text = text.replace("dip: 0 deg, spacing: 3 m, count: 8", "dip: 0 deg, spacing: 0.25 m, count: 8")
    plan = make_plan(load_scene(write(tmp_path, text)))
    assert plan.smeared == ("bedding",)
    out = plan.text()
    assert "joints of bedding: smeared" in out and "joints of cross: discrete" in out
    assert "the dominant set (mobilised friction 3.00)" in out
    # A budget below the bench's mixed gap keeps both discrete.
    plan = make_plan(load_scene(write(tmp_path, text.replace("error_budget: 10 %", "error_budget: 1 %"), "tight.yaml")))
    assert plan.smeared == ()


def test_a_smeared_set_gives_the_discrete_answer_under_uniform_stress(tmp_path):
    discrete_scene = load_scene(write(tmp_path, BLOCK))
    smeared_scene = load_scene(write(tmp_path, BLOCK + "plan: {smeared: [bed]}\n", "smeared.yaml"))
    plan = make_plan(smeared_scene)
    assert plan.smeared == ("bed",)
    assert "joints of bed: smeared" in plan.text()
    a = run_scene(discrete_scene, make_plan(discrete_scene), str(tmp_path / "a"))
    b = run_scene(smeared_scene, plan, str(tmp_path / "b"))
    top_discrete = a.row("jointed", "load").monitors["top"][1]
    top_smeared = b.row("jointed", "load").monitors["top"][1]
    # The vertical joint sits at zero normal stress, on its law's kink (k_r regularised): it moves
    # the top by a few 1e-6 of the settlement, the same in both models (it stays discrete).
    assert top_discrete == pytest.approx(closed_form(), rel=1e-5)
    assert top_smeared == pytest.approx(top_discrete, rel=1e-6)


def test_unknown_smeared_set_is_named(tmp_path):
    path = write(tmp_path, BLOCK + "plan: {smeared: [cross]}\n")
    code, out, err = cli("plan", path)
    assert code == 2 and "plan.smeared" in err and "cross" in err and "line" in err


def _summary_value(text, label):
    line = next(t for t in text.splitlines() if label in t)
    return float(line.split()[-1])


def test_smeared_sets_have_summary_rows_equal_to_the_law(tmp_path):
    # Mixed model (bed smeared, vertical discrete) under a uniform 10 MPa: every point of the
    # smeared set sits at σ_n = 10 MPa and closes the law's Δ(σ) = σ V_m / (K_ni V_m + σ), which
    # the run reports for the set (a 1e-6 table: its share is far below the check).
    scene = load_scene(write(tmp_path, BLOCK + "plan: {smeared: [bed], table_tolerance: 1e-6}\n"))
    result = run_scene(scene, make_plan(scene), str(tmp_path / "o"))
    row = result.row("jointed", "load")
    closure = SIGMA * VM / (KNI * VM + SIGMA)
    assert row.smeared == ("bed",)
    assert row.per_set["bed"][0] == pytest.approx(closure, rel=1e-5)
    assert row.per_set["bed"][1] == pytest.approx(SIGMA, rel=1e-6)
    assert row.slipping_per_set["bed"] == 0
    assert row.max_closure == pytest.approx(closure, rel=1e-5)
    # the discrete vertical set carries nothing (σ_xx = 0): σ_n 0 to roundoff
    assert abs(row.per_set["vertical"][1]) < 1e-3 * SIGMA
    # summary.txt has the rows, as the table prints them (5 digits)
    summary = (tmp_path / "o" / "summary.txt").read_text(encoding="utf-8")
    assert "bed (smeared): max closure [mm]" in summary
    assert _summary_value(summary, "bed (smeared): max closure [mm]") == float(f"{closure * 1e3:.5g}")
    assert _summary_value(summary, "bed (smeared): max σ_n [MPa]") == float(f"{SIGMA * 1e-6:.5g}")
    assert _summary_value(summary, "bed (smeared): slipping points") == 0


def test_the_table_range_check_covers_smeared_sets(tmp_path):
    text = BLOCK + "plan: {smeared: [bed], table_max_stress: 5 MPa}\n"
    code, out, err = cli("run", write(tmp_path, text), "--output", tmp_path / "o")
    assert code == 0, out + err
    assert ("warning: smeared joint set bed: σ_n reaches 10 MPa in stage 'load', beyond its table "
            "(0 - 5 MPa)") in out + err
    # the model's own check of its smeared sets (rockjoint.fem.mechanics.law_range, from the law's status)
    assert "in stage 'load' (smeared joint sets): joint 'bed':" in out + err
    assert "σ_n reaches 10 MPa where its table covers σ_n 0 - 5 MPa" in out + err
    assert "warning: joint set vertical" not in out + err  # the discrete set stays at 0


def test_smeared_slipping_points_are_counted(tmp_path):
    # A smeared set dipping 45° with φ = 20°, c = 0 in a uniaxial 10 MPa: τ/σ_n = tan 45° > tan 20°
    # at every point, so every quadrature point of the set slides (plane strain, rock laterally
    # supported on the left: the mass still stands, the set is smeared in every block).
    text = f"""\
name: smeared slip
geometry:
  kind: block
  size: [1 m, 1 m]
  joint_sets:
    - {{name: inclined, point: [0.5 m, 0.5 m], dip: 45 deg, dip_direction: 90 deg, spacing: 0.1 m, count: 1}}
rock: {{young: 50 GPa, poisson: 0.25}}
joints:
  inclined:
    law:
      model: barton_bandis
      parameters: {{initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}}
    residual_stiffness: 1 MPa/m
    strength: {{model: coulomb, friction_angle: 20 deg, cohesion: 0 MPa}}
supports: {{bottom: y, left: x, right: x}}
stages:
  - name: load
    steps: 2
    loads: {{top: {{traction: [0 MPa, -10 MPa]}}}}
error_budget: 10 %
mesh: {{size: 0.5 m}}
plan: {{smeared: [inclined], intact: false}}
outputs: {{pictures: false, xdmf: false, monitor: [top]}}
"""
    code, out, err = cli("run", write(tmp_path, text), "--output", tmp_path / "o")
    assert code == 0, out + err
    summary = (tmp_path / "o" / "summary.txt").read_text(encoding="utf-8")
    assert _summary_value(summary, "inclined (smeared): slipping points") > 0
