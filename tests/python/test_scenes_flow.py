# SPDX-License-Identifier: MIT
"""A scene's flow (outputs: {flow: {heads: ...}}, docs/flow.md): the column scene with heads on its
sides. The jointed model's joint carries the cubic law's closed form at the closure its law gives
(Barton-Bandis inverse at the column's stress, written out here), the intact model the Darcy
closed form of its rock permeability, both in the summary; the network is written for ParaView;
the schema names every mistake."""
import os

import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint.scenes import SceneError, load_scene, make_plan, run_scene  # noqa: E402
from rockjoint.scenes.runner import summary_table  # noqa: E402
from scene_cases import COLUMN, write  # noqa: E402

RHO_G_MU = 998.2 * 9.80665 / 1.002e-3     # ρ g / μ of water at 20 °C [1/(m s)]
KNI, VM, STRESS = 20e9, 0.2e-3, 10e6       # the column scene's law and load
E0, K_ROCK = 0.3e-3, 1e-18                 # initial aperture [m], rock permeability [m²]
WIDTH, HEIGHT = 0.1, 0.1                   # [m]
H_LEFT, H_RIGHT = 50.0, 10.0               # [m]
FLOW = """      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
    flow: {law: cubic_law, initial_aperture: 0.3 mm}
"""
LAW_TEXT = """      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
"""


def scene_text(flow_entry=FLOW, outputs="outputs: {monitor: [top], flow: {heads: {left: 50 m, right: 10 m}}}"):
    assert LAW_TEXT in COLUMN
    text = COLUMN.replace(LAW_TEXT, flow_entry).replace("outputs: {monitor: [top]}", outputs)
    text = text.replace("  poisson: 0.25\n", "  poisson: 0.25\n  permeability: 1e-18 m²\n")
    return text + "plan: {table_tolerance: 1e-7}\n"


def test_jointed_and_intact_flow_against_closed_forms(tmp_path):
    scene = load_scene(write(tmp_path, scene_text()))
    result = run_scene(scene, make_plan(scene), str(tmp_path / "out"))
    closure = STRESS * VM / (KNI * VM + STRESS)
    joint = RHO_G_MU * (E0 - closure) ** 3 / 12 * (H_LEFT - H_RIGHT) / WIDTH     # per metre [m²/s]
    rock = RHO_G_MU * K_ROCK * (H_LEFT - H_RIGHT) / WIDTH * HEIGHT
    j, i = result.row("jointed", "load"), result.row("intact", "load")
    # the table (tolerance 1e-7) and the FE closure (Newton to 1e-10) are the only departures
    assert j.flow_rates["left"] == pytest.approx(joint, rel=1e-5)
    assert j.flow_rates["right"] == pytest.approx(-joint, rel=1e-5)
    assert i.flow_rates["left"] == pytest.approx(rock, rel=1e-8)
    assert "jointed_flow.xdmf" in result.files
    text = summary_table(result)
    assert "flow in at left [L/min/m]" in text and f"{joint * 6e4:.5g}" in text


@pytest.mark.parametrize("edit, words", [
    ((FLOW, LAW_TEXT), "give the set's transmissivity"),
    (("{law: cubic_law, initial_aperture: 0.3 mm}", "{law: cubic_law}"), "cubic_law needs initial_aperture"),
    (("{law: cubic_law, initial_aperture: 0.3 mm}", "{law: darcy, initial_aperture: 0.3 mm}"),
     "'darcy' is not a transmissivity law"),
    (("{law: cubic_law, initial_aperture: 0.3 mm}", "{law: cubic_law, initial_aperture: 0.3 mm, jrc: 8}"),
     "not a parameter of cubic_law"),
    (("{law: cubic_law, initial_aperture: 0.3 mm}", "{law: walls}"), "needs the set's walls"),
    (("left: 50 m", "east: 50 m"), "no boundary 'east'"),
    (("left: 50 m", "left: 50"), "has no unit"),
])
def test_bad_flow_entries_are_named(tmp_path, edit, words):
    with pytest.raises(SceneError, match=words):
        load_scene(write(tmp_path, scene_text().replace(*edit)))


def test_a_set_from_its_walls_carries_their_transmissivity(tmp_path):
    """law: topography with flow: {law: walls}: the jointed column's flow equals (ρ g / μ) T Δh / W
    with T of the same walls (built here from the scene's scan: BEM contact and Reynolds flow at the
    loads of the exact contact curve up to the plan's table stress) at the joint's FE closure."""
    import numpy as np
    from rockjoint import composite_modulus, contact, flow
    from rockjoint import topography as topo
    from rockjoint.scenes import ladder
    topo_text = ("      topography: {hurst: 0.8, rms_height: 0.2 mm, points: 64, spacing: 0.5 mm, "
                 "matedness: 2.5 mm, seed: 3}\n    flow: {law: walls}\n")
    scene = load_scene(write(tmp_path, scene_text(flow_entry=topo_text)))
    plan = make_plan(scene)
    result = run_scene(scene, plan, str(tmp_path / "out"))
    j = result.row("jointed", "load")
    closure = j.per_set["joint"][0]                      # uniform: the column carries σ everywhere
    spec = topo.SelfAffineSpec(hurst_exponent=0.8, rms_height=0.2e-3)
    upper, lower = topo.mated_pair(spec, (64, 64), 0.5e-3, 2.5e-3, seed=3)
    aperture = topo.composite_topography(upper, lower, offset=(0, 0)).aperture
    curve = contact.closure_curve(aperture, composite_modulus(50e9, 0.25),
                                  ladder.contact_stresses(plan.table_max_stress), flow=True)
    t = flow.transmissivity_law("walls", curve=curve).transmissivity(closure)
    expected = RHO_G_MU * t * (H_LEFT - H_RIGHT) / WIDTH
    assert np.isfinite(expected) and expected > 0
    assert j.flow_rates["left"] == pytest.approx(expected, rel=1e-6)
