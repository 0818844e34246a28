# SPDX-License-Identifier: MIT
"""Equivalent continuum on 2 ranks: the smeared column, the mixed column and a slipping inclined
set give the serial answers (closed forms, and the serial run of the slip case on COMM_SELF)."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

from continuum_cases import (HEIGHT, bb_closure, column, fail_first_newton, material,  # noqa: E402
                             rock_strain, sliding_answer, sliding_column, top_load, vertical)

STRESS = 5e6


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_smeared_and_mixed_columns_in_parallel(dim):
    assert MPI.COMM_WORLD.size == 2
    smeared = column(dim, smeared={"block_1": material(dim, [(vertical(dim), HEIGHT / 2)])})
    top_load(smeared, dim, STRESS)
    smeared.solve()
    closed = -(rock_strain(dim, STRESS) * HEIGHT + 2 * bb_closure(STRESS))
    assert smeared.boundary_mean_displacement("top")[dim - 1] == pytest.approx(closed, rel=1e-9)
    mixed = column(dim, (1.0, 2.0), smeared={"block_3": material(dim, [(vertical(dim), 0.25)])})
    top_load(mixed, dim, STRESS)
    mixed.solve()
    closed = -(rock_strain(dim, STRESS) * HEIGHT + 6 * bb_closure(STRESS))
    assert mixed.boundary_mean_displacement("top")[dim - 1] == pytest.approx(closed, rel=1e-9)


def slipping_column(comm):
    """The sliding column loaded past its strength in 3 steps: its faces' moves and largest slip."""
    model = sliding_column(comm)
    model.solve(load_steps=3)
    return sliding_answer(model)


@pytest.mark.mpi
def test_slipping_set_in_parallel_equals_serial():
    top, right, slip = slipping_column(MPI.COMM_WORLD)
    assert slip > 1e-5  # the set slips
    serial = slipping_column(MPI.COMM_SELF)
    np.testing.assert_allclose(top, serial[0], rtol=1e-8)
    np.testing.assert_allclose(right, serial[1], rtol=1e-8)
    assert slip == pytest.approx(serial[2], rel=1e-8)


@pytest.mark.mpi
def test_pseudo_transient_continuation_in_parallel_equals_serial(monkeypatch):
    """A load step solved by pseudo-transient continuation (its first Newton made to fail) on 2 ranks
    and on one: the same displacements and slip."""
    answers = []
    for comm in (MPI.COMM_WORLD, MPI.COMM_SELF):
        fail_first_newton(monkeypatch)
        model = sliding_column(comm)
        result = model.solve()
        assert "pseudo-transient" in result.reports[-1].reason
        answers.append(sliding_answer(model))
    (top, right, slip), serial = answers
    assert slip > 1e-5
    np.testing.assert_allclose(top, serial[0], rtol=1e-8)
    np.testing.assert_allclose(right, serial[1], rtol=1e-8)
    assert slip == pytest.approx(serial[2], rel=1e-8)
