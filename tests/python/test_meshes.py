# SPDX-License-Identifier: MIT
"""rockjoint.meshes: gmsh builders, node splitting per block, joint-facet pairing, save/load.

Reference values are closed-form geometry (areas/volumes of the cut block, joint lengths/areas,
normals from dip and dip direction) and combinatorics recomputed here independently of the code.
"""
import math
from collections import defaultdict

import numpy as np
import pytest

from rockjoint.meshes import Joint, JointedMesh, column, joint_set, jointed_block


# ---- independent helpers -----------------------------------------------------------------------
def facet_measure(x):
    """Length (2 points) or area (3 points) of facets x: (m, k, gdim)."""
    if x.shape[1] == 2:
        return np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
    return 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)


def facet_normal(x):
    """Unit right-hand normal of facets (the JointedMesh convention)."""
    if x.shape[1] == 2:
        t = x[:, 1] - x[:, 0]
        n = np.stack([t[:, 1], -t[:, 0]], axis=1)
    else:
        n = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    return n / np.linalg.norm(n, axis=1)[:, None]


def blocks_of_nodes(m):
    out = defaultdict(set)
    for cell, block in zip(m.cells, m.cell_blocks):
        for v in cell:
            out[int(v)].add(int(block))
    return out


def interblock_facets(m):
    """Facets of the glued mesh shared by cells of two blocks, as frozensets of glued nodes."""
    owner = defaultdict(list)
    nv = m.cells.shape[1]
    for c, cell in enumerate(m.glue[m.cells]):
        for i in range(nv):
            owner[frozenset(np.delete(cell, i).tolist())].append(c)
    return {f for f, cs in owner.items() if len(cs) == 2 and m.cell_blocks[cs[0]] != m.cell_blocks[cs[1]]}


def check_split_invariants(m):
    n_orig = m.num_original_nodes
    # originals first, copies glued to originals with identical coordinates
    assert np.array_equal(m.glue[:n_orig], np.arange(n_orig))
    assert np.all(m.glue[n_orig:] < n_orig)
    assert np.array_equal(m.points, m.points[m.glue])
    # no node shared across a joint: every node belongs to exactly one block
    per_node = blocks_of_nodes(m)
    assert all(len(b) == 1 for b in per_node.values())
    # one copy per block touching an original node (T-junctions included)
    glued_blocks = defaultdict(set)
    for cell, block in zip(m.glue[m.cells], m.cell_blocks):
        for v in cell:
            glued_blocks[int(v)].add(int(block))
    copies = np.bincount(m.glue, minlength=n_orig)
    assert all(copies[v] == len(b) for v, b in glued_blocks.items())
    # pairs: split, coincident, glue equal entrywise, exactly the inter-block facets
    fm, fp = m.joint_facets_minus, m.joint_facets_plus
    assert np.all(fm != fp)
    assert np.array_equal(m.glue[fm], m.glue[fp])
    assert np.array_equal(m.points[fm], m.points[fp])
    assert {frozenset(r) for r in m.glue[fm].tolist()} == interblock_facets(m)
    assert len(interblock_facets(m)) == fm.shape[0]
    # each side's facet belongs to its cell; minus has the lower block tag
    cm, cp = m.joint_facet_cells[:, 0], m.joint_facet_cells[:, 1]
    assert all(set(f) <= set(m.cells[c]) for f, c in zip(fm.tolist(), cm))
    assert all(set(f) <= set(m.cells[c]) for f, c in zip(fp.tolist(), cp))
    assert np.all(m.cell_blocks[cm] < m.cell_blocks[cp])
    # the right-hand normal of the minus order points from the minus cell into the plus cell
    n = facet_normal(m.points[fm])
    centroid_m = m.points[m.cells[cm]].mean(axis=1)
    centroid_p = m.points[m.cells[cp]].mean(axis=1)
    f0 = m.points[fm].mean(axis=1)
    assert np.all(np.einsum("ij,ij->i", n, centroid_m - f0) < 0)
    assert np.all(np.einsum("ij,ij->i", n, centroid_p - f0) > 0)
    # boundary facets are exterior facets of single cells
    for f in m.boundary_facets[:50].tolist():
        assert sum(set(f) <= set(c) for c in m.cells.tolist()) == 1


# ---- columns -----------------------------------------------------------------------------------
@pytest.mark.parametrize("dim", [2, 3])
def test_column_split_pairs_volumes_and_groups(dim):
    width, height, heights = 1.0, 2.0, [0.5, 1.2]
    m = column(width, height, heights, dim=dim, mesh_size=0.3)
    assert m.cell_type == ("triangle" if dim == 2 else "tetrahedron")
    assert m.points.shape[1] == dim
    check_split_invariants(m)
    section = width ** (dim - 1)
    thickness = np.diff([0.0] + heights + [height])
    blocks = m.block_measures()
    assert sorted(m.names["blocks"].values()) == ["block_1", "block_2", "block_3"]
    for k, t in enumerate(thickness, start=1):  # block_1 is the bottom one
        assert blocks[m.tag("blocks", f"block_{k}")] == pytest.approx(section * t, rel=1e-12)
    assert sum(blocks.values()) == pytest.approx(section * height, rel=1e-12)
    # each joint covers the section; minus (lower block) below: normal +vertical
    for i, h in enumerate(heights, start=1):
        sel = m.joint_tags == m.tag("joints", f"joint_{i}")
        x = m.points[m.joint_facets_minus[sel]]
        assert np.allclose(x[..., -1], h)
        assert facet_measure(x).sum() == pytest.approx(section, rel=1e-12)
        up = np.zeros(dim)
        up[-1] = 1.0
        assert np.allclose(facet_normal(x), up)
    expected = {"bottom", "top", "left", "right"} | ({"front", "back"} if dim == 3 else set())
    assert set(m.names["boundaries"].values()) == expected
    faces = {"bottom": section, "top": section, "left": height * width ** (dim - 2),
             "right": height * width ** (dim - 2), "front": width * height, "back": width * height}
    for name in expected:
        sel = m.boundary_tags == m.tag("boundaries", name)
        assert facet_measure(m.points[m.boundary_facets[sel]]).sum() == pytest.approx(faces[name], rel=1e-12)


def test_missing_group_name_is_a_clear_error():
    m = column(1.0, 1.0, [0.5], dim=2, mesh_size=0.5)
    with pytest.raises(KeyError, match="no joint group named 'joint_9'.*joint_1"):
        m.tag("joints", "joint_9")
    with pytest.raises(KeyError, match="available.*bottom"):
        m.tag("boundaries", "floor")


# ---- inclined joints, sets, T-junctions -----------------------------------------------------------
def test_inclined_joint_2d_through_centre_halves_the_block():
    dip = 30.0
    m = jointed_block((2.0, 1.0), [Joint((1.0, 0.5), dip, 90.0)], mesh_size=0.15)
    check_split_invariants(m)
    b = m.block_measures()
    assert list(b.values()) == pytest.approx([1.0, 1.0], rel=1e-12)  # central symmetry of the rectangle
    x = m.points[m.joint_facets_minus]
    assert facet_measure(x).sum() == pytest.approx(1.0 / math.sin(math.radians(dip)), rel=1e-12)
    d = math.radians(dip)  # upward normal of a joint dipping toward +x
    assert np.allclose(facet_normal(x), [math.sin(d), math.cos(d)])


def test_inclined_joint_3d_area_volumes_and_normal():
    dip, dd = 30.0, 0.0  # dips toward +y: z = 0.5 - tan(dip) (y - 0.5) stays inside the unit cube
    m = jointed_block((1.0, 1.0, 1.0), [Joint((0.5, 0.5, 0.5), dip, dd)], mesh_size=0.25)
    check_split_invariants(m)
    assert list(m.block_measures().values()) == pytest.approx([0.5, 0.5], rel=1e-12)
    x = m.points[m.joint_facets_minus]
    assert facet_measure(x).sum() == pytest.approx(1.0 / math.cos(math.radians(dip)), rel=1e-12)
    d = math.radians(dip)
    assert np.allclose(facet_normal(x), [0.0, math.sin(d), math.cos(d)])


def test_joint_set_3d_dipping_volumes():
    spacing = 0.25
    js = joint_set(spacing, 20.0, 135.0, origin=(0.5, 0.5, 0.5), count=3, name="S")
    m = jointed_block((1.0, 1.0, 1.0), js, mesh_size=0.25)
    check_split_invariants(m)
    assert sorted(m.names["joints"].values()) == ["S_1", "S_2", "S_3"]
    assert sum(m.block_measures().values()) == pytest.approx(1.0, rel=1e-12)
    # joints are parallel planes spacing apart along their common normal
    d, a = math.radians(20.0), math.radians(135.0)
    n = np.array([math.sin(d) * math.sin(a), math.sin(d) * math.cos(a), math.cos(d)])
    offsets = sorted({round(float(np.mean(m.points[m.joint_facets_minus[m.joint_tags == t]].reshape(-1, 3) @ n)), 9)
                      for t in np.unique(m.joint_tags)})
    assert np.diff(offsets) == pytest.approx([spacing, spacing], rel=1e-9)


@pytest.mark.parametrize("dim", [2, 3])
def test_t_junctions_one_copy_per_block(dim):
    c = (0.5,) * (dim - 1)
    js = [Joint(c + (0.3,), 0.0, 90.0, "h1"), Joint(c + (0.7,), 0.0, 90.0, "h2"),
          Joint(c + (0.5,), 90.0, 90.0, "v", ("h1", "h2"))]  # vertical joint x = 0.5 between h1 and h2
    m = jointed_block((1.0,) * dim, js, mesh_size=0.2 if dim == 2 else 0.3)
    check_split_invariants(m)
    b = m.block_measures()
    assert sorted(b.values()) == pytest.approx([0.2, 0.2, 0.3, 0.3], rel=1e-12)
    # nodes on the T lines (x = 0.5, z = 0.3 or 0.7) touch 3 blocks: 3 copies each
    x = m.points
    on_t = (np.abs(x[:, 0] - 0.5) < 1e-12) & ((np.abs(x[:, -1] - 0.3) < 1e-12) | (np.abs(x[:, -1] - 0.7) < 1e-12))
    originals = np.unique(m.glue[on_t])
    assert originals.size >= (2 if dim == 2 else 4)
    assert np.all(np.bincount(m.glue)[originals] == 3)
    v = m.joint_tags == m.tag("joints", "v")
    assert facet_measure(x[m.joint_facets_minus[v]]).sum() == pytest.approx(0.4, rel=1e-12)
    assert np.allclose(x[m.joint_facets_minus[v]][..., 0], 0.5)


def test_crossing_joints_2d_four_blocks_and_cross_node():
    js = [Joint((0.5, 0.5), 45.0, 90.0, "a"), Joint((0.5, 0.5), 45.0, 270.0, "b")]
    m = jointed_block((1.0, 1.0), js, mesh_size=0.2)
    check_split_invariants(m)
    assert list(m.block_measures().values()) == pytest.approx([0.25] * 4, rel=1e-12)
    centre = np.flatnonzero(np.all(np.abs(m.points - 0.5) < 1e-12, axis=1))
    assert centre.size == 4  # the X node: one copy per block


# ---- refinement --------------------------------------------------------------------------------
def test_refinement_makes_joint_adjacent_cells_smaller():
    h, hj = 0.2, 0.03
    coarse = column(1.0, 1.0, [0.5], dim=2, mesh_size=h)
    fine = column(1.0, 1.0, [0.5], dim=2, mesh_size=h, joint_mesh_size=hj, refine_distance=0.2)
    for m in (coarse, fine):
        check_split_invariants(m)
    assert sum(fine.block_measures().values()) == pytest.approx(1.0, rel=1e-12)
    jl = facet_measure(fine.points[fine.joint_facets_minus])
    assert jl.mean() < 2.0 * hj  # joint edges follow joint_mesh_size
    assert facet_measure(coarse.points[coarse.joint_facets_minus]).mean() > 0.5 * h
    area = fine.cell_measures()
    ymid = fine.points[fine.cells].mean(axis=1)[:, 1]
    near = area[np.abs(ymid - 0.5) < hj]
    far = area[np.abs(ymid - 0.5) > 0.4]
    assert near.mean() < 0.1 * far.mean()
    assert fine.joint_tags.size > 3 * coarse.joint_tags.size


def test_refinement_3d_joint_facets_smaller():
    fine = column(1.0, 1.0, [0.5], dim=3, mesh_size=0.35, joint_mesh_size=0.12, refine_distance=0.2)
    check_split_invariants(fine)
    edge = np.sqrt(facet_measure(fine.points[fine.joint_facets_minus]) * 4 / math.sqrt(3))
    assert edge.mean() < 1.6 * 0.12
    area = fine.cell_measures()
    zmid = fine.points[fine.cells].mean(axis=1)[:, 2]
    assert area[np.abs(zmid - 0.5) < 0.06].mean() < 0.3 * area[np.abs(zmid - 0.5) > 0.35].mean()


# ---- save / load -------------------------------------------------------------------------------
def test_save_load_round_trip(tmp_path):
    m = column(1.0, 1.0, [0.4], dim=3, mesh_size=0.4)
    path = tmp_path / "m.npz"
    m.save(path)
    r = JointedMesh.load(path)
    assert r.cell_type == m.cell_type and r.names == m.names
    for name in ("points", "cells", "cell_blocks", "glue", "joint_facets_minus", "joint_facets_plus",
                 "joint_facet_cells", "joint_tags", "boundary_facets", "boundary_tags"):
        a, b = getattr(m, name), getattr(r, name)
        assert a.dtype == b.dtype and np.array_equal(a, b), name


def test_load_errors(tmp_path):
    with pytest.raises(OSError, match="cannot read"):
        JointedMesh.load(tmp_path / "missing.npz")
    np.savez(tmp_path / "other.npz", a=np.zeros(3))
    with pytest.raises(ValueError, match="no header"):
        JointedMesh.load(tmp_path / "other.npz")
    m = column(1.0, 1.0, [0.4], dim=2, mesh_size=0.5)
    with pytest.raises(ValueError, match=r"\.npz"):
        m.save(tmp_path / "m.msh")
    m.save(tmp_path / "m.npz")
    data = dict(np.load(tmp_path / "m.npz"))
    data["header"] = np.array(str(data["header"]).replace('"version": 1', '"version": 99'))
    np.savez(tmp_path / "v99.npz", **data)
    with pytest.raises(ValueError, match="version 99"):
        JointedMesh.load(tmp_path / "v99.npz")
    data = dict(np.load(tmp_path / "m.npz"))
    del data["glue"]
    np.savez(tmp_path / "noglue.npz", **data)
    with pytest.raises(ValueError, match="glue"):
        JointedMesh.load(tmp_path / "noglue.npz")


def test_jointed_mesh_rejects_unpermuted_plus_side():
    m = column(1.0, 1.0, [0.5], dim=2, mesh_size=0.5)
    with pytest.raises(ValueError, match="permuted"):
        JointedMesh(**{**m.__dict__, "joint_facets_plus": m.joint_facets_plus[:, ::-1]})


# ---- clear errors ------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    (dict(mesh_size=-0.1), "mesh_size must be a finite number > 0"),
    (dict(mesh_size=0.1, joint_mesh_size=0.2), "joint_mesh_size .* must not exceed mesh_size"),
    (dict(mesh_size=float("nan")), "mesh_size"),
])
def test_bad_sizes(kwargs, match):
    with pytest.raises(ValueError, match=match):
        jointed_block((1.0, 1.0), [Joint((0.5, 0.5), 0.0)], **kwargs)


def test_bad_geometry_errors():
    with pytest.raises(ValueError, match="size\\[1\\] must be a finite number > 0"):
        jointed_block((1.0, -1.0), [], mesh_size=0.1)
    with pytest.raises(ValueError, match="does not cut the block"):
        jointed_block((1.0, 1.0), [Joint((0.5, 1.5), 0.0)], mesh_size=0.2)
    with pytest.raises(ValueError, match="does not cut the block"):  # lies on the bottom face
        jointed_block((1.0, 1.0, 1.0), [Joint((0.5, 0.5, 0.0), 0.0)], mesh_size=0.2)
    with pytest.raises(ValueError, match="dip must be in \\[0, 90\\]"):
        jointed_block((1.0, 1.0), [Joint((0.5, 0.5), 120.0)], mesh_size=0.2)
    with pytest.raises(ValueError, match="dip_direction must be 90"):
        jointed_block((1.0, 1.0), [Joint((0.5, 0.5), 30.0, 45.0)], mesh_size=0.2)
    with pytest.raises(ValueError, match="bounded_by entry 'nope'"):
        jointed_block((1.0, 1.0), [Joint((0.5, 0.5), 0.0, bounded_by=("nope",))], mesh_size=0.2)
    with pytest.raises(ValueError, match="unique"):
        jointed_block((1.0, 1.0), [Joint((0.5, 0.3), 0.0, name="j"), Joint((0.5, 0.6), 0.0, name="j")],
                      mesh_size=0.2)
    with pytest.raises(ValueError, match="not strictly inside"):
        column(1.0, 1.0, [0.5, 1.0], mesh_size=0.2)
    with pytest.raises(ValueError, match="distinct"):
        column(1.0, 1.0, [0.5, 0.5], mesh_size=0.2)
    with pytest.raises(ValueError, match="algorithm_3d must be one of"):
        column(1.0, 1.0, [0.5], dim=3, mesh_size=0.2, algorithm_3d="fast")
    with pytest.raises(ValueError, match="count must be an integer"):
        joint_set(0.1, origin=(0.5, 0.5), count=0)


def test_dangling_joint_is_rejected():
    # "a" ends on "v" at x = 0.5, but "v" only exists above z = 0.7: a's tip dangles inside a block
    js = [Joint((0.5, 0.7), 0.0, 90.0, "upper"), Joint((0.5, 0.85), 90.0, 90.0, "v", ("upper",)),
          Joint((0.25, 0.5), 0.0, 90.0, "a", ("v",))]
    with pytest.raises(ValueError, match="joint 'a' does not separate two blocks"):
        jointed_block((1.0, 1.0), js, mesh_size=0.2)


def test_builders_on_nonzero_rank_return_none():
    class FakeComm:
        rank = 1
    assert column(1.0, 1.0, [0.5], mesh_size=0.5, comm=FakeComm()) is None


def test_hxt_algorithm_gives_a_valid_split_mesh():
    m = column(1.0, 1.0, [0.3, 0.6], dim=3, mesh_size=0.25, algorithm_3d="hxt")
    check_split_invariants(m)
    assert list(m.block_measures().values()) == pytest.approx([0.3, 0.3, 0.4], rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_intact_block_without_joints(dim):
    m = jointed_block((2.0,) + (1.0,) * (dim - 1), [], mesh_size=0.4)
    assert m.joint_tags.size == 0 and m.points.shape[0] == m.num_original_nodes
    assert m.block_measures() == pytest.approx({1: 2.0})


@pytest.mark.parametrize("jointed", [False, True])
def test_laboratory_scale_cube_is_meshed_with_its_boundaries(jointed):
    """A 150 mm cube (the lab specimen of Tang & Jiao 2018): OCC pads bounding boxes by an
    absolute ~1e-7 m, which must not stop the faces of a small block being classified."""
    side = 0.150
    joints = [Joint((side / 2, side / 2, side / 2), 0.0, 90.0, "joint")] if jointed else []
    m = jointed_block((side, side, side), joints, dim=3, mesh_size=0.05)
    assert set(m.names["boundaries"].values()) == {"left", "right", "front", "back", "bottom", "top"}
    assert sum(m.block_measures().values()) == pytest.approx(side**3, rel=1e-12)
    assert (m.joint_tags.size > 0) == jointed


# ---- elements of all entities in one gmsh call -----------------------------------------------------
def two_crossing_joints(dim):
    centre = (0.5,) * (dim - 1)
    return [Joint(centre + (0.4,), 0.0, 90.0, "flat"), Joint((0.45,) + centre, 60.0, 90.0, "dipping")]


@pytest.mark.parametrize("dim", [2, 3])
def test_facets_get_the_entities_gmsh_gives_them(dim, monkeypatch):
    """The builders read every facet in one gmsh call and find its entity (a joint piece, a
    boundary face) from the order gmsh lists them in: the entities that asking each entity for
    its elements, one call each, gives."""
    from rockjoint.meshes import builders
    counts = []
    found = builders._facet_entities

    def compare(gmsh, fd, facets, facet_tags, n_nodes):
        entity = found(gmsh, fd, facets, facet_tags, n_nodes)
        entities = np.array([t for _, t in gmsh.model.getEntities(fd)])
        assert np.array_equal(entity, builders._facet_entities_one_by_one(gmsh, fd, entities, facet_tags))
        counts.append((np.unique(entity).size, entities.size))
        return entity

    monkeypatch.setattr(builders, "_facet_entities", compare)
    m = jointed_block((1.0,) * dim, two_crossing_joints(dim), mesh_size=0.25)
    check_split_invariants(m)
    assert len(counts) == 1 and counts[0][0] == counts[0][1] > 8   # joint pieces and boundary faces


def test_facets_are_read_one_entity_at_a_time_when_gmsh_lists_them_otherwise(monkeypatch, caplog):
    """Should gmsh list the elements in another order than its entities, the builders notice it
    and ask every entity for its elements: the same mesh, a warning."""
    import gmsh
    expected = jointed_block((1.0, 1.0), two_crossing_joints(2), mesh_size=0.25)
    entities = gmsh.model.getEntities

    def reversed_curves(dim=-1):
        out = entities(dim)
        return out[::-1] if dim == 1 else out

    monkeypatch.setattr(gmsh.model, "getEntities", reversed_curves)
    with caplog.at_level("WARNING", logger="rockjoint.meshes.builders"):
        m = jointed_block((1.0, 1.0), two_crossing_joints(2), mesh_size=0.25)
    assert "did not list the 1D elements entity by entity" in caplog.text
    for name in ("points", "cells", "cell_blocks", "joint_facets_minus", "joint_facets_plus", "joint_tags",
                 "boundary_facets", "boundary_tags"):
        assert np.array_equal(getattr(m, name), getattr(expected, name)), name


def test_builders_mesh_simplices_whatever_the_callers_recombination_option():
    """gmsh options are global: a caller's Mesh.RecombineAll = 1 (quadrangles for its own model)
    neither reaches the builders' meshes nor is lost."""
    import gmsh
    from rockjoint.meshes.builders import _ensure_gmsh
    _ensure_gmsh(gmsh)
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    try:
        m = column(1.0, 1.0, [0.5], mesh_size=0.25)
        assert gmsh.option.getNumber("Mesh.RecombineAll") == 1
    finally:
        gmsh.option.setNumber("Mesh.RecombineAll", 0)
    assert m.cell_type == "triangle" and m.block_measures() == pytest.approx({1: 0.5, 2: 0.5}, rel=1e-12)


def test_the_mesh_carries_each_joints_set():
    """names["joint_sets"]: joint_set() names its joints' set, a column's joints are the set
    'joint', a joint given alone is a set of its own; the record survives save/load."""
    joints = joint_set(0.3, 0.0, 90.0, origin=(0.5, 0.2), count=2, name="bedding") + [
        Joint((0.5, 0.5), 90.0, 90.0, "fault")]
    m = jointed_block((1.0, 1.0), joints, dim=2, mesh_size=0.3)
    assert m.joint_sets() == {"bedding_1": "bedding", "bedding_2": "bedding", "fault": "fault"}
    assert set(column(1.0, 1.0, [0.3, 0.6], mesh_size=0.4).joint_sets().values()) == {"joint"}


def test_joint_sets_round_trip_and_stray_tags_are_refused(tmp_path):
    m = jointed_block((1.0, 1.0), joint_set(0.3, 0.0, 90.0, origin=(0.5, 0.2), count=2, name="b"),
                      dim=2, mesh_size=0.3)
    m.save(tmp_path / "m.npz")
    assert JointedMesh.load(tmp_path / "m.npz").joint_sets() == m.joint_sets()
    names = dict(m.names, joint_sets={**m.names["joint_sets"], 999: "ghost"})
    arrays = {k: getattr(m, k) for k in ("points", "cells", "cell_blocks", "glue", "joint_facets_minus",
                                          "joint_facets_plus", "joint_facet_cells", "joint_tags",
                                          "boundary_facets", "boundary_tags")}
    with pytest.raises(ValueError, match=r"joint_sets.*\[999\].*no joints"):
        JointedMesh(cell_type=m.cell_type, names=names, **arrays)
