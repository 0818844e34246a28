# SPDX-License-Identifier: MIT
"""meshes.from_gmsh_model / from_msh_file: the user's own gmsh model, read by physical names.

References: closed-form geometry of the case (a square/cube cut through its centre by a joint
dipping 30°: each block holds half the area/volume, the joint is SIZE/cos(dip) long or
SIZE²/cos(dip) in area), and the gmsh mesh itself (node and element counts). Every malformed
model must raise a ValueError that names the group or entity and says what to do.
"""
import math

import gmsh
import numpy as np
import pytest

from rockjoint import meshes
from rockjoint.meshes.builders import _ensure_gmsh

import user_model_geometry as case


@pytest.fixture(autouse=True)
def gmsh_model():
    _ensure_gmsh(gmsh)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.option.setNumber("Mesh.RecombineAll", 0)
    before = len(gmsh.model.list())
    yield
    while len(gmsh.model.list()) > before:  # the models this test added
        gmsh.model.remove()
    gmsh.option.setNumber("Mesh.RecombineAll", 0)  # gmsh options are global: quadrangles end here


def facet_measure(x):
    if x.shape[1] == 2:
        return np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
    return 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)


@pytest.mark.parametrize("dim", [2, 3])
def test_blocks_joint_and_boundaries_are_read_and_split(dim):
    case.build_gmsh_model(gmsh, dim, 0.5 if dim == 2 else 0.7)
    n_gmsh_nodes = gmsh.model.mesh.getNodes()[0].size
    jm = meshes.from_gmsh_model(joints=["fault"])
    assert sorted(jm.names["blocks"].values()) == ["lower", "upper"]
    assert list(jm.names["joints"].values()) == ["fault"]
    expected_sides = {"bottom", "top", "left", "right"} | ({"front", "back"} if dim == 3 else set())
    assert set(jm.names["boundaries"].values()) == expected_sides
    # Each block holds half the square/cube (the joint passes through the centre).
    half = 0.5 * case.SIZE ** dim
    for tag, volume in jm.block_measures().items():
        assert volume == pytest.approx(half, rel=1e-10), jm.names["blocks"][tag]
    # Joint length/area from the pairs, and the split: one copy per joint node.
    joint = facet_measure(jm.points[jm.joint_facets_minus]).sum()
    assert joint == pytest.approx(case.SIZE ** (dim - 1) / math.cos(case.DIP), rel=1e-10)
    joint_nodes = np.unique(jm.joint_facets_minus)
    assert jm.points.shape[0] == n_gmsh_nodes + joint_nodes.size
    # Minus side = lower physical tag; the normal points into the other block (upward here).
    x = jm.points[jm.joint_facets_minus]
    n = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]) if dim == 3 else \
        np.stack([(x[:, 1] - x[:, 0])[:, 1], -(x[:, 1] - x[:, 0])[:, 0]], axis=1)
    minus_block = jm.cell_blocks[jm.joint_facet_cells[:, 0]]
    lower = jm.tag("blocks", "lower")
    upward = n[:, dim - 1] > 0
    assert np.all(upward == (minus_block == lower)) and np.all(minus_block == min(jm.names["blocks"]))


def test_a_msh_file_reads_like_the_model(tmp_path):
    case.build_gmsh_model(gmsh, 2, 0.5)
    from_model = meshes.from_gmsh_model(joints=["fault"], boundaries=["bottom", "top"])
    path = str(tmp_path / "case.msh")
    gmsh.write(path)
    gmsh.model.remove()
    from_file = meshes.from_msh_file(path, joints=["fault"], boundaries=["bottom", "top"])
    # The .msh text keeps 16 significant digits.
    np.testing.assert_allclose(from_file.points, from_model.points, rtol=0, atol=1e-14 * case.SIZE)
    for name in ("cells", "cell_blocks", "joint_facets_minus", "joint_facets_plus", "boundary_tags"):
        assert np.array_equal(getattr(from_model, name), getattr(from_file, name)), name
    assert from_file.names == from_model.names
    with pytest.raises(ValueError, match="no file"):
        meshes.from_msh_file(str(tmp_path / "none.msh"), joints=[])


def test_missing_groups_are_named_with_the_available_ones():
    case.build_gmsh_model(gmsh, 2, 0.5)
    with pytest.raises(ValueError, match=r"joints: no dimension-1 physical group named 'upper'; 'upper' is a "
                                         r"dimension-2 group; available: "
                                         r"\['bottom', 'fault', 'left', 'right', 'top'\]"):
        meshes.from_gmsh_model(joints=["upper"])
    with pytest.raises(ValueError, match=r"blocks: no dimension-2 physical group named 'granite'; available: "
                                         r"\['lower', 'upper'\]"):
        meshes.from_gmsh_model(joints=["fault"], blocks=["granite", "lower"])
    with pytest.raises(ValueError, match=r"boundaries: no dimension-1 physical group named 'roof'"):
        meshes.from_gmsh_model(joints=["fault"], boundaries=["roof"])
    with pytest.raises(ValueError, match=r"listed as joints and as boundaries"):
        meshes.from_gmsh_model(joints=["fault"], boundaries=["fault"])
    with pytest.raises(ValueError, match=r"give a list of group names, got the string 'fault'"):
        meshes.from_gmsh_model(joints="fault")
    with pytest.raises(ValueError, match=r"no block: add dimension-2 physical groups for the blocks"):
        meshes.from_gmsh_model(joints=["fault"], blocks=[])


def test_an_interface_that_is_not_a_joint_says_what_to_do():
    case.build_gmsh_model(gmsh, 2, 0.5, name_joint=False)
    with pytest.raises(ValueError, match=r"interface entity \(1, \d+\) between blocks 'lower' and 'upper' is in no "
                                         r"joint group: add it to a joint group .* or put both volumes in one block"):
        meshes.from_gmsh_model(joints=[])


def test_a_joint_that_is_not_between_two_blocks():
    case.build_gmsh_model(gmsh, 2, 0.5)
    with pytest.raises(ValueError, match=r"joint 'bottom': entity \(1, \d+\) bounds 1 block volume\(s\), not 2"):
        meshes.from_gmsh_model(joints=["fault", "bottom"])
    # A dangling joint: a crack from the left side that ends inside the square.
    gmsh.model.add("dangling")
    occ = gmsh.model.occ
    body = occ.addRectangle(0, 0, 0, 2, 2)
    crack = occ.addLine(occ.addPoint(0, 1, 0), occ.addPoint(1, 1, 0))
    _, pieces = occ.fragment([(2, body)], [(1, crack)])
    occ.synchronize()
    gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, [t for _, t in pieces[0]]), "rock")
    gmsh.model.setPhysicalName(1, gmsh.model.addPhysicalGroup(1, [t for _, t in pieces[1]]), "crack")
    gmsh.model.mesh.generate(2)
    # gmsh 4.13 reports an embedded (dangling) curve with no upward adjacency (0), 4.6 with its surface (1)
    with pytest.raises(ValueError, match=r"joint 'crack': entity \(1, \d+\) bounds [01] block volume\(s\), not 2: "
                                         r"a joint must lie between two blocks .*occ.fragment"):
        meshes.from_gmsh_model(joints=["crack"])


def test_a_joint_inside_one_block_and_a_boundary_inside_the_model():
    case.build_gmsh_model(gmsh, 2, 0.5)
    both = [t for _, t in gmsh.model.getEntities(2)]
    gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, both), "all_rock")
    with pytest.raises(ValueError, match=r"joint 'fault': entity \(1, \d+\) lies between two volumes of the same "
                                         r"block 'all_rock'"):
        meshes.from_gmsh_model(joints=["fault"], blocks=["all_rock"])
    with pytest.raises(ValueError, match=r"boundary 'fault': entity \(1, \d+\) bounds 2 block volume\(s\); a named "
                                         r"boundary must lie on the outer surface"):
        meshes.from_gmsh_model(joints=[], blocks=["all_rock"], boundaries=["fault"])
    with pytest.raises(ValueError, match=r"entity \(2, \d+\) is in blocks 'lower' and 'all_rock'"):
        meshes.from_gmsh_model(joints=["fault"])


def test_unmeshed_second_order_and_quadrangle_meshes_are_refused():
    case.build_gmsh_model(gmsh, 2, None)
    with pytest.raises(ValueError, match=r"the model has no mesh: call gmsh.model.mesh.generate\(2\) first"):
        meshes.from_gmsh_model(joints=["fault"])
    gmsh.model.remove()
    case.build_gmsh_model(gmsh, 2, 0.5, order=2)
    with pytest.raises(ValueError, match=r"second-order .*Triangle 6.*Mesh.ElementOrder = 1"):
        meshes.from_gmsh_model(joints=["fault"])
    gmsh.model.remove()
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    case.build_gmsh_model(gmsh, 2, 0.5)
    with pytest.raises(ValueError, match=r"block '(lower|upper)': entity \(2, \d+\) has Quadrilateral 4 elements; "
                                         r"rockjoint needs linear triangles"):
        meshes.from_gmsh_model(joints=["fault"])


def test_a_model_with_no_block_groups():
    gmsh.model.add("bare")
    gmsh.model.occ.addRectangle(0, 0, 0, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.model.mesh.generate(2)
    with pytest.raises(ValueError, match=r"no block: add dimension-2 physical groups"):
        meshes.from_gmsh_model(joints=[])
