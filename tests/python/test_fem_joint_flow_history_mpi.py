# SPDX-License-Identifier: MIT
"""Flow with history on 2 ranks (docs/flow.md "Transmissivity with history (issue 41)"): the
column of flow_history_cases.py loaded and unloaded, each point's largest closure gathered over
the stages, equals the closed form of the law with history and the serial run."""
import numpy as np
import pytest
from mpi4py import MPI

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint import flow  # noqa: E402
from rockjoint.fem import network_flow  # noqa: E402
from rockjoint.fem.water.joint_flow import Fluid  # noqa: E402
from joint_flow_cases import APERTURE, HEADS, LOAD, WIDTH  # noqa: E402
from flow_history_cases import (LOSS, bb_closure, branch_transmissivity, check_coupled_twice,  # noqa: E402
                                coupled_twice, cycled_column, unloaded_closures)
from mpi_ranks import two_ranks  # noqa: E402


@pytest.mark.mpi
def test_unloaded_network_with_history_on_two_ranks():
    comm = two_ranks()
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=APERTURE, hydraulic_loss=LOSS)
    laws = {"joint_1": law, "joint_2": law}
    parallel = network_flow(cycled_column(comm), laws, HEADS)
    factor = Fluid().conductivity_factor * (HEADS["left"] - HEADS["right"]) / WIDTH
    expected = factor * sum(branch_transmissivity(d, bb_closure(LOAD)) for d in unloaded_closures().values())
    assert parallel.flow_rates["left"] == pytest.approx(expected, rel=1e-7)
    serial = network_flow(cycled_column(MPI.COMM_SELF), laws, HEADS)
    np.testing.assert_allclose(np.sort(serial.point_transmissivity), np.sort(parallel.point_transmissivity),
                               rtol=1e-9)
    assert serial.flow_rates["left"] == pytest.approx(parallel.flow_rates["left"], rel=1e-9)


@pytest.mark.mpi
def test_coupling_iterates_do_not_enter_the_largest_closure_on_two_ranks():
    """test_joint_flow_history.py's two coupled solves on 2 ranks: the same checks, and the same
    transmissivities as the serial run."""
    comm = two_ranks()
    model, network, accepted = coupled_twice(comm)
    check_coupled_twice(model, network, accepted)
    _, serial, _ = coupled_twice(MPI.COMM_SELF)
    np.testing.assert_allclose(np.sort(serial.point_transmissivity), np.sort(network.point_transmissivity),
                               rtol=1e-9)
