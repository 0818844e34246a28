# SPDX-License-Identifier: MIT
"""The nonlinear problem of a jointed rock model: the one interface that both the project's
Newton (newton.solve_load_path) and PETSc SNES (stages.snes_load_path, through the
snes_problem.JointedSNESProblem adapter that the user's problems use too) drive.

The residual at the load factor λ (model.py's docstring)::

    r = K u + K_fc u_c + ∫ε(v):σ0 dx - f(λ) + r_joint(u) [+ r_smeared(u)],

zero at supported dofs; the Jacobian K + J_joint(u) [+ J_smeared(u)]. The parts: the blocks'
bulk matrix K (assembled here when the supports change), the load path (loads.py, load_path.py:
f(λ), the prescribed displacements and their lift, the in-situ term), the joints (JointCoupling),
the smeared joint sets (equivalent_continuum.SmearedBlocks, or None) and the linear solver.
"""
from __future__ import annotations

import time

import numpy as np
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from ..compat import la_petsc
from .contact_cycling import ContactCycling
from .joint_initial_state import initial_jump
from ..solvers.linear_solver import LinearSolveError, LinearSolver, resolve_kind, rigid_body_modes
from ..solvers.newton import NewtonProblem
from ..solvers.snes_problem import JointedSNESProblem


def make_linear_solver(V, kind: str, options: dict, prefix: str | None, symmetric: bool) -> LinearSolver:
    """The linear solver of a displacement space V: kind "auto" (linear_solver.resolve_kind by
    the number of dofs and the Jacobian's symmetry), "direct", "lagged" or "iterative" (with V's
    rigid-body modes for GAMG)."""
    num_dofs = V.dofmap.index_map.size_global * V.dofmap.index_map_bs
    kind = resolve_kind(kind, num_dofs, V.mesh.geometry.dim, symmetric)
    return LinearSolver(V.mesh.comm, kind, num_dofs=num_dofs,
                        near_nullspace=rigid_body_modes(V) if kind == "iterative" else None,
                        symmetric=symmetric, options=options, prefix=prefix)


class JointedProblem(JointedSNESProblem, NewtonProblem):
    """F(u) = 0 of a jointed rock model at its load factor `load_factor`, for the project's Newton,
    PETSc SNES (`snes_solver()`, `snes_F`, `snes_J`) or a user's Newton.

    Newton's protocol (newton.NewtonProblem): residual_norm() -> ||F|| (inf if not finite),
    update_jacobian(), solve_increment(rtol), increment_norms(), admissible_step(fraction),
    apply_increment(α), load_norm(λ), save_state() / restore_state() / commit_state(). SNES's
    (snes_problem.JointedSNESProblem): residual(x, b) and jacobian(x, A) at a trial x (copied
    into u first), matrix(), vector(). A non-finite joint
    traction or a failed local solve of a smeared set gives an infinite residual (a SNES
    function-domain error). Built by JointedRockModel, which calls connect() and set_supports()
    before the first solve (model.problem() returns it ready)."""

    def __init__(self, blocks, load_path, smeared, closure_limit: float | None):
        self.blocks, self.load_path, self.smeared = blocks, load_path, smeared
        self.u, self.du = blocks.u, blocks.du
        self.comm = blocks.mesh.comm
        self.closure_fraction = None if closure_limit is None else float(closure_limit)
        self.coupling = None          #: JointCoupling (connect())
        self.linear_solver = None     #: LinearSolver (connect())
        self.is_linear = False        #: no joints and no smeared sets (connect())
        self.K = self.J = None        #: bulk matrix with the supports, Jacobian (set_supports())
        self.bcs: list = []           #: DirichletBCs of every support (set_supports())
        #: int8 mask of the supported local dofs, ghosts included (set_supports())
        self.constrained = np.zeros(0, dtype=np.int8)
        self._constrained_owned = np.zeros(0, dtype=np.int32)
        self.load_factor = 0.0
        V = blocks.V
        self.r = la_petsc.create_vector([(V.dofmap.index_map, V.dofmap.index_map_bs)])
        self._r_joint = self.r.duplicate()
        self._saved = None            # (u, load factor) of the last converged load step
        # water in the joints (rockjoint.fem.water.joint_pressure): p per joint point at the end
        # of the next stage, ramped from its value at the stage's start; None: dry
        self._pressure_target = self._pressure_start = self._pressure_applied = None
        #: water p0 [Pa] per joint point from the initial state on (set_initial_joint_pressure)
        self.initial_pressure = None
        #: what a singular solve should add to its error (e.g. the joints the water opens)
        self.failure_hints: list = []
        #: the joints' contact at each residual of the load step (why Newton stagnates: contact_cycling.py)
        self.cycling = ContactCycling()
        self.step_iterations = 0      #: Newton iterations of the load step being solved
        self.clock = None             #: progress clock (stages.StageClock) of the stage being solved
        #: wall-clock seconds on this rank: bulk_assembly (K), interface_residual and
        #: interface_jacobian (all calls), matrix_copy, linear_solve (all solves), newton
        #: (JointedRockModel.solve total), setup
        self.timings = {"bulk_assembly": 0.0, "interface_residual": 0.0, "interface_jacobian": 0.0,
                        "matrix_copy": 0.0, "linear_solve": 0.0, "newton": 0.0, "setup": 0.0}
        #: number of calls behind the timings
        self.counts = {"interface_residual": 0, "interface_jacobian": 0, "linear_solve": 0,
                       "nonfinite_residuals": 0}

    # ---- set-up --------------------------------------------------------------------------
    def connect(self, coupling, linear_solver, has_joints: bool) -> None:
        """The joints (JointCoupling) and the linear solver, once, before the first solve."""
        self.coupling, self.linear_solver = coupling, linear_solver
        self.is_linear = not has_joints and self.smeared is None

    def set_supports(self, supports: tuple) -> None:
        """(DirichletBCs, int8 mask of the supported local dofs) of the load path: the bulk
        matrix K with them (identity rows) and the Jacobian's storage."""
        t0 = time.perf_counter()
        self.bcs, self.constrained = supports
        V = self.blocks.V
        n_owned = V.dofmap.index_map.size_local * V.dofmap.index_map_bs
        self._constrained_owned = np.flatnonzero(self.constrained[:n_owned]).astype(np.int32)
        for A in (self.K, self.J):
            if A is not None:
                A.destroy()
        self.coupling.set_supports(self.bcs)
        K = self.coupling.create_matrix(self.blocks.a_form)  # joint couplings reserved (pitfall 4)
        fem_petsc.assemble_matrix(K, self.blocks.a_form, self.bcs)
        K.assemble()
        self.K, self.J = K, K.duplicate(copy=True)
        self.timings["bulk_assembly"] += time.perf_counter() - t0

    def set_initial_state(self, behaviours: dict, joint_names: dict, vertex_rule: bool) -> None:
        """u = 0 and the loads of the initial state; with an in-situ stress, joints pre-closed
        (initial jump j0 = (-Δ0, τ0/k_s), Δ0 the closure at σ_n0 - α p0, σ_n0 = -n·σ0·n and p0 the
        initial water, self.initial_pressure) and the equilibrium checked (ValueError). behaviours: {joint tag: JointBehaviour}; joint_names: {name: tag}."""
        lp = self.load_path
        self.u.x.array[:] = 0.0
        lp.start()
        if lp.in_situ is None:
            return
        gdim = self.blocks.gdim
        p0 = self.initial_pressure
        self.coupling.set_initial_jump(initial_jump(self.coupling.interface, lp.in_situ, behaviours, gdim,
                                                    joint_names, vertex_rule, p0))
        if p0 is not None:   # in place from the start: every stage ramps from it
            self._pressure_target, self._pressure_applied = np.array(p0, dtype=float), np.array(p0, dtype=float)
            self.coupling.interface.set_pore_pressure(self._pressure_applied)
        if self.smeared is not None:
            self.smeared.set_in_situ(lp.in_situ)
        self.begin_stage(hold=True)
        lp.check_initial_equilibrium(self.residual_norm())

    # ---- stages --------------------------------------------------------------------------
    def begin_stage(self, hold: bool = False) -> None:
        """Load factor 0 of a stage (hold: the loads stay those of the stage's start)."""
        self.load_path.begin_stage(self.u.x.array, hold=hold)
        self.load_factor = 0.0
        self.step_iterations = 0
        if self._pressure_target is not None:   # the water ramps from where it stands now
            self._pressure_start = (np.zeros_like(self._pressure_target) if self._pressure_applied is None
                                    else self._pressure_applied.copy())

    def explained(self, error: Exception) -> Exception:
        """`error`, or for a singular solve (LinearSolveError) with failure_hints a LinearSolveError
        that adds them (caused by `error`)."""
        if not (isinstance(error, LinearSolveError) and self.failure_hints):
            return error
        out = LinearSolveError(f"{error}. {' '.join(self.failure_hints)}")
        out.__cause__ = error
        return out

    def set_pressure_target(self, pressure: np.ndarray) -> None:
        """The fluid pressure p [Pa] at every joint point of this rank at the end of the next
        stage (ramped over it like the loads, from its value at the stage's start)."""
        self._pressure_target = np.array(pressure, dtype=float)

    def _apply_pressure(self) -> None:
        """p(λ) = p_start + λ (p_target - p_start) into the joints (once per load factor)."""
        if self._pressure_target is None or self._pressure_start is None:
            return
        p = self._pressure_start + self.load_factor * (self._pressure_target - self._pressure_start)
        if self._pressure_applied is None or not np.array_equal(p, self._pressure_applied):
            self.coupling.interface.set_pore_pressure(p)
            self._pressure_applied = p

    # ---- the residual and the Jacobian ---------------------------------------------------
    def load_norm(self, load_factor: float) -> float:
        """Scale of the forces at `load_factor`: ||f(λ)|| (+ ||∫ε(v):σ0||)."""
        return self.load_path.load_norm(load_factor)

    def _joint_forces(self) -> bool:
        """r_joint(u) into self._r_joint (owned entries complete); False if not finite."""
        t0 = time.perf_counter()
        self._apply_pressure()
        rj = self._r_joint
        with rj.localForm() as loc:
            loc.set(0.0)
            finite = self.coupling.add_residual(self.u, loc.array)  # collective
        # Ghost contributions go to their owners (docs/fem.md, pitfall 5).
        rj.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self.timings["interface_residual"] += time.perf_counter() - t0
        self.counts["interface_residual"] += 1
        return finite

    def residual_norm(self) -> float:
        """F at the current u into the problem's own vector `r`, returning ||F|| (inf if not
        finite); the prescribed displacements of the load factor go into u first."""
        lp = self.load_path
        lp.apply(self.load_factor, self.u)
        r = self.r
        if not self._joint_forces():
            # Never hand on a stale residual: SNES and our Newton both see an infinite one and
            # cut the step.
            r.set(np.inf)
            self.counts["nonfinite_residuals"] += 1
            return np.inf
        self.cycling.record(self.coupling.interface)
        self.K.mult(self.u.x.petsc_vec, r)
        lp.add_external(r)
        r.axpy(1.0, self._r_joint)
        if self.smeared is not None and not self.smeared.add_residual(r):
            r.set(np.inf)  # a local solve of the smeared sets failed: cut the step
            self.counts["nonfinite_residuals"] += 1
            return np.inf
        with r.localForm() as loc:  # owned entries come first in the local form
            loc.array[self._constrained_owned] = 0.0
        nrm = r.norm()
        return nrm if np.isfinite(nrm) else np.inf

    def update_jacobian(self) -> None:
        """The Jacobian at the current u into the problem's own matrix `J`."""
        self.assemble_jacobian(self.J)

    def assemble_residual(self, b: PETSc.Vec) -> bool:
        """The residual at the current u into `b`; False if it is not finite (a failed trial)."""
        finite = bool(np.isfinite(self.residual_norm()))
        self.r.copy(b)
        return finite

    def assemble_jacobian(self, A: PETSc.Mat) -> None:
        """A = K + joint tangent at u (A has K's nonzero pattern, e.g. matrix())."""
        t0 = time.perf_counter()
        self.K.copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)  # bulk, constant
        t1 = time.perf_counter()
        self.timings["matrix_copy"] += t1 - t0
        if self.smeared is not None:
            self.smeared.add_jacobian(A, self.bcs)
        self.coupling.add_jacobian(self.u, A)
        A.assemble()
        self.timings["interface_jacobian"] += time.perf_counter() - t1
        self.counts["interface_jacobian"] += 1
        self.step_iterations += 1

    def matrix(self) -> PETSc.Mat:
        """A matrix with the joint-aware sparsity (the bulk pattern plus cross-joint couplings)."""
        return self.K.duplicate(copy=True)

    def vector(self) -> PETSc.Vec:
        """A vector with the residual's layout."""
        return self.r.duplicate()

    # ---- Newton's increments ---------------------------------------------------------------
    def solve_increment(self, rtol: float | None = None) -> int:
        """du = -J⁻¹ r to the relative tolerance rtol (None: the linear solver's); returns the
        Krylov iterations."""
        t0 = time.perf_counter()
        self.r.scale(-1.0)
        try:
            its = self.linear_solver.solve(self.J, self.r, self.du.x.petsc_vec, rtol=rtol)
        finally:
            self.r.scale(-1.0)
            self.timings["linear_solve"] += time.perf_counter() - t0
            self.counts["linear_solve"] += 1
        # Supported rows are identity rows with a zero right-hand side, so du = 0 there only if
        # the solve is exact; a loose (inexact Newton) solve leaves an error the zeroed residual
        # would never see: the supports would drift.
        with self.du.x.petsc_vec.localForm() as loc:
            loc.array[self._constrained_owned] = 0.0
        self.du.x.scatter_forward()
        return its

    def increment_norms(self) -> tuple:
        """(||du||, ||u||) of the last Newton increment and the current displacement [m]."""
        return self.du.x.petsc_vec.norm(), self.u.x.petsc_vec.norm()

    def admissible_step(self, fraction: float) -> float:
        """Largest α <= 1 such that u + α du closes no joint point by more than `fraction` of its
        remaining room to the law's maximum closure (Δ <= Δ + fraction (Δ_max - Δ))."""
        return self.coupling.admissible_step(self.u, self.du, fraction)

    def apply_increment(self, alpha: float) -> None:
        """u ← u + α du, ghosts updated."""
        self.u.x.petsc_vec.axpy(alpha, self.du.x.petsc_vec)
        self.u.x.scatter_forward()

    # ---- converged and trial state ---------------------------------------------------------
    def save_state(self) -> None:
        """Remember u and the load factor of the converged step (restore_state goes back to them)."""
        self._saved = (self.u.x.array.copy(), self.load_factor)
        self.cycling.clear()

    def stagnation_hint(self) -> str:
        """Why the load step's Newton stagnates, if its joints' contact cycles (collective)."""
        return self.cycling.hint(self.coupling, self.comm)

    def restore_state(self) -> None:
        """Back to the last saved (converged) step: u, load factor and the joints' trial state."""
        arr, self.load_factor = self._saved
        self.u.x.array[:] = arr
        self.load_path.forget_applied()
        self.coupling.revert_state()
        if self.smeared is not None:
            self.smeared.revert_state()

    def commit_state(self) -> None:
        """A load step converged: the joints' trial state becomes their converged state (the
        range of their laws is checked once per stage, by stages.stage_result)."""
        self.coupling.commit_state(check_range=False)
        if self.smeared is not None:
            self.smeared.commit_state()
        if self.clock is not None:
            self.clock.step(self.load_factor, self.step_iterations)
        self.step_iterations = 0

    def reset_state(self) -> None:
        """The joints' and smeared sets' path-dependent state back to the virgin one."""
        self.coupling.reset_state()
        if self.smeared is not None:
            self.smeared.reset_state()

    # ---- forces -----------------------------------------------------------------------------
    def reactions(self) -> dict:
        """{(boundary, component): force the support exerts on the rock} at the current state."""
        lp = self.load_path
        lp.apply(self.load_factor, self.u)
        force = lp.internal_force(self.u)
        self._joint_forces()
        force.axpy(1.0, self._r_joint)
        if self.smeared is not None:
            self.smeared.add_residual(force)
        out = lp.reactions(force)
        force.destroy()
        return out
