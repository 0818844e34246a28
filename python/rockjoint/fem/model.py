"""JointedRockModel: elastic rock blocks (DOLFINx) + zero-thickness joints (rockjoint C++).

    model = JointedRockModel(dmesh, rock={"block_1": (E, nu), ...}, joints={"joint_1": law},
                             shear_stiffness=1e10, plane="strain")
    model.fix("bottom", "y"); model.fix("left", "x")
    model.add_traction("top", (0.0, -1e6))
    solution = model.solve(load_steps=1)
    model.write_xdmf("out.xdmf")

Units: SI (Pa, m, N). Compression positive for joint normal stress; closure Δ = -[[u]]·n.
Supports are zero displacements of the chosen components. The bulk is linear elastic, so its
matrix K (with the supports) and the load vector f are assembled once; Newton's residual is
r = K u - λ f + r_joint(u), with r_joint added to the ghosted local vector before the reverse
ghost update, and the Jacobian is K + J_joint(u) (joint blocks via MatSetValuesLocal, rows and
columns of supported dofs left out, so supported rows stay identity rows).
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np
import ufl
from dolfinx import cpp as _dcpp
from dolfinx import fem, la
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from .. import _rockjoint
from .interface import JointBehaviour, JointInterface, ShearModel
from .linear_solver import LinearSolver, LinearSolveError, rigid_body_modes  # noqa: F401
from .newton import ConvergenceError, NewtonOptions, newton, solve_load_path  # noqa: F401
from .strength import StrengthModel, make_strength

log = logging.getLogger(__name__)

_COMPONENTS = {"x": 0, "y": 1, "z": 2}


def _names(dmesh, kind: str) -> dict:
    """{name: tag} of the mesh's groups of `kind`."""
    return {str(n): int(t) for t, n in dmesh.names[kind].items()}


def _lookup(dmesh, kind: str, name: str) -> int:
    names = _names(dmesh, kind)
    if name not in names:
        singular = {"blocks": "block", "joints": "joint", "boundaries": "boundary"}[kind]
        raise ValueError(f"unknown {singular} {name!r}; available {kind}: {sorted(names)}")
    return names[name]


def _per_joint(value, joint_names, what: str) -> dict:
    """A float for every joint, or a {joint name: float} dict (missing joints get 0)."""
    if isinstance(value, dict):
        unknown = set(value) - set(joint_names)
        if unknown:
            raise ValueError(f"{what}: unknown joint(s) {sorted(unknown)}; available joints: {sorted(joint_names)}")
        return {n: float(value.get(n, 0.0)) for n in joint_names}
    return {n: float(value) for n in joint_names}


@dataclass
class Loads:
    tractions: list = field(default_factory=list)    #: (boundary name, vector [Pa])
    body_forces: list = field(default_factory=list)  #: vector [N/m³]
    supports: list = field(default_factory=list)     #: (boundary name, component indices)


@dataclass
class JointedSolution:
    """Result of JointedRockModel.solve: the displacement, the joint point state and the history."""
    displacement: fem.Function
    joints: dict       #: point state on this rank (see JointInterface.state)
    reports: list      #: newton.StepReport per attempted load step
    model: "JointedRockModel"

    def gather_joints(self) -> dict:
        """The joint point state of all ranks, concatenated (on every rank)."""
        comm = self.model.comm
        out = {}
        for k, v in self.joints.items():
            parts = comm.allgather(np.asarray(v))
            out[k] = np.concatenate(parts, axis=0)
        return out

    @property
    def newton_iterations(self) -> int:
        return sum(r.iterations for r in self.reports)

    def beyond_law_range(self) -> dict:
        """{joint name: number of points (all ranks)} whose law answered outside its range:
        status validity_limit (a table driven past its last knot, continued linearly; a Tang &
        Jiao law at its cap). Empty when every point is inside its law's range."""
        status = np.asarray(self.joints["status"])
        tags = np.asarray(self.joints["tag"])
        limit = int(_rockjoint.constitutive.Status.validity_limit)
        out = {}
        for name, tag in _names(self.model.dmesh, "joints").items():
            count = self.model.comm.allreduce(int(np.count_nonzero((status == limit) & (tags == tag))))
            if count:
                out[name] = count
        return out


class JointedRockModel:
    """A jointed rock mass: elastic blocks + joints with closure laws, loads, supports.

    dmesh: rockjoint.fem.distributed_mesh.DistributedJointMesh (mesh, cell_blocks, boundaries,
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
        rockjoint.fem.make_strength). With a strength the Jacobian is non-symmetric (LU / GMRES)
        and the slip is committed only when a load step converges.
    plane: "strain" (default) or "stress" in 2D; None (or "3D") in 3D.
    quadrature: "nodal" (default; smooth tractions for stiff joints) or "gauss".
    linear_solver: "auto" (MUMPS up to 60k dofs, else CG+GAMG), "direct" or "iterative".
    newton: NewtonOptions (tolerances, closure limit, load-step control, verbosity).
    petsc_options: {option: value} for the linear solver's KSP/PC, without the leading dash
        (DOLFINx convention, e.g. {"ksp_type": "gmres", "pc_type": "hypre"}); applied after the
        defaults of `linear_solver`, so they override them.
    options_prefix: the linear solver's PETSc options prefix (default: a unique one), so that
        command-line options such as -<prefix>ksp_monitor reach it.
    """

    def __init__(self, dmesh, element_degree: int = 1, rock=None, joints=None, shear_stiffness=0.0,
                 shear_stiffness_ratio=None, residual_stiffness=0.0, strength=None,
                 plane: str | None = None,
                 quadrature: str = "nodal", linear_solver: str = "auto",
                 newton: NewtonOptions | None = None, petsc_options: dict | None = None,
                 options_prefix: str | None = None):
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
        if petsc_options is not None and not isinstance(petsc_options, dict):
            raise ValueError(f"petsc_options must be a dict {{option: value}}, got "
                             f"{type(petsc_options).__name__}")
        for key in petsc_options or {}:
            if not isinstance(key, str) or key.startswith("-") or not key:
                raise ValueError(f"petsc_options key {key!r}: give option names without the "
                                 f"leading dash, e.g. 'ksp_type'")
        self.petsc_options = dict(petsc_options or {})
        if options_prefix is not None and (not isinstance(options_prefix, str)
                                           or options_prefix.startswith("-")):
            raise ValueError(f"options_prefix {options_prefix!r}: a string without a leading dash")
        self.options_prefix = options_prefix
        self.newton_options = newton or NewtonOptions()
        self.rock = self._check_rock(rock)
        self.behaviours = self._check_joints(joints, shear_stiffness, shear_stiffness_ratio, residual_stiffness,
                                             strength)
        self.loads = Loads()
        #: wall-clock seconds on this rank: bulk_assembly (K and f, once), interface_residual and
        #: interface_jacobian (all calls), linear_solve (all solves), newton (solve() total), setup
        self.timings = {"bulk_assembly": 0.0, "interface_residual": 0.0, "interface_jacobian": 0.0,
                        "matrix_copy": 0.0, "linear_solve": 0.0, "newton": 0.0, "setup": 0.0}
        #: number of calls behind the timings
        self.counts = {"interface_residual": 0, "interface_jacobian": 0, "linear_solve": 0}
        self._ready = False
        self.solution = None

    # ---- input checks --------------------------------------------------------------------
    def _check_rock(self, rock) -> dict:
        blocks = _names(self.dmesh, "blocks")
        if rock is None:
            raise ValueError(f"rock properties are missing; give rock={{block: (E, nu)}} for blocks {sorted(blocks)}")
        if not isinstance(rock, dict):
            rock = {b: rock for b in blocks}
        unknown = set(rock) - set(blocks)
        if unknown:
            raise ValueError(f"rock: unknown block(s) {sorted(unknown)}; available blocks: {sorted(blocks)}")
        missing = set(blocks) - set(rock)
        if missing:
            raise ValueError(f"rock: no (E, nu) for block(s) {sorted(missing)}")
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
        names = _names(self.dmesh, "joints")
        joints = joints or {}
        unknown = set(joints) - set(names)
        if unknown:
            raise ValueError(f"joints: unknown joint(s) {sorted(unknown)}; available joints: {sorted(names)}")
        missing = set(names) - set(joints)
        if missing:
            raise ValueError(f"joints: no closure law for joint(s) {sorted(missing)}; give joints={{name: law}}")
        ks = _per_joint(ks, names, "shear_stiffness")
        kr = _per_joint(kr, names, "residual_stiffness")
        ratio = None if ratio is None else _per_joint(ratio, names, "shear_stiffness_ratio")
        strengths = _per_joint_strength(strength, names)
        out = {}
        for name, law in joints.items():
            if not isinstance(law, _rockjoint.constitutive.ClosureLaw):
                raise ValueError(f"joints[{name!r}] must be a rockjoint closure law or table, got {type(law).__name__}")
            if ratio is None:
                b = JointBehaviour(law, ShearModel.constant, shear_stiffness=ks[name], residual_stiffness=kr[name],
                                   strength=strengths[name])
            else:
                b = JointBehaviour(law, ShearModel.proportional, shear_stiffness_ratio=ratio[name],
                                   residual_stiffness=kr[name], strength=strengths[name])
            out[names[name]] = b
        return out

    def _component_indices(self, components) -> list:
        if components in ("all", None):
            return list(range(self.gdim))
        if isinstance(components, (str, int)):
            components = [components]
        out = []
        for c in components:
            i = _COMPONENTS.get(c, c) if isinstance(c, str) else c
            if not isinstance(i, (int, np.integer)) or not 0 <= i < self.gdim:
                raise ValueError(f"support component {c!r} is invalid; use 'x', 'y'{', z' if self.gdim == 3 else ''}, "
                                 f"an index < {self.gdim} or 'all'")
            out.append(int(i))
        return out

    def _vector(self, value, what: str) -> np.ndarray:
        v = np.asarray(value, dtype=float)
        if v.shape != (self.gdim,) or not np.all(np.isfinite(v)):
            raise ValueError(f"{what} must be {self.gdim} finite components, got {value!r}")
        return v

    # ---- loads and supports --------------------------------------------------------------
    def fix(self, boundary: str, components="all", block: str | None = None) -> None:
        """Zero displacement of `components` ("x", "y", "z", indices or "all") on a named boundary;
        with `block`, only on the part of the boundary that belongs to that block (e.g. a roller
        under one block while the block above it, held by a joint, may slide)."""
        _lookup(self.dmesh, "boundaries", boundary)
        block_tag = None if block is None else _lookup(self.dmesh, "blocks", block)
        self.loads.supports.append((boundary, self._component_indices(components), block_tag))
        self._ready = False

    def add_traction(self, boundary: str, traction) -> None:
        """Surface traction vector [Pa] on a named boundary (scaled by the load factor)."""
        _lookup(self.dmesh, "boundaries", boundary)
        self.loads.tractions.append((boundary, self._vector(traction, "traction")))
        self._ready = False

    def add_body_force(self, force) -> None:
        """Body force per unit volume [N/m³] in every block (scaled by the load factor)."""
        self.loads.body_forces.append(self._vector(force, "body force"))
        self._ready = False

    # ---- setup -----------------------------------------------------------------------------
    def _setup(self) -> None:
        t0 = time.perf_counter()
        mesh, gdim, tdim = self.mesh, self.gdim, self.mesh.topology.dim
        V = fem.VectorFunctionSpace(mesh, ("Lagrange", self.degree))
        self.V = V
        self.u = fem.Function(V, name="displacement")
        self.du = fem.Function(V)

        # Lamé parameters per cell from the block tags (DG0).
        Q = fem.FunctionSpace(mesh, ("DG", 0))
        lam, mu = fem.Function(Q), fem.Function(Q)
        tags = self.dmesh.cell_blocks
        ncells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
        cell_tag = np.full(ncells, -1, dtype=np.int64)
        cell_tag[tags.indices] = tags.values
        lam_a, mu_a = np.full(ncells, np.nan), np.full(ncells, np.nan)
        for tag, (E, nu) in self.rock.items():
            sel = cell_tag == tag
            mu_a[sel] = E / (2 * (1 + nu))
            l = E * nu / ((1 + nu) * (1 - 2 * nu))
            if self.plane == "stress":
                l = 2 * l * mu_a[sel] / (l + 2 * mu_a[sel])
            lam_a[sel] = l
        if np.isnan(mu_a).any():
            raise ValueError("some cells carry no block tag with rock properties")
        dofs = Q.dofmap.list.array
        lam.x.array[dofs] = lam_a
        mu.x.array[dofs] = mu_a
        self._lame = (lam, mu)

        def eps(w):
            return ufl.sym(ufl.grad(w))

        def sigma(w):
            return 2 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(gdim)

        self.sigma = sigma
        du_, v = ufl.TrialFunction(V), ufl.TestFunction(V)
        a_form = fem.form(ufl.inner(sigma(du_), eps(v)) * ufl.dx)
        ds = ufl.Measure("ds", domain=mesh, subdomain_data=self.dmesh.boundaries)
        L = ufl.inner(fem.Constant(mesh, np.zeros(gdim)), v) * ufl.dx
        for name, t in self.loads.tractions:
            L += ufl.inner(fem.Constant(mesh, t), v) * ds(_lookup(self.dmesh, "boundaries", name))
        for f in self.loads.body_forces:
            L += ufl.inner(fem.Constant(mesh, f), v) * ufl.dx
        L_form = fem.form(L)

        # Supports: zero components on boundaries.
        fdim = tdim - 1
        mesh.topology.create_connectivity(fdim, tdim)
        bcs = []
        f2c = mesh.topology.connectivity(fdim, tdim)
        for name, comps, block_tag in self.loads.supports:
            facets = self.dmesh.boundary(name)
            if block_tag is not None:
                facets = np.array([f for f in facets if cell_tag[f2c.links(f)[0]] == block_tag], dtype=np.int32)
            for c in comps:
                Vc = V.sub(c)
                dofs_c = fem.locate_dofs_topological(Vc, fdim, facets)
                bcs.append(fem.dirichletbc(PETSc.ScalarType(0), dofs_c, Vc))
        self.bcs = bcs
        imap, bs = V.dofmap.index_map, V.dofmap.index_map_bs
        n_local_unrolled = (imap.size_local + imap.num_ghosts) * bs
        constrained = np.zeros(n_local_unrolled, dtype=np.int8)
        for bc in bcs:
            idx, _ = bc.dof_indices()
            constrained[idx] = 1
        self._constrained = constrained
        self._constrained_owned = np.flatnonzero(constrained[: imap.size_local * bs]).astype(np.int32)

        # Joints and the sparsity pattern with the cross-joint couplings (docs/fem.md, pitfall 4).
        self.interface = JointInterface(V, self.dmesh.pairs, self.behaviours, self.quadrature)
        sp = _dcpp.fem.create_sparsity_pattern(mesh.topology, [V.dofmap._cpp_object] * 2,
                                               {_dcpp.fem.IntegralType.cell})
        self.interface.insert_sparsity(sp)
        sp.assemble()
        K = _dcpp.la.petsc.create_matrix(self.comm, sp)
        # Explicit zeros reserve the joint couplings: PETSc drops unset preallocated entries at the
        # final assembly, and J is refreshed from K with SAME_NONZERO_PATTERN.
        self.interface.add_jacobian(K, np.zeros(n_local_unrolled), constrained, scale=0.0)
        t1 = time.perf_counter()
        fem_petsc.assemble_matrix(K, a_form, bcs)
        K.assemble()
        f = fem_petsc.assemble_vector(L_form)
        f.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        fem_petsc.set_bc(f, bcs)
        self.timings["bulk_assembly"] = time.perf_counter() - t1
        self.K, self.f = K, f
        self.J = K.duplicate(copy=True)
        self.r = f.duplicate()
        self._r_joint = la.create_petsc_vector(imap, bs)
        self.f_norm = f.norm()
        self.a_form, self.L_form = a_form, L_form

        num_dofs = imap.size_global * bs
        # Friction couples the shear strength to the normal stress: an unsymmetric tangent.
        symmetric = all(b.shear_model == ShearModel.constant and b.strength.model == StrengthModel.none
                        for b in self.behaviours.values())
        nullspace = None
        kind = self.linear_solver_kind
        if kind == "iterative" or (kind == "auto" and num_dofs > 60_000):
            nullspace = rigid_body_modes(V)
        self.linear_solver = LinearSolver(self.comm, kind, num_dofs=num_dofs, near_nullspace=nullspace,
                                          symmetric=symmetric, options=self.petsc_options,
                                          prefix=self.options_prefix)
        self.num_dofs = num_dofs
        self.load_factor = 0.0
        self._saved = None
        self.timings["setup"] = time.perf_counter() - t0
        self._ready = True

    # ---- the problem interface used by newton.py ------------------------------------------
    def load_norm(self, load_factor: float) -> float:
        return abs(load_factor) * self.f_norm

    def residual(self) -> float:
        t0 = time.perf_counter()
        rj = self._r_joint
        with rj.localForm() as loc:
            loc.set(0.0)
            finite = self.interface.add_residual(self.u.x.array, loc.array)
        # Ghost contributions go to their owners (docs/fem.md, pitfall 5).
        rj.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self.timings["interface_residual"] += time.perf_counter() - t0
        self.counts["interface_residual"] += 1
        finite = self.comm.allreduce(bool(finite), op=_min_op())
        if not finite:
            return np.inf
        r = self.r
        self.K.mult(self.u.vector, r)
        r.axpy(-self.load_factor, self.f)
        r.axpy(1.0, rj)
        with r.localForm() as loc:  # owned entries come first in the local form
            loc.array[self._constrained_owned] = 0.0
        nrm = r.norm()
        return nrm if np.isfinite(nrm) else np.inf

    def jacobian(self) -> None:
        t0 = time.perf_counter()
        self.K.copy(self.J, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)  # J = K (bulk, constant)
        t1 = time.perf_counter()
        self.timings["matrix_copy"] += t1 - t0
        t0 = t1
        self.interface.add_jacobian(self.J, self.u.x.array, self._constrained)
        self.J.assemble()
        self.timings["interface_jacobian"] += time.perf_counter() - t0
        self.counts["interface_jacobian"] += 1

    def solve_increment(self) -> None:
        t0 = time.perf_counter()
        self.r.scale(-1.0)
        try:
            self.linear_solver.solve(self.J, self.r, self.du.vector)
        finally:
            self.r.scale(-1.0)
            self.timings["linear_solve"] += time.perf_counter() - t0
            self.counts["linear_solve"] += 1
        self.du.x.scatter_forward()

    def increment_norms(self) -> tuple:
        """(||du||, ||u||) of the last Newton increment and the current displacement [m]."""
        return self.du.vector.norm(), self.u.vector.norm()

    def admissible_step(self, fraction: float) -> float:
        alpha = self.interface._cpp.admissible_step_length(self.u.x.array, self.du.x.array, fraction)
        return self.comm.allreduce(alpha, op=_min_op())

    def apply_increment(self, alpha: float) -> None:
        self.u.vector.axpy(alpha, self.du.vector)
        self.u.x.scatter_forward()

    def save_state(self) -> None:
        self._saved = (self.u.x.array.copy(), self.load_factor)

    def restore_state(self) -> None:
        arr, self.load_factor = self._saved
        self.u.x.array[:] = arr
        self.interface.revert_state()

    def commit_state(self) -> None:
        """Accept the joint point state (slip, dilation) after a converged load step."""
        self.interface.commit_state()

    # ---- solve and output -----------------------------------------------------------------
    def solve(self, load_steps: int = 1, restart: bool = True) -> JointedSolution:
        """Apply the loads in (adaptive) load steps from zero (restart=True) or from the last
        solution, and return the JointedSolution. Raises ConvergenceError / LinearSolveError."""
        if not self._ready:
            self._setup()
        if restart:
            self.u.x.array[:] = 0.0
            self.load_factor = 0.0
            self.interface.reset_state()
        t0 = time.perf_counter()
        reports = solve_load_path(self, load_steps, self.newton_options)
        self.timings["newton"] += time.perf_counter() - t0
        self.interface.update_state(self.u.x.array)
        self.solution = JointedSolution(self.u, self.interface.state(), reports, self)
        beyond = self.solution.beyond_law_range()
        if beyond and self.comm.rank == 0:
            # Never silent: the answer there is the table's linear continuation, not the law.
            log.warning("joint law driven past its range (status validity_limit) at %s; the "
                        "response there is the table's linear continuation: tabulate to a higher "
                        "maximum stress", ", ".join(f"{n} ({c} points)" for n, c in beyond.items()))
        return self.solution

    def advance(self, load_factor: float, load_steps: int = 1) -> JointedSolution:
        """Continue the load path from the current load factor to `load_factor` (lower = unloading,
        higher than 1 = overloading) in `load_steps` equal Newton steps, committing the joint state
        (slip, dilation) after each; starts from zero on first use. Raises ConvergenceError naming
        the failed step (the state of the last converged step is kept)."""
        if not self._ready:
            self._setup()
        start = self.load_factor
        for k in range(1, int(load_steps) + 1):
            target = start + (float(load_factor) - start) * k / load_steps
            self.save_state()
            report = newton(self, target, self.newton_options)
            if not report.converged:
                self.restore_state()
                raise ConvergenceError(f"advance: the step to load factor {target:.6g} failed "
                                       f"({report.reason}); kept the state at {self.load_factor:.6g}")
            self.commit_state()
        self.interface.update_state(self.u.x.array)
        self.solution = JointedSolution(self.u, self.interface.state(), [], self)
        return self.solution

    def boundary_mean_displacement(self, boundary: str) -> np.ndarray:
        """Mean displacement vector [m] over a named boundary (∫u ds / ∫ds, all ranks)."""
        tag = _lookup(self.dmesh, "boundaries", boundary)
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


def _per_joint_strength(value, joint_names) -> dict:
    """{joint name: JointStrength} from None, one description for all joints, or a dict keyed by
    joint names (a dict whose keys are all joint names is per joint; otherwise one description)."""
    if isinstance(value, dict) and value and set(value) <= set(joint_names):
        return {n: make_strength(value.get(n), n) for n in joint_names}
    if isinstance(value, dict) and value and set(value) & set(joint_names):
        raise ValueError(f"strength: mixes joint names {sorted(set(value) & set(joint_names))} with "
                         f"other keys {sorted(set(value) - set(joint_names))}")
    return {n: make_strength(value, n) for n in joint_names}


def _min_op():
    from mpi4py import MPI
    return MPI.MIN
