# SPDX-License-Identifier: MIT
"""Water in the joints from the initial state on (issue 45, item 4: a water table): the in-situ
stress is the total stress, the joints are pre-closed at the effective stress σ_n0 - α p0, so the
in-situ stage stays at u = 0 with the closure of the law at σ - α p0 (the closed form of
joint_pressure_cases.closure, independent of the code), point by point for a pressure that varies
along the joint; a later stage ramps from p0."""
import numpy as np
import pytest
from mpi4py import MPI

from fe_stack import require_fe
require_fe()

from joint_pressure_cases import SIGMA, closure, loaded_column  # noqa: E402
from rockjoint.fem import InSituStress  # noqa: E402
from rockjoint.fem.water.joint_pressure import set_initial_joint_pressure, set_joint_pressure  # noqa: E402


def column_in_situ(dim: int, alpha: float = 1.0, in_situ: bool = True):
    """The column of joint_pressure_cases without its top load, under an isotropic in-situ stress
    σ instead (the top free: σ0·n is carried there as a traction)."""
    model = loaded_column(dim, alpha=alpha, loaded=False)
    if in_situ:
        model.set_in_situ_stress(InSituStress.uniform(-SIGMA * np.eye(dim)))
    return model


@pytest.mark.parametrize("dim", [2, 3])
def test_in_situ_joints_are_pre_closed_at_the_effective_stress(dim):
    p0 = 2e6
    model = column_in_situ(dim)
    set_initial_joint_pressure(model, p0)
    state = model.solve(name="in-situ").gather_joints()
    np.testing.assert_allclose(state["closure"], closure(SIGMA - p0), rtol=1e-9)
    np.testing.assert_allclose(state["normal_stress"], SIGMA - p0, rtol=1e-9)   # the law's σ'
    assert model.comm.allreduce(float(np.abs(model.u.x.array).max(initial=0.0)), op=MPI.MAX) < 1e-12
    # the water drains over the next stage: the joint closes to the law's closure at the total σ
    set_joint_pressure(model, 0.0)
    np.testing.assert_allclose(model.solve(name="drained").gather_joints()["closure"], closure(SIGMA), rtol=1e-8)


def test_a_pressure_that_varies_along_the_joint_pre_closes_each_point_at_its_own():
    """p0 = 1 + 3 x MPa along the joint (x in [0, 1] m), α = 0.8: every point at Δ(σ - α p0(x))."""
    model = column_in_situ(2, alpha=0.8)
    set_initial_joint_pressure(model, lambda x: 1e6 + 3e6 * x[0])
    state = model.solve(name="in-situ").gather_joints()
    x = np.asarray(state["coordinates"]).reshape(-1, 2)[:, 0]
    expected = [closure(SIGMA - 0.8 * (1e6 + 3e6 * xi)) for xi in x]
    np.testing.assert_allclose(state["closure"], expected, rtol=1e-9)
    assert model.comm.allreduce(float(np.abs(model.u.x.array).max(initial=0.0)), op=MPI.MAX) < 1e-12


def test_initial_water_is_refused_where_it_has_no_place():
    with pytest.raises(RuntimeError, match="set_in_situ_stress first"):
        set_initial_joint_pressure(column_in_situ(2, in_situ=False), 1e6)
    model = column_in_situ(2)
    with pytest.raises(ValueError, match=r"initial water in joint 'joint_1' reaches its in-situ normal stress"):
        set_initial_joint_pressure(model, 6e6)
        model.solve(name="in-situ")
    model = column_in_situ(2)
    model.solve(name="in-situ")
    with pytest.raises(RuntimeError, match="before the first solve"):
        set_initial_joint_pressure(model, 1e6)
