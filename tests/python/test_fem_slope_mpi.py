# SPDX-License-Identifier: MIT
"""The strength-reduction factor of safety on 2 ranks (ctest pytest_mpi2_fem) = serial, in 2D and on
the extruded slope of test_fem_slope_3d.py: every
trial holds or fails alike (the failure is collective: Newton's norms and MUMPS' null pivots are
global), so the search takes the same steps to the same F."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from mpi_ranks import two_ranks  # noqa: E402
from slope_cases import slope_mesh, trial_solver  # noqa: E402
from test_fem_slope_3d import LENGTH, PHI, SIZES  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402


@pytest.mark.mpi
def test_factor_of_safety_on_two_ranks_is_the_serial_one():
    comm = two_ranks()
    phi, c = math.radians(30.0), 60e3
    parallel = factor_of_safety(trial_solver(slope_mesh(comm=comm), phi, c), tolerance=0.01)
    serial = factor_of_safety(trial_solver(slope_mesh(comm=MPI.COMM_SELF), phi, c), tolerance=0.01)
    assert [(f, held) for f, held, _ in parallel.trials] == [(f, held) for f, held, _ in serial.trials]
    assert parallel.factor == serial.factor
    assert parallel.moving == serial.moving and len(parallel.moving) == 1
    for block, motion in serial.block_motion.items():
        assert parallel.block_motion[block] == pytest.approx(motion, rel=1e-6, abs=1e-12)


@pytest.mark.mpi
def test_the_extruded_slope_on_two_ranks_is_the_serial_one():
    comm = two_ranks()
    # a loose bracket (10 %: fewer trials, each a 3D solve on both ranks and serially on each): the
    # search's steps are compared, not F against limit equilibrium (test_fem_slope_3d.py does that)
    parallel = factor_of_safety(trial_solver(slope_mesh(*SIZES, comm=comm, length=LENGTH), PHI, 0.0), tolerance=0.1)
    serial = factor_of_safety(trial_solver(slope_mesh(*SIZES, comm=MPI.COMM_SELF, length=LENGTH), PHI, 0.0),
                              tolerance=0.1)
    assert [(f, held) for f, held, _ in parallel.trials] == [(f, held) for f, held, _ in serial.trials]
    assert parallel.factor == serial.factor and parallel.moving == serial.moving
