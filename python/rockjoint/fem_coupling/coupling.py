"""Joints as a building block of the user's own DOLFINx model (docs/user-model.md).

The user keeps their mesh, function space, UFL forms, boundary conditions and solver; rockjoint
adds the joints:

    coupling = JointCoupling(V, dmesh, {"fault": table}, shear_stiffness=1e9, bcs=bcs)
    A = coupling.create_matrix(a)                 # the form's sparsity + cross-joint couplings
    # residual:  assemble_vector(b, L); coupling.add_residual(u, b); apply_lifting(...);
    #            b.ghostUpdate(ADD, REVERSE); set_bc(...)
    # Jacobian:  A.zeroEntries(); coupling.add_jacobian(u, A); assemble_matrix(A, a, bcs); A.assemble()
    alpha = coupling.admissible_step(u, du)       # closure limiter along u + alpha du

or, with a UFL residual F(u; v), :class:`JointedNonlinearProblem`: DOLFINx 0.11's SNES-based
``dolfinx.fem.petsc.NonlinearProblem`` with the joints added (same constructor, ``solve()``,
``solver``, ``F``, ``J``, ``A``, ``b``, ``x``, ``u``).

What this module takes care of (docs/fem.md, pitfalls 3-7): dofs of each pair from ``V.dofmap``
(P1/P2, any dof numbering: never node·gdim + c); the cross-joint couplings in the matrix's
sparsity, reserved with explicit zeros so a final assembly does not drop them; joint residuals
added to the local ghosted vector before the reverse ghost update; joint Jacobian blocks added
before DOLFINx's matrix assembly (which flushes and inserts the Dirichlet diagonal), with the
rows and columns of supported dofs left out; the step shortened so no closure passes a fraction
of its remaining room to a law's maximum closure.
"""
from __future__ import annotations

import logging
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np
import ufl
from dolfinx import cpp as _dcpp
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from ..joint import joint_behaviours, symmetric_tangent
from .compat import create_vector, la_petsc
from .distributed_mesh import DistributedJointMesh, JointPairs, names_of
from .interface import JointInterface
from .snes_problem import JointedSNESProblem

log = logging.getLogger(__name__)

__all__ = ["JointCoupling", "JointedNonlinearProblem", "joint_behaviours", "supported_dofs"]


def supported_dofs(V: fem.FunctionSpace, bcs: Iterable[fem.DirichletBC]) -> np.ndarray:
    """Mask (int8, 1 = supported) over the local unrolled dofs of V, ghosts included, of every dof
    a DirichletBC in `bcs` prescribes (whole-space or component bcs, V.sub(i))."""
    imap, bs = V.dofmap.index_map, V.dofmap.index_map_bs
    n = (imap.size_local + imap.num_ghosts) * bs
    mask = np.zeros(n, dtype=np.int8)
    for i, bc in enumerate(bcs):
        if not isinstance(bc, fem.DirichletBC):
            raise TypeError(f"bcs[{i}] must be a dolfinx.fem.DirichletBC, got {type(bc).__name__}")
        if not _same_space(bc.function_space, V):
            raise ValueError(f"bcs[{i}] constrains a function space that is not the displacement space "
                             "V (or one of its components V.sub(i))")
        idx, _ = bc.dof_indices()
        idx = np.asarray(idx)
        if idx.size and (idx.min() < 0 or idx.max() >= n):
            raise ValueError(f"bcs[{i}]: dof indices in [{idx.min()}, {idx.max()}] lie outside the "
                             f"{n} local dofs of V")
        mask[idx] = 1
    return mask


def _same_space(W, V) -> bool:
    """W (Python or C++ function space) is V or a component V.sub(i) of it."""
    return V._cpp_object.contains(getattr(W, "_cpp_object", W))


class JointCoupling:
    """The joints of a mesh bound to the user's displacement space V.

    V: vector Lagrange space of degree 1 or 2 on the split mesh (block size = gdim).
    joints: the DistributedJointMesh (pairs and joint names from it), or its JointPairs with
        `joint_tags` = {joint name: tag}.
    laws: {joint name: law} for every joint (see rockjoint.joint.joint_behaviours); shear_stiffness,
        shear_stiffness_ratio, residual_stiffness, strength: as in joint_behaviours.
    quadrature: "nodal" (default; smooth tractions for stiff joints) or "gauss" (P1 only).
    bcs: the Dirichlet conditions of the problem; their dofs' rows and columns are left out of the
        joint Jacobian and rows out of the joint residual (see set_supports).
    Arrays: "local" means this rank's unrolled dofs of V, ghosts included (u.x.array layout).
    """

    def __init__(self, V: fem.FunctionSpace, joints: DistributedJointMesh | JointPairs,
                 laws: Mapping[str, object], *, joint_tags: Mapping[str, int] | None = None,
                 shear_stiffness=0.0, shear_stiffness_ratio=None, residual_stiffness=0.0,
                 strength=None, quadrature: str = "nodal", bcs: Sequence[fem.DirichletBC] = ()):
        gdim = V.mesh.geometry.dim
        element = V.ufl_element()
        if V.dofmap.index_map_bs != gdim or element.family_name not in ("P", "Q") \
                or element.discontinuous or element.embedded_superdegree not in (1, 2):
            raise ValueError(f"V must be a vector Lagrange space of degree 1 or 2 with {gdim} components "
                             f"(fem.functionspace(mesh, ('Lagrange', 1, (gdim,)))), got {element} with block "
                             f"size {V.dofmap.index_map_bs}")
        if isinstance(joints, DistributedJointMesh):
            if joints.mesh is not V.mesh:
                raise ValueError("V is not built on the mesh of the DistributedJointMesh `joints`")
            pairs = joints.pairs
            names = names_of(joints, "joints")
            if joint_tags is not None:
                raise ValueError("joint_tags: the joint names come from the DistributedJointMesh; give "
                                 "joint_tags only with JointPairs")
        elif isinstance(joints, JointPairs):
            if joint_tags is None:
                raise ValueError("joint_tags={joint name: tag} is required when joints are JointPairs")
            pairs, names = joints, {str(n): int(t) for n, t in joint_tags.items()}
            stray = set(np.unique(pairs.joint_tags).tolist()) - set(names.values())
            if stray:
                raise ValueError(f"joint_tags: the pairs carry tags {sorted(stray)} that no name maps to "
                                 f"(names: {names})")
        else:
            raise TypeError(f"joints must be a DistributedJointMesh or JointPairs, got {type(joints).__name__}")
        tdim = V.mesh.topology.dim
        num_cells = V.mesh.topology.index_map(tdim).size_local + V.mesh.topology.index_map(tdim).num_ghosts
        for what in ("minus_cells", "plus_cells"):
            c = np.asarray(getattr(pairs, what))
            if c.size and (c.min() < 0 or c.max() >= num_cells):
                raise ValueError(f"joints: pair {what} in [{c.min()}, {c.max()}] outside the {num_cells} "
                                 "local cells of V's mesh")
        if quadrature == "gauss" and element.embedded_superdegree != 1:
            raise ValueError("quadrature='gauss' is for P1 only; use 'nodal' with P2")
        self.V = V
        self.joint_tags = names
        self.behaviours = joint_behaviours(names, laws, shear_stiffness=shear_stiffness,
                                           shear_stiffness_ratio=shear_stiffness_ratio,
                                           residual_stiffness=residual_stiffness, strength=strength)
        self.interface = JointInterface(V, pairs, self.behaviours, quadrature)
        imap, bs = V.dofmap.index_map, V.dofmap.index_map_bs
        self._imap, self._bs = imap, bs
        self.num_local_dofs = (imap.size_local + imap.num_ghosts) * bs
        self._work = la_petsc.create_vector([(imap, bs)])  # ghosted copy of a Vec's owned entries
        self._residual = np.zeros(self.num_local_dofs)
        self.set_supports(bcs)

    # ---- supports ------------------------------------------------------------------------
    def set_supports(self, bcs: Sequence[fem.DirichletBC]) -> None:
        """Take the supported dofs from a list of DirichletBC (replacing earlier ones)."""
        self.supported = supported_dofs(self.V, bcs)

    @property
    def symmetric(self) -> bool:
        """True if the joint tangent is symmetric (constant shear stiffness and no strength on every
        joint: friction couples the shear strength to the normal stress)."""
        return symmetric_tangent(self.behaviours)

    # ---- matrix --------------------------------------------------------------------------
    def insert_sparsity(self, pattern: _dcpp.la.SparsityPattern) -> None:
        """Insert the cross-joint couplings into an unassembled sparsity pattern of V × V."""
        self.interface.insert_sparsity(pattern)

    def create_matrix(self, a: fem.Form) -> PETSc.Mat:
        """A PETSc matrix with the sparsity of the bilinear form `a` (on V × V) plus the cross-joint
        couplings, reserved with explicit zeros (docs/fem.md, pitfall 4). Use it in place of
        dolfinx.fem.petsc.create_matrix(a)."""
        if not isinstance(a, fem.Form):
            raise TypeError(f"a must be a compiled bilinear form (dolfinx.fem.form(...)), got {type(a).__name__}")
        if a.rank != 2 or any(W.component() or not _same_space(W, self.V) for W in a.function_spaces):
            raise ValueError("a must be a bilinear form on V × V (the coupling's displacement space)")
        pattern = fem.create_sparsity_pattern(a)
        self.insert_sparsity(pattern)
        pattern.finalize()
        return self.interface.create_matrix(pattern)

    # ---- residual and Jacobian -----------------------------------------------------------
    def add_residual(self, u, b) -> bool:
        """Add the joint forces at u into b, the user's residual vector after assemble_vector and
        before apply_lifting / the reverse ghost update (docs/fem.md, pitfall 5). Rows of supported
        dofs are left out. b: a ghosted PETSc Vec of V (its local form is used) or a local array.
        Returns False on every rank if a traction is not finite on some rank (a closure at or
        beyond a law's maximum closure: shorten the step with admissible_step). Collective."""
        u_local = self._local(u, "u")
        r = self._residual
        r[:] = 0.0
        finite = bool(self.interface.add_residual(u_local, r))
        r[self.supported != 0] = 0.0
        if isinstance(b, PETSc.Vec):
            with b.localForm() as loc:
                self._check_size(loc.array, "b (local form, ghosts included)")
                loc.array[:] += r
        else:
            arr = self._check_size(b, "b")
            arr += r
        return bool(self.V.mesh.comm.allreduce(finite, op=MPI.MIN))

    def add_jacobian(self, u, A: PETSc.Mat, scale: float = 1.0) -> None:
        """Add `scale` × the joint tangent at u into A (MatSetValuesLocal, ADD_VALUES, no flush),
        before dolfinx.fem.petsc.assemble_matrix(A, a, bcs) (docs/fem.md, pitfall 5); rows and
        columns of supported dofs are left out. A must come from create_matrix."""
        if not isinstance(A, PETSc.Mat):
            raise TypeError(f"A must be a PETSc Mat (from JointCoupling.create_matrix), got {type(A).__name__}")
        n = self._imap.size_global * self._bs
        if A.getSize() != (n, n):
            raise ValueError(f"A is {A.getSize()}, expected ({n}, {n}) for the dofs of V")
        self.interface.add_jacobian(A, self._local(u, "u"), self.supported, float(scale))

    # ---- step control --------------------------------------------------------------------
    def admissible_step(self, u, du, fraction: float = 0.95) -> float:
        """Largest α in (0, 1] such that no joint closure along u + α du moves past `fraction` of
        its remaining room to the law's maximum closure (fraction to the boundary; 1 for laws
        without one). Collective: the same α on every rank (docs/fem.md, pitfall 7)."""
        if not (0.0 < fraction < 1.0):
            raise ValueError(f"fraction = {fraction} must be in (0, 1)")
        u_local = np.array(self._local(u, "u"))  # a copy: _local(du) may reuse the work vector
        return self.interface.admissible_step(u_local, self._local(du, "du"), fraction)

    # ---- joint state ---------------------------------------------------------------------
    @property
    def num_points(self) -> int:
        """Joint quadrature points on this rank (pair-major)."""
        return self.interface.num_points

    def point_frames(self) -> np.ndarray:
        """(num_points, gdim, gdim) local frame of every point, rows n, t1[, t2] (global components)."""
        return self.interface.point_frames()

    def set_initial_jump(self, initial_jump) -> None:
        """Initial local jump j0 (num_points, gdim) [m], components (normal, t1[, t2]): the law sees
        j0 + Q [[u]]; a joint pre-closed to Δ0 has j0[:, 0] = -Δ0 (in-situ state)."""
        self.interface.set_initial_jump(initial_jump)

    def commit_state(self) -> None:
        """Accept the joints' trial state (slip history) after a converged solve or load step."""
        self.interface.commit_state()

    def revert_state(self) -> None:
        """Discard the joints' trial state after a failed solve."""
        self.interface.revert_state()

    def reset_state(self) -> None:
        """Virgin point state everywhere (no slip, no dilation, bonds intact): a new analysis."""
        self.interface.reset_state()

    def state(self, u) -> dict:
        """Joint point state at u on this rank: coordinates, tag, closure [m], normal_stress [Pa,
        compression +], shear_traction [Pa], status, normal (see JointInterface.state)."""
        self.interface.update_state(self._local(u, "u"))
        return self.interface.state()

    # ---- helpers -------------------------------------------------------------------------
    def _check_size(self, arr, what: str) -> np.ndarray:
        arr = np.asarray(arr) if not isinstance(arr, np.ndarray) else arr
        if arr.ndim != 1 or arr.size != self.num_local_dofs or arr.dtype != np.float64:
            raise ValueError(f"{what}: expected a float64 array of the {self.num_local_dofs} local dofs of V "
                             f"(ghosts included), got shape {arr.shape} and dtype {arr.dtype}")
        return arr

    def _local(self, v, what: str) -> np.ndarray:
        """Local values (ghosts included) of a Function of V, a PETSc Vec of V or a local array."""
        if isinstance(v, fem.Function):
            if v.function_space.component() or not _same_space(v.function_space, self.V):
                raise ValueError(f"{what} must be a Function of the coupling's space V")
            return v.x.array
        if isinstance(v, PETSc.Vec):
            n_owned = self._imap.size_local * self._bs
            if v.getLocalSize() != n_owned:
                raise ValueError(f"{what}: a PETSc Vec with {v.getLocalSize()} owned entries on this rank; "
                                 f"V has {n_owned}")
            v.copy(self._work)  # owned entries; ghosts refreshed from their owners
            self._work.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
            with self._work.localForm() as loc:
                return loc.array.copy()
        return self._check_size(v, what)


class JointedNonlinearProblem(JointedSNESProblem):
    """The user's nonlinear problem F(u; v) = 0 plus the joints, solved by PETSc SNES: DOLFINx
    0.11's ``dolfinx.fem.petsc.NonlinearProblem`` (same constructor and attributes) with the
    joint-aware Jacobian matrix, joint forces in the residual, a non-finite joint traction
    reported to SNES as a function-domain error, and the closure limiter as a line-search
    pre-check (snes_problem.JointedSNESProblem). The same on DOLFINx 0.9.

        problem = JointedNonlinearProblem(F, u, coupling, bcs=bcs, petsc_options_prefix="slope_",
                                          petsc_options={"snes_rtol": 1e-10, "ksp_type": "preonly",
                                                         "pc_type": "lu"})
        problem.solve()                               # u updated in place
        assert problem.solver.getConvergedReason() > 0

    F: the UFL residual (internal minus external virtual work); u: the displacement Function on
    the coupling's V; coupling: the JointCoupling of the joints; bcs: Dirichlet conditions (also
    given to the coupling); J: the Jacobian form (default: the derivative of F in u);
    petsc_options_prefix: the SNES's options prefix (required, as in DOLFINx 0.11: options on
    the command line reach it); petsc_options: {option: value} without the leading dash, set on
    the SNES (and its KSP/PC) under that prefix; closure_fraction: the limiter's fraction of a
    closure's remaining room to the law's maximum closure. For a linear-elastic bulk F is linear
    in u and only the joints make the problem nonlinear.
    """

    def __init__(self, F: ufl.Form, u: fem.Function, coupling: JointCoupling, *,
                 petsc_options_prefix: str, bcs: Sequence[fem.DirichletBC] | None = None,
                 J: ufl.Form | None = None, petsc_options: Mapping[str, object] | None = None,
                 closure_fraction: float = 0.95, form_compiler_options: dict | None = None,
                 jit_options: dict | None = None):
        if not isinstance(coupling, JointCoupling):
            raise TypeError(f"coupling must be a JointCoupling, got {type(coupling).__name__}")
        if not isinstance(u, fem.Function) or u.function_space.component() \
                or not _same_space(u.function_space, coupling.V):
            raise ValueError("u must be a Function of the coupling's displacement space V")
        if not (0.0 < closure_fraction < 1.0):
            raise ValueError(f"closure_fraction = {closure_fraction} must be in (0, 1)")
        if not isinstance(petsc_options_prefix, str) or not petsc_options_prefix:
            raise ValueError("petsc_options_prefix must be a non-empty string (as for DOLFINx's "
                             "NonlinearProblem), e.g. 'jointed_'")
        self.u, self.coupling, self.bcs = u, coupling, list(bcs or [])
        self.closure_fraction = closure_fraction
        coupling.set_supports(self.bcs)
        params = dict(form_compiler_options=form_compiler_options or {}, jit_options=jit_options or {})
        self._L = fem.form(F, **params)
        if J is None:
            J = ufl.derivative(F, u, ufl.TrialFunction(u.function_space))
        self._a = fem.form(J, **params)
        self._A = None
        #: True if the last residual had a non-finite joint traction
        self.nonfinite = False
        self._snes = self.snes_solver(petsc_options=petsc_options, options_prefix=petsc_options_prefix)
        self._x = self.vector()

    @property
    def F(self) -> fem.Form:
        """The compiled residual form."""
        return self._L

    @property
    def J(self) -> fem.Form:
        """The compiled Jacobian form."""
        return self._a

    @property
    def A(self) -> PETSc.Mat:
        """The Jacobian matrix (joint-aware sparsity)."""
        return self.matrix()

    @property
    def b(self) -> PETSc.Vec:
        """The residual vector SNES evaluates into."""
        return self._snes.getFunction()[0]

    @property
    def x(self) -> PETSc.Vec:
        """The solution vector SNES iterates on (does not share memory with u)."""
        return self._x

    @property
    def solver(self) -> PETSc.SNES:
        """The SNES."""
        return self._snes

    def solve(self) -> fem.Function:
        """Solve from the current u; u holds the last iterate afterwards (converged or not: check
        ``solver.getConvergedReason() > 0``, or set ``snes_error_if_not_converged``)."""
        self.u.x.petsc_vec.copy(self._x)
        self._snes.solve(None, self._x)
        self._copy_into_u(self._x)
        return self.u

    def matrix(self) -> PETSc.Mat:
        """The Jacobian matrix with the cross-joint couplings (created once, then reused)."""
        if self._A is None:
            self._A = self.coupling.create_matrix(self._a)
        return self._A

    def vector(self) -> PETSc.Vec:
        """A residual vector (ghosted, layout of V)."""
        return create_vector(self.u.function_space)

    def load_norm(self) -> float:
        """‖F(0)‖, the residual norm at u = 0 (the load, supports applied; u is left unchanged).
        An absolute tolerance from it ({"snes_atol": 1e-10 * load_norm()}) measures the residual
        against the load, whatever the starting u."""
        saved = self.u.x.array.copy()
        self.u.x.array[:] = 0.0
        b = self.vector()
        try:
            self.residual(self.u.x.petsc_vec, b)
            return b.norm()
        finally:
            self.u.x.array[:] = saved
            b.destroy()

    # ---- assembly (JointedSNESProblem) ----------------------------------------------------
    def assemble_residual(self, b: PETSc.Vec) -> bool:
        """Bulk form, joints (before lifting and the reverse ghost update), Dirichlet rows."""
        x = self.u.x.petsc_vec
        with b.localForm() as loc:
            loc.set(0.0)
        fem_petsc.assemble_vector(b, self._L)
        finite = self.coupling.add_residual(self.u, b)
        fem_petsc.apply_lifting(b, [self._a], bcs=[self.bcs], x0=[x], alpha=-1.0)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        fem_petsc.set_bc(b, self.bcs, x, -1.0)
        if not finite and self.u.function_space.mesh.comm.rank == 0:
            log.info("joint traction not finite: a closure reached a law's maximum closure; the "
                     "step is cut (SNES function-domain error)")
        return finite

    def assemble_jacobian(self, A: PETSc.Mat) -> None:
        """Joint blocks first, then the bulk form and the Dirichlet rows."""
        A.zeroEntries()
        self.coupling.add_jacobian(self.u, A)
        fem_petsc.assemble_matrix(A, self._a, self.bcs)
        A.assemble()
