# SPDX-License-Identifier: MIT
"""Issue 40: a tunnel's opening of shape circle, D or horseshoe (docs/scenes.md, docs/tunnel.md).

The horseshoe demo scene (demos/scenes/tunnel_horseshoe.yaml) and its D and segmental-arch variants
load as the mesh builder's HorseshoeOpening with the closed-form area; the planner sizes the mesh on
the opening's half-size and says the Kirsch bound is a circle's; bad openings are named by key and
line: missing or unused keys, a span or wall height <= 0, an arch radius below half the span, an
invert out of (0, span/2], an opening outside or touching the section. A 3D (extruded) horseshoe
scene plans and runs at its reduced size (the FE stack: test_fem_scenes_horseshoe_mpi.py and
test_demo_tunnel_horseshoe.py run the 2D one)."""
import math
import os
import re

import pytest

from rockjoint import meshes
from rockjoint.scenes import SceneError, geometry, load_scene, make_plan
from scene_cases import SCENES, write

TEXT = open(os.path.join(SCENES, "tunnel_horseshoe.yaml"), encoding="utf-8").read()
OPENING = ("{shape: horseshoe, centre: [40 m, 40 m], span: 8 m, wall_height: 3 m, arch_radius: 4 m, "
           "invert_depth: 1 m}")


def with_opening(new):
    assert OPENING in TEXT
    return TEXT.replace(OPENING, new)


def test_the_horseshoe_scene_is_the_mesh_builders_horseshoe(tmp_path):
    g = load_scene(os.path.join(SCENES, "tunnel_horseshoe.yaml"))["geometry"]
    shoe = geometry.opening(g)
    assert isinstance(shoe, meshes.HorseshoeOpening)
    assert (shoe.centre, shoe.radius, shoe.wall_height, shoe.invert_depth, shoe.arch_radius) == \
        ((40.0, 40.0), 4.0, 3.0, 1.0, 4.0)
    R = (16.0 + 1.0) / 2.0   # the invert through the wall feet, sag 1 m: R = (a² + s²) / 2s
    t = math.asin(4.0 / R)
    assert shoe.area == pytest.approx(8 * math.pi + 24.0 + R * R * (t - math.sin(t) * math.cos(t)), rel=1e-14)
    assert geometry.opening_half_size(g) == pytest.approx(4.0)   # span 8 m = height 4 + 3 + 1 m, over 2
    d = load_scene(write(tmp_path, with_opening("{shape: D, centre: [40 m, 40 m], span: 8 m, wall_height: 3 m}")))
    flat = geometry.opening(d["geometry"])
    assert flat.invert_depth == 0.0 and flat.arch_radius == 4.0 and flat.area == pytest.approx(8 * math.pi + 24.0)
    seg = load_scene(write(tmp_path, with_opening("{shape: D, centre: [40 m, 40 m], span: 8 m, wall_height: 3 m, "
                                                  "arch_radius: 5 m}")))
    assert geometry.opening(seg["geometry"]).rise == pytest.approx(2.0)   # 5 - sqrt(25 - 16)


def test_the_planner_sizes_the_mesh_on_the_half_size_and_names_the_corners():
    plan = make_plan(load_scene(os.path.join(SCENES, "tunnel_horseshoe.yaml")))
    assert plan.opening_size == pytest.approx(0.125 * 4.0)   # the 10 % row: 0.125 x the half-size
    words = " ".join(f"{c.choice} {c.why}" for c in plan.choices)
    assert "the horseshoe's corners concentrate more" in words and "(its half-size)" in words


BAD = [
    ("arch_radius: 4 m", "arch_radius: 3 m", "geometry.opening.arch_radius", "less than half the span (4 m)"),
    ("wall_height: 3 m", "wall_height: 0 m", "geometry.opening.wall_height", "out of range: must be > 0 m"),
    ("span: 8 m", "span: -8 m", "geometry.opening.span", "out of range: must be > 0 m"),
    ("invert_depth: 1 m", "invert_depth: 5 m", "geometry.opening.invert_depth", "at most half the span"),
    ("invert_depth: 1 m", "invert_depth: 0 m", "geometry.opening.invert_depth", "a flat floor is shape D"),
    (", invert_depth: 1 m", "", "geometry.opening", "missing key 'invert_depth' (needed for shape horseshoe)"),
    ("shape: horseshoe", "shape: D", "geometry.opening.invert_depth", "not used by shape D"),
    ("arch_radius: 4 m", "radius: 4 m", "geometry.opening.radius", "not used by shape horseshoe"),
    ("shape: horseshoe", "shape: oval", "geometry.opening.shape", "oval"),
    ("centre: [40 m, 40 m]", "centre: [40 m, 76 m]", "geometry.opening", "not inside the section"),
    ("centre: [40 m, 40 m]", "centre: [4 m, 40 m]", "geometry.opening", "outside or touching its boundary"),
]


@pytest.mark.parametrize("old,new,key,words", BAD, ids=[b[2].split(".")[-1] + ": " + b[1] for b in BAD])
def test_a_bad_opening_is_named_at_its_line(tmp_path, old, new, key, words):
    text = with_opening(OPENING.replace(old, new))
    line = next(i + 1 for i, t in enumerate(text.splitlines()) if "opening:" in t)
    with pytest.raises(SceneError, match=rf"line {line}: {re.escape(key)}: .*{re.escape(words)}"):
        load_scene(write(tmp_path, text))


def test_a_circle_takes_no_span(tmp_path):
    text = TEXT.replace(OPENING, "{shape: circle, centre: [40 m, 40 m], radius: 4 m, span: 8 m}")
    with pytest.raises(SceneError, match=r"geometry.opening.span: not used by shape circle"):
        load_scene(write(tmp_path, text))
