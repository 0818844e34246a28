# SPDX-License-Identifier: MIT
"""Stages of a load path, their results, and PETSc SNES driving a stage.

A stage is one JointedRockModel.solve(): the loads go linearly from the previous stage's values
(load factor λ = 0) to the values set now (λ = 1). `Stage` is the declarative form used by
`JointedRockModel.run`. `snes_load_path` drives the model's problem (problem.JointedProblem, the
object the project's Newton drives too) with PETSc SNES.
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from dolfinx import fem
from petsc4py import PETSc

from ..mesh.distributed_mesh import names_of
from .law_range import check_range, summarize
from ..solvers.newton import StepReport, solve_load_path

log = logging.getLogger(__name__)


@dataclass
class StageResult:
    """Result of one stage (JointedRockModel.solve): displacement (a copy, relative to the initial
    state), joint point state, support reactions and the Newton history; a record of values that
    holds no part of the model (the model keeps its stages: model.stages)."""
    displacement: fem.Function
    joints: dict       #: point state on this rank (see JointInterface.state)
    reports: list      #: newton.StepReport per attempted load step
    comm: object       #: the model's MPI communicator (gather_joints, summary)
    joint_names: dict  #: {joint name: tag} of the model's mesh (the same on every rank)
    name: str = ""
    #: {(boundary, "x"|"y"|"z"): force the support exerts on the rock [N; N/m in 2D]}, all ranks
    reactions: dict = field(default_factory=dict)
    elapsed: float = 0.0  #: wall time of the stage [s]

    def gather_joints(self) -> dict:
        """The joint point state of all ranks, concatenated (on every rank)."""
        comm = self.comm
        return {k: np.concatenate(comm.allgather(np.asarray(v)), axis=0) for k, v in self.joints.items()}

    @property
    def newton_iterations(self) -> int:
        """Newton iterations of the stage, summed over its steps."""
        return sum(r.iterations for r in self.reports)

    def summary(self) -> dict:
        """{joint name: law_range.JointSummary} of the stage's joint state over all ranks (the
        same on every rank; collective)."""
        return summarize(self.comm, self.joints, self.joint_names)

    def beyond_law_range(self) -> dict:
        """{joint name: number of points (all ranks)} whose law answered outside its range:
        status validity_limit (a table driven past its last knot, continued linearly; a Tang &
        Jiao law at its cap). Empty when every point is inside its law's range. Collective."""
        return {name: s.beyond_range for name, s in self.summary().items() if s.beyond_range}


@dataclass
class Stage:
    """A declarative stage for JointedRockModel.run: `actions(model)` changes loads and supports
    (add_*, fix, excavate, handle.value = ..., handle.remove()) before the stage is solved."""
    name: str
    load_steps: int = 1
    actions: Callable | None = None
    solver: str = "newton"


def stage_result(model, problem, name: str, reports: list, elapsed: float) -> StageResult:
    """The StageResult of the stage `problem` just solved; where a joint law was driven past its
    range, a RangeWarning (rank 0) or BeyondRangeError (every rank), as the model's beyond_range
    says (law_range.check_range, through the coupling: the check of every path)."""
    # Re-evaluated from the state just committed: a point that slid in the last step sits on
    # its strength and reads "slip" (joint_slip.cpp labels by where τ is).
    state = problem.coupling.state(problem.u)
    disp = fem.Function(problem.u.function_space, name="displacement")
    disp.x.array[:] = problem.u.x.array
    result = StageResult(disp, state, reports, model.comm, names_of(model.dmesh, "joints"), name,
                         problem.reactions(), elapsed)
    # Never silent: past a table's last knot the answer is its linear continuation, not the law.
    problem.coupling.check_range(where=f"in stage {name!r}")  # the state just evaluated at u
    if model.smeared is not None:   # the smeared sets, by the same check
        state, sets, behaviours = model.smeared.point_state()
        check_range(model.comm, summarize(model.comm, state, sets), behaviours, model.beyond_range,
                    f"in stage {name!r} (smeared joint sets)")
    return result


def snes_load_path(problem, load_steps: int, options) -> list:
    """Drive the problem's (problem.JointedProblem) load factor from 0 to 1 with PETSc SNES
    solving each load step, the steps controlled as for the project's Newton
    (newton.solve_load_path: halved on failure, a function-domain error (non-finite joint
    traction) included, grown after easy ones, the joint state committed after every converged
    step and reverted after a failed one). Returns the StepReports."""
    solver = problem.linear_solver
    snes = problem.snes_solver(options_prefix=solver.ksp.getOptionsPrefix(), ksp=solver.ksp)
    _flag_matrix(solver, snes.getJacobian()[0])
    norms = []
    snes.setMonitor(lambda s, it, rnorm: norms.append(rnorm))
    x = problem.u.x.petsc_vec.copy()

    def solve_step(_, target, step, start):
        problem.load_factor = target
        problem.residual_norm()  # sets the prescribed displacements of λ = target into u
        scale = problem.load_norm(target)
        snes.setTolerances(atol=max(options.atol + options.rtol * scale, 1e-300), rtol=1e-14,
                           stol=0.0, max_it=options.max_iterations)
        snes.setFromOptions()  # user options (petsc_options, command line) win
        problem.u.x.petsc_vec.copy(x)
        norms.clear()
        snes.solve(None, x)
        reason = snes.getConvergedReason()
        if reason > 0:
            problem.update_solution(x)  # the converged x into u before the state is committed
        return StepReport(target, residual_norms=list(norms), step_lengths=[1.0] * snes.getIterationNumber(),
                          converged=reason > 0, reason=f"SNES reason {_snes_reason(reason)}")

    try:
        return solve_load_path(problem, load_steps, options, solve_step=solve_step)
    finally:
        solver.unflag()
        snes.setKSP(PETSc.KSP().create(problem.comm))  # the model keeps its own KSP alive
        snes.destroy()
        x.destroy()


def _snes_reason(reason: int) -> str:
    """'DIVERGED_FUNCTION_DOMAIN (-2)' for a SNES converged reason."""
    names = {v: k for k, v in vars(PETSc.SNES.ConvergedReason).items() if isinstance(v, int)}
    return f"{names.get(reason, '?')} ({reason})"


def _flag_matrix(solver, A) -> None:
    """What LinearSolver.solve tells before a solve, for the matrix SNES hands its KSP (undone by
    solver.unflag() when the load path ends)."""
    solver.flag(A)


class StageClock:
    """Progress of a stage on rank 0 (logger rockjoint.fem.mechanics.stages, INFO): stage k/n, load factor,
    Newton iterations of the step, elapsed time."""

    def __init__(self, comm, label: str):
        self.comm, self.label = comm, label
        self.start = time.perf_counter()

    def step(self, load_factor: float, iterations: int) -> None:
        """Log (rank 0) a converged step: load factor, Newton iterations and elapsed time."""
        if self.comm.rank == 0:
            log.info("stage %s: λ = %.4g converged in %d Newton iteration(s), %.2f s elapsed",
                     self.label, load_factor, iterations, time.perf_counter() - self.start)

    @property
    def elapsed(self) -> float:
        """Seconds since the stage started."""
        return time.perf_counter() - self.start
