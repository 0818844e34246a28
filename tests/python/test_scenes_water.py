# SPDX-License-Identifier: MIT
"""A scene's water (`water:`, docs/flow.md "Water in scenes"): the column scene (one horizontal
Barton-Bandis joint, cubic-law transmissivity, soft blocks that pass the stress on uniformly) under
an isotropic in-situ stress σ = 10 MPa, below a water table. Against closed forms written out here, independent of the code:

- the table's hydrostatic p0 = ρ g (z_table - z) in the joint; its in-situ closure the law's at
  σ - p0 (Barton-Bandis inverse);
- one way, heads h_L, h_R on the sides: the cubic law at that closure, Q = (ρ g/μ) T Δh / W
  (per metre in 2D; times the depth W of the 3D column);
- two ways: T follows p = ρ g (h - z) along the joint, q = -(ρ g/μ) T(h) dh/dx constant, so
  Q W = (ρ g/μ) ∫ T(Δ(σ - ρ g (h - z))) dh from h_R to h_L (SciPy quad);
- unloaded below the water's pressure (one way: p stays p0), the joint is held open by the water
  alone: k_r Δ = σ - p0 < 0, every point counted as opened by water; dry, none.
"""
import os

import numpy as np
import pytest
from scipy.integrate import quad

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint.scenes import SceneError, load_scene, make_plan, run_scene  # noqa: E402
from rockjoint.scenes.runner import summary_table  # noqa: E402
from scene_cases import COLUMN, write  # noqa: E402

RHO, G, MU = 998.2, 9.80665, 1.002e-3        # water at 20 °C, standard gravity
KNI, VM, E0 = 20e9, 0.2e-3, 0.3e-3             # the law, the initial aperture [m]
SIGMA, WIDTH, Z_JOINT = 10e6, 0.1, 0.05         # in-situ stress [Pa], column width, joint height [m]
TABLE, H_LEFT, H_RIGHT = 500.0, 500.0, 440.0    # [m]
P0 = RHO * G * (TABLE - Z_JOINT)


def closure(s, kr=0.0):
    """Δ with σ_BB(Δ) + k_r Δ = s (σ_BB = K Δ / (1 - Δ/V)); open (s < 0): k_r Δ = s."""
    if s <= 0:
        return s / kr
    if kr == 0:
        return s * VM / (KNI * VM + s)
    a, b = kr / VM, -(KNI + kr + s / VM)
    return (-b - (b * b - 4 * a * s) ** 0.5) / (2 * a)


def transmissivity(s):
    """The cubic law T = e³/12 of the aperture e = E0 - Δ(s) [m³]."""
    return (E0 - closure(s)) ** 3 / 12


def scene_text(water, stages="  - {name: hold}\n", residual="", extra="", soft=True, dim=2):
    text = COLUMN.replace("    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}\n",
                          "    flow: {law: cubic_law, initial_aperture: 0.3 mm}\n" + residual)
    text = text.replace("  - name: load\n    loads: {top: {traction: [0 MPa, -10 MPa]}}\n", stages)
    text = text.replace("mesh: {size: 25 mm}", "mesh: {size: 25 mm, joint_size: 2.5 mm}")
    # soft blocks (E << the joint's stiffness x the column's height): they pass the stress to the
    # joint uniformly, whatever its stiffness along it (no arching: σ_n = σ, the references' case)
    if dim == 3:   # the column as a 0.1 m deep box, its joint a plane; 10 mm triangles on it
        text = text.replace("geometry: {kind: column,", "geometry: {kind: column, dimension: 3,")
        text = text.replace("joint_size: 2.5 mm", "joint_size: 10 mm")
        text = text.replace("supports: {bottom: y, left: x}", "supports: {bottom: z, left: x, front: y}")
    if soft:
        text = text.replace("  young: 50 GPa\n  poisson: 0.25\n", "  young: 1 MPa\n  poisson: 0\n")
    return (text + "in_situ: {vertical: 10 MPa, horizontal_ratio: 1}\nplan: {table_tolerance: 1e-7}\n"
            + (f"water: {water}\n" if water else "") + extra)


def run(tmp_path, text):
    tmp_path.mkdir(exist_ok=True)
    scene = load_scene(write(tmp_path, text))
    return run_scene(scene, make_plan(scene), str(tmp_path / "out"))


@pytest.mark.parametrize("dim, coupling", [(2, "one_way"), (2, "two_way"), (3, "two_way")])
def test_the_table_pre_closes_the_joint_and_the_flow_follows_the_coupling(tmp_path, dim, coupling):
    """In 3D the flow is the 2D flow per metre times the column's depth (WIDTH)."""
    result = run(tmp_path, scene_text(f"{{table: {TABLE:g} m, coupling: {coupling}, heads: "
                                      f"{{left: {H_LEFT:g} m, right: {H_RIGHT:g} m}}}}", dim=dim))
    depth = WIDTH if dim == 3 else 1.0
    one_way = depth * RHO * G / MU * transmissivity(SIGMA - P0) * (H_LEFT - H_RIGHT) / WIDTH
    two_way = depth * RHO * G / MU / WIDTH * quad(lambda h: transmissivity(SIGMA - RHO * G * (h - Z_JOINT)),
                                          H_RIGHT, H_LEFT, epsabs=0, epsrel=1e-12)[0]
    assert abs(two_way / one_way - 1) > 0.02          # the two answers differ: the test tells them apart
    for stage in ("in-situ", "hold"):
        row = result.row("jointed", stage)
        expected = one_way if coupling == "one_way" else two_way
        assert row.flow_rates["left"] == pytest.approx(expected, rel=1e-5), stage
        assert row.flow_rates["right"] == pytest.approx(-row.flow_rates["left"], rel=1e-9)
        assert row.water.opened_by_water == 0
        if coupling == "one_way":   # the joint sees the table's water only
            assert row.max_closure == pytest.approx(closure(SIGMA - P0), rel=1e-6)
            assert row.water.max_pressure == pytest.approx(P0, rel=1e-12)
        else:                       # the left end's water, ρ g (h_L - z), now acting on the joint
            assert row.water.max_pressure == pytest.approx(RHO * G * (H_LEFT - Z_JOINT), rel=1e-8)
            # from the table's water the in-situ stage must iterate; the next starts where it ended
            assert row.water.iterations >= (2 if stage == "in-situ" else 1)
    assert result.row("intact", "hold").water.max_pressure == 0.0
    # the network for ParaView: the pressure beside the head, p = ρ g (h - z) at every node
    import meshio  # Debian python3-meshio, as the writer
    grid = meshio.read(str(tmp_path / "out" / "jointed_flow.xdmf"))
    z = grid.points[:, dim - 1]
    assert grid.point_data["pressure_Pa"] == pytest.approx(RHO * G * (grid.point_data["head_m"] - z), rel=1e-12)
    assert grid.point_data["pressure_Pa"].max() == pytest.approx(RHO * G * (H_LEFT - Z_JOINT), rel=1e-12)
    text = summary_table(result)
    assert "water: largest joint p [MPa]" in text and f"{P0 * 1e-6:14.5g}" in text


def test_water_alone_holds_an_unloaded_joint_open(tmp_path):
    """k_r = 1 GPa/m; the top pulled up by 6 MPa leaves σ = 4 MPa on the joint, below p0 = 4.9 MPa."""
    kr = 1e9
    unload = "  - name: unload\n    loads: {top: {traction: [0 MPa, 6 MPa]}}\n"
    residual = "    residual_stiffness: 1 GPa/m\n"
    wet = run(tmp_path / "wet", scene_text(f"{{table: {TABLE:g} m}}", unload, residual, soft=False)).row("jointed", "unload")
    dry = run(tmp_path / "dry", scene_text("", unload, residual, soft=False)).row("jointed", "unload")
    # open (Δ < 0): k_r Δ = σ - p0. The scene's law is a table, whose linear continuation below
    # Δ = 0 still carries a little stress (-152 Pa at this Δ, 1.7e-4 of σ - p0): that is the
    # departure allowed here, not the water's
    assert wet.max_closure == pytest.approx(closure(SIGMA - 6e6 - P0, kr), rel=2e-4)
    assert wet.water.opened_by_water == 2 * 40   # every point: 40 joint elements of 2.5 mm, 2 points each
    assert dry.max_closure == pytest.approx(closure(SIGMA - 6e6, kr), rel=1e-6)
    assert dry.water.opened_by_water == 0 and not dry.water.wet


@pytest.mark.parametrize("water, words", [
    ("{coupling: two_way}", "two_way needs the flow's boundaries"),
    ("{coupling: both}", "'both' is not one of one_way, two_way"),
    ("{table: 500}", "has no unit"),
    ("{heads: {east: 10 m}}", "no boundary 'east'"),
    ("{pressures: {left: -1 MPa}}", "out of range"),
    ("{opening: drained}", "a column has no opening"),
    ("{tide: 3 m}", "unknown key 'tide'"),
])
def test_bad_water_is_named(tmp_path, water, words):
    with pytest.raises(SceneError, match=words):
        load_scene(write(tmp_path, scene_text(water)))


def test_water_and_the_older_flow_output_are_not_both_given(tmp_path):
    text = scene_text("{heads: {left: 10 m}}").replace("outputs: {monitor: [top]}",
                                                        "outputs: {monitor: [top], flow: {heads: {left: 10 m}}}")
    with pytest.raises(SceneError, match="the scene has water"):
        load_scene(write(tmp_path, text))
    with pytest.raises(SceneError, match="needs the in-situ stress"):
        load_scene(write(tmp_path, scene_text("{table: 10 m}").replace(
            "in_situ: {vertical: 10 MPa, horizontal_ratio: 1}\n", "")))


def test_the_picture_colours_the_joints_by_their_water(tmp_path, monkeypatch):
    """scene.png gets a row with the jointed model's joints coloured by p [MPa]: the colours are
    the joints' pressures, from the left end's ρ g (h_L - z) down to the right end's (two ways)."""
    from rockjoint.scenes import pictures
    drawn, save = [], pictures.save

    def keep(fig, path):
        for ax in fig.axes:
            for lines in ax.collections:
                if ax.get_title().endswith("water in the joints") and lines.get_array() is not None \
                        and lines.get_array().size and hasattr(lines, "get_segments"):
                    drawn.append(np.asarray(lines.get_array()))
        save(fig, path)

    monkeypatch.setattr(pictures, "save", keep)
    run(tmp_path, scene_text(f"{{table: {TABLE:g} m, coupling: two_way, heads: "
                             f"{{left: {H_LEFT:g} m, right: {H_RIGHT:g} m}}}}"))
    (values,) = drawn
    assert values.max() == pytest.approx(RHO * G * (H_LEFT - Z_JOINT) * 1e-6, rel=1e-8)
    assert values.min() == pytest.approx(RHO * G * (H_RIGHT - Z_JOINT) * 1e-6, rel=1e-8)


def test_a_drained_opening_alone_gives_no_flow_before_it_is_excavated(tmp_path):
    """water: {table, opening: drained} and no other boundary: before excavation nothing drains
    (no flow, the table's water stays); after it, two ways, with nothing to recharge it the steady
    network drains into the opening: no net flow, and every head within the wall's (h = z there,
    z from 36 to 44 m: the maximum principle), so p <= ρ g (44 m - z) <= ρ g 44 m."""
    from scene_cases import SCENES
    text = open(os.path.join(SCENES, "tunnel_below_water_table.yaml"), encoding="utf-8").read()
    text = text.replace("  heads: {left: 140 m, right: 140 m, bottom: 140 m, top: 140 m}\n", "")
    scene = load_scene(write(tmp_path, text)).at_reduced_size()
    result = run_scene(scene, make_plan(scene), str(tmp_path / "out"))
    before, after = result.row("jointed", "in-situ"), result.row("jointed", "excavation")
    assert before.flow_rates is None and before.water.max_pressure == pytest.approx(RHO * G * 140.0, rel=1e-12)
    assert abs(after.flow_rates["opening"]) < 1e-12 and after.water.iterations > 0
    assert after.water.max_pressure <= RHO * G * 44.0 * (1 + 1e-9)
