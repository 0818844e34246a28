# SPDX-License-Identifier: MIT
"""Values of a DOLFINx function at given points, on every rank (point probes for verification and plots).

Each rank evaluates the points that fall in its owned cells (DOLFINx bounding-box tree, then the exact
cell collision); the value of a point found on several ranks (on a partition boundary) is taken from
the lowest rank, so the answer does not depend on the partition beyond round-off.
"""
from __future__ import annotations

import numpy as np
from dolfinx import fem, geometry
from mpi4py import MPI



def probe(function, points) -> np.ndarray:
    """(n, value size) values of ``function`` at ``points`` (n, gdim) [m], the same on every rank.

    Raises ValueError naming the first point outside the mesh (a point in a hole, or beyond the boundary).
    """
    mesh = function.function_space.mesh
    comm = mesh.comm
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim != 2 or pts.shape[1] not in (2, 3) or not np.all(np.isfinite(pts)):
        raise ValueError(f"probe: points must be an (n, 2 or 3) array of finite coordinates, got shape {pts.shape}")
    x = np.zeros((pts.shape[0], 3))
    x[:, :pts.shape[1]] = pts
    tdim = mesh.topology.dim
    n_owned = mesh.topology.index_map(tdim).size_local
    # Boxes padded by round-off of the mesh's size: a point on the outer boundary (a joint's end)
    # computed 1e-13 outside must still be found (DOLFINx 0.9's bb_tree pads by 0 by default).
    extent = comm.allreduce(float(np.ptp(mesh.geometry.x, axis=0).max()) if mesh.geometry.x.size else 0.0,
                            op=MPI.MAX)
    tree = geometry.bb_tree(mesh, tdim, padding=1e-10 * extent)
    candidates = geometry.compute_collisions_points(tree, x)
    colliding = geometry.compute_colliding_cells(mesh, candidates, x)
    found = np.full(x.shape[0], -1, dtype=np.int32)
    for i in range(x.shape[0]):
        cells = colliding.links(i)
        cells = cells[cells < n_owned]
        if cells.size:
            found[i] = cells[0]
    size = int(np.prod(function.ufl_shape)) if function.ufl_shape else 1
    local = np.zeros((x.shape[0], size))
    mine = np.flatnonzero(found >= 0)
    if mine.size:
        local[mine] = function.eval(x[mine], found[mine]).reshape(mine.size, size)
    rank_of = np.where(found >= 0, comm.rank, comm.size).astype(np.int64)
    owner = np.empty_like(rank_of)
    comm.Allreduce(rank_of, owner, op=MPI.MIN)
    missing = np.flatnonzero(owner == comm.size)
    if missing.size:
        raise ValueError(f"probe: point {tuple(pts[missing[0]].tolist())} lies outside the mesh "
                         f"({missing.size} of {pts.shape[0]} points)")
    local[owner != comm.rank] = 0.0
    values = np.empty_like(local)
    comm.Allreduce(local, values, op=MPI.SUM)
    return values


def stress_function(model, u=None, degree: int | None = None) -> fem.Function:
    """σ(u) of a JointedRockModel (the elastic stress of the displacement u, default the model's,
    tension positive [Pa]) in a discontinuous tensor space of ``degree`` (default element degree - 1)."""
    u = model.u if u is None else u
    mesh = model.mesh
    degree = model.degree - 1 if degree is None else int(degree)
    T = fem.functionspace(mesh, ("DG", degree, (mesh.geometry.dim, mesh.geometry.dim)))
    s = fem.Function(T, name="stress")
    s.interpolate(fem.Expression(model.blocks.sigma(u), T.element.interpolation_points))
    return s




__all__ = ["probe", "stress_function"]
