# SPDX-License-Identifier: MIT
"""Pseudo-transient continuation of a load step with smeared joint sets (docs/equivalent-continuum.md,
"Robustness", 3.).

Sets that slide with a non-associated flow rule make the rate-independent equivalent continuum
lose uniqueness: on the tunnel bench the slip settles in one row of points or the next, and
Newton cycles between the two (period 2) at a fixed load. Making the sets viscous for a while
restores a unique, positive-definite step (equivalent_continuum.py, Duvaut-Lions), and the
stationary state of those pseudo-time steps is the rate-independent equilibrium again
(Kelley & Keyes 1998, pseudo-transient continuation):

1. the load step goes to its load factor with r = Δt/τ = relaxation_initial;
2. further pseudo-time steps at that load, r doubled (up to relaxation_max) after each that
   converged, quartered (and retried) after one that failed;
3. after each, the rate-independent residual at the current displacement: once it meets the
   Newton tolerance, the step has converged (the caller commits it).

The path to the equilibrium is the viscous one, so a path-dependent result may differ from a
rate-independent load stepping that converges (measured in bench/results/continuum.md).
"""
from __future__ import annotations

import logging
import time
from dataclasses import replace

import numpy as np

from .newton import ConvergenceError, StepReport, newton

log = logging.getLogger(__name__)


def solve_step_with_relaxation(problem, smeared, load_factor: float, options, step: int = 1,
                               start: float | None = None) -> StepReport:
    """One load step of `problem` (the model, at its last converged state) to `load_factor`:
    Newton; if that fails and options.relaxation_initial is set, pseudo-transient continuation
    with the viscous sets of `smeared` (SmearedBlocks). Returns the StepReport (iterations of
    every pseudo-time step). Raises ConvergenceError if the continuation cannot go on (r below
    1e-6 relaxation_initial or relaxation_max_steps reached): the model is then left at its
    last pseudo-time step, a viscous state that is not a rate-independent equilibrium."""
    start = time.perf_counter() if start is None else start
    reached = problem.load_factor  # the last converged load factor
    first = newton(problem, load_factor, options, step=step, start=start)
    if first.converged or options.relaxation_initial is None:
        return first
    problem.restore_state()
    report = first  # the failed Newton's record, extended by every pseudo-time step's
    r0 = min(float(options.relaxation_initial), options.relaxation_max)
    r = r0
    quiet = replace(options, verbose=False)  # one log line per pseudo-time step instead
    if options.verbose and problem.comm.rank == 0:
        log.info("load step %d to λ = %.6g: %s; pseudo-transient continuation from r = Δt/τ = %g",
                 step, load_factor, first.reason, r)
    try:
        for k in range(int(options.relaxation_max_steps)):
            smeared.relaxation = r
            problem.save_state()
            pseudo = newton(problem, load_factor, quiet, step=step, start=start)
            _extend(report, pseudo)
            if not pseudo.converged:
                problem.restore_state()
                r *= 0.25
                if r < 1e-6 * r0:
                    break
                continue
            problem.commit_state()
            smeared.relaxation = None
            rnorm = problem.residual_norm()
            tol = options.atol + options.rtol * problem.load_norm(load_factor)
            if options.verbose and problem.comm.rank == 0:
                log.info("  pseudo-time step %d (r = %.3g, %d Newton its): rate-independent ||r|| = %.3e "
                         "(tolerance %.3e)  %.1f s", k + 1, r, pseudo.iterations, rnorm, tol,
                         time.perf_counter() - start)
            if np.isfinite(rnorm) and rnorm <= tol:
                report.converged = True
                report.reason = f"pseudo-transient continuation, {k + 1} pseudo-time steps"
                return report
            # Doubled after every converged pseudo-time step, whatever its iteration count: a
            # schedule set by counts would differ between runs on 1 and on 2 ranks (round-off
            # moves a count across the threshold) and so would the path.
            r = min(2.0 * r, options.relaxation_max)
    finally:
        smeared.relaxation = None
    raise ConvergenceError(
        f"load stepping failed at load factor {reached:.6g}: the pseudo-transient continuation of the "
        f"step to λ = {load_factor:.6g} did not reach the rate-independent equilibrium (r = Δt/τ = "
        f"{r:.3g}, {options.relaxation_max_steps} pseudo-time steps at most); the model is left at "
        f"its last pseudo-time step, which is not in equilibrium")


def _extend(report: StepReport, other: StepReport) -> None:
    report.residual_norms += other.residual_norms
    report.step_lengths += other.step_lengths
    report.forcing += other.forcing
    report.linear_iterations += other.linear_iterations
