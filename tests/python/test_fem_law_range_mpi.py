# SPDX-License-Identifier: MIT
"""Past a law's range on 2 ranks (mpirun -n 2 ... -m mpi; issue 39, item 1): the warning comes
once, from rank 0, with the values gathered over both ranks; strict mode raises on both ranks
(no rank left waiting in a collective); the summary is the same on every rank and equals the
serial one of the same column (law_range_case: σ_n = 10 MPa on every joint point, closed form).
"""
import warnings

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

from rockjoint.fem import BeyondRangeError, JointedRockModel, NewtonOptions, RangeWarning  # noqa: E402

import law_range_case as case  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402


def solve_recording(problem):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        problem.solve()
    assert problem.solver.getConvergedReason() > 0
    return [str(w.message) for w in record if issubclass(w.category, RangeWarning)]


@pytest.mark.mpi
def test_two_ranks_warn_once_on_rank_0_with_the_gathered_values():
    comm = two_ranks()
    dmesh = case.column(comm)
    problem = case.problem(dmesh, case.SHORT)
    messages = solve_recording(problem)
    summary = problem.coupling.summary(problem.u)["joint_1"]
    # the joint's points really are spread over both ranks, and the summary gathers them
    local = problem.coupling.state(problem.u)
    assert min(comm.allgather(local["closure"].size)) > 0
    assert summary.points == case.gathered(comm, local, "closure").size
    assert comm.allgather(summary) == [summary, summary]
    serial = case.problem(case.column(MPI.COMM_SELF), case.SHORT)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        serial.solve()
    s = serial.coupling.summary(serial.u)["joint_1"]
    assert (s.points, s.status) == (summary.points, summary.status)
    np.testing.assert_allclose([s.max_normal_stress, s.max_closure], [summary.max_normal_stress, summary.max_closure],
                               rtol=1e-9)
    np.testing.assert_allclose(summary.max_normal_stress, case.LOAD, rtol=1e-9)
    # last, as they differ by rank (a failure on one rank must not leave the other in a collective)
    if comm.rank == 0:
        (message,) = messages
        assert f"joint 'joint_1': {summary.points} of {summary.points} points past the range" in message
        assert "σ_n reaches 10 MPa" in message and "0 - 2 MPa" in message
    else:
        assert messages == []


@pytest.mark.mpi
def test_strict_mode_raises_on_both_ranks():
    comm = two_ranks()
    problem = case.problem(case.column(comm), case.SHORT, beyond_range="raise")
    with pytest.raises(BeyondRangeError, match="σ_n reaches 10 MPa"):
        problem.solve()
    comm.barrier()  # both ranks got here: none is left in a collective


@pytest.mark.mpi
def test_a_table_that_covers_the_load_is_silent_on_both_ranks():
    comm = two_ranks()
    problem = case.problem(case.column(comm), case.LONG)
    assert solve_recording(problem) == []
    assert problem.coupling.summary(problem.u)["joint_1"].beyond_range == 0


@pytest.mark.mpi
def test_jointed_rock_model_warns_once_from_rank_0():
    comm = two_ranks()
    model = JointedRockModel(case.column(comm), rock=(case.E, case.NU), joints={"joint_1": case.SHORT},
                             shear_stiffness=1e9, plane="strain", newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -case.LOAD))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        result = model.solve(load_steps=2, name="load")
    messages = [str(w.message) for w in record if issubclass(w.category, RangeWarning)]
    summary = result.summary()
    assert summary == comm.bcast(summary, root=0) and summary["joint_1"].beyond_range > 0
    assert len(messages) == (1 if comm.rank == 0 else 0)
    if comm.rank == 0:
        assert "in stage 'load'" in messages[0] and "σ_n reaches 10 MPa" in messages[0]

