# SPDX-License-Identifier: MIT
"""A user's own model for the coupling-API tests, on the geometry of user_model_geometry.

The gmsh model is read with meshes.from_gmsh_model; the FE model is written in plain DOLFINx/UFL
(E per block, gravity, a traction on top with a shear part) with JointCoupling for the joint. The same problem through
JointedRockModel is the independent reference: it assembles K once and runs the project's own
Newton, while the user path assembles the UFL residual every iteration under PETSc SNES
(JointedNonlinearProblem, shaped as DOLFINx 0.11's NonlinearProblem).
"""
import itertools

import numpy as np
import ufl
from dolfinx import fem
from petsc4py import PETSc

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointCoupling, JointedNonlinearProblem, JointedRockModel, NewtonOptions, distribute
from user_model_geometry import DIP, SIZE, build_gmsh_model  # noqa: F401  (re-exported for the tests)

E_BLOCK = {"lower": 30e9, "upper": 10e9}       # [Pa]
POISSON = 0.25
WEIGHT = 2.6e4                                 # ρ g [N/m³]
TOP_TRACTION = {2: (0.4e6, -4e6), 3: (0.4e6, 0.0, -4e6)}  # [Pa]
LAW = rockjoint.BartonBandis(1e10, 1e-3)       # K_ni [Pa/m], V_m [m]
SHEAR_STIFFNESS = 2e9                          # [Pa/m]
# Newton with a full step and direct solves; snes_rtol relative to F(u = 0), the load.
SNES_OPTIONS = {"snes_rtol": 1e-10, "snes_atol": 1e-14, "snes_stol": 0.0, "snes_max_it": 30,
                "snes_linesearch_type": "basic",
                "ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"}
_PREFIXES = itertools.count()


def unique_prefix(stem: str = "user") -> str:
    """A fresh options prefix (the same sequence on every rank)."""
    return f"{stem}{next(_PREFIXES)}_"


def distributed_case(gmsh, dim, mesh_size, comm):
    """Build the gmsh model on rank 0, read it, distribute it over comm."""
    jm = None
    if comm.rank == 0:
        build_gmsh_model(gmsh, dim, mesh_size)
        try:
            jm = meshes.from_gmsh_model(joints=["fault"])
        finally:
            gmsh.model.remove()
    return distribute(jm, comm)


def user_problem(dmesh, degree=1, law=LAW, petsc_options=None, prefix=None):
    """The user's UFL model + the joint; returns the JointedNonlinearProblem (SNES_OPTIONS unless
    petsc_options are given)."""
    mesh = dmesh.mesh
    dim = mesh.geometry.dim
    V = fem.functionspace(mesh, ("Lagrange", degree, (mesh.geometry.dim,)))
    u, v = fem.Function(V), ufl.TestFunction(V)
    Q = fem.functionspace(mesh, ("DG", 0))
    E = fem.Function(Q)
    tags = dmesh.cell_blocks
    for name, value in E_BLOCK.items():
        E.x.array[Q.dofmap.list.ravel()[tags.indices[tags.values == dmesh.block_tag(name)]]] = value
    mu, lam = E / (2 * (1 + POISSON)), E * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
    eps = ufl.sym(ufl.grad(u))
    sigma = 2 * mu * eps + lam * ufl.tr(eps) * ufl.Identity(dim)
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=dmesh.boundaries)
    top = {n: t for t, n in dmesh.names["boundaries"].items()}["top"]
    gravity = np.zeros(dim)
    gravity[-1] = -WEIGHT
    F = (ufl.inner(sigma, ufl.sym(ufl.grad(v))) * ufl.dx - ufl.inner(fem.Constant(mesh, gravity), v) * ufl.dx
         - ufl.inner(fem.Constant(mesh, np.array(TOP_TRACTION[dim])), v) * ds(top))
    bcs = [fem.dirichletbc(np.zeros(dim, dtype=PETSc.ScalarType),
                           fem.locate_dofs_topological(V, dim - 1, dmesh.boundary("bottom")), V),
           fem.dirichletbc(PETSc.ScalarType(0.0),
                           fem.locate_dofs_topological(V.sub(0), dim - 1, dmesh.boundary("left")), V.sub(0))]
    if dim == 3:
        bcs.append(fem.dirichletbc(PETSc.ScalarType(0.0),
                                   fem.locate_dofs_topological(V.sub(1), 2, dmesh.boundary("front")), V.sub(1)))
    coupling = JointCoupling(V, dmesh, {"fault": law}, shear_stiffness=SHEAR_STIFFNESS, bcs=bcs)
    return JointedNonlinearProblem(F, u, coupling, bcs=bcs, petsc_options_prefix=unique_prefix() if prefix is None else prefix,
                                   petsc_options=SNES_OPTIONS if petsc_options is None else petsc_options)


def solve(problem):
    """problem.solve(), as a DOLFINx 0.11 user solves a NonlinearProblem; SNES iterations."""
    problem.solve()
    assert problem.solver.getConvergedReason() > 0, problem.solver.getConvergedReason()
    return problem.solver.getIterationNumber()


def rock_model(dmesh, degree=1, law=LAW):
    """The same problem through JointedRockModel (the reference)."""
    dim = dmesh.mesh.geometry.dim
    model = JointedRockModel(dmesh, element_degree=degree, rock={b: (E, POISSON) for b, E in E_BLOCK.items()},
                             joints={"fault": law}, shear_stiffness=SHEAR_STIFFNESS,
                             plane="strain" if dim == 2 else None,
                             newton=NewtonOptions(rtol=1e-11, verbose=False), linear_solver="direct")
    model.fix("bottom", "all")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    gravity = [0.0] * dim
    gravity[-1] = -WEIGHT
    model.add_body_force(gravity)
    model.add_traction("top", TOP_TRACTION[dim])
    model.solve()
    return model
