# SPDX-License-Identifier: MIT
"""Joint-network flow on 2 ranks equals the closed form and the serial numbers (each rank solves
the gathered network: the same NetworkFlow on every rank, whatever the partition)."""
import numpy as np
import pytest
from mpi4py import MPI

from fe_stack import require_fe  # noqa: E402
require_fe()

from joint_flow_cases import HEADS, WIDTH, cubic_law, expected_rate, solved_column  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402
from rockjoint.fem.water.joint_flow import network_flow  # noqa: E402


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_parallel_joints_on_two_ranks(dim):
    comm = two_ranks()
    model = solved_column(dim, (1.0, 2.0), comm=comm)
    flow = network_flow(model, {"joint_1": cubic_law, "joint_2": cubic_law}, HEADS)
    assert flow.flow_rates["left"] == pytest.approx(expected_rate(dim, 2), rel=1e-9)
    linear = HEADS["left"] + (HEADS["right"] - HEADS["left"]) * flow.nodes[:, 0] / WIDTH
    np.testing.assert_allclose(flow.head, linear, rtol=0, atol=1e-9 * HEADS["left"])
    # every rank holds the same network and heads
    heads = comm.allgather(flow.head)
    np.testing.assert_array_equal(heads[0], heads[1])
    # the serial run of the same mesh (rank 0's own communicator) gives the same nodes and heads
    serial = network_flow(solved_column(dim, (1.0, 2.0), comm=MPI.COMM_SELF),
                          {"joint_1": cubic_law, "joint_2": cubic_law}, HEADS)
    np.testing.assert_allclose(serial.nodes, flow.nodes, rtol=0, atol=1e-12)
    np.testing.assert_allclose(serial.head, flow.head, rtol=0, atol=1e-9 * HEADS["left"])
    assert serial.flow_rates["left"] == pytest.approx(flow.flow_rates["left"], rel=1e-9)
