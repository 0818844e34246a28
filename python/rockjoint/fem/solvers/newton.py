# SPDX-License-Identifier: MIT
"""Newton's method with a closure-limiting step and adaptive load stepping.

The problem is a `NewtonProblem` (below): the one protocol that the project's Newton drives,
written down rather than probed: residual_norm() (||r||, inf if not finite), update_jacobian(),
solve_increment(rtol), admissible_step(fraction), apply_increment(α), load_norm(λ),
save_state()/restore_state()/commit_state() (after every converged load step), increment_norms()
(or None), is_linear and comm.
Newton stops on the residual (relative to the load, or to the initial residual when the load
is zero), on an increment at round-off, and fails on stagnation or a non-finite residual. Stiffening laws (Barton-Bandis: σ → ∞ as Δ → V_m) defeat plain
Newton from zero once the load passes about K_ni·V_m (docs/fem.md, pitfall 7): every
step is shortened so that no closure moves more than `closure_limit` (0.95) of its remaining
room to the law's maximum closure (fraction to the boundary; with Δ = 0 at the start this is
the "no closure past 0.95 V_m" rule, and it still lets converged closures approach V_m).
A Newton step after which the residual is not finite (a local solve of a smeared joint set
failed, docs/equivalent-continuum.md; a closure past a law's maximum without the limiter) is
halved, at most `max_backtracks` times, before the load step is given up (the smeared tunnels of
bench/results/continuum.md rely on it; docs/equivalent-continuum.md, "Robustness").
A load step that fails (too many iterations, non-finite residual) is cut in half; a step that
converges in at most `easy_iterations` lets the next one grow by `growth`. After a converged load
step the problem's commit_state() (if it has one) makes the path-dependent joint state the new
reference; after a failed one restore_state() reverts u, the load factor and the trial state.

Inexact Newton (Eisenstat & Walker 1996, choice 2): unless the problem is linear (`is_linear`), step k is solved only to the relative linear
residual η_k = γ (||r_k|| / ||r_k-1||)^α, safeguarded by η_k >= γ η_k-1^α when that exceeds 0.1
(no sudden tightening), η_k <= forcing_max, and η_k >= 0.5 tol / ||r_k|| (no oversolving of the
last step, Kelley 1995, Eq. 6.20); when the predicted residual η_k ||r_k|| is within 10 tol, the
step aims at the tolerance at once (η_k = 0.5 tol / ||r_k||) rather than leave the last factor
to one more Newton iteration. Early steps are cheap and the last ones tight. Convergence is
always judged on the true residual ||r||, so the answer meets the same tolerance as with exact
linear solves.
"""
from __future__ import annotations

import abc
import logging
import time
from dataclasses import dataclass, field

import numpy as np

#: Progress (residual norms, step cuts) at INFO on rank 0; enable with logging.basicConfig.
log = logging.getLogger(__name__)


class ConvergenceError(RuntimeError):
    """Newton or the load stepping could not reach the requested load. `load_factor`: the last
    converged one (None where not known); `hint`: why the last step failed, if the problem could
    say (NewtonProblem.stagnation_hint), else ""."""

    def __init__(self, message: str, load_factor: float | None = None, hint: str = ""):
        super().__init__(message)
        self.load_factor, self.hint = load_factor, hint


class NewtonProblem(abc.ABC):
    """The protocol of a problem F(u; λ) = 0 that `newton` and `solve_load_path` drive (the model's
    `JointedProblem`, a user's own). The solver calls exactly these and nothing else:

    - residual_norm() -> ||F|| at the current u and load_factor (inf if not finite: the step is
      cut); update_jacobian(); solve_increment(rtol) -> Krylov iterations or None (rtol: the
      linear tolerance of inexact Newton, None: the solver's own);
    - admissible_step(fraction) -> the largest α <= 1 keeping every closure within `fraction` of
      its room (1.0 without joints); apply_increment(α): u += α du;
    - load_norm(λ): the force scale the tolerance is relative to;
    - save_state() / restore_state() around a load step, commit_state() after a converged one
      (path-dependent state; nothing by default);
    - increment_norms() -> (||du||, ||u||) for the round-off stop, or None (the default: no such
      stop); is_linear (no inexact Newton: one exact solve is the answer); comm (the rank that
      logs; None: serial).
    """

    load_factor: float = 0.0
    is_linear: bool = False
    comm = None

    @abc.abstractmethod
    def residual_norm(self) -> float:
        """||F|| at the current u and load factor (inf if not finite)."""

    @abc.abstractmethod
    def update_jacobian(self) -> None:
        """The Jacobian at the current u."""

    @abc.abstractmethod
    def solve_increment(self, rtol: float | None = None) -> int | None:
        """du = -J⁻¹ F to the relative linear tolerance rtol; the Krylov iterations or None."""

    @abc.abstractmethod
    def admissible_step(self, fraction: float) -> float:
        """The step length α in (0, 1] the closure limiter allows."""

    @abc.abstractmethod
    def apply_increment(self, alpha: float) -> None:
        """u += α du."""

    @abc.abstractmethod
    def load_norm(self, load_factor: float) -> float:
        """The scale of the forces at `load_factor`."""

    @abc.abstractmethod
    def save_state(self) -> None:
        """Keep u, the load factor and the trial state before a load step."""

    @abc.abstractmethod
    def restore_state(self) -> None:
        """Back to the state save_state() kept (a failed load step)."""

    def commit_state(self) -> None:
        """A load step converged: its trial state becomes the converged one (none by default)."""

    def increment_norms(self) -> tuple | None:
        """(||du||, ||u||) of the last increment, or None (no round-off stop)."""
        return None

    def stagnation_hint(self) -> str:
        """Words on why Newton fails to converge at this load step (e.g. points whose state
        cycles between iterates), added to the failure's reason; "" (the default): nothing known.
        Collective."""
        return ""


def _with_hint(problem, report: StepReport) -> StepReport:
    """The failed step's report with the problem's stagnation_hint() in `hint` and its reason."""
    report.hint = problem.stagnation_hint()
    if report.hint:
        report.reason += "; " + report.hint
    return report


def _check_problem(problem) -> None:
    if not isinstance(problem, NewtonProblem):
        raise TypeError(f"Newton drives a rockjoint.fem.solvers.newton.NewtonProblem; got a "
                        f"{type(problem).__name__} (subclass NewtonProblem and implement its methods)")


@dataclass
class NewtonOptions:
    """Options of the project's Newton load stepping (solve_load_path)."""

    rtol: float = 1e-10              #: ||r|| <= rtol · ||λ f_ext|| (+ atol) → converged
    atol: float = 0.0                #: absolute residual tolerance [N]
    max_iterations: int = 30
    #: a step may close at most this fraction of Δ_max - Δ (None: no limiter; a step past a law's
    #: maximum closure then gives a non-finite residual and is cut)
    closure_limit: float | None = 0.95
    min_load_increment: float = 1e-6  #: smallest load-factor increment before giving up
    growth: float = 1.5
    easy_iterations: int = 5
    #: backtracking (Armijo on ||r||, halving up to max_backtracks times, the last trial kept) after
    #: the closure limit: off by default (the full step keeps quadratic convergence); it helps when
    #: many points sit at the open/closed kink (stiff joints carrying ~zero normal stress)
    line_search: bool = False
    #: halvings of the line search, and of a step whose residual is not finite
    max_backtracks: int = 8
    #: converged when a step moves u by at most this × ||u|| (nothing left above round-off; used
    #: only if the problem offers increment_norms())
    increment_rtol: float = 1e-14
    #: failed (stagnation) when ||r|| has not fallen below stagnation_factor × its value
    #: stagnation_window iterations earlier; the load step is then cut
    stagnation_window: int = 8
    stagnation_factor: float = 0.9
    verbose: bool = True  #: log the residual of every iteration (INFO, logger rockjoint.fem.solvers.newton)
    #: linear tolerance of each Newton step: "eisenstat_walker" (inexact Newton, module docstring)
    #: or "fixed" (every step to the linear solver's own rtol)
    forcing: str = "eisenstat_walker"
    #: η of the first iteration of a load step, and the upper bound of η: tighter than the
    #: textbook 0.3 / 0.9, because while a stiffening law drives ||r|| up (the first steps from
    #: rest overshoot the closure), choice 2 would keep η at its bound and waste Newton iterations
    #: (docs/fem.md, "Inexact Newton"; runs with these values: bench/results/fem_dolfinx0.11.md)
    forcing_initial: float = 0.1
    forcing_max: float = 0.5
    forcing_gamma: float = 0.9       #: γ of choice 2
    forcing_alpha: float = 2.0       #: α of choice 2
    #: smeared joint sets (equivalent continuum): a load step whose Newton fails is solved again
    #: by pseudo-transient continuation (pseudo_transient.py: viscous sets with r = Δt/τ from
    #: relaxation_initial, doubled after every converged pseudo-time step, to the rate-independent
    #: equilibrium); None: off (the step is cut as for discrete joints). The default 1 is the value
    #: the smeared tunnels of bench/results/continuum.md run with (docs/equivalent-continuum.md,
    #: "Robustness", 3.)
    relaxation_initial: float | None = 1.0
    relaxation_max_steps: int = 200  #: pseudo-time steps of one such load step before giving up
    #: largest r: each pseudo-time step then still removes all but 1/(1 + r) of the viscous
    #: overstress, and the tangent keeps D/(1 + r) (Newton failed at r = 6.6e4 on the sliding column
    #: of tests/python/test_fem_pseudo_transient.py, where r <= 3.3e4 converged in 2-4 iterations)
    relaxation_max: float = 1e4

    def __post_init__(self):
        if self.closure_limit is not None and not 0.0 < self.closure_limit < 1.0:
            raise ValueError(f"NewtonOptions.closure_limit must be in (0, 1) or None, got {self.closure_limit!r}")
        if self.forcing not in ("eisenstat_walker", "fixed"):
            raise ValueError(f"NewtonOptions.forcing must be 'eisenstat_walker' or 'fixed', got "
                             f"{self.forcing!r}")
        for name in ("forcing_initial", "forcing_max", "forcing_gamma"):
            value = getattr(self, name)
            if not 0.0 < value < 1.0:
                raise ValueError(f"NewtonOptions.{name} must be in (0, 1), got {value!r}")
        if self.relaxation_initial is not None and not (np.isfinite(self.relaxation_initial)
                                                        and self.relaxation_initial > 0.0):
            raise ValueError(f"NewtonOptions.relaxation_initial must be > 0 or None, got "
                             f"{self.relaxation_initial!r}")
        if not (np.isfinite(self.relaxation_max) and self.relaxation_max > 0.0):
            raise ValueError(f"NewtonOptions.relaxation_max must be > 0, got {self.relaxation_max!r}")
        if int(self.relaxation_max_steps) != self.relaxation_max_steps or self.relaxation_max_steps < 1:
            raise ValueError(f"NewtonOptions.relaxation_max_steps must be an integer >= 1, got "
                             f"{self.relaxation_max_steps!r}")
        if not 1.0 < self.forcing_alpha <= 2.0:
            raise ValueError(f"NewtonOptions.forcing_alpha must be in (1, 2], got {self.forcing_alpha!r}")


@dataclass
class StepReport:
    """Convergence record of one attempted load step."""
    load_factor: float
    residual_norms: list = field(default_factory=list)  #: ||r|| before each iteration [N]
    step_lengths: list = field(default_factory=list)    #: α of each update (1 = full Newton step)
    forcing: list = field(default_factory=list)         #: linear rtol η of each step (None: fixed)
    linear_iterations: list = field(default_factory=list)  #: Krylov iterations of each step
    converged: bool = False
    reason: str = ""
    hint: str = ""   #: the problem's stagnation_hint() when the step stagnated or ran out of iterations

    @property
    def iterations(self) -> int:
        """Newton iterations of the step."""
        return len(self.step_lengths)


def solve_load_path(problem, load_steps: int, options: NewtonOptions, *, target: float = 1.0,
                    adaptive: bool = True, solve_step=None) -> list:
    """Drive problem.load_factor (usually 0) to `target` (1: the stage's full loads; below the
    current factor unloads along the path, above 1 overloads). Before each step the problem's
    state is saved; a converged step is committed (problem.commit_state, if it has one), a failed
    one restored. adaptive: a failed step is halved (ConvergenceError below
    options.min_load_increment) and one that converged in at most options.easy_iterations lets
    the next grow by options.growth; otherwise `load_steps` equal steps and a failed one raises
    ConvergenceError. solve_step(problem, load_factor, step, start) -> StepReport solves one step
    (default: the project's newton). Returns the StepReports (failed attempts included)."""
    if int(load_steps) != load_steps or load_steps < 1:
        raise ValueError(f"load_steps must be an integer >= 1, got {load_steps!r}")
    if solve_step is None:
        def solve_step(p, load_factor, step, start):
            return newton(p, load_factor, options, step=step, start=start)
    reports = []
    lam = float(problem.load_factor)
    increment = (target - lam) / load_steps
    start = time.perf_counter()
    _check_problem(problem)

    def reached(x: float) -> bool:
        return abs(target - x) <= 1e-12 * max(1.0, abs(target))

    while not reached(lam):
        step_to = lam + increment
        if reached(step_to) or (step_to - target) * (target - lam) > 0:  # do not pass the target
            step_to = target
        problem.save_state()
        report = solve_step(problem, step_to, len(reports) + 1, start)
        reports.append(report)
        if report.converged:
            lam = step_to
            problem.commit_state()
            if adaptive and report.iterations <= options.easy_iterations:
                increment *= options.growth
            continue
        problem.restore_state()
        if not adaptive:
            raise ConvergenceError(f"the load step to λ = {step_to:.6g} failed ({report.reason}); the "
                                   f"state is kept at the last converged λ = {lam:.6g}", lam, report.hint)
        increment *= 0.5
        if options.verbose and _rank(problem) == 0:
            log.info("load step %d to λ = %.6g failed (%s); cutting the increment to %.3g",
                     len(reports), step_to, report.reason, abs(increment))
        if abs(increment) < options.min_load_increment:
            raise ConvergenceError(
                f"load stepping failed: increment {abs(increment):.3g} below min_load_increment "
                f"{options.min_load_increment:g} at load factor {lam:.6g} (last failure: {report.reason})",
                lam, report.hint)
    return reports


def newton(problem, load_factor: float, options: NewtonOptions, step: int = 1,
           start: float | None = None) -> StepReport:
    """Newton iterations at a fixed load factor (the problem keeps u; restore on failure).
    step, start: load-step number and perf_counter() origin, for the progress log only."""
    start = time.perf_counter() if start is None else start
    _check_problem(problem)
    problem.load_factor = load_factor
    report = StepReport(load_factor)
    scale = problem.load_norm(load_factor)
    tol = options.atol + options.rtol * scale
    inexact = options.forcing == "eisenstat_walker" and not problem.is_linear
    for it in range(options.max_iterations + 1):
        rnorm = problem.residual_norm()
        cuts = 0  # halvings of the last step after a non-finite residual
        while not np.isfinite(rnorm) and report.step_lengths and cuts < options.max_backtracks:
            # The step led where the residual is not finite (a local solve failed, a closure
            # passed the law's maximum): go back to half of it rather than fail the load step.
            half = 0.5 * report.step_lengths[-1]
            problem.apply_increment(-half)
            report.step_lengths[-1] = half
            cuts += 1
            rnorm = problem.residual_norm()
        report.residual_norms.append(rnorm)
        if it == 0 and scale == 0.0 and np.isfinite(rnorm):
            # No load at this step (e.g. unloading to zero): relative to the initial residual.
            tol = options.atol + options.rtol * rnorm
        if options.verbose and _rank(problem) == 0:
            last = ""
            if report.step_lengths:
                eta = report.forcing[-1]
                last = (f"  α = {report.step_lengths[-1]:.3g}"
                        + (f"  η = {eta:.2g}" if eta is not None else "")
                        + (f"  Krylov {report.linear_iterations[-1]}"
                           if report.linear_iterations[-1] is not None else ""))
            log.info("step %d  λ = %.6g  it %2d  ||r|| = %.6e%s  %.1f s", step, load_factor, it,
                     rnorm, last, time.perf_counter() - start)
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
            return _with_hint(problem, report)
        problem.update_jacobian()
        eta = _forcing(report, options, tol) if inexact else None
        its = problem.solve_increment(rtol=eta)
        report.forcing.append(eta)
        report.linear_iterations.append(its)
        # Closure-limiting step: no closure may move more than `closure_limit` of its remaining
        # room to the law's maximum closure (Δ is linear in α, so α is exact, not halved).
        alpha = 1.0 if options.closure_limit is None else problem.admissible_step(options.closure_limit)
        if not alpha > 1e-12:
            report.reason = f"closure-limiting step length {alpha:.3g} (no admissible step)"
            return report
        if options.line_search:
            alpha = _backtrack(problem, alpha, rnorm, options)
        else:
            problem.apply_increment(alpha)
        report.step_lengths.append(alpha)
        norms = problem.increment_norms()
        if norms is not None:
            du, u = norms
            if alpha * du <= options.increment_rtol * u:
                report.converged = True
                report.reason = (f"step {alpha * du:.3e} <= increment_rtol × ||u|| (residual "
                                 f"{rnorm:.3e} at round-off)")
                return report
    report.reason = f"no convergence in {options.max_iterations} iterations"
    _with_hint(problem, report)
    return report


def _forcing(report: StepReport, options: NewtonOptions, tol: float) -> float:
    """Eisenstat-Walker choice 2 with safeguards (module docstring) for the next linear solve."""
    norms, previous = report.residual_norms, report.forcing
    if len(norms) < 2 or previous[-1] is None:
        eta = options.forcing_initial
    else:
        g, a = options.forcing_gamma, options.forcing_alpha
        eta = g * (norms[-1] / norms[-2]) ** a
        floor = g * previous[-1] ** a
        if floor > 0.1:
            eta = max(eta, floor)
    eta = min(eta, options.forcing_max)
    finish = 0.5 * tol / norms[-1]
    # Near the end (the predicted residual η ||r|| within 10 tol), aim at the tolerance now: a few
    # more Krylov iterations are cheaper than one more Newton iteration. No oversolving: a linear
    # residual below half the Newton tolerance buys nothing.
    if eta * norms[-1] < 10.0 * tol:
        eta = finish
    return float(min(max(eta, finish), options.forcing_max))


def _backtrack(problem, alpha: float, rnorm: float, options: NewtonOptions) -> float:
    """Apply α du, halving α until ||r|| decreases (Armijo, c = 1e-4); returns the α applied."""
    for k in range(options.max_backtracks + 1):
        problem.apply_increment(alpha)
        trial = problem.residual_norm()
        if trial <= (1.0 - 1e-4 * alpha) * rnorm or k == options.max_backtracks:
            return alpha
        problem.apply_increment(-alpha)
        alpha *= 0.5
    return alpha


def _rank(problem) -> int:
    """MPI rank of the problem's communicator (0 without one): progress is logged once."""
    return problem.comm.rank if problem.comm is not None else 0
