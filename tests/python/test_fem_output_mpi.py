# SPDX-License-Identifier: MIT
"""rockjoint.fem.output.fields.gather_triangles: every owned cell once, on rank 0, with the displacement
at its vertices; the same picture on 1 and 2 ranks."""
import numpy as np
import pytest
from mpi4py import MPI

from fe_stack import require  # noqa: E402
require("rockjoint._rockjoint_fem_coupling")

from dolfinx import fem  # noqa: E402

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import distribute  # noqa: E402
from rockjoint.fem.output.fields import gather_triangles  # noqa: E402

WIDTH, HEIGHT = 2.0, 3.0


def _check_gathered_triangles():
    comm = MPI.COMM_WORLD
    dmesh = distribute(meshes.column(WIDTH, HEIGHT, [1.0, 2.0], dim=2, mesh_size=0.4, comm=comm), comm)
    V = fem.functionspace(dmesh.mesh, ("Lagrange", 1, (dmesh.mesh.geometry.dim,)))
    u = fem.Function(V)
    u.interpolate(lambda x: np.stack([1e-3 * x[0] - 2e-3 * x[1], 5e-4 * x[0] * x[1]]))  # P1 exact at nodes
    owned = dmesh.mesh.topology.index_map(2).size_local
    total = comm.allreduce(owned)
    tri, at_vertices, ids = gather_triangles(u, cell_values=np.full(owned, comm.rank))
    if comm.rank != 0:
        assert tri is None and at_vertices is None and ids is None
        return
    assert tri.shape == at_vertices.shape == (total, 3, 2)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    assert area.sum() == pytest.approx(WIDTH * HEIGHT, rel=1e-12)   # every cell exactly once
    x, y = tri[..., 0], tri[..., 1]
    np.testing.assert_allclose(at_vertices[..., 0], 1e-3 * x - 2e-3 * y, atol=1e-15)
    np.testing.assert_allclose(at_vertices[..., 1], 5e-4 * x * y, atol=1e-15)
    assert set(np.unique(ids)) == set(range(comm.size))             # the rows of every rank


def test_gather_triangles_serial():
    _check_gathered_triangles()


@pytest.mark.mpi
def test_gather_triangles_on_two_ranks():
    _check_gathered_triangles()


def test_gather_triangles_refuses_3d_and_wrong_cell_values():
    comm = MPI.COMM_WORLD
    dmesh = distribute(meshes.column(1.0, 1.0, [], dim=2, mesh_size=0.5, comm=comm), comm)
    u = fem.Function(fem.functionspace(dmesh.mesh, ("Lagrange", 2, (dmesh.mesh.geometry.dim,))))
    with pytest.raises(ValueError, match="P1 displacement on a 2D triangle mesh"):
        gather_triangles(u)
    u1 = fem.Function(fem.functionspace(dmesh.mesh, ("Lagrange", 1, (dmesh.mesh.geometry.dim,))))
    with pytest.raises(ValueError, match="cell_values has 1 rows"):
        gather_triangles(u1, cell_values=np.zeros(1))
