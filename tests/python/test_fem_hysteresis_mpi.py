# SPDX-License-Identifier: MIT
"""The hysteretic FE column on 2 ranks equals the closed form through the load cycle (the same
checks as the serial test, test_fem_hysteresis.py), with the point history kept per rank."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from hysteresis_cases import check_cycle, hysteretic_column, run_cycle  # noqa: E402


@pytest.mark.mpi
def test_column_cycle_on_two_ranks():
    check_cycle(*run_cycle(hysteretic_column(mesh_size=0.2)))
