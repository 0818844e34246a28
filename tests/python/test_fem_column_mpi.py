# SPDX-License-Identifier: MIT
"""The joint column on 2 ranks (run by ctest pytest_mpi2_fem: mpirun -n 2 ... -m mpi).

Same closed form as test_fem_column.py (rollers, free sides: uniform uniaxial stress), and the
same answer as a serial solve of the same mesh on MPI.COMM_SELF (1 vs 2 ranks).
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, LinearSolveError  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402

E, NU = 20e9, 0.25
HEIGHT, JOINTS = 3.0, (1.0, 2.0)
KNI, VM = 1e10, 1e-3


def solve_column(dim, comm, stress, linear_solver="direct"):
    law = rockjoint.BartonBandis(KNI, VM)
    jm = meshes.column(1.0, HEIGHT, JOINTS, dim=dim, mesh_size=0.5 if dim == 3 else 0.25, comm=comm)
    dmesh = distribute(jm, comm)
    model = JointedRockModel(dmesh, rock=(E, NU), joints={"joint_1": law, "joint_2": law},
                             shear_stiffness=1e9, plane="strain" if dim == 2 else None,
                             linear_solver=linear_solver)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    top = [0.0] * dim
    top[-1] = -stress
    model.add_traction("top", top)
    sol = model.solve()
    return model, sol


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_column_on_two_ranks_matches_closed_form_and_serial(dim):
    comm = two_ranks()
    stress = 5e6
    model, sol = solve_column(dim, comm, stress)
    # The mesh is really distributed (both ranks own cells).
    owned = model.mesh.topology.index_map(dim).size_local
    assert comm.allreduce(owned > 0, op=MPI.LAND)
    npairs = comm.allreduce(model.interface.num_pairs)
    closure = stress * VM / (KNI * VM + stress)
    modulus = E / (1 - NU**2) if dim == 2 else E
    ref = -(stress * HEIGHT / modulus + len(JOINTS) * closure)
    u_top = model.boundary_mean_displacement("top")[dim - 1]
    assert u_top == pytest.approx(ref, rel=1e-8)
    joints = sol.gather_joints()
    np.testing.assert_allclose(joints["closure"], closure, rtol=1e-8)

    # 1 rank vs 2 ranks: the same mesh solved serially on every rank.
    serial, ssol = solve_column(dim, MPI.COMM_SELF, stress)
    assert serial.boundary_mean_displacement("top")[dim - 1] == pytest.approx(u_top, rel=1e-10)
    assert serial.interface.num_pairs == npairs  # every pair assembled exactly once in parallel


@pytest.mark.mpi
def test_iterative_solver_on_two_ranks():
    """CG + GAMG with the per-block rigid-body near-nullspace gives the same answer."""
    stress = 5e6
    model, _ = solve_column(3, MPI.COMM_WORLD, stress, linear_solver="iterative")
    closure = stress * VM / (KNI * VM + stress)
    ref = -(stress * HEIGHT / E + len(JOINTS) * closure)
    assert model.boundary_mean_displacement("top")[2] == pytest.approx(ref, rel=1e-8)
    assert model.linear_solver.kind == "iterative"


@pytest.mark.mpi
def test_singular_model_fails_cleanly_on_two_ranks():
    """A block held only by a joint in tension: every rank raises LinearSolveError."""
    comm = MPI.COMM_WORLD
    jm = meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=0.25, comm=comm)
    dmesh = distribute(jm, comm)
    model = JointedRockModel(dmesh, rock=(E, NU), joints={"joint_1": rockjoint.BartonBandis(KNI, VM)},
                             shear_stiffness=1e9)
    model.fix("bottom", "all")
    model.add_traction("top", (0.0, 1e6))  # pulls the top block off
    with pytest.raises(LinearSolveError):
        model.solve()
