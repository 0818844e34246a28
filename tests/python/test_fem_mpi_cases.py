# SPDX-License-Identifier: MIT
"""The serial joint-model checks repeated on 2 ranks (ctest pytest_mpi2_fem). Each calls the serial
test's body with MPI.COMM_WORLD meshes: ghosted joint nodes, pairs on the minus-cell owner,
residual contributions sent to owners, Jacobian blocks in off-process rows."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import test_fem_api as api  # noqa: E402  (tests/python is on sys.path under pytest)
import test_fem_column as column  # noqa: E402
import test_fem_hard_cases as hard  # noqa: E402
import test_fem_inclined as inclined  # noqa: E402
import test_fem_jacobian as jacobian  # noqa: E402
import test_fem_modulus as modulus  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_tang_jiao_column_on_two_ranks(dim):
    two_ranks()
    column.test_column_tang_jiao_table_matches_its_inverse(dim)


@pytest.mark.mpi
@pytest.mark.parametrize("dim,quadrature,shear", [(2, "gauss", "proportional"), (3, "nodal", "constant")])
def test_jacobian_fd_on_two_ranks(dim, quadrature, shear):
    two_ranks()
    jacobian.test_global_jacobian_matches_finite_differences(dim, quadrature, shear)


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_inclined_joint_on_two_ranks(dim):
    two_ranks()
    inclined.test_inclined_joint_tractions_match_uniform_stress_state(dim, "nodal")


@pytest.mark.mpi
def test_equivalent_modulus_ontwo_ranks():
    two_ranks()
    modulus.test_equivalent_modulus_of_joint_set(3)


@pytest.mark.mpi
def test_step_control_ontwo_ranks():
    two_ranks()
    hard.test_load_far_beyond_kni_vm_in_one_step_converges_by_closure_limiting()
    hard.test_residual_stiffness_gives_the_documented_opening("table")


@pytest.mark.mpi
def test_p2_ontwo_ranks():
    two_ranks()
    jm = api.meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=0.5, comm=MPI.COMM_WORLD)
    api.test_p2_column_matches_closed_form(api.distribute(jm, MPI.COMM_WORLD))
