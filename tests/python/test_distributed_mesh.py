# SPDX-License-Identifier: MIT
"""rockjoint.fem.mesh.distributed_mesh in serial: DOLFINx mesh, tags and joint pairs from a JointedMesh.

References: the JointedMesh's own facet pairs (built by a different code path: glued facet table on the
input mesh) and closed-form block volumes / face areas. Facet vertices are read through DOLFINx's
cell->facet and facet->vertex connectivity, independently of the pairing code's local numbering.
"""
import os

import numpy as np
import pytest
from mpi4py import MPI

import dolfinx
from rockjoint.fem.mesh.distributed_mesh import distribute, pair_vertex_positions
from rockjoint.meshes import Joint, column, jointed_block

from mesh_checks import facet_coordinates, owned_block_measures, sorted_rows


def pair_facet_coordinates(d, cells, local_facets):
    return facet_coordinates(d.mesh, cells, local_facets)


def check_pairs_against_jointed_mesh(d, jm):
    p = d.pairs
    assert len(p) == jm.joint_tags.size
    n_owned = d.mesh.topology.index_map(d.mesh.topology.dim).size_local
    assert np.all(p.minus_cells < n_owned) and np.all(p.plus_cells < n_owned)
    xm = pair_facet_coordinates(d, p.minus_cells, p.minus_local_facets)
    xp = pair_facet_coordinates(d, p.plus_cells, p.plus_local_facets)
    assert sorted_rows(xm) == sorted_rows(xp)  # coincident pointwise (as sets of vertices per facet)
    ref = jm.points[jm.joint_facets_minus]
    assert sorted(zip(p.joint_tags.tolist(), sorted_rows(xm))) == \
        sorted(zip(jm.joint_tags.tolist(), sorted_rows(ref)))
    # minus side = lower block tag
    blocks = dict(zip(d.cell_blocks.indices.tolist(), d.cell_blocks.values.tolist()))
    assert all(blocks[m] < blocks[q] for m, q in zip(p.minus_cells.tolist(), p.plus_cells.tolist()))
    # the pair's cells lie on opposite sides of the facet plane
    tdim = d.mesh.topology.dim
    x = d.mesh.geometry.x[:, :d.mesh.geometry.dim]
    dofs = d.mesh.geometry.dofmaps[0]
    cm, cp = x[dofs[p.minus_cells]].mean(axis=1), x[dofs[p.plus_cells]].mean(axis=1)
    if tdim == 2:
        t = xm[:, 1] - xm[:, 0]
        n = np.stack([t[:, 1], -t[:, 0]], axis=1)
    else:
        n = np.cross(xm[:, 1] - xm[:, 0], xm[:, 2] - xm[:, 0])
    side_m = np.einsum("ij,ij->i", n, cm - xm[:, 0])
    side_p = np.einsum("ij,ij->i", n, cp - xm[:, 0])
    assert np.all(side_m * side_p < 0)


@pytest.mark.parametrize("dim", [2, 3])
def test_serial_column_pairs_tags_and_volumes(dim):
    jm = column(1.0, 2.0, [0.5, 1.2], dim=dim, mesh_size=0.3)
    d = distribute(jm, MPI.COMM_WORLD)
    assert d.mesh.topology.index_map(0).size_global == jm.points.shape[0]  # no vertex added or merged
    assert d.mesh.topology.index_map(dim).size_global == jm.cells.shape[0]
    check_pairs_against_jointed_mesh(d, jm)
    ref = {1: 0.5, 2: 0.7, 3: 0.8}
    assert owned_block_measures(d) == pytest.approx(ref, rel=1e-12)
    assert np.array_equal(np.unique(d.pairs.joint_tags), [100, 101])
    # boundary facets: the bottom face has measure width^(dim-1)
    bottom = d.boundary("bottom")
    nodes = dolfinx.mesh.entities_to_geometry(d.mesh, dim - 1, bottom, False)
    xb = d.mesh.geometry.x[nodes][..., :dim]
    assert np.allclose(xb[..., -1], 0.0)
    if dim == 2:
        area = np.linalg.norm(xb[:, 1] - xb[:, 0], axis=1).sum()
    else:
        area = 0.5 * np.linalg.norm(np.cross(xb[:, 1] - xb[:, 0], xb[:, 2] - xb[:, 0]), axis=1).sum()
    assert area == pytest.approx(1.0, rel=1e-12)
    assert d.block_tag("block_2") == 2 and d.joint_tag("joint_1") == 100


def test_serial_t_junction_3d():
    js = [Joint((0.5, 0.5, 0.3), 0.0, 90.0, "h1"), Joint((0.5, 0.5, 0.7), 0.0, 90.0, "h2"),
          Joint((0.5, 0.5, 0.5), 60.0, 90.0, "v", ("h1", "h2"))]
    jm = jointed_block((1.0, 1.0, 1.0), js, mesh_size=0.3)
    d = distribute(jm, MPI.COMM_WORLD)
    check_pairs_against_jointed_mesh(d, jm)
    assert sum(owned_block_measures(d).values()) == pytest.approx(1.0, rel=1e-12)
    assert owned_block_measures(d) == pytest.approx(jm.block_measures(), rel=1e-12)


def test_boundary_lookup_errors():
    d = distribute(column(1.0, 1.0, [0.5], dim=2, mesh_size=0.5), MPI.COMM_WORLD)
    with pytest.raises(KeyError, match="no boundary group named 'floor'.*bottom"):
        d.boundary("floor")
    with pytest.raises(ValueError, match="must be a string"):
        d.boundary(1)
    with pytest.raises(KeyError, match="no joint named 'j'"):
        d.joint_tag("j")


def test_distribute_requires_a_mesh_on_rank_0():
    with pytest.raises(ValueError, match="rank 0 must pass a JointedMesh"):
        distribute(None, MPI.COMM_WORLD)


@pytest.mark.parametrize("dim", [2, 3])
def test_pair_vertex_positions_match_and_orient(dim):
    js = [Joint((0.5,) * (dim - 1) + (0.4,), 25.0, 90.0), Joint((0.5,) * (dim - 1) + (0.8,), 0.0, 90.0)]
    jm = jointed_block((1.0,) * dim, js, mesh_size=0.25)
    d = distribute(jm, MPI.COMM_WORLD)
    p = d.pairs
    pm, pp = pair_vertex_positions(d)
    x = d.mesh.geometry.x[:, :dim]
    dofs = d.mesh.geometry.dofmaps[0]
    xm = x[np.take_along_axis(dofs[p.minus_cells], pm, axis=1)]
    xp = x[np.take_along_axis(dofs[p.plus_cells], pp, axis=1)]
    assert np.array_equal(xm, xp)  # entrywise coincident
    # the positions are the vertices of the paired facets (read through DOLFINx connectivity)
    assert sorted_rows(xm) == sorted_rows(pair_facet_coordinates(d, p.minus_cells, p.minus_local_facets))
    assert sorted_rows(xp) == sorted_rows(pair_facet_coordinates(d, p.plus_cells, p.plus_local_facets))
    assert np.all(pm != p.minus_local_facets[:, None]) and np.all(pp != p.plus_local_facets[:, None])
    # right-hand normal of the minus order points into the plus cell; for these joints it is the upward
    # normal of the joint (the minus block is below)
    if dim == 2:
        t = xm[:, 1] - xm[:, 0]
        n = np.stack([t[:, 1], -t[:, 0]], axis=1)
    else:
        n = np.cross(xm[:, 1] - xm[:, 0], xm[:, 2] - xm[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    d25 = np.radians(25.0)
    up25 = np.array([np.sin(d25), np.cos(d25)] if dim == 2 else [np.sin(d25), 0.0, np.cos(d25)])
    up0 = np.eye(dim)[-1]
    first = p.joint_tags == d.joint_tag("joint_1")
    assert np.allclose(n[first], up25) and np.allclose(n[~first], up0)


_PARTITION_SCRIPT = """
import hashlib
import numpy as np
from mpi4py import MPI
import rockjoint.fem  # noqa: F401 - the import sets the partitioner's threads
from dolfinx.mesh import CellType, create_unit_cube
comm = MPI.COMM_WORLD
mesh = create_unit_cube(comm, 30, 30, 30, CellType.tetrahedron)
n = mesh.topology.index_map(3).size_local
mine = np.sort(np.asarray(mesh.topology.original_cell_index[:n], dtype=np.int64))
digests = comm.gather(hashlib.sha1(mine.tobytes()).hexdigest(), root=0)
if comm.rank == 0:
    print("partition", mesh.topology.index_map(3).size_global, *digests)
"""


def test_partition_is_the_same_at_every_launch():
    """Three launches on 2 ranks partition a mesh of 162k cells identically. PT-SCOTCH's threads
    made Debian 13's partition differ at every launch (distributed_mesh.py, docs/fem.md pitfall 17);
    rockjoint.fem runs it with one thread unless the user chose otherwise."""
    import subprocess
    import sys
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.pop("SCOTCH_PTHREAD_NUMBER", None)
    runs = [subprocess.run(["mpirun", "-n", "2", sys.executable, "-c", _PARTITION_SCRIPT], env=env,
                           capture_output=True, text=True, timeout=600) for _ in range(3)]
    for r in runs:
        assert r.returncode == 0, r.stderr[-2000:]
    lines = [[w for w in r.stdout.splitlines() if w.startswith("partition")] for r in runs]
    assert all(len(x) == 1 for x in lines), [r.stdout for r in runs]
    assert int(lines[0][0].split()[1]) > 50_000
    assert lines[0] == lines[1] == lines[2]


def test_serial_mesh_keeps_the_cells_in_order_and_equals_dolfinx():
    """compat.create_serial_mesh (DOLFINx >= 0.10: our _rockjoint_dolfinx, create_mesh without the
    Gibbs-Poole-Stockmeyer reordering; 0.9: dolfinx.mesh.create_mesh) gives the mesh DOLFINx gives:
    the same cells on the same points (compared through the original cell index), the same area.
    With the module the cells stay in input order; the module must be built where it can be."""
    import ufl
    import basix.ufl
    from rockjoint.fem import compat
    from rockjoint.meshes import CircularOpening, joint_set, tunnel_section
    has_hook = tuple(int(p) for p in dolfinx.__version__.split(".")[:2]) >= (0, 10)
    assert (compat.create_mesh_in_order is not None) == has_hook
    joints = joint_set(1.0, 0.0, 90.0, origin=(10.0, 0.3), count=16, name="bed") + \
        joint_set(1.5, 70.0, 90.0, origin=(2.0, 8.0), count=12, name="cross")
    jm = tunnel_section(20.0, 16.0, CircularOpening((10.0, 8.0), 2.0), joints, mesh_size=1.0)
    domain = ufl.Mesh(basix.ufl.element("Lagrange", "triangle", 1, shape=(2,)))
    cells = jm.cells.astype(np.int64)
    ours = compat.create_serial_mesh(MPI.COMM_SELF, cells, domain, jm.points)
    theirs = dolfinx.mesh.create_mesh(MPI.COMM_SELF, cells, e=domain, x=jm.points)

    def cell_points(m):
        dofmap = m.geometry.dofmaps[0] if hasattr(m.geometry, "dofmaps") else m.geometry.dofmap
        x = m.geometry.x[:, :2]
        order = np.argsort(np.asarray(m.topology.original_cell_index))
        return np.sort(np.round(x[dofmap[order]], 12).reshape(len(order), -1), axis=1)

    assert np.array_equal(cell_points(ours), cell_points(theirs))
    area = [dolfinx.fem.assemble_scalar(dolfinx.fem.form(1.0 * ufl.dx(domain=m))) for m in (ours, theirs)]
    assert area[0] == pytest.approx(area[1], rel=1e-13) and area[0] == pytest.approx(jm.cell_measures().sum(),
                                                                                      rel=1e-13)
    if has_hook:
        assert np.array_equal(np.asarray(ours.topology.original_cell_index), np.arange(len(cells)))

