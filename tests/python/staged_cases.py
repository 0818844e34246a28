# SPDX-License-Identifier: MIT
"""Small models shared by the staged-analysis tests (test_fem_staged*.py, test_fem_in_situ.py)."""
import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute
from rockjoint.meshes.node_splitting import build_jointed_mesh

E, NU = 20e9, 0.25
KNI, VM = 1e10, 1e-3  # Barton-Bandis K_ni [Pa/m], V_m [m]
E_PLANE = E / (1 - NU**2)  # plane-strain modulus
M_OEDOMETER = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))  # constrained modulus λ + 2μ
QUIET = NewtonOptions(verbose=False)


def bb_closure(stress):
    """Barton-Bandis closure Δ(σ) = σ V_m / (K_ni V_m + σ) (closed form)."""
    return stress * VM / (KNI * VM + stress)


def column(width=1.0, height=2.0, joint_heights=(1.0,), comm=MPI.COMM_WORLD, mesh_size=0.25, degree=1,
           **kw):
    """2D plane-strain column, rollers at the bottom (y) and on the left (x), Barton-Bandis joints."""
    jm = meshes.column(width, height, joint_heights, dim=2, mesh_size=mesh_size, comm=comm)
    law = rockjoint.BartonBandis(KNI, VM)
    joints = {f"joint_{i + 1}": law for i in range(len(joint_heights))}
    kw.setdefault("newton", QUIET)
    model = JointedRockModel(distribute(jm, comm), element_degree=degree, rock=(E, NU), joints=joints,
                             shear_stiffness=1e9, **kw)
    model.fix("bottom", "y")
    model.fix("left", "x")
    return model


def quarter_annulus(inner, outer, n_radial, n_angular, comm=MPI.COMM_WORLD):
    """Structured quarter ring inner <= r <= outer, 0 <= θ <= π/2 (a hole of radius `inner`):
    boundaries "inner", "outer", "left" (x = 0), "bottom" (y = 0); one block, no joints."""
    if comm.rank != 0:
        return distribute(None, comm)
    r = np.linspace(inner, outer, n_radial + 1)
    t = np.linspace(0.0, 0.5 * np.pi, n_angular + 1)
    R, T = np.meshgrid(r, t, indexing="ij")
    points = np.column_stack([(R * np.cos(T)).ravel(), (R * np.sin(T)).ravel()])
    node = np.arange(points.shape[0]).reshape(n_radial + 1, n_angular + 1)
    a, b = node[:-1, :-1].ravel(), node[1:, :-1].ravel()
    c, d = node[1:, 1:].ravel(), node[:-1, 1:].ravel()
    cells = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    edges = {1: np.column_stack([node[0, :-1], node[0, 1:]]),     # inner
             2: np.column_stack([node[-1, :-1], node[-1, 1:]]),   # outer
             3: np.column_stack([node[:-1, -1], node[1:, -1]]),   # left (θ = π/2)
             4: np.column_stack([node[:-1, 0], node[1:, 0]])}     # bottom (θ = 0)
    names = {"blocks": {1: "block_1"}, "joints": {},
             "boundaries": {1: "inner", 2: "outer", 3: "left", 4: "bottom"}}
    jm = build_jointed_mesh(points, cells, "triangle", np.ones(cells.shape[0], dtype=np.int32),
                            np.empty((0, 2), dtype=np.int64), np.empty(0, dtype=np.int32),
                            np.vstack(list(edges.values())),
                            np.concatenate([np.full(len(e), k, dtype=np.int32) for k, e in edges.items()]),
                            names)
    return distribute(jm, comm)


def lame_radial_displacement(r, inner, outer, pressure_in, pressure_out=0.0):
    """Lamé thick-walled cylinder, plane strain: u_r(r) for internal pressure p_i, external p_o
    (compression positive), u_r = A r + B / r with σ_r = 2(λ+μ) A - 2μ B / r²."""
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    # σ_r(inner) = -p_i, σ_r(outer) = -p_o
    M = np.array([[2 * (lam + mu), -2 * mu / inner**2], [2 * (lam + mu), -2 * mu / outer**2]])
    A, B = np.linalg.solve(M, [-pressure_in, -pressure_out])
    return A * r + B / r


def radial_displacement_at(model, radius, tol=1e-9):
    """(angles, u_r) of the displacement at the dof nodes on the circle r = radius (this rank)."""
    x = model.V.tabulate_dof_coordinates()[:, :2]
    on = np.abs(np.hypot(x[:, 0], x[:, 1]) - radius) < tol * radius
    u = model.u.x.array.reshape(-1, 2)[on]
    e = x[on] / radius
    return np.arctan2(x[on, 1], x[on, 0]), np.sum(u * e, axis=1)
