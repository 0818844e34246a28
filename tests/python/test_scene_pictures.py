# SPDX-License-Identifier: MIT
"""Scene pictures a rock engineer reads at a glance (rockjoint.scenes.pictures): a tunnel scene adds
the opening four radii across, at a stated magnification that draws the largest displacement as a
few per cent of the radius; joints are drawn by state (stick, slip, open) with a legend of the
states present; a 3D tunnel gets the same view on the section through the opening. The figure
written is captured (pictures.save) and read back: titles, axis limits, caption, legend."""
import os
import re

import numpy as np
import pytest

from rockjoint.scenes import load_scene, make_plan, pictures, run_scene
from scene_cases import SCENES, write

CAPTION = re.compile(r"displacements x (\S+): the largest, (\S+) mm,\nis drawn as (\S+) % of the "
                     r"radius \((\S+) m\)")


def run_capturing(scene_path, output, monkeypatch):
    """Run a scene reduced; return (scene, result, {model: joint states}, the figure's axes)."""
    figures, states = [], {}
    save, joint_states = pictures.save, pictures.joint_states

    def keep(fig, path):
        figures.append([(ax.get_title(), ax.get_xlim(), ax.get_ylim(),
                         [t.get_text() for t in ax.texts],
                         [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else None)
                        for ax in fig.axes])
        save(fig, path)

    def record(model):
        out = joint_states(model)
        states[len(states)] = out
        return out

    monkeypatch.setattr(pictures, "save", keep)
    monkeypatch.setattr(pictures, "joint_states", record)
    scene = load_scene(str(scene_path)).at_reduced_size()
    result = run_scene(scene, make_plan(scene), str(output))
    assert len(figures) == 1 and os.path.getsize(os.path.join(output, "scene.png")) > 10000
    return scene, result, states, figures[0]


def check_opening_view(axes, opening, largest_model_displacement, title_part, section=False):
    """The opening views: four radii across, centred; the caption's numbers agree with each other;
    one magnification puts the largest displacement of the views at 2-5 % of the radius. Returns
    the views."""
    (cx, cy), r = opening["centre"][:2], opening["radius"]
    views = [a for a in axes if "opening (4 radii across)" in a[0]]
    assert len(views) == 2 and all(title_part in a[0] for a in views)   # jointed and intact
    largest, scales = [], set()
    for title, xlim, ylim, texts, _ in views:
        assert xlim == pytest.approx((cx - 2 * r, cx + 2 * r)) and ylim == pytest.approx((cy - 2 * r, cy + 2 * r))
        (m,) = [CAPTION.search(t) for t in texts if CAPTION.search(t)]
        scale, mm, percent, radius = (float(g) for g in m.groups())
        assert radius == r
        assert 100 * scale * mm * 1e-3 / r <= 5.0, title
        assert float(percent) == pytest.approx(100 * scale * mm * 1e-3 / r, rel=0.05)
        largest.append(mm * 1e-3)
        scales.add(scale)
    # one magnification for all views (jointed and intact compare at a glance), chosen so that
    # the largest displacement of any view is drawn as 2-5 % of the radius
    assert len(scales) == 1
    assert 2.0 <= 100 * scales.pop() * max(largest) / r <= 5.0
    # the largest displacement in the views is the model's (at the opening's wall), to the caption's
    # 3 digits; a 3D section shows the in-plane part at one y: not more, and most of it here (a
    # prism held at both ends deforms nearly in plane strain)
    if section:
        assert 0.95 * largest_model_displacement <= max(largest) <= largest_model_displacement * (1 + 5e-3)
    else:
        assert max(largest) == pytest.approx(largest_model_displacement, rel=5e-3)
    return views


def test_tunnel_picture_has_the_opening_view_and_joint_states(tmp_path, monkeypatch):
    scene, result, states, axes = run_capturing(os.path.join(SCENES, "tunnel.yaml"), tmp_path / "t",
                                                monkeypatch)
    opening = scene.data["geometry"]["opening"]
    jointed = result.row("jointed", "lining")
    views = check_opening_view(axes, opening, jointed.max_displacement, "tunnel")
    # joints by state: the legend of the jointed views lists exactly the states of its points,
    # slip among them (the summary counts slipping points); the intact model has no legend
    present = set(states[0]["state"])
    assert jointed.slipping > 0 and "slip" in present
    expected = [f"joint: {s}" for s in pictures.STATE_COLOURS if s in present]
    overview = [a for a in axes if a[0].startswith("tunnel: jointed (u x")]
    assert len(overview) == 1 and overview[0][4] == expected
    assert views[0][4] == expected and views[1][4] is None
    assert int(np.count_nonzero(states[0]["state"] == "slip")) == jointed.slipping


#: a 3D tunnel (its section extruded 4 m along y) held at both ends, excavated in situ
TUNNEL_3D = """\
name: tunnel3d
geometry:
  kind: tunnel
  width: 32 m
  height: 32 m
  length: 4 m
  opening: {shape: circle, centre: [16 m, 16 m], radius: 4 m}
rock: {young: 50 GPa, poisson: 0.25}
in_situ: {vertical: 7.9461 MPa, horizontal_ratio: 0.5}
supports: {left: x, right: x, bottom: z, top: z, front: y, back: y}
stages:
  - {name: excavation, excavate: opening, steps: 2}
error_budget: 10 %
mesh: {size: 2 m}
outputs: {pictures: true, xdmf: false, monitor: [opening]}
reduced: {mesh_size: 4 m, load_steps: 2}
"""


def test_3d_tunnel_picture_has_the_section_through_the_opening(tmp_path, monkeypatch):
    path = write(tmp_path, TUNNEL_3D)
    scene, result, _, axes = run_capturing(path, tmp_path / "t3", monkeypatch)
    # the section's in-plane displacement (u_x, u_z) at its largest is at most the model's |u|
    views = check_opening_view(axes, scene.data["geometry"]["opening"],
                               result.row("jointed", "excavation").max_displacement, "tunnel3d", section=True)
    assert all("section y = 2 m" in title for title, *_ in views)


def test_nice_scale_and_joint_segments():
    assert [pictures.nice_scale(v) for v in (1.0, 3.7, 180.0, 0.049)] == [1.0, 2.0, 100.0, 0.02]
    # one joint along x with a gap (an opening) between x = 2 and x = 10: not bridged; each point
    # owns half a gap on each side, coloured by its own state
    x = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [10.0, 0.0], [11.0, 0.0]])
    state = np.array(["stick", "slip", "slip", "open", "stick"], dtype=object)
    segments = pictures.joint_segments(x, state, np.zeros(5, int), lambda p: np.zeros_like(p))
    lengths = {k: float(np.abs(v[:, 1, 0] - v[:, 0, 0]).sum()) for k, v in segments.items()}
    assert lengths == pytest.approx({"stick": 1.0, "slip": 1.5, "open": 0.5})


def test_joints_near_a_3d_section_are_its_layer_of_nodes_in_section_coordinates():
    # a horizontal joint z = 5 with nodes at y = 0, 1, 2 (1 apart); the section y = 1.2 takes the
    # layer y = 1 and gives (x, z)
    x = np.array([[float(i), float(y), 5.0] for y in (0, 1, 2) for i in range(3)])
    joints = {"x": x, "state": np.array(["stick", "slip", "open"] * 3, dtype=object),
              "tag": np.zeros(9, int)}
    section = np.array([[[0, 0], [1, 0], [0, 1]]], float)    # edges about 1 long
    near = pictures._near_section(joints, 1.2, section)
    np.testing.assert_array_equal(near["x"], [[0, 5], [1, 5], [2, 5]])
    assert list(near["state"]) == ["stick", "slip", "open"]


TUNNEL_3D_JOINTED = TUNNEL_3D.replace("name: tunnel3d\n", "name: tunnel3d jointed\n").replace(
    "radius: 4 m}\n", """radius: 4 m}
  joint_sets:
    - {name: bedding, point: [16 m, 2 m, 19 m], dip: 0 deg, spacing: 6 m, count: 1}
    - {name: cross, point: [21 m, 2 m, 16 m], dip: 60 deg, dip_direction: 90 deg, spacing: 6 m, count: 1}
""").replace("supports:", """joints:
  bedding: &law
    law:
      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
    strength: {model: coulomb, friction_angle: 30 deg, cohesion: 0 MPa}
  cross: *law
supports:""").replace("mesh: {size: 2 m}", "mesh: {size: 2 m, joint_size: 1 m}")


def plane_strain_twin(scene_3d: str) -> str:
    """The 2D scene of a 3D tunnel held at both ends: its section, the joint sets through (x, z)."""
    out = scene_3d.replace("  length: 4 m\n", "").replace("[16 m, 2 m, 19 m]", "[16 m, 19 m]")
    out = out.replace("[21 m, 2 m, 16 m]", "[21 m, 16 m]")
    return out.replace("supports: {left: x, right: x, bottom: z, top: z, front: y, back: y}",
                       "supports: {left: x, right: x, bottom: y, top: y}")


def test_3d_tunnel_with_joint_sets_is_its_plane_strain_section(tmp_path):
    """A prism held at both ends (front, back: y) deforms in plane strain, so the 3D tunnel with
    joint sets along its axis gives the 2D scene's answer (an independent computation: triangles
    and line joints against tetrahedra and joint planes). Measured at this mesh (2 m, joints 1 m):
    intact 0.6 %, jointed with slip 1.1 %; bounds 1 % and 3 %. (Closer to a mechanism the slip
    grows and so does the gap between the two discretisations: 6 % at φ = 25°, 11 % at 20°.)"""
    from rockjoint.scenes import run_scene as run
    rows = {}
    for dim, text in ((3, TUNNEL_3D_JOINTED), (2, plane_strain_twin(TUNNEL_3D_JOINTED))):
        text = text.replace("pictures: true", "pictures: false")
        scene = load_scene(str(write(tmp_path, text)))
        assert scene.data["geometry"]["dimension"] == dim
        result = run(scene, make_plan(scene), str(tmp_path / f"d{dim}"))
        rows[dim] = {m: result.row(m, "excavation") for m in ("jointed", "intact")}
    assert rows[3]["jointed"].slipping > 0 and rows[2]["jointed"].slipping > 0
    assert rows[3]["intact"].max_displacement == pytest.approx(rows[2]["intact"].max_displacement, rel=0.01)
    assert rows[3]["jointed"].max_displacement == pytest.approx(rows[2]["jointed"].max_displacement, rel=0.03)
    # the joints matter: the jointed opening moves clearly more than the intact one
    assert rows[2]["jointed"].max_displacement > 1.2 * rows[2]["intact"].max_displacement


def test_3d_tunnel_with_joint_sets_runs_and_draws_them_on_the_section(tmp_path, monkeypatch):
    """Joint sets in a 3D tunnel run along its axis (y): each is the section's joint extruded. The
    run meshes them as planes (every joint point lies on its set's plane), and the section view
    draws them by state with a legend of exactly the states present near the section."""
    path = write(tmp_path, TUNNEL_3D_JOINTED)
    scene, result, states, axes = run_capturing(path, tmp_path / "t3j", monkeypatch)
    joints = states[0]
    x = np.asarray(joints["x"])
    assert x.shape[1] == 3 and x.shape[0] > 0
    # every joint point on one of the two planes: z = 19 (bedding) or the 60° plane through
    # (21, ·, 16) dipping toward +x, normal (sin 60°, 0, cos 60°)
    n = np.array([np.sin(np.radians(60.0)), 0.0, np.cos(np.radians(60.0))])
    on_bedding = np.abs(x[:, 2] - 19.0) < 1e-9
    on_cross = np.abs((x - [21.0, 0.0, 16.0]) @ n) < 1e-9
    assert np.all(on_bedding | on_cross) and on_bedding.any() and on_cross.any()
    assert x[:, 1].min() == pytest.approx(0.0) and x[:, 1].max() == pytest.approx(4.0)   # whole length
    views = check_opening_view(axes, scene.data["geometry"]["opening"],
                               result.row("jointed", "excavation").max_displacement, "tunnel3d jointed",
                               section=True)
    legend = views[0][4]
    assert legend and all(t.startswith("joint: ") for t in legend) and views[1][4] is None


def test_3d_tunnel_joint_set_across_the_axis_is_refused(tmp_path):
    from rockjoint.scenes import SceneError
    bad = TUNNEL_3D_JOINTED.replace("dip: 60 deg, dip_direction: 90 deg", "dip: 60 deg, dip_direction: 0 deg")
    with pytest.raises(SceneError, match="runs along the tunnel axis y"):
        load_scene(str(write(tmp_path, bad)))
    outside = TUNNEL_3D_JOINTED.replace("[16 m, 2 m, 19 m]", "[16 m, 5 m, 19 m]")   # y beyond the length
    with pytest.raises(SceneError, match="not inside the geometry"):
        load_scene(str(write(tmp_path, outside)))
