# SPDX-License-Identifier: MIT
"""Newton's stopping rules on scalar problems with known answers: the residual tolerance relative
to the load (or to the initial residual when the load is zero), an increment at round-off, and
stagnation (rockjoint.fem.solvers.newton; no DOLFINx needed)."""
import math

import numpy as np
import pytest

from rockjoint.fem.solvers.newton import NewtonOptions, NewtonProblem, newton, solve_load_path


class Scalar(NewtonProblem):
    """r(u) = k u + c u³ - λ f: a stiffening spring, a NewtonProblem (newton.py's protocol)."""

    def __init__(self, k=2.0, c=1.0, f=3.0, u=0.0, noise=0.0):
        self.k, self.c, self.f, self.u, self.noise = k, c, f, u, noise
        self.load_factor, self.du, self._saved = 0.0, 0.0, None

    def load_norm(self, lam):
        return abs(lam * self.f)

    def r(self):
        return self.k * self.u + self.c * self.u**3 - self.load_factor * self.f

    def residual_norm(self):
        return abs(self.r()) + self.noise

    def update_jacobian(self):
        pass

    def solve_increment(self, rtol=None):
        self.du = -self.r() / (self.k + 3 * self.c * self.u**2)

    def admissible_step(self, fraction):
        return 1.0

    def apply_increment(self, alpha):
        self.u += alpha * self.du

    def increment_norms(self):
        return abs(self.du), abs(self.u)

    def save_state(self):
        self._saved = (self.u, self.load_factor)

    def restore_state(self):
        self.u, self.load_factor = self._saved


QUIET = NewtonOptions(verbose=False)


def test_loaded_spring_converges_to_the_root():
    p = Scalar()
    assert newton(p, 1.0, QUIET).converged
    assert p.u == pytest.approx(1.0, rel=1e-12)   # 2u + u³ = 3 has the root u = 1


def test_zero_load_from_rest_converges_without_iterating():
    p = Scalar(f=0.0)
    report = newton(p, 1.0, QUIET)
    assert report.converged and report.iterations == 0 and p.u == 0.0


def test_unloading_to_zero_load_converges_relative_to_the_initial_residual():
    # A tolerance relative to the (zero) load could never be met: rtol · 0 = 0.
    p = Scalar(f=0.0, u=1.5)
    report = newton(p, 1.0, QUIET)
    assert report.converged
    assert abs(p.u) <= 1e-9 and report.residual_norms[-1] <= 1e-10 * report.residual_norms[0]


def test_a_residual_floor_above_the_tolerance_stops_on_the_increment():
    # ||r|| can never go below the floor 1e-6 (e.g. round-off of a large model), but u stops
    # moving: converged on the increment, at the root u = 1.
    p = Scalar(noise=1e-6)
    report = newton(p, 1.0, QUIET)
    assert report.converged and "increment_rtol" in report.reason
    assert p.u == pytest.approx(1.0, rel=1e-13)


def test_a_step_that_does_not_reduce_the_residual_is_stagnation_and_cuts_the_load():
    p = Scalar()
    p.solve_increment = lambda rtol=None: setattr(p, "du", 0.0)   # a useless linear solve
    p.increment_norms = lambda: (1.0, 1.0)              # (and no increment convergence)
    report = newton(p, 1.0, NewtonOptions(verbose=False, stagnation_window=4))
    assert not report.converged and report.reason.startswith("stagnation")
    assert report.iterations == 4
    p.load_factor = 0.0   # the load path starts from the unloaded state
    with pytest.raises(Exception, match="load stepping failed"):
        solve_load_path(p, 1, NewtonOptions(verbose=False, stagnation_window=4,
                                            min_load_increment=0.2))


def test_a_step_into_a_non_finite_residual_is_halved_instead_of_failing_the_load_step():
    # The residual is not finite beyond u = 1.3 (a closure past a law's maximum, a failed local
    # solve): the first full step from rest, du = 1.5, lands there and is halved to 0.75.
    p = Scalar()
    finite = p.residual_norm
    p.residual_norm = lambda: finite() if p.u <= 1.3 else math.inf
    report = newton(p, 1.0, QUIET)
    assert report.converged and p.u == pytest.approx(1.0, rel=1e-12)
    assert report.step_lengths[0] == 0.5
    # With no halvings allowed, the same step fails on the non-finite residual.
    p.u = 0.0
    report = newton(p, 1.0, NewtonOptions(verbose=False, max_backtracks=0))
    assert not report.converged and report.reason.startswith("non-finite")


class Recording(Scalar):
    """The scalar spring with the optional protocol: commit_state, and a linear solve that takes
    (and records) the forcing term rtol."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.commits, self.restores, self.asked = 0, 0, []

    def commit_state(self):
        self.commits += 1

    def restore_state(self):
        self.restores += 1
        super().restore_state()

    def solve_increment(self, rtol=None):
        self.asked.append(rtol)
        super().solve_increment(rtol)
        return 1


def test_commit_after_every_converged_load_step_restore_after_a_failed_one():
    p = Recording()
    reports = solve_load_path(p, 3, QUIET)
    assert all(r.converged for r in reports) and p.commits == len(reports) == 3 and p.restores == 0
    # A step whose Newton cannot converge in one iteration fails, is restored and cut; its
    # halves converge (the spring is nearly linear below λ = 0.1) and are committed.
    p = Recording(c=50.0)
    reports = solve_load_path(p, 1, NewtonOptions(verbose=False, max_iterations=3, growth=1.0))
    failed = [r for r in reports if not r.converged]
    assert failed and p.restores == len(failed) and p.commits == len(reports) - len(failed)
    assert abs(2 * p.u + 50 * p.u**3 - 3.0) <= 1e-10 * 3.0   # the root of 2u + 50u³ = 3


def test_forcing_terms_follow_eisenstat_walker_choice_2_with_safeguards():
    p = Recording(c=5.0)
    opts = NewtonOptions(verbose=False, rtol=1e-12)
    report = newton(p, 1.0, opts)
    assert report.converged
    r, eta = report.residual_norms, p.asked
    tol = 1e-12 * 3.0
    assert eta[0] == 0.1   # forcing_initial
    for k in range(1, len(eta)):
        expected = 0.9 * (r[k] / r[k - 1]) ** 2          # choice 2, γ = 0.9, α = 2
        if 0.9 * eta[k - 1] ** 2 > 0.1:                  # no sudden tightening
            expected = max(expected, 0.9 * eta[k - 1] ** 2)
        expected = min(expected, 0.5)                    # forcing_max
        if expected * r[k] < 10 * tol:                   # aim at the tolerance near the end
            expected = 0.5 * tol / r[k]
        expected = min(max(expected, 0.5 * tol / r[k]), 0.5)   # no oversolving
        assert eta[k] == pytest.approx(expected, rel=1e-12)
    # A linear problem (is_linear) and fixed forcing solve to the linear solver's own tolerance.
    p = Recording()
    p.is_linear = True
    newton(p, 1.0, QUIET)
    assert set(p.asked) == {None}
    p = Recording()
    newton(p, 1.0, NewtonOptions(verbose=False, forcing="fixed"))
    assert set(p.asked) == {None}


def test_bad_forcing_options_are_refused_with_their_range():
    with pytest.raises(ValueError, match="forcing must be"):
        NewtonOptions(forcing="loose")
    with pytest.raises(ValueError, match=r"forcing_max must be in \(0, 1\), got 1.5"):
        NewtonOptions(forcing_max=1.5)
    with pytest.raises(ValueError, match=r"forcing_alpha must be in \(1, 2\]"):
        NewtonOptions(forcing_alpha=3.0)


def test_newton_drives_a_newton_problem_and_names_the_protocol_otherwise():
    class Duck:   # the methods, but not the declared protocol: refused, not probed
        load_factor = 0.0
    for solve in (lambda p: newton(p, 1.0, QUIET), lambda p: solve_load_path(p, 1, QUIET)):
        with pytest.raises(TypeError, match="NewtonProblem"):
            solve(Duck())


def test_a_problem_without_increment_norms_stops_on_the_residual_alone():
    class NoNorms(Scalar):
        def increment_norms(self):
            return None
    p = NoNorms()
    report = newton(p, 1.0, QUIET)
    assert report.converged and "round-off" not in report.reason
    assert p.u == pytest.approx(1.0, rel=1e-12)
