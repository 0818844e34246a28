# SPDX-License-Identifier: MIT
"""Water in a joint on 2 ranks (ctest pytest_mpi2_fem): the closed form and the serial answer."""
import numpy as np
import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from joint_pressure_cases import SIGMA, closure, column, with_water  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_water_in_the_joint_on_two_ranks_is_the_serial_answer(dim):
    comm = two_ranks()
    state = with_water(column(dim, comm), 3e6)
    np.testing.assert_allclose(state["closure"], closure(SIGMA - 3e6), rtol=1e-8)
    serial = with_water(column(dim, MPI.COMM_SELF), 3e6)
    order = np.lexsort(np.asarray(state["coordinates"]).reshape(-1, dim).T)
    order_s = np.lexsort(np.asarray(serial["coordinates"]).reshape(-1, dim).T)
    np.testing.assert_allclose(np.asarray(state["closure"])[order], np.asarray(serial["closure"])[order_s],
                               rtol=1e-10)


@pytest.mark.mpi
def test_coupled_water_on_two_ranks_is_the_serial_answer():
    """The staggered coupling (gathered network, the same ω on every rank) on 2 ranks."""
    from test_fem_coupled_water import coupled_joint
    comm = two_ranks()
    _, water, _, x = coupled_joint(0.1, comm)
    _, serial, _, xs = coupled_joint(0.1, MPI.COMM_SELF)
    assert water.iterations == serial.iterations
    np.testing.assert_allclose(water.pressure[np.argsort(x)], serial.pressure[np.argsort(xs)], rtol=1e-9)
