"""JointedRockModel: elastic rock blocks (DOLFINx) + zero-thickness joints (rockjoint C++),
followed along a staged load path (docs/staged-analysis.md).

    model = JointedRockModel(dmesh, rock={"block_1": (E, nu), ...}, joints={"joint_1": law},
                             shear_stiffness=1e10, plane="strain", density=2700.0)
    model.fix("bottom", "y"); model.fix("left", "x")
    model.set_in_situ_stress(InSituStress.depth_dependent(surface=500.0, density=2700.0, k0=0.5))
    model.solve(name="in-situ")                       # the initial state: u = 0
    model.excavate("tunnel"); model.solve(load_steps=5, name="excavation")
    model.add_pressure("tunnel", 1e6); model.solve(name="lining")

Units: SI (Pa, m, N). Compression positive for joint normal stress; closure Δ = -[[u]]·n; bulk
stress tensors tension positive. The bulk is linear elastic: its matrix K (with the supports) is
assembled when the supports change, the load vectors when the loads change. Newton's residual is
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
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from .behaviours import joint_behaviours, symmetric_tangent
from .compat import la_petsc
from .distributed_mesh import lookup, names_of
from .elastic_blocks import ElasticBlocks
from .equivalent_continuum import SmearedBlocks
from .in_situ import STANDARD_GRAVITY, InSituStress
from .joint_initial_state import initial_jump
from .coupling import JointCoupling
from .linear_solver import LinearSolver, resolve_kind, rigid_body_modes
from .load_path import LoadPath
from .loads import Load, Support
from .newton import NewtonOptions, solve_load_path
from .petsc_options import check_options_prefix, check_petsc_options
from .pseudo_transient import solve_step_with_relaxation
from .stages import JointedProblem, Stage, StageClock, StageResult, snes_load_path
from ..validation import positive_number

log = logging.getLogger(__name__)

def _per_block(blocks: dict, value, what: str, missing_message: str) -> dict:
    """{block name: value} from one value for every block or a dict that names them all."""
    if not isinstance(value, dict):
        return {b: value for b in blocks}
    unknown = set(value) - set(blocks)
    if unknown:
        raise ValueError(f"{what}: unknown block(s) {sorted(unknown)}; available blocks: {sorted(blocks)}")
    missing = set(blocks) - set(value)
    if missing:
        raise ValueError(f"{what}: " + missing_message.format(sorted(missing)))
    return value


class JointedRockModel:
    """A jointed rock mass: elastic blocks + joints with closure laws, loads, supports.

    dmesh: rockjoint.fem_coupling.distributed_mesh.DistributedJointMesh (mesh, cell_blocks, boundaries,
        names, pairs).
    element_degree: 1 or 2 (P2 uses the nodal joint rule).
    rock: {block name: (E [Pa], ν)} for every block, or one (E, ν) for all blocks.
    joints: {joint name: ClosureLaw} for every joint (any rockjoint law or table).
    shear_stiffness: joint shear stiffness k_s [Pa/m], constant (float, or {joint name: float}).
    shear_stiffness_ratio: if given, k_s = ratio × current normal stiffness instead (per-joint dict
        allowed); the Jacobian is then non-symmetric (GMRES with the iterative solver).
    residual_stiffness: k_r [Pa/m] spring in parallel with every law, in tension and compression
        (float or dict; default 0: a block held only by an open joint is then a singular system and
        solve() raises LinearSolveError instead of returning garbage).
    strength: joint shear strength (docs/joint-strength.md): None (elastic joints), one description
        for every joint, or {joint name: description}; a description is a JointStrength or a dict
        {"model": "coulomb" | "barton", "friction_angle": rad, "cohesion": Pa, ...} (see
        rockjoint.fem_coupling.make_strength). With a strength the Jacobian is non-symmetric (LU / GMRES)
        and the slip is committed only when a load step converges.
    plane: "strain" (default) or "stress" in 2D; None (or "3D") in 3D.
    quadrature: "nodal" (default; smooth tractions for stiff joints) or "gauss".
    linear_solver: "auto" (MUMPS up to 60k dofs in 2D and 5k in 3D, 250k in 2D for a
        non-symmetric Jacobian, else CG/GMRES + GAMG; see linear_solver.DIRECT_DOF_LIMIT),
        "direct", "lagged" (a factorisation reused as GMRES's preconditioner) or "iterative".
    newton: NewtonOptions (tolerances, closure limit, load-step control, verbosity).
    petsc_options: {option: value} for the linear solver's KSP/PC, without the leading dash
        (DOLFINx convention, e.g. {"ksp_type": "gmres", "pc_type": "hypre"}); applied after the
        defaults of `linear_solver`, so they override them.
    options_prefix: the linear solver's PETSc options prefix (default: a unique one), so that
        command-line options such as -<prefix>ksp_monitor reach it (SNES options too, with
        solve(solver="snes")).
    density: rock density ρ [kg/m³], one value or {block name: ρ}; gives gravity ρ g on the blocks
        (the load handle `model.gravity`). None: no gravity.
    gravity: g [m/s²] acting along -y (2D) / -z (3D), or a gravity vector.
    continuum: {block name: rockjoint._rockjoint.continuum.EquivalentContinuum} (its E, ν those of
        the block): joint sets smeared in these blocks (docs/equivalent-continuum.md); the other
        blocks stay elastic and may hold discrete joints. Plane strain in 2D.
    """

    def __init__(self, dmesh, element_degree: int = 1, rock=None, joints=None, shear_stiffness=0.0,
                 shear_stiffness_ratio=None, residual_stiffness=0.0, strength=None,
                 plane: str | None = None,
                 quadrature: str = "nodal", linear_solver: str = "auto",
                 newton: NewtonOptions | None = None, petsc_options: dict | None = None,
                 options_prefix: str | None = None, density=None, gravity=STANDARD_GRAVITY,
                 continuum: dict | None = None):
        self.dmesh = dmesh
        self.mesh = dmesh.mesh
        self.comm = self.mesh.comm
        self.gdim = self.mesh.geometry.dim
        if element_degree not in (1, 2):
            raise ValueError(f"element_degree must be 1 or 2, got {element_degree!r}")
        if element_degree == 2 and quadrature != "nodal":
            raise ValueError("element_degree=2 supports the 'nodal' joint quadrature only")
        self.degree = element_degree
        if self.gdim == 2:
            plane = "strain" if plane is None else plane
            if plane not in ("strain", "stress"):
                raise ValueError(f"plane must be 'strain' or 'stress' in 2D, got {plane!r}")
        elif plane not in (None, "3D", "3d"):
            raise ValueError(f"plane={plane!r} is meaningless in 3D; pass plane=None")
        self.plane = plane if self.gdim == 2 else None
        self.quadrature = quadrature
        self.linear_solver_kind = linear_solver
        self.petsc_options = check_petsc_options(petsc_options)
        self.options_prefix = check_options_prefix(options_prefix)
        self.newton_options = newton or NewtonOptions()
        self.rock = self._check_rock(rock)
        self.behaviours = self._check_joints(joints, shear_stiffness, shear_stiffness_ratio, residual_stiffness,
                                             strength)
        self.densities = self._check_density(density)  #: {block name: ρ [kg/m³]} ({} without gravity)
        self.stages: list[StageResult] = []  #: the result of every stage, in order
        # The parts, each with explicit inputs: the blocks' space and forms, the load path on
        # them; the joints (JointCoupling) and the linear solver come with the first solve.
        t0 = time.perf_counter()
        self.blocks = ElasticBlocks(dmesh, self.rock, self.densities, self.degree, self.plane)
        self.load_path = LoadPath(dmesh, self.blocks, self.densities, gravity)
        self.V, self.u, self.du = self.blocks.V, self.blocks.u, self.blocks.du
        #: smeared joint sets (equivalent continuum) in the blocks named in `continuum`, or None
        self.smeared = None
        if continuum:
            self.smeared = SmearedBlocks(self.blocks, dmesh, {lookup(dmesh, "blocks", name): m
                                                              for name, m in continuum.items()}, self.rock)
        self.sigma, self.eps = self.blocks.sigma, self.blocks.eps
        self.coupling: JointCoupling | None = None
        self.linear_solver: LinearSolver | None = None
        #: wall-clock seconds on this rank: bulk_assembly (K and f, once), interface_residual and
        #: interface_jacobian (all calls), linear_solve (all solves), newton (solve() total), setup
        self.timings = {"bulk_assembly": 0.0, "interface_residual": 0.0, "interface_jacobian": 0.0,
                        "matrix_copy": 0.0, "linear_solve": 0.0, "newton": 0.0,
                        "setup": time.perf_counter() - t0}
        #: number of calls behind the timings
        self.counts = {"interface_residual": 0, "interface_jacobian": 0, "linear_solve": 0,
                       "nonfinite_residuals": 0}
        self._initialised = False    # initial state (in-situ loads, joint pre-closure) set
        self._advancing = False      # a stage opened by advance() is in progress
        self._clock = None           # progress clock of the stage being solved
        self._stage_label = None     # "k/n" while run() drives the stages
        self._step_iterations = 0    # Newton iterations of the load step being solved
        self._saved = None           # (u, load factor) of the last converged load step
        self.load_factor = 0.0
        self.K = self.J = None       # bulk matrix with the supports, Jacobian
        self.r = la_petsc.create_vector([(self.V.dofmap.index_map, self.V.dofmap.index_map_bs)])
        self._r_joint = self.r.duplicate()
        self.solution = None

    # ---- input checks --------------------------------------------------------------------
    def _check_rock(self, rock) -> dict:
        blocks = names_of(self.dmesh, "blocks")
        if rock is None:
            raise ValueError(f"rock properties are missing; give rock={{block: (E, nu)}} for blocks {sorted(blocks)}")
        rock = _per_block(blocks, rock, "rock", "no (E, nu) for block(s) {}")
        out = {}
        for name, value in rock.items():
            try:
                E, nu = (float(v) for v in value)
            except (TypeError, ValueError):
                raise ValueError(f"rock[{name!r}] must be (E [Pa], nu), got {value!r}") from None
            if not (np.isfinite(E) and E > 0):
                raise ValueError(f"rock[{name!r}]: Young's modulus E = {E} Pa is invalid; it must be finite and > 0")
            if not (-1.0 < nu < 0.5):
                raise ValueError(f"rock[{name!r}]: Poisson's ratio nu = {nu} is invalid; it must be in (-1, 0.5)")
            out[blocks[name]] = (E, nu)
        return out

    def _check_joints(self, joints, ks, ratio, kr, strength=None) -> dict:
        return joint_behaviours(names_of(self.dmesh, "joints"), joints or {}, shear_stiffness=ks,
                                shear_stiffness_ratio=ratio, residual_stiffness=kr, strength=strength,
                                argument="joints", closure_laws_only=True)

    def _check_density(self, density) -> dict:
        if density is None:
            return {}
        density = _per_block(names_of(self.dmesh, "blocks"), density, "density",
                             "no value for block(s) {} (give one for every block)")
        return {name: positive_number(f"density[{name!r}]", rho, unit="kg/m³") for name, rho in density.items()}

    @property
    def gravity(self) -> Load | None:
        """The gravity load handle (None without a density)."""
        return self.load_path.gravity

    @property
    def in_situ(self) -> InSituStress | None:
        return self.load_path.in_situ

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
        self._initialised = False

    # ---- setup -----------------------------------------------------------------------------
    def _prepare(self) -> None:
        if self.coupling is None:
            self._setup_joints_and_solver()
        lp = self.load_path
        if lp.supports_dirty:
            self._setup_supports()
        if lp.forms_dirty:
            lp.compile_forms()
        lp.collect_prescribed(self.u.x.array)
        if not self._initialised:
            self._initial_state()

    def _setup_joints_and_solver(self) -> None:
        """The joints, through the public API a user's own model uses (docs/user-model.md): the
        model is a client of JointCoupling like any DOLFINx model; and the linear solver."""
        t0 = time.perf_counter()
        names = names_of(self.dmesh, "joints")
        self.coupling = JointCoupling(self.V, self.dmesh, {n: self.behaviours[t] for n, t in names.items()},
                                      quadrature=self.quadrature)
        imap, bs = self.V.dofmap.index_map, self.V.dofmap.index_map_bs
        num_dofs = imap.size_global * bs
        symmetric = symmetric_tangent(self.behaviours) and self.smeared is None
        kind = resolve_kind(self.linear_solver_kind, num_dofs, self.gdim, symmetric)
        nullspace = rigid_body_modes(self.V) if kind == "iterative" else None
        self.linear_solver = LinearSolver(self.comm, kind, num_dofs=num_dofs, near_nullspace=nullspace,
                                          symmetric=symmetric,
                                          options=self.petsc_options, prefix=self.options_prefix)
        self.num_dofs = num_dofs
        self.timings["setup"] += time.perf_counter() - t0

    def _setup_supports(self) -> None:
        """Dirichlet dofs of every support and the bulk matrix K with them (identity rows)."""
        t0 = time.perf_counter()
        bcs, constrained = self.load_path.dirichlet()
        self.bcs = bcs
        self._constrained = constrained
        n_owned = self.V.dofmap.index_map.size_local * self.V.dofmap.index_map_bs
        self._constrained_owned = np.flatnonzero(constrained[:n_owned]).astype(np.int32)
        for A in (self.K, self.J):
            if A is not None:
                A.destroy()
        self.coupling.set_supports(bcs)
        K = self.coupling.create_matrix(self.blocks.a_form)  # joint couplings reserved (pitfall 4)
        fem_petsc.assemble_matrix(K, self.blocks.a_form, bcs)
        K.assemble()
        self.K, self.J = K, K.duplicate(copy=True)
        self.timings["bulk_assembly"] += time.perf_counter() - t0

    def _initial_state(self) -> None:
        """u = 0 and the loads of the initial state; with an in-situ stress, joints pre-closed
        (initial jump j0 = (-Δ0, τ0/k_s), Δ0 the closure at σ_n0 = -n·σ0·n) and the equilibrium
        checked."""
        lp = self.load_path
        self.u.x.array[:] = 0.0
        lp.start()
        self._initialised = True
        if lp.in_situ is None:
            return
        vertex_rule = self.quadrature == "nodal" and self.degree == 1
        self.coupling.set_initial_jump(initial_jump(self.coupling.interface, lp.in_situ, self.behaviours,
                                                    self.gdim, names_of(self.dmesh, "joints"), vertex_rule))
        if self.smeared is not None:
            self.smeared.set_in_situ(lp.in_situ)
        self._begin_stage(next_loads=lp.state)
        rnorm = self.residual()
        scale = self.load_norm(0.0)
        tolerance = lp.equilibrium_tolerance
        if not rnorm <= tolerance * scale:
            raise ValueError(
                f"the in-situ stress is not in equilibrium with the model's loads: the initial residual is "
                f"{rnorm:.3e} N, {rnorm / max(scale, 1e-300):.2e} of the in-situ forces (allowed "
                f"{tolerance:g}). A uniform σ0 needs no gravity (density=None); a depth-dependent one needs "
                f"gravity with the same density; a field must satisfy div σ0 + ρ g = 0 (a discretisation "
                f"imbalance of a non-linear field: raise set_in_situ_stress(..., equilibrium_tolerance=))")

    def _begin_stage(self, next_loads=None) -> None:
        self.load_path.begin_stage(self.u.x.array, next_loads)
        self.load_factor = 0.0
        self._step_iterations = 0

    def _end_stage(self, reached: float) -> None:
        self.load_path.end_stage(reached)

    def _reactions(self) -> dict:
        """{(boundary, component): force the support exerts on the rock} at the current state."""
        lp = self.load_path
        lp.apply(self.load_factor, self.u)
        self.blocks.w.x.array[:] = self.u.x.array
        force = lp.assemble(self.blocks.internal_form)
        if lp.r_sigma0 is not None:
            force.axpy(1.0, lp.r_sigma0)
        self._joint_forces()
        force.axpy(1.0, self._r_joint)
        if self.smeared is not None:
            self.smeared.add_residual(force)
        out = lp.reactions(force)
        force.destroy()
        return out

    @property
    def interface(self):
        """The joints' JointInterface (owned by the model's JointCoupling): point state and
        geometry for inspection."""
        return self.coupling.interface

    # ---- the problem interface used by newton.py ------------------------------------------
    def load_norm(self, load_factor: float) -> float:
        """Scale of the forces at `load_factor`: ||f(λ)|| (+ ||∫ε(v):σ0||)."""
        return self.load_path.load_norm(load_factor)

    def _joint_forces(self) -> bool:
        """r_joint(u) into self._r_joint (owned entries complete); False if not finite."""
        t0 = time.perf_counter()
        rj = self._r_joint
        with rj.localForm() as loc:
            loc.set(0.0)
            finite = self.coupling.add_residual(self.u, loc.array)  # collective
        # Ghost contributions go to their owners (docs/fem.md, pitfall 5).
        rj.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self.timings["interface_residual"] += time.perf_counter() - t0
        self.counts["interface_residual"] += 1
        return finite

    def residual(self) -> float:
        lp = self.load_path
        lp.apply(self.load_factor, self.u)
        r = self.r
        if not self._joint_forces():
            # Never hand on a stale residual: SNES (through JointedProblem) and our Newton both
            # see an infinite one and cut the step.
            r.set(np.inf)
            self.counts["nonfinite_residuals"] += 1
            return np.inf
        self.K.mult(self.u.x.petsc_vec, r)
        if lp.any_prescribed:
            r.axpy(1.0, lp.lift)
        if lp.r_sigma0 is not None:
            r.axpy(1.0, lp.r_sigma0)
        r.axpy(-1.0, lp.f_lambda)
        r.axpy(1.0, self._r_joint)
        if self.smeared is not None and not self.smeared.add_residual(r):
            r.set(np.inf)  # a local solve of the smeared sets failed: cut the step
            self.counts["nonfinite_residuals"] += 1
            return np.inf
        with r.localForm() as loc:  # owned entries come first in the local form
            loc.array[self._constrained_owned] = 0.0
        nrm = r.norm()
        return nrm if np.isfinite(nrm) else np.inf

    def jacobian(self) -> None:
        self.jacobian_into(self.J)

    def jacobian_into(self, A) -> None:
        """A = K + joint tangent at u (A has K's nonzero pattern, e.g. JointedProblem.matrix())."""
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
        self._step_iterations += 1

    @property
    def is_linear(self) -> bool:
        """No joints: the model is linear (Newton then solves to the full linear tolerance)."""
        return not self.behaviours and self.smeared is None

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
        return self.coupling.admissible_step(self.u, self.du, fraction)

    def apply_increment(self, alpha: float) -> None:
        self.u.x.petsc_vec.axpy(alpha, self.du.x.petsc_vec)
        self.u.x.scatter_forward()

    def save_state(self) -> None:
        self._saved = (self.u.x.array.copy(), self.load_factor)

    def restore_state(self) -> None:
        """Back to the last saved (converged) step: u, load factor and the joints' trial state."""
        arr, self.load_factor = self._saved
        self.u.x.array[:] = arr
        self.load_path.applied = None
        self.coupling.revert_state()
        if self.smeared is not None:
            self.smeared.revert_state()

    def commit_state(self) -> None:
        """A load step converged: the joints' trial state becomes their converged state."""
        self.coupling.commit_state()
        if self.smeared is not None:
            self.smeared.commit_state()
        if self._clock is not None:
            self._clock.step(self.load_factor, self._step_iterations)
        self._step_iterations = 0

    def problem(self) -> JointedProblem:
        """The model as a problem object (F, J) for PETSc SNES or a user's Newton, at the current
        stage's load factor (`model.load_factor`)."""
        self._prepare()
        if not self.load_path.stage_open:
            self._begin_stage()
        return JointedProblem(self)

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
        if restart and self.coupling is not None:
            self.coupling.reset_state()  # path-dependent point state
            if self.smeared is not None:
                self.smeared.reset_state()
            self._initialised = False
            self._advancing = False
        self._prepare()
        self._close_advanced_stage()
        k = len(self.stages) + 1
        name = name or f"stage_{k}"
        label = self._stage_label or str(k)
        self._clock = StageClock(self.comm, f"{label} ({name})")
        self._begin_stage()
        t0 = time.perf_counter()
        try:
            if solver == "newton":
                reports = solve_load_path(self, load_steps, self.newton_options,
                                          solve_step=self._step_solver())
            else:
                reports = snes_load_path(self, load_steps, self.newton_options)
        except Exception:
            self._end_stage(self.load_factor)
            raise
        finally:
            self.timings["newton"] += time.perf_counter() - t0
            self._clock = None
        self._end_stage(1.0)
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
        if not self._advancing:
            self._prepare()
            self._begin_stage()
            self._advancing = True
        t0 = time.perf_counter()
        reports = solve_load_path(self, load_steps, self.newton_options, target=target, adaptive=False,
                                  solve_step=self._step_solver())
        return self._stage_result(f"advance to {target:g}", reports, time.perf_counter() - t0)

    def _step_solver(self):
        """The load-step solver: Newton, and with smeared sets its pseudo-transient continuation
        when Newton fails (pseudo_transient.py); None: solve_load_path's plain Newton."""
        if self.smeared is None:
            return None
        smeared = self.smeared

        def solve_step(problem, load_factor, step, start):
            return solve_step_with_relaxation(problem, smeared, load_factor, self.newton_options, step, start)
        return solve_step

    def _close_advanced_stage(self) -> None:
        """After advance(): the loads of the factor reached become the next stage's start."""
        if self._advancing:
            self._end_stage(self.load_factor)
            self._advancing = False

    def run(self, stages: list) -> list:
        """Solve a sequence of Stage(name, load_steps, actions, solver) in order (actions(model)
        changes the loads first); progress as 'stage k/n'. Returns their StageResults."""
        out = []
        for k, stage in enumerate(stages, start=1):
            if not isinstance(stage, Stage):
                raise ValueError(f"run: stage {k} is a {type(stage).__name__}, not a Stage")
            if stage.actions is not None:
                stage.actions(self)
            self._stage_label = f"{k}/{len(stages)}"
            try:
                out.append(self.solve(stage.load_steps, stage.name, stage.solver))
            finally:
                self._stage_label = None
        return out

    def _stage_result(self, name: str, reports: list, elapsed: float) -> StageResult:
        # Re-evaluated from the state just committed: a point that slid in the last step sits on
        # its strength and reads "slip" (joint_slip.cpp labels by where τ is).
        state = self.coupling.state(self.u)
        disp = fem.Function(self.V, name="displacement")
        disp.x.array[:] = self.u.x.array
        result = StageResult(disp, state, reports, self, name, self._reactions(), elapsed)
        self.stages.append(result)
        self.solution = result
        beyond = result.beyond_law_range()
        if beyond and self.comm.rank == 0:
            # Never silent: the answer there is the table's linear continuation, not the law.
            log.warning("joint law driven past its range (status validity_limit) at %s; the "
                        "response there is the table's linear continuation: tabulate to a higher "
                        "maximum stress", ", ".join(f"{n} ({c} points)" for n, c in beyond.items()))
        return result

    def total_stress(self, degree: int | None = None) -> fem.Function:
        """Total stress σ0 + σ(u) [Pa, tension positive] interpolated in a discontinuous tensor
        space of `degree` (default: element degree - 1, exact for σ(u))."""
        self._prepare()
        degree = self.degree - 1 if degree is None else degree
        T = fem.functionspace(self.mesh, ("DG", degree, (self.mesh.geometry.dim, self.mesh.geometry.dim)))
        stress = self.sigma(self.u)
        if self.in_situ is not None:
            stress = stress + self.load_path.sigma0
        points = T.element.interpolation_points
        out = fem.Function(T, name="total_stress")
        out.interpolate(fem.Expression(stress, points))
        return out

    def boundary_mean_displacement(self, boundary: str) -> np.ndarray:
        """Mean displacement vector [m] over a named boundary (∫u ds / ∫ds, all ranks)."""
        tag = lookup(self.dmesh, "boundaries", boundary)
        ds = ufl.Measure("ds", domain=self.mesh, subdomain_data=self.dmesh.boundaries)(tag)
        area = self.comm.allreduce(fem.assemble_scalar(fem.form(fem.Constant(self.mesh, 1.0) * ds)))
        return np.array([self.comm.allreduce(fem.assemble_scalar(fem.form(self.u[i] * ds))) / area
                         for i in range(self.gdim)])

    def write_xdmf(self, path: str) -> list:
        """Write the displacement (XDMF/HDF5) and the joint point state (<stem>_joints.xdmf;
        not written for a model without joints). Returns the written paths."""
        from .output import write_xdmf
        if self.solution is None:
            raise RuntimeError("write_xdmf: call solve() first")
        return write_xdmf(self, path)
