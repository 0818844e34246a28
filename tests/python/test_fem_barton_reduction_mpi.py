# SPDX-License-Identifier: MIT
"""The Barton block of test_fem_barton_reduction.py on 2 ranks: the closed-form factor bracketed
as in serial, and every trial holds or fails as the serial run's."""
import pytest
from mpi4py import MPI

from fe_stack import require_fe
require_fe()

from mpi_ranks import two_ranks  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402
from test_fem_barton_reduction import block_trials, check_block_factor  # noqa: E402


@pytest.mark.mpi
def test_block_on_a_barton_joint_on_two_ranks():
    found, _ = check_block_factor(two_ranks())
    serial = factor_of_safety(block_trials(MPI.COMM_SELF), tolerance=0.01)
    assert [(f, held) for f, held, _ in serial.trials] == [(f, held) for f, held, _ in found.trials]
