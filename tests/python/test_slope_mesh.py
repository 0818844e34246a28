# SPDX-License-Identifier: MIT
"""The slope section builder (meshes/slope.py, issue 40 item 1): the outline's groups have the
lengths of the geometry (closed forms), the blocks and joints of a plane failure, the joint
facets on their lines, and bad geometry named."""
import math

import numpy as np
import pytest

from rockjoint import meshes
from rockjoint.meshes.slope import SlopeGeometry, slope_section

GEOMETRY = SlopeGeometry(height=30.0, face_angle=60.0, base=15.0, toe_distance=20.0, crest_distance=30.0)


def group_length(jm, name):
    tag = {v: k for k, v in jm.names["boundaries"].items()}[name]
    f = jm.boundary_facets[jm.boundary_tags == tag]
    return float(np.linalg.norm(jm.points[f[:, 1]] - jm.points[f[:, 0]], axis=1).sum())


def plane_failure_joints(crack_x):
    plane = meshes.Joint(point=GEOMETRY.toe, dip=35.0, dip_direction=270.0, name="plane", bounded_by=("crack",))
    crack = meshes.Joint(point=(crack_x, 44.0), dip=90.0, dip_direction=90.0, name="crack", bounded_by=("plane",))
    return [plane, crack]


def test_the_outline_has_the_geometry_of_the_slope():
    jm = slope_section(GEOMETRY, [], mesh_size=3.0)
    g = GEOMETRY
    run = g.height / math.tan(math.radians(g.face_angle))
    expected = {"bottom": g.width, "right": g.base + g.height, "top": g.crest_distance,
                "face": g.height / math.sin(math.radians(g.face_angle)), "toe": g.toe_distance, "left": g.base}
    for name, length in expected.items():
        assert group_length(jm, name) == pytest.approx(length, rel=1e-12), name
    assert g.width == pytest.approx(g.toe_distance + run + g.crest_distance)
    a, b = (jm.points[jm.cells[:, k]] - jm.points[jm.cells[:, 0]] for k in (1, 2))
    area = 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]).sum()
    assert area == pytest.approx(g.width * (g.base + g.height) - g.toe_distance * g.height - 0.5 * run * g.height,
                                 rel=1e-12)


def test_a_plane_and_its_crack_cut_a_block_out_of_the_slope():
    crack_x = GEOMETRY.crest[0] + 6.0
    jm = slope_section(GEOMETRY, plane_failure_joints(crack_x), mesh_size=3.0, joint_mesh_size=1.0)
    assert len(jm.names["blocks"]) == 3            # the block, the rock behind and under it, the toe's wedge below
    assert sorted(jm.names["joints"].values()) == ["crack", "plane"]
    tags = {v: k for k, v in jm.names["joints"].items()}
    x = jm.points[jm.joint_facets_minus]
    crack = x[jm.joint_tags == tags["crack"]]
    np.testing.assert_allclose(crack[..., 0], crack_x, atol=1e-9)
    plane = x[jm.joint_tags == tags["plane"]]
    np.testing.assert_allclose(plane[..., 1] - GEOMETRY.base, (plane[..., 0] - GEOMETRY.toe[0]) * math.tan(math.radians(35)),
                               atol=1e-9)
    assert plane[..., 0].max() == pytest.approx(crack_x, abs=1e-9)          # the plane ends on the crack
    assert crack[..., 1].min() == pytest.approx(GEOMETRY.base + (crack_x - 20.0) * math.tan(math.radians(35)), abs=1e-9)


def test_bad_slopes_are_refused_by_name():
    with pytest.raises(ValueError, match="face_angle"):
        SlopeGeometry(height=30.0, face_angle=95.0, base=15.0, toe_distance=20.0, crest_distance=30.0)
    with pytest.raises(ValueError, match="height"):
        SlopeGeometry(height=-1.0, face_angle=60.0, base=15.0, toe_distance=20.0, crest_distance=30.0)
    with pytest.raises(ValueError, match="joint 'high' .*misses the slope"):
        slope_section(GEOMETRY, [meshes.Joint(point=(10.0, 80.0), dip=0.0, name="high")], mesh_size=3.0)
    # the plane ends on the crack's line below where the crack (bounded by a shallow joint) exists
    with pytest.raises(ValueError, match="joint 'plane' does not separate two blocks.*bounded_by"):
        slope_section(GEOMETRY, [meshes.Joint(point=(60.0, 44.8), dip=90.0, name="crack", bounded_by=("shallow",)),
                                 meshes.Joint(point=(60.0, 44.5), dip=0.0, name="shallow"),
                                 meshes.Joint(point=GEOMETRY.toe, dip=35.0, dip_direction=270.0, name="plane",
                                              bounded_by=("crack",))],
                      mesh_size=3.0)
