# SPDX-License-Identifier: MIT
"""The assembled Newton Jacobian (bulk + joints, through PETSc) against central differences of
the assembled residual along random free directions: one check for every FE Jacobian test, and
the loaded block it is checked on."""
import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute


def sheared_block(dim, comm=MPI.COMM_WORLD, **model_options):
    """A unit block cut by a joint dipping 25° (Barton-Bandis, k_ni = 2e10 Pa/m, V_m = 1 mm), fixed
    at the bottom and loaded on top by a shear traction of 1 MPa and a normal one of 8 MPa: not yet
    solved. model_options go to JointedRockModel (shear stiffness, strength, quadrature, ...)."""
    jm = meshes.jointed_block((1.0,) * dim, [meshes.Joint((0.5,) * dim, 25.0, 90.0, "j")], dim=dim,
                              mesh_size=0.35 if dim == 2 else 0.5, comm=comm)
    model = JointedRockModel(distribute(jm, comm), rock=(10e9, 0.3), joints={"j": rockjoint.BartonBandis(2e10, 1e-3)},
                             plane="strain" if dim == 2 else None, newton=NewtonOptions(verbose=False),
                             **model_options)
    model.fix("bottom", "all")
    top = [0.0] * dim
    top[0], top[-1] = 1e6, -8e6
    model.add_traction("top", top)
    return model


def assert_jacobian_matches_fd(model, u0, relative_step, seed=0, draws=3, tol=1e-6, label=""):
    """|FD(v) - J v| < tol |J v| for `draws` random directions v (zero on supported dofs), central
    differences with the step relative_step × max|u0| (the same on every rank). Restores u0."""
    comm = model.comm
    problem = model.problem()  # the object the model's Newton drives
    model.u.x.array[:] = u0
    problem.residual_norm()
    problem.update_jacobian()
    J = problem.J
    free = problem.constrained == 0
    rng = np.random.default_rng(seed)
    u_max = comm.allreduce(np.abs(u0).max(), op=MPI.MAX)
    for _ in range(draws):
        v = model.u.x.petsc_vec.duplicate()
        with v.localForm() as loc:
            loc.array[:] = rng.uniform(-1, 1, loc.array.size) * free
        v.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        Jv = v.duplicate()
        J.mult(v, Jv)
        h = relative_step * u_max / max(v.norm(PETSc.NormType.INFINITY), 1e-300)
        res = []
        for sign in (1.0, -1.0):
            with v.localForm() as vl:
                model.u.x.array[:] = u0 + sign * h * vl.array
            problem.residual_norm()
            res.append(problem.r.copy())
        fd = res[0] - res[1]
        fd.scale(1.0 / (2 * h))
        fd.axpy(-1.0, Jv)
        assert fd.norm() < tol * Jv.norm(), f"{label}|FD - J v| / |J v| = {fd.norm() / Jv.norm():.2e}"
    model.u.x.array[:] = u0
