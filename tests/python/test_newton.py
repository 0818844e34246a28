"""Newton's stopping rules on scalar problems with known answers: the residual tolerance relative
to the load (or to the initial residual when the load is zero), an increment at round-off, and
stagnation (rockjoint.fem.newton; no DOLFINx needed)."""
import math

import numpy as np
import pytest

from rockjoint.fem.newton import NewtonOptions, newton, solve_load_path


class Scalar:
    """r(u) = k u + c u³ - λ f: a stiffening spring with the problem interface of newton.py."""

    def __init__(self, k=2.0, c=1.0, f=3.0, u=0.0, noise=0.0):
        self.k, self.c, self.f, self.u, self.noise = k, c, f, u, noise
        self.load_factor, self.du, self._saved = 0.0, 0.0, None

    def load_norm(self, lam):
        return abs(lam * self.f)

    def r(self):
        return self.k * self.u + self.c * self.u**3 - self.load_factor * self.f

    def residual(self):
        return abs(self.r()) + self.noise

    def jacobian(self):
        pass

    def solve_increment(self):
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
    p.solve_increment = lambda: setattr(p, "du", 0.0)   # a useless linear solve
    p.increment_norms = lambda: (1.0, 1.0)              # (and no increment convergence)
    report = newton(p, 1.0, NewtonOptions(verbose=False, stagnation_window=4))
    assert not report.converged and report.reason.startswith("stagnation")
    assert report.iterations == 4
    p.load_factor = 0.0   # the load path starts from the unloaded state
    with pytest.raises(Exception, match="load stepping failed"):
        solve_load_path(p, 1, NewtonOptions(verbose=False, stagnation_window=4,
                                            min_load_increment=0.2))
