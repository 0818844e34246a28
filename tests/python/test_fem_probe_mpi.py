# SPDX-License-Identifier: MIT
"""rockjoint.fem.output.probe: point values of DOLFINx functions, the same on every rank and partition.

Reference: a P1 function interpolating a linear field f(x, y) = 2 + 3x - 5y is exact everywhere,
so the probe must return f at any point of the mesh (here a tunnel section with joints: points in
different blocks, near the opening, on 1 or 2 ranks); a point inside the opening is refused.
"""
import numpy as np
import pytest

from fe_stack import require  # noqa: E402
require("dolfinx")
from dolfinx import fem  # noqa: E402
from mpi4py import MPI  # noqa: E402

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import distribute  # noqa: E402
from rockjoint.fem.output.probe import probe  # noqa: E402


def linear_function():
    comm = MPI.COMM_WORLD
    jm = meshes.tunnel_section(20.0, 16.0, meshes.CircularOpening((10.0, 8.0), 2.0),
                               meshes.joint_set(3.0, 0.0, 90.0, origin=(10.0, 6.5), count=2, name="bed"),
                               mesh_size=2.0, opening_mesh_size=0.5, comm=comm)
    dmesh = distribute(jm, comm)
    V = fem.functionspace(dmesh.mesh, ("Lagrange", 1, (dmesh.mesh.geometry.dim,)))
    u = fem.Function(V)
    u.interpolate(lambda x: np.stack([2 + 3 * x[0] - 5 * x[1], x[0] * 0 + 7.0]))
    return u


def field(points):
    return np.stack([2 + 3 * points[:, 0] - 5 * points[:, 1], np.full(points.shape[0], 7.0)], axis=1)


@pytest.mark.mpi
def test_probe_returns_the_field_on_every_rank():
    u = linear_function()
    rng = np.random.default_rng(3)
    pts = rng.uniform([0.1, 0.1], [19.9, 15.9], size=(200, 2))
    pts = pts[np.hypot(pts[:, 0] - 10.0, pts[:, 1] - 8.0) > 2.2]  # out of the opening
    values = probe(u, pts)
    assert values == pytest.approx(field(pts), abs=1e-10)
    # every rank holds the same answer
    gathered = MPI.COMM_WORLD.allgather(values)
    assert all(np.array_equal(g, gathered[0]) for g in gathered)


@pytest.mark.mpi
def test_probe_refuses_a_point_in_the_opening():
    u = linear_function()
    with pytest.raises(ValueError, match=r"point \(10.0, 8.5\) lies outside the mesh"):
        probe(u, np.array([[5.0, 5.0], [10.0, 8.5]]))
    with pytest.raises(ValueError, match="points must be an"):
        probe(u, np.array([1.0, 2.0, 3.0]))
