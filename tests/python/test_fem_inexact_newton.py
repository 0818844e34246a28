# SPDX-License-Identifier: MIT
"""Inexact Newton (Eisenstat-Walker forcing) with a lagged GAMG preconditioner gives the exact
answer of a 3D blocky case and holds its supports.

Two joints dipping 60° (toward +x) and 30° (toward -x) cross at the centre of a unit cube (4
blocks). Principal stresses (2, 2, 5) MPa act as tractions on all six faces and only the corner
block is held (rollers bottom z, left x, front y): the exact solution is that stress, uniform in
every block, plus a constant jump per joint. Every joint point then carries σ_n = n·σn and
|τ| = |σn - σ_n n| and closes Δ(σ_n) of its Barton-Bandis law, and the supported displacements are
zero, whatever the linear tolerances of the Newton steps were.
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402
from petsc4py import PETSc  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402

STRESS = np.array([2e6, 2e6, 5e6])   # compression along x, y, z [Pa]
LAW = rockjoint.BartonBandis(1e10, 1e-3)


@pytest.fixture(scope="module")
def dmesh():
    comm = MPI.COMM_WORLD
    joints = [meshes.Joint((0.5, 0.5, 0.5), 60.0, 90.0, "steep"),
              meshes.Joint((0.5, 0.5, 0.5), 30.0, 270.0, "flat")]
    return distribute(meshes.jointed_block((1.0, 1.0, 1.0), joints, dim=3, mesh_size=0.15, comm=comm), comm)


def blocky_model(dmesh, shear=None, **newton):
    model = JointedRockModel(dmesh, rock=(20e9, 0.25), joints={"steep": LAW, "flat": LAW},
                             linear_solver="iterative", newton=NewtonOptions(verbose=False, **newton),
                             **(shear or {"shear_stiffness": 1e9}))
    # block_1 has the lowest centre of mass: the wedge under both joints, holding the corner 0.
    for face, axis in (("bottom", "z"), ("left", "x"), ("front", "y")):
        model.fix(face, axis, block="block_1")
    for face, axis, outward in (("left", 0, -1), ("right", 0, 1), ("front", 1, -1), ("back", 1, 1),
                                ("bottom", 2, -1), ("top", 2, 1)):
        t = np.zeros(3)
        t[axis] = STRESS[axis] * -outward
        model.add_traction(face, t)
    return model


def assert_exact(model, sol):
    joints = sol.gather_joints()
    n = joints["normal"]
    sigma_n = (n**2 * STRESS).sum(axis=1)
    tau = np.linalg.norm(-(STRESS * n) + sigma_n[:, None] * n, axis=1)
    assert np.ptp(sigma_n) > 1e6   # both joints present: σ_n = 2.75 and 4.25 MPa
    np.testing.assert_allclose(joints["normal_stress"], sigma_n, rtol=1e-8)
    np.testing.assert_allclose(np.linalg.norm(joints["shear_traction"], axis=1), tau, rtol=1e-8)
    np.testing.assert_allclose(joints["closure"], [LAW.closure_at_stress(s) for s in sigma_n], rtol=1e-8)
    # The supports hold exactly (a loose linear solve must not let them drift).
    n_owned = model.u.x.index_map.size_local * model.u.x.block_size
    owned = np.flatnonzero(model.problem().constrained[:n_owned])
    assert owned.size > 0 or model.comm.size > 1
    assert np.all(model.u.x.array[owned] == 0.0)


def test_inexact_newton_with_a_lagged_preconditioner_gives_the_exact_blocky_answer(dmesh):
    model = blocky_model(dmesh)
    sol = model.solve()
    assert_exact(model, sol)
    forcing = [e for r in sol.reports for e in r.forcing]
    assert forcing[0] == 0.1 and max(forcing) > 1e-3 and min(forcing) < 1e-3   # loose, then tight
    assert model.linear_solver.setups == 1   # one GAMG hierarchy for the whole Newton solve


def test_inexact_newton_needs_fewer_krylov_iterations_than_exact_steps(dmesh):
    inexact, exact = blocky_model(dmesh), blocky_model(dmesh, forcing="fixed")
    exact_sol = exact.solve()
    assert_exact(exact, exact_sol)
    assert all(e is None for r in exact_sol.reports for e in r.forcing)
    inexact.solve()
    assert sum(inexact.linear_solver.iterations) < 0.8 * sum(exact.linear_solver.iterations)


def test_inexact_newton_with_gmres_on_an_unsymmetric_jacobian_gives_the_exact_answer(dmesh):
    """k_s proportional to the normal stiffness: an unsymmetric Jacobian, GMRES (right
    preconditioned, so the forcing term bounds the true residual) with the lagged GAMG."""
    model = blocky_model(dmesh, shear={"shear_stiffness_ratio": 0.1})
    sol = model.solve()
    ksp = model.linear_solver.ksp
    # Right preconditioning: GMRES minimises the true residual, the one η bounds.
    assert ksp.getType() == "gmres" and ksp.getPCSide() == PETSc.PC.Side.RIGHT
    assert_exact(model, sol)
    assert max(e for r in sol.reports for e in r.forcing) >= 0.1
