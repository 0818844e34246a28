# SPDX-License-Identifier: MIT
"""On 2 ranks, inexact Newton with the lagged preconditioner gives the exact answer of the blocky
case (test_fem_inexact_newton.py) and one GAMG set-up, as in serial."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from test_fem_inexact_newton import assert_exact, blocky_model, dmesh  # noqa: E402,F401

pytestmark = pytest.mark.mpi


def test_inexact_newton_on_ranks_gives_the_exact_blocky_answer(dmesh):  # noqa: F811
    model = blocky_model(dmesh)
    sol = model.solve()
    assert_exact(model, sol)
    assert model.linear_solver.setups == 1
