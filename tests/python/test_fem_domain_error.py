# SPDX-License-Identifier: MIT
"""A step past a law's maximum closure: the joint residual is not finite, and both solvers of
JointedRockModel cut the step instead of continuing from a stale or garbage residual.

Barton-Bandis column (K_ni = 1e10 Pa/m, V_m = 1 mm) loaded to σ = 20 MPa in one load step with
the closure limiter switched off: Newton's first step from rest closes each joint by about
σ / K_ni = 2 mm > V_m, beyond the law's range, so the trial residual is infinite. PETSc SNES
must receive that as a function-domain error (SNESSetFunctionDomainError) and the project's
Newton as an infinite residual norm; either way the load step is cut, and the answer is the
closed form top displacement -(σ H / E' + N Δ(σ)), Δ(σ) = V_m σ / (K_ni V_m + σ).
"""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import rockjoint  # noqa: E402
from rockjoint.fem import NewtonOptions  # noqa: E402

from test_fem_column import KNI, VM, column_model, expected_top  # noqa: E402

STRESS = 20e6


@pytest.mark.parametrize("solver, line_search", [("snes", "basic"), ("newton", None)])
def test_a_nonfinite_joint_residual_fails_the_step_and_the_load_step_is_cut(solver, line_search):
    """Without backtracking a trial past the law's range fails the Newton step: SNES's solve
    with a diverged reason (the domain error fails its line search), the project's Newton (its
    halving of a non-finite step switched off) on its infinite residual; the load stepping then
    halves the step and reaches the load."""
    law = rockjoint.BartonBandis(KNI, VM)
    assert STRESS / KNI > VM  # the first Newton step from rest leaves the law's range
    options = {"snes_linesearch_type": line_search} if line_search else None
    model = column_model(2, law, newton=NewtonOptions(closure_limit=None, verbose=False, max_backtracks=0),
                         petsc_options=options)
    model.add_traction("top", (0.0, -STRESS))
    result = model.solve(load_steps=1, solver=solver)
    assert model.counts["nonfinite_residuals"] >= 1
    failed = [r for r in result.reports if not r.converged]
    assert failed, "the step that met the non-finite residual was not cut"
    # PETSc 3.22's basic line search turns the domain error into a failed line search
    expected = ("DIVERGED_FUNCTION_DOMAIN", "DIVERGED_LINE_SEARCH") if solver == "snes" else ("non-finite residual",)
    assert all(any(e in r.reason for e in expected) for r in failed), [r.reason for r in failed]
    assert result.reports[-1].converged
    top = model.boundary_mean_displacement("top")[1]
    assert top == pytest.approx(expected_top(2, STRESS, VM * STRESS / (KNI * VM + STRESS)), rel=1e-8)


def test_the_project_newton_halves_a_step_into_a_nonfinite_residual():
    """The project's Newton (default max_backtracks) halves the step that left the law's range,
    as SNES's backtracking does: the load step converges without being cut."""
    model = column_model(2, rockjoint.BartonBandis(KNI, VM),
                         newton=NewtonOptions(closure_limit=None, verbose=False))
    model.add_traction("top", (0.0, -STRESS))
    result = model.solve(load_steps=1)
    assert model.counts["nonfinite_residuals"] >= 1
    assert len(result.reports) == 1 and result.reports[0].converged
    assert min(result.reports[0].step_lengths) < 1.0
    top = model.boundary_mean_displacement("top")[1]
    assert top == pytest.approx(expected_top(2, STRESS, VM * STRESS / (KNI * VM + STRESS)), rel=1e-8)


def test_snes_backtracking_line_search_cuts_the_newton_step_at_the_domain_error():
    """SNES's default backtracking line search (bt) takes the domain error as a failed trial and
    shortens the Newton step itself: the load step converges without being cut."""
    model = column_model(2, rockjoint.BartonBandis(KNI, VM),
                         newton=NewtonOptions(closure_limit=None, verbose=False))
    model.add_traction("top", (0.0, -STRESS))
    result = model.solve(load_steps=1, solver="snes")
    assert model.counts["nonfinite_residuals"] >= 1
    assert result.reports[-1].converged
    top = model.boundary_mean_displacement("top")[1]
    assert top == pytest.approx(expected_top(2, STRESS, VM * STRESS / (KNI * VM + STRESS)), rel=1e-8)


def test_the_snes_path_with_the_limiter_meets_no_nonfinite_residual():
    """With the closure limiter (the default) SNES's pre-check keeps every trial in range."""
    model = column_model(2, rockjoint.BartonBandis(KNI, VM), newton=NewtonOptions(verbose=False))
    model.add_traction("top", (0.0, -STRESS))
    model.solve(load_steps=1, solver="snes")
    assert model.counts["nonfinite_residuals"] == 0
    closure = VM * STRESS / (KNI * VM + STRESS)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(expected_top(2, STRESS, closure), rel=1e-8)
