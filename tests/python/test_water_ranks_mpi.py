# SPDX-License-Identifier: MIT
"""The coupled water on several ranks is the serial answer (issue 45, item 2: "serial equals 2 and
3 ranks"): ctest runs this file under `mpirun -n 2` (pytest_mpi2_water) and `-n 3`
(pytest_mpi3_water, an odd count: a rank may hold none of the joint). The network is gathered
and the iterates too, so the iterations and the pressures must agree to the solvers' tolerance."""
import numpy as np
import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402


def several_ranks(comm=MPI.COMM_WORLD):
    assert comm.size in (2, 3), "run with mpirun -n 2 or -n 3"
    return comm


def by_position(state, dim):
    """The order of the joint points by their coordinates (rounded: the two walls' copies of a
    node carry the same pressure, so their relative order does not matter)."""
    x = np.round(np.asarray(state["coordinates"], dtype=float).reshape(-1, dim), 9)
    return np.lexsort(x.T)


@pytest.mark.mpi
@pytest.mark.parametrize("dim, size", [(2, 0.1), (3, 0.25)])
def test_coupled_steady_water_is_the_serial_answer(dim, size):
    from test_fem_coupled_water import coupled_joint
    comm = several_ranks()
    _, water, state, _ = coupled_joint(size, comm, dim=dim)
    _, serial, state_s, _ = coupled_joint(size, MPI.COMM_SELF, dim=dim)
    assert water.iterations == serial.iterations
    np.testing.assert_allclose(water.pressure[by_position(state, dim)], serial.pressure[by_position(state_s, dim)],
                               rtol=1e-9, atol=1e-3)


@pytest.mark.mpi
@pytest.mark.parametrize("coupling", ["two_way", "one_way"])
def test_transient_water_is_the_serial_answer(coupling):
    from test_fem_transient_water import run
    comm = several_ranks()
    _, water, state, error, _ = run(coupling, 5, comm=comm, joint_size=0.05)
    _, serial, state_s, error_s, _ = run(coupling, 5, comm=MPI.COMM_SELF, joint_size=0.05)
    assert water.iterations == serial.iterations
    np.testing.assert_allclose(water.pressures[-1][by_position(state, 2)], serial.pressures[-1][by_position(state_s, 2)],
                               rtol=1e-9, atol=1e-3)
    assert error == pytest.approx(error_s, rel=1e-6)
