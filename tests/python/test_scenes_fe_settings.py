# SPDX-License-Identifier: MIT
"""The planner's FE defaults are the FE speed-vs-error report's recommendations (issue 19: "the
planner's defaults come from this report"): scenes/defaults.py's FE_SETTINGS equal the rows of
bench/results/fe_speed_vs_error.json that met their budget, and the plan applies them."""
import json
import os

import pytest

from rockjoint.scenes import defaults, load_scene, make_plan

ROOT = os.environ.get("ROCKJOINT_SOURCE_DIR",
                      os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def _report_rows():
    with open(os.path.join(ROOT, "bench", "results", "fe_speed_vs_error.json")) as f:
        return [r for r in json.load(f)["by_budget"] if r.get("met")]


def test_defaults_are_the_report_rows():
    rows = {r["error_budget"]: r for r in _report_rows()}
    assert sorted(rows) == sorted(s.error_budget for s in defaults.FE_SETTINGS)
    for s in defaults.FE_SETTINGS:
        r = rows[s.error_budget]
        assert s.element_degree == r["element_degree"]
        assert s.quadrature == r["joint_quadrature"]
        assert s.opening_size_over_radius == pytest.approx(r["opening_mesh_size_over_radius"])
        assert s.joint_size_over_spacing == pytest.approx(r["joint_mesh_size_over_spacing"])
        assert s.far_size_over_radius == pytest.approx(r["far_mesh_size_over_radius"])
        assert s.table_tolerance == pytest.approx(r["table_tolerance"])
        assert s.load_steps == r["excavation_load_steps"]
        assert s.measured_error == pytest.approx(r["answer_error"], rel=0.01)
        assert s.measured_error_second_scene == pytest.approx(r["second_scene_answer_error"], rel=0.01)
        assert max(r["answer_error"], r["second_scene_answer_error"]) <= s.error_budget


@pytest.mark.parametrize("budget, expect", [(0.2, 0.1), (0.1, 0.1), (0.05, 0.03), (0.03, 0.03)])
def test_loosest_row_within_the_budget(budget, expect):
    settings, met = defaults.fe_settings(budget)
    assert met and settings.error_budget == expect


def test_budget_tighter_than_the_report_says_so():
    settings, met = defaults.fe_settings(0.001)
    assert not met and settings.error_budget == min(s.error_budget for s in defaults.FE_SETTINGS)


def test_tunnel_plan_applies_the_report_ratios():
    scene = load_scene(os.path.join(ROOT, "demos", "scenes", "tunnel.yaml"))
    plan = make_plan(scene)
    fe, _ = defaults.fe_settings(scene.data["error_budget"])
    g = scene.data["geometry"]
    radius = g["opening"]["radius"]
    spacing = min(s["spacing"] for s in g["joint_sets"])
    h = scene.data["mesh"]["size"]
    assert plan.opening_size == pytest.approx(min(h, fe.opening_size_over_radius * radius))
    assert plan.joint_size == pytest.approx(min(h, fe.joint_size_over_spacing * spacing))
    assert plan.element_degree == fe.element_degree and plan.quadrature == fe.quadrature
    assert plan.table_tolerance == fe.table_tolerance
