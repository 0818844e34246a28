# SPDX-License-Identifier: MIT
"""Water that pushes back (issue 45, item 1): a joint with fluid pressure p sees σ'_n = σ_n - α p
in its law and strength, and the water pushes both walls apart; against the closed forms of
joint_pressure_cases.py (Barton-Bandis, uniaxial column: σ_n = σ everywhere on the joint)."""
import numpy as np
import pytest

from fe_stack import require_fe
require_fe()

import rockjoint  # noqa: E402
from joint_pressure_cases import SIGMA, closure, column, with_water  # noqa: E402
from rockjoint.fem.solvers.linear_solver import LinearSolveError  # noqa: E402
from rockjoint.fem.water.joint_pressure import set_joint_pressure  # noqa: E402


@pytest.mark.parametrize("dim", [2, 3])
def test_closure_is_the_laws_at_the_effective_stress(dim):
    model = column(dim)
    dry = model.stages[-1].gather_joints()
    np.testing.assert_allclose(dry["closure"], closure(SIGMA), rtol=1e-9)
    for p in (1e6, 3e6, 4.5e6):       # p ramps over each stage from the last one's value
        state = with_water(model, p)
        np.testing.assert_allclose(state["closure"], closure(SIGMA - p), rtol=1e-8)
        np.testing.assert_allclose(state["normal_stress"], SIGMA - p, rtol=1e-8)   # the law's σ'
    # the water drained again: the joint closes back to its dry closure (an elastic law)
    np.testing.assert_allclose(with_water(model, 0.0)["closure"], closure(SIGMA), rtol=1e-8)


def test_effective_stress_coefficient_scales_the_water():
    model = column(2, alpha=0.6)
    np.testing.assert_allclose(with_water(model, 4e6)["closure"], closure(SIGMA - 0.6 * 4e6), rtol=1e-8)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_joint_opens_as_the_water_reaches_the_stress(dim):
    """Hydraulic jacking: with a residual stiffness k_r the joint closes as the water rises and
    opens by (σ - p)/k_r past p = σ (the law carries nothing there)."""
    kr = 1e9
    model = column(dim, residual_stiffness=kr)
    for p in (4.9e6, 5.0e6, 5.5e6):
        state = with_water(model, p, load_steps=2)
        np.testing.assert_allclose(state["closure"], closure(SIGMA - p, kr), rtol=1e-7, atol=1e-15)
    assert np.all(state["closure"] < 0) and np.all(state["status"] == int(rockjoint.Status.open))


def test_bad_pressures_are_refused_with_their_reason():
    model = column(2)
    with pytest.raises(ValueError, match="not finite"):
        set_joint_pressure(model, float("nan"))
    with pytest.raises(ValueError, match="joint points on this rank"):
        set_joint_pressure(model, np.zeros(3))
    with pytest.raises(ValueError, match="effective_stress_coefficient.*\\[0, 1\\]"):
        column(2, alpha=1.5)


def test_water_that_opens_an_unheld_joint_is_named_when_nothing_holds_the_block():
    """Hydraulic jacking without a residual stiffness: the water opens the whole joint, the top
    block is then held by nothing, and the solve's error names the joint, the pressure and the
    stress (as an open joint is named for tension). The same water below the stress is fine."""
    model = column(2)                                   # k_r = 0
    with_water(model, 4.9e6)                            # below σ: fine
    set_joint_pressure(model, 5.2e6)
    with pytest.raises(LinearSolveError, match=r"joint 'joint_1'.*water up to 5\.2 MPa.*residual_stiffness"):
        model.solve(name="water 5.2 MPa")
