# SPDX-License-Identifier: MIT
"""JointedRockModel: elastic rock blocks (DOLFINx) + zero-thickness joints (rockjoint C++),
followed along a staged load path (docs/staged-analysis.md)::

    model = JointedRockModel(dmesh, rock={"block_1": (E, nu), ...}, joints={"joint_1": law},
                             shear_stiffness=1e10, plane="strain", density=2700.0)
    model.fix("bottom", "y"); model.fix("left", "x")
    model.set_in_situ_stress(InSituStress.depth_dependent(surface=500.0, density=2700.0, k0=0.5))
    model.solve(name="in-situ")                       # the initial state: u = 0
    model.excavate("tunnel"); model.solve(load_steps=5, name="excavation")
    model.add_pressure("tunnel", 1e6); model.solve(name="lining")

Units: SI (Pa, m, N). Compression positive for joint normal stress; closure Δ = -[[u]]·n; bulk
stress tensors tension positive. The bulk is linear elastic: its matrix K (with the supports) is
assembled when the supports change, the load vectors when the loads change. Newton's residual is::

    r = K u + K_fc u_c + ∫ε(v):σ0 dx - f(λ) + r_joint(u),   f(λ) = f_prev + λ (f_next - f_prev),

zero at supported dofs, whose values u_c are the prescribed displacements of λ (K has identity
rows and zero columns there, so K_fc u_c brings the prescribed values back in). r_joint is added
to the ghosted local vector before the reverse ghost update; the Jacobian is K + J_joint(u) (joint
blocks via MatSetValuesLocal, rows and columns of supported dofs left out).
"""
from __future__ import annotations

import logging
import time

import numpy as np
from dolfinx import fem

from ...joint import joint_behaviours, symmetric_tangent
from ..output import monitors
from ..output import fields as output
from .coupling import JointCoupling
from ..mesh.distributed_mesh import lookup, names_of
from .elastic_blocks import ElasticBlocks
from .equivalent_continuum import SmearedBlocks
from .in_situ import STANDARD_GRAVITY, InSituStress
from .law_range import check_beyond_range
from ..solvers.linear_solver import LinearSolver
from .load_path import LoadPath
from .loads import Load, Support
from .model_inputs import check_density, check_element, check_plane, check_rock
from ..solvers.newton import NewtonOptions, solve_load_path
from ..solvers.petsc_options import check_options_prefix, check_petsc_options
from .problem import JointedProblem, make_linear_solver
from ..solvers.pseudo_transient import solve_step_with_relaxation
from .stages import Stage, StageClock, StageResult, snes_load_path, stage_result

log = logging.getLogger(__name__)


class JointedRockModel:
    """A jointed rock mass: elastic blocks + joints with closure laws, loads, supports.

    :dmesh: rockjoint.fem.mesh.distributed_mesh.DistributedJointMesh (mesh, cell_blocks, boundaries,
        names, pairs).
    :element_degree: 1 or 2 (P2 uses the nodal joint rule).
    :rock: {block name: (E [Pa], ν)} for every block, or one (E, ν) for all blocks.
    :joints: {joint name: ClosureLaw} for every joint (any rockjoint law or table).
    :shear_stiffness: joint shear stiffness k_s [Pa/m], constant (float, or {joint name: float}).
    :shear_stiffness_ratio: if given, k_s = ratio × current normal stiffness instead (per-joint dict
        allowed); the Jacobian is then non-symmetric (GMRES with the iterative solver).
    :residual_stiffness: k_r [Pa/m] spring in parallel with every law, in tension and compression
        (float or dict; default 0: a block held only by an open joint is then a singular system and
        solve() raises LinearSolveError instead of returning garbage).
    :strength: joint shear strength (docs/joint-strength.md): None (elastic joints), one description
        for every joint, or {joint name: description}; a description is a JointStrength or a dict
        {"model": "coulomb" | "barton", "friction_angle": rad, "cohesion": Pa, ...} (see
        rockjoint.fem.make_strength). With a strength the Jacobian is non-symmetric (LU / GMRES)
        and the slip is committed only when a load step converges.
    :plane: "strain" (default) or "stress" in 2D; None (or "3D") in 3D.
    :quadrature: "nodal" (default; smooth tractions for stiff joints) or "gauss".
    :linear_solver: "auto" (MUMPS up to 60k dofs in 2D and 5k in 3D, 250k in 2D for a
        non-symmetric Jacobian, else CG/GMRES + GAMG; see linear_solver.DIRECT_DOF_LIMIT),
        "direct", "lagged" (a factorisation reused as FGMRES's preconditioner) or "iterative".
    :newton: NewtonOptions (tolerances, closure limit, load-step control, verbosity).
    :petsc_options: {option: value} for the linear solver's KSP/PC, without the leading dash
        (DOLFINx convention, e.g. {"ksp_type": "gmres", "pc_type": "hypre"}); applied after the
        defaults of `linear_solver`, so they override them.
    :options_prefix: the linear solver's PETSc options prefix (default: a unique one), so that
        command-line options such as -<prefix>ksp_monitor reach it (SNES options too, with
        solve(solver="snes")).
    :density: rock density ρ [kg/m³], one value or {block name: ρ}; gives gravity ρ g on the blocks
        (the load handle `model.gravity`). None: no gravity.
    :gravity: g [m/s²] acting along -y (2D) / -z (3D), or a gravity vector.
    :continuum: {block name: rockjoint.continuum.EquivalentContinuum} (its E, ν those of
        the block): joint sets smeared in these blocks (docs/equivalent-continuum.md); the other
        blocks stay elastic and may hold discrete joints. Plane strain in 2D.
    :beyond_range: "warn" (a RangeWarning) or "raise" (BeyondRangeError): a law past its range (law_range.py).
    :effective_stress_coefficient: α of σ'_n = σ_n - α p for water in the joints (fem.water.joint_pressure).

    Composed of: blocks (ElasticBlocks), load_path (LoadPath), smeared (SmearedBlocks or None)
    and the problem (problem.JointedProblem: F, J, joints, linear solver) that the project's
    Newton and PETSc SNES both drive; the model owns the inputs, the stages and their results.
    """

    def __init__(self, dmesh, element_degree: int = 1, rock=None, joints=None, shear_stiffness=0.0,
                 shear_stiffness_ratio=None, residual_stiffness=0.0, strength=None,
                 plane: str | None = None,
                 quadrature: str = "nodal", linear_solver: str = "auto",
                 newton: NewtonOptions | None = None, petsc_options: dict | None = None,
                 options_prefix: str | None = None, density=None, gravity=STANDARD_GRAVITY,
                 continuum: dict | None = None, beyond_range: str = "warn", effective_stress_coefficient=1.0):
        t0 = time.perf_counter()
        self.dmesh = dmesh
        self.mesh = dmesh.mesh
        self.comm = self.mesh.comm
        self.gdim = self.mesh.geometry.dim
        self.degree = check_element(element_degree, quadrature)
        self.plane = check_plane(self.gdim, plane)
        self.quadrature, self.beyond_range = quadrature, check_beyond_range(beyond_range)
        self.newton_options = newton or NewtonOptions()
        self._solver_settings = (linear_solver, check_petsc_options(petsc_options), check_options_prefix(options_prefix))
        self.rock = check_rock(dmesh, rock)  #: {block tag: (E [Pa], ν)}
        #: {joint tag: JointBehaviour} (rockjoint.joint)
        self.behaviours = joint_behaviours(names_of(dmesh, "joints"), joints or {}, shear_stiffness=shear_stiffness,
                                           shear_stiffness_ratio=shear_stiffness_ratio,
                                           residual_stiffness=residual_stiffness, strength=strength,
                                           effective_stress_coefficient=effective_stress_coefficient,
                                           argument="joints", closure_laws_only=True)
        self.densities = check_density(dmesh, density)  #: {block name: ρ [kg/m³]} ({} without gravity)
        self.stages: list[StageResult] = []  #: the result of every stage, in order
        self.solution: StageResult | None = None  #: the last stage's result
        self.blocks = ElasticBlocks(dmesh, self.rock, self.densities, self.degree, self.plane)
        self.load_path = LoadPath(dmesh, self.blocks, self.densities, gravity)
        self.V, self.u = self.blocks.V, self.blocks.u
        #: smeared joint sets (equivalent continuum) in the blocks named in `continuum`, or None
        self.smeared = None
        if continuum:
            self.smeared = SmearedBlocks(self.blocks, dmesh, {lookup(dmesh, "blocks", name): m
                                                              for name, m in continuum.items()}, self.rock)
        self._problem = JointedProblem(self.blocks, self.load_path, self.smeared, self.newton_options.closure_limit)
        self._problem.timings["setup"] = time.perf_counter() - t0

    # ---- what the parts hold -----------------------------------------------------------------
    @property
    def gravity(self) -> Load | None:
        """The gravity load handle (None without a density)."""
        return self.load_path.gravity

    @property
    def interface(self):
        """The joints' JointInterface (point state and geometry, for inspection)."""
        return self._problem.coupling.interface

    @property
    def linear_solver(self) -> LinearSolver | None:
        """The linear solver (after the first solve)."""
        return self._problem.linear_solver

    @property
    def num_dofs(self) -> int:
        """Global number of displacement dofs."""
        return self.V.dofmap.index_map.size_global * self.V.dofmap.index_map_bs

    timings = property(lambda self: self._problem.timings, doc="seconds per part (JointedProblem.timings)")
    counts = property(lambda self: self._problem.counts, doc="calls behind the timings (JointedProblem.counts)")
    load_factor = property(lambda self: self._problem.load_factor, doc="λ of the current stage")

    # ---- loads and supports (handles; changes take effect at the next stage) --------------
    def fix(self, boundary: str, components="all", block: str | None = None, value=0.0) -> Support:
        """Prescribed displacement `value` [m] (0: a fixed support) of `components` ("x", "y",
        "z", indices or "all") on a named boundary; one value or one per component. With `block`,
        only on the part of the boundary that belongs to that block (e.g. a roller under one block
        while the block above it, held by a joint, may slide). A non-zero or changed value is
        ramped over the next stage from the displacement the dofs have then; value=None holds
        the dofs where they are (a support installed in a later stage)."""
        return self.load_path.fix(boundary, components, block, value)

    def add_traction(self, boundary: str, traction) -> Load:
        """Surface traction [Pa] on a named boundary: a vector, or a callable f(x) -> (gdim, n)
        of the coordinates x (3, n) (interpolated in the displacement space)."""
        return self.load_path.add_load("traction", boundary, traction)

    def add_pressure(self, boundary: str, pressure: float) -> Load:
        """Normal pressure p [Pa] on a named boundary (curved ones too): traction t = -p n, n the
        outward normal of the rock; p > 0 pushes on the surface."""
        return self.load_path.add_load("pressure", boundary, pressure)

    def add_body_force(self, force) -> Load:
        """Body force per unit volume [N/m³] in every block."""
        return self.load_path.add_load("body_force", None, force)

    def excavate(self, boundary: str, fraction_left: float = 0.0) -> Load:
        """Excavation of an opening meshed as a hole: the in-situ traction σ0·n that `boundary`
        carries in the initial state is ramped to `fraction_left` of itself (default 0) over the
        next stage. The handle's value is that fraction; remove() puts the traction back."""
        return self.load_path.excavate(boundary, fraction_left)

    def set_in_situ_stress(self, in_situ: InSituStress, equilibrium_tolerance: float = 1e-8) -> None:
        """The initial stress σ0 (before the first stage): the bulk stress, the tractions σ0·n on
        every named boundary (carried by the supports on supported components), gravity, and
        joints pre-closed to their law's closure at the initial normal stress make an equilibrium
        state with u = 0; ValueError if σ0 and the model's gravity disagree, or (at the first
        solve) if the initial residual exceeds equilibrium_tolerance × the in-situ forces. A field
        that P1/P2 cannot balance exactly (a non-linear from_function field, a gradient along joints
        with P2 in 3D) needs a larger tolerance; the first stage then moves u by the imbalance."""
        if self.stages:
            raise RuntimeError("set_in_situ_stress: the in-situ stress is the initial state; set it before "
                               "the first solve()")
        self.load_path.set_in_situ_stress(in_situ, equilibrium_tolerance)

    # ---- setup -----------------------------------------------------------------------------
    def prepare(self) -> JointedProblem:
        """Set up what the next solve needs (joints and linear solver once; the bulk matrix when
        the supports changed; the load forms; the initial state) and return the problem."""
        p = self._problem
        if p.coupling is None:
            t0 = time.perf_counter()
            p.connect(JointCoupling(self.V, self.dmesh, {n: self.behaviours[t] for n, t in
                                                         names_of(self.dmesh, "joints").items()},
                                    quadrature=self.quadrature, beyond_range=self.beyond_range),
                      make_linear_solver(self.V, *self._solver_settings,
                                         symmetric=symmetric_tangent(self.behaviours) and self.smeared is None),
                      bool(self.behaviours))
            p.timings["setup"] += time.perf_counter() - t0
        supports = self.load_path.refresh(self.u.x.array)
        if supports is not None:
            p.set_supports(supports)
        if not self.load_path.stage.initial_state_set:
            self.load_path.stage.initial_state_set = True
            vertex_rule = self.quadrature == "nodal" and self.degree == 1  # joint_initial_state.py
            p.set_initial_state(self.behaviours, names_of(self.dmesh, "joints"), vertex_rule)
        return p

    def problem(self) -> JointedProblem:
        """The model's nonlinear problem (F, J) for PETSc SNES or a user's Newton, at the current
        stage's load factor (`problem.load_factor`): the object the model's own solvers drive."""
        p = self.prepare()
        if not self.load_path.stage.begun:
            p.begin_stage()
        return p

    # ---- solve and output -----------------------------------------------------------------
    def solve(self, load_steps: int = 1, name: str | None = None, solver: str = "newton",
              restart: bool = False) -> StageResult:
        """Solve one stage: the loads go from the previous stage's values to the ones set now in
        (adaptive) load steps, from the converged state (restart=True: from the initial state).
        solver: "newton" (the project's, with the closure-limiting step) or "snes" (PETSc SNES,
        options through petsc_options/options_prefix). Returns the StageResult (also appended to
        model.stages). Raises ConvergenceError / LinearSolveError; the model then stays at the
        last converged load step."""
        if solver not in ("newton", "snes"):
            raise ValueError(f"solver must be 'newton' or 'snes', got {solver!r}")
        if restart and self._problem.coupling is not None:
            self._problem.reset_state()  # path-dependent point state
            self.load_path.stage.initial_state_set = False
            self.load_path.stage.advancing = False
        p = self.prepare()
        self._close_advanced_stage()
        k = len(self.stages) + 1
        name = name or f"stage_{k}"
        p.clock = StageClock(self.comm, f"{self.load_path.stage.label or str(k)} ({name})")
        p.begin_stage()
        t0 = time.perf_counter()
        try:
            if solver == "newton":
                reports = solve_load_path(p, load_steps, self.newton_options, solve_step=self._step_solver())
            else:
                reports = snes_load_path(p, load_steps, self.newton_options)
        except Exception as e:
            self.load_path.end_stage(p.load_factor)
            raise p.explained(e)
        finally:
            p.timings["newton"] += time.perf_counter() - t0
            p.clock = None
        self.load_path.end_stage(1.0)
        return self._stage_result(name, reports, time.perf_counter() - t0)

    def advance(self, load_factor: float, load_steps: int = 1) -> StageResult:
        """Continue the current stage's load path to `load_factor` in `load_steps` equal Newton
        steps, committing the joint state after each: below the current factor unloads along the
        path, above 1 overloads (f(λ) = f_prev + λ (f_next - f_prev) extrapolated). Starts a stage
        (from the loads set now) if none is open; changes to the loads take effect at the next
        solve(). Raises ConvergenceError naming the failed step (the last converged one is kept)."""
        if int(load_steps) != load_steps or load_steps < 1:
            raise ValueError(f"load_steps must be an integer >= 1, got {load_steps!r}")
        target = float(load_factor)
        if not np.isfinite(target):
            raise ValueError(f"load_factor must be finite, got {load_factor!r}")
        if not self.load_path.stage.advancing:
            self.prepare().begin_stage()
            self.load_path.stage.advancing = True
        t0 = time.perf_counter()
        reports = solve_load_path(self._problem, load_steps, self.newton_options, target=target, adaptive=False,
                                  solve_step=self._step_solver())
        return self._stage_result(f"advance to {target:g}", reports, time.perf_counter() - t0)

    def _step_solver(self):
        """The load-step solver: Newton, and with smeared sets its pseudo-transient continuation
        when Newton fails (pseudo_transient.py); None: solve_load_path's plain Newton."""
        if self.smeared is None:
            return None
        smeared, options = self.smeared, self.newton_options

        def solve_step(problem, load_factor, step, start):
            return solve_step_with_relaxation(problem, smeared, load_factor, options, step, start)
        return solve_step

    def _close_advanced_stage(self) -> None:
        """After advance(): the loads of the factor reached become the next stage's start."""
        if self.load_path.stage.advancing:
            self.load_path.end_stage(self._problem.load_factor)

    def run(self, stages: list) -> list:
        """Solve a sequence of Stage(name, load_steps, actions, solver) in order (actions(model)
        changes the loads first); progress as 'stage k/n'. Returns their StageResults."""
        out = []
        for k, stage in enumerate(stages, start=1):
            if not isinstance(stage, Stage):
                raise ValueError(f"run: stage {k} is a {type(stage).__name__}, not a Stage")
            if stage.actions is not None:
                stage.actions(self)
            self.load_path.stage.label = f"{k}/{len(stages)}"
            try:
                out.append(self.solve(stage.load_steps, stage.name, stage.solver))
            finally:
                self.load_path.stage.label = None
        return out

    def _stage_result(self, name: str, reports: list, elapsed: float) -> StageResult:
        result = stage_result(self, self._problem, name, reports, elapsed)
        self.stages.append(result)
        self.solution = result
        return result

    def total_stress(self, degree: int | None = None) -> fem.Function:
        """Total stress σ0 + σ(u) [Pa, tension positive] interpolated in a discontinuous tensor
        space of `degree` (default: element degree - 1, exact for σ(u))."""
        self.prepare()
        sigma0 = self.load_path.sigma0 if self.load_path.in_situ is not None else None
        return monitors.total_stress(self.u, self.blocks.sigma, sigma0,
                                     self.degree - 1 if degree is None else degree)

    def boundary_mean_displacement(self, boundary: str) -> np.ndarray:
        """Mean displacement vector [m] over a named boundary (∫u ds / ∫ds, all ranks)."""
        return monitors.boundary_mean_displacement(self, boundary)

    def mean_normal_displacement(self, boundary: str) -> float:
        """∫ u·n ds / ∫ ds over a named boundary, n the rock's outward normal [m] (all ranks)."""
        return monitors.mean_normal_displacement(self, boundary)

    def write_xdmf(self, path: str) -> list:
        """Write the displacement (XDMF/HDF5) and the joint point state (<stem>_joints.xdmf;
        not written for a model without joints). Returns the written paths."""
        if self.solution is None:
            raise RuntimeError("write_xdmf: call solve() first")
        return output.write_xdmf(self, path)
