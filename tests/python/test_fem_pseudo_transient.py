# SPDX-License-Identifier: MIT
"""Pseudo-transient continuation of a load step with smeared sets (pseudo_transient.py): the viscous
pseudo-time steps end at the rate-independent equilibrium, a continuation that cannot finish says
so, and bad options are refused. The first Newton of the step is made to fail on purpose (the
tunnel bench's period-2 cycle takes minutes to reach), so that the continuation is what solves it."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint.fem import ConvergenceError, NewtonOptions  # noqa: E402
from continuum_cases import fail_first_newton, sliding_answer as answer, sliding_column  # noqa: E402


@pytest.fixture
def first_newton_fails(monkeypatch):
    return fail_first_newton(monkeypatch)


def test_continuation_ends_at_a_rate_independent_equilibrium(first_newton_fails):
    """The committed end state of the viscous path is an equilibrium of the rate-independent model:
    its residual, evaluated afresh from the committed state, meets the tolerance, and every point's
    shear traction on the set is within the Coulomb strength. The path differs from one
    rate-independent step (sliding is path dependent: the rollers make the slip non-uniform), so
    the answer is compared with that step's to 1 % only (measured: 5e-4 to 8e-4 on PETSc 3.22 and 3.25)."""
    first_newton_fails["first"] = False
    reference = sliding_column()
    reference.solve()
    top, right, slip = answer(reference)
    assert slip > 1e-5  # the set slides

    first_newton_fails["first"] = True
    model = sliding_column()
    result = model.solve()
    assert "pseudo-transient" in result.reports[-1].reason
    assert result.reports[-1].iterations > reference.stages[-1].newton_iterations  # viscous path taken
    assert model.smeared.relaxation is None  # rate-independent again afterwards
    options = model.newton_options
    problem = model.problem()
    assert problem.residual_norm() <= options.rtol * problem.load_norm(1.0)

    sigma = model.smeared.stress.x.array.reshape(-1, 3)  # (xx, yy, xy) [Pa], tension +
    th = np.radians(35.0)
    n, t = np.array([-np.sin(th), np.cos(th)]), np.array([np.cos(th), np.sin(th)])
    S = np.zeros((sigma.shape[0], 2, 2))
    S[:, 0, 0], S[:, 1, 1], S[:, 0, 1], S[:, 1, 0] = sigma[:, 0], sigma[:, 1], sigma[:, 2], sigma[:, 2]
    traction = S @ n
    normal, shear = -(traction @ n), np.abs(traction @ t)
    assert np.all(normal > 0)
    # Within the strength to the local solve's tolerance: its residual B^T σ - t/s is converged to
    # 1e-10 of its scale (|B^T D ε| + |B^T D B| |j| ~ 3e8 Pa/m here), i.e. s × 0.03 Pa/m = 0.015 Pa
    # of traction against τ_y >= 3e5 Pa: 5e-8 relative.
    ratio = shear / (np.tan(np.radians(20.0)) * normal)
    assert ratio.max() <= 1 + 1e-7
    assert np.sum(ratio >= 1 - 1e-7) > 0  # some points on it: sliding

    t_, r_, s_ = answer(model)
    np.testing.assert_allclose(t_, top, rtol=1e-2)
    np.testing.assert_allclose(r_, right, rtol=1e-2)
    assert s_ == pytest.approx(slip, rel=1e-2)


def test_continuation_that_cannot_finish_raises(first_newton_fails):
    """One pseudo-time step at r = 1e-3 leaves most of the joints' deformation to come: the step
    is refused with an error that says the model is not in equilibrium."""
    model = sliding_column(relaxation_initial=1e-3, relaxation_max_steps=1)
    with pytest.raises(ConvergenceError, match="not reach the rate-independent equilibrium"):
        model.solve()
    assert model.smeared.relaxation is None


def test_without_continuation_the_failed_step_is_cut(first_newton_fails):
    """relaxation_initial=None: the failed step goes back to the load stepping (cut and retried)."""
    model = sliding_column(relaxation_initial=None)
    result = model.solve()
    assert not result.reports[0].converged and result.reports[0].reason == "failed on purpose"
    assert all("pseudo" not in r.reason for r in result.reports)


@pytest.mark.parametrize("bad", [{"relaxation_initial": 0.0}, {"relaxation_initial": -1.0},
                                 {"relaxation_initial": float("nan")}, {"relaxation_max_steps": 0},
                                 {"relaxation_max": 0.0}, {"relaxation_max": float("inf")},
                                 {"relaxation_max_steps": 2.5}])
def test_bad_continuation_options(bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        NewtonOptions(**bad)
