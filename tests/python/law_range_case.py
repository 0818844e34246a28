# SPDX-License-Identifier: MIT
"""A user's model of a column cut by one horizontal joint under a uniaxial load, for the range
checks (issue 39): rollers at the bottom and on the left, free sides, so the stress is uniform,
σ_yy = -LOAD in every block, and every joint point carries σ_n = LOAD (closed form, any mesh).
The law is tabulated to 2 MPa and the load is 10 MPa: every point is past the table.
"""
import numpy as np
import ufl
from dolfinx import fem
from petsc4py import PETSc

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointCoupling, JointedNonlinearProblem, distribute

E, NU = 20e9, 0.25                        # [Pa], plane strain
LOAD = 10e6                               # σ_n on the joint [Pa]
LAW = rockjoint.BartonBandis(1e10, 1e-3)  # K_ni [Pa/m], V_m [m] (KNI, VM below)
SHORT = rockjoint.tabulate(LAW, max_stress=2e6)    # covers 0 - 2 MPa
LONG = rockjoint.tabulate(LAW, max_stress=30e6)    # covers the load
SNES_OPTIONS = {"snes_rtol": 1e-10, "snes_atol": 1e-14, "snes_stol": 0.0, "snes_max_it": 30,
                "snes_linesearch_type": "basic", "ksp_type": "preonly", "pc_type": "lu",
                "pc_factor_mat_solver_type": "mumps"}
_COUNT = [0]


def column(comm):
    """The column 4 m wide, 2 m high with a joint at 1 m (DistributedJointMesh on comm): wider
    than high, so that two ranks share the joint."""
    return distribute(meshes.column(4.0, 2.0, (1.0,), dim=2, mesh_size=0.25, comm=comm), comm)


def problem(dmesh, table, **coupling_options) -> JointedNonlinearProblem:
    """The user's plane-strain UFL model with the joint, loaded by LOAD on top."""
    mesh = dmesh.mesh
    V = fem.functionspace(mesh, ("Lagrange", 1, (2,)))
    u, v = fem.Function(V), ufl.TestFunction(V)
    mu, lam = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    eps = ufl.sym(ufl.grad(u))
    sigma = 2 * mu * eps + lam * ufl.tr(eps) * ufl.Identity(2)
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=dmesh.boundaries)
    F = (ufl.inner(sigma, ufl.sym(ufl.grad(v))) * ufl.dx
         - ufl.inner(fem.Constant(mesh, (0.0, -LOAD)), v) * ds(dmesh.boundary_tag("top")))
    bcs = [fem.dirichletbc(PETSc.ScalarType(0.0), fem.locate_dofs_topological(V.sub(1), 1, dmesh.boundary("bottom")),
                           V.sub(1)),
           fem.dirichletbc(PETSc.ScalarType(0.0), fem.locate_dofs_topological(V.sub(0), 1, dmesh.boundary("left")),
                           V.sub(0))]
    coupling = JointCoupling(V, dmesh, {"joint_1": table}, shear_stiffness=1e9, bcs=bcs, **coupling_options)
    _COUNT[0] += 1
    return JointedNonlinearProblem(F, u, coupling, bcs=bcs, petsc_options_prefix=f"range{_COUNT[0]}_",
                                   petsc_options=SNES_OPTIONS)


KNI, VM = 1e10, 1e-3                      # LAW's K_ni [Pa/m], V_m [m]


def law_closure(stress: float) -> float:
    """Barton-Bandis closure at σ_n [m], closed form: Δ = σ V_m / (K_ni V_m + σ)."""
    return stress * VM / (KNI * VM + stress)


def continued_closure(max_stress: float, stress: float) -> float:
    """Closure on the linear continuation of a Barton-Bandis table ending at max_stress, at σ_n =
    stress [m], closed form: Δ = Δ_max + (σ - σ_max) / k(Δ_max), k(Δ) = K_ni V_m² / (V_m - Δ)²."""
    end = law_closure(max_stress)
    return end + (stress - max_stress) * (VM - end) ** 2 / (KNI * VM**2)


def gathered(comm, state: dict, key: str) -> np.ndarray:
    return np.concatenate(comm.allgather(np.asarray(state[key])))
