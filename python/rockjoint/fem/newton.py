"""Newton's method with a closure-limiting step and adaptive load stepping.

The problem object supplies residual() (returns ||r||, inf if not finite), jacobian(),
solve_increment(), admissible_step(fraction), apply_increment(α), load_norm(λ),
save_state()/restore_state() and optionally increment_norms() -> (||du||, ||u||), comm and
commit_state() (called after every converged load step).
Newton stops on the residual (relative to the load, or to the initial residual when the load
is zero), on an increment at round-off, and fails on stagnation or a non-finite residual. Stiffening laws (Barton-Bandis: σ → ∞ as Δ → V_m) defeat plain
Newton from zero once the load passes about K_ni·V_m (docs/fem.md, pitfall 7): every
step is shortened so that no closure moves more than `closure_limit` (0.95) of its remaining
room to the law's maximum closure (fraction to the boundary; with Δ = 0 at the start this is
the "no closure past 0.95 V_m" rule, and it still lets converged closures approach V_m).
A load step that fails (too many iterations, non-finite residual) is cut in half; a step that
converges in at most `easy_iterations` lets the next one grow by `growth`.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np

#: Progress (residual norms, step cuts) at INFO on rank 0; enable with logging.basicConfig.
log = logging.getLogger(__name__)


class ConvergenceError(RuntimeError):
    """Newton or the load stepping could not reach the requested load."""


@dataclass
class NewtonOptions:
    rtol: float = 1e-10              #: ||r|| <= rtol · ||λ f_ext|| (+ atol) → converged
    atol: float = 0.0                #: absolute residual tolerance [N]
    max_iterations: int = 30
    closure_limit: float = 0.95      #: a step may close at most this fraction of Δ_max - Δ
    min_load_increment: float = 1e-6  #: smallest load-factor increment before giving up
    growth: float = 1.5
    easy_iterations: int = 5
    #: backtracking (Armijo on ||r||, halving up to max_backtracks times, the last trial kept) after
    #: the closure limit: off by default (the full step keeps quadratic convergence); it helps when
    #: many points sit at the open/closed kink (stiff joints carrying ~zero normal stress)
    line_search: bool = False
    max_backtracks: int = 8
    #: converged when a step moves u by at most this × ||u|| (nothing left above round-off; used
    #: only if the problem offers increment_norms())
    increment_rtol: float = 1e-14
    #: failed (stagnation) when ||r|| has not fallen below stagnation_factor × its value
    #: stagnation_window iterations earlier; the load step is then cut
    stagnation_window: int = 8
    stagnation_factor: float = 0.9
    verbose: bool = True  #: log the residual of every iteration (INFO, logger rockjoint.fem.newton)


@dataclass
class StepReport:
    """Convergence record of one attempted load step."""
    load_factor: float
    residual_norms: list = field(default_factory=list)  #: ||r|| before each iteration [N]
    step_lengths: list = field(default_factory=list)    #: α of each update (1 = full Newton step)
    converged: bool = False
    reason: str = ""

    @property
    def iterations(self) -> int:
        return len(self.step_lengths)


def solve_load_path(problem, load_steps: int, options: NewtonOptions) -> list:
    """Drive the load factor from problem.load_factor (usually 0) to 1. Returns the StepReports
    (failed attempts included); raises ConvergenceError if the increment falls below the minimum."""
    if int(load_steps) != load_steps or load_steps < 1:
        raise ValueError(f"load_steps must be an integer >= 1, got {load_steps!r}")
    reports = []
    lam = problem.load_factor
    increment = (1.0 - lam) / load_steps
    while lam < 1.0 - 1e-14:
        target = min(1.0, lam + increment)
        if 1.0 - target < 1e-12:
            target = 1.0
        problem.save_state()
        report = newton(problem, target, options)
        reports.append(report)
        if report.converged:
            lam = target
            commit = getattr(problem, "commit_state", None)  # path-dependent joints (CONTRACTS B)
            if commit is not None:
                commit()
            if report.iterations <= options.easy_iterations:
                increment *= options.growth
        else:
            problem.restore_state()
            increment *= 0.5
            if options.verbose and _rank(problem) == 0:
                log.info("load step to λ = %.6g failed (%s); cutting the increment to %.3g",
                         target, report.reason, increment)
            if increment < options.min_load_increment:
                raise ConvergenceError(
                    f"load stepping failed: increment {increment:.3g} below min_load_increment "
                    f"{options.min_load_increment:g} at load factor {lam:.6g} (last failure: {report.reason})")
    return reports


def newton(problem, load_factor: float, options: NewtonOptions) -> StepReport:
    """Newton iterations at a fixed load factor (the problem keeps u; restore on failure)."""
    problem.load_factor = load_factor
    report = StepReport(load_factor)
    scale = problem.load_norm(load_factor)
    tol = options.atol + options.rtol * scale
    for it in range(options.max_iterations + 1):
        rnorm = problem.residual()
        report.residual_norms.append(rnorm)
        if it == 0 and scale == 0.0 and np.isfinite(rnorm):
            # No load at this step (e.g. unloading to zero): relative to the initial residual.
            tol = options.atol + options.rtol * rnorm
        if options.verbose and _rank(problem) == 0:
            alpha = f"  α = {report.step_lengths[-1]:.3g}" if report.step_lengths else ""
            log.info("λ = %.6g  it %2d  ||r|| = %.6e%s", load_factor, it, rnorm, alpha)
        if not np.isfinite(rnorm):
            report.reason = "non-finite residual (closure beyond the law's maximum?)"
            return report
        if rnorm <= tol:
            report.converged = True
            return report
        if it == options.max_iterations:
            break
        window = options.stagnation_window
        if it >= window and not rnorm < options.stagnation_factor * report.residual_norms[-1 - window]:
            report.reason = (f"stagnation: ||r|| = {rnorm:.3e} has not fallen below "
                             f"{options.stagnation_factor:g} × its value {window} iterations ago")
            return report
        problem.jacobian()
        problem.solve_increment()
        # Closure-limiting step: no closure may move more than `closure_limit` of its remaining
        # room to the law's maximum closure (Δ is linear in α, so α is exact, not halved).
        alpha = problem.admissible_step(options.closure_limit)
        if not alpha > 1e-12:
            report.reason = f"closure-limiting step length {alpha:.3g} (no admissible step)"
            return report
        if options.line_search:
            alpha = _backtrack(problem, alpha, rnorm, options)
        else:
            problem.apply_increment(alpha)
        report.step_lengths.append(alpha)
        norms = getattr(problem, "increment_norms", None)
        if norms is not None:
            du, u = norms()
            if alpha * du <= options.increment_rtol * u:
                report.converged = True
                report.reason = (f"step {alpha * du:.3e} <= increment_rtol × ||u|| (residual "
                                 f"{rnorm:.3e} at round-off)")
                return report
    report.reason = f"no convergence in {options.max_iterations} iterations"
    return report


def _backtrack(problem, alpha: float, rnorm: float, options: NewtonOptions) -> float:
    """Apply α du, halving α until ||r|| decreases (Armijo, c = 1e-4); returns the α applied."""
    for k in range(options.max_backtracks + 1):
        problem.apply_increment(alpha)
        trial = problem.residual()
        if trial <= (1.0 - 1e-4 * alpha) * rnorm or k == options.max_backtracks:
            return alpha
        problem.apply_increment(-alpha)
        alpha *= 0.5
    return alpha


def _rank(problem) -> int:
    """MPI rank of the problem's communicator (0 without one): progress is logged once."""
    comm = getattr(problem, "comm", None)
    return comm.rank if comm is not None else 0
