# SPDX-License-Identifier: MIT
"""Joints as a building block of the user's own DOLFINx model (docs/user-model.md).

The user keeps their mesh, function space, UFL forms, boundary conditions and solver; rockjoint
adds the joints::

    coupling = JointCoupling(V, dmesh, {"fault": table}, shear_stiffness=1e9, bcs=bcs)
    A = coupling.create_matrix(a)                 # the form's sparsity + cross-joint couplings
    # residual:  assemble_vector(b, L); coupling.add_residual(u, b); apply_lifting(...);
    #            b.ghostUpdate(ADD, REVERSE); set_bc(...)
    # Jacobian:  A.zeroEntries(); coupling.add_jacobian(u, A); assemble_matrix(A, a, bcs); A.assemble()
    alpha = coupling.admissible_step(u, du)       # closure limiter along u + alpha du
    coupling.commit_state()                       # after a converged solve: accept the state, and
                                                  # warn (or raise) if a law was driven past its range
    coupling.summary(u)                           # {joint: JointSummary} over all ranks

or, with a UFL residual F(u; v), nonlinear_problem.JointedNonlinearProblem (solved by SNES, with
the keywords and attributes of DOLFINx 0.11's ``dolfinx.fem.petsc.NonlinearProblem``).

What this module takes care of (docs/fem.md, pitfalls 3-7): dofs of each pair from ``V.dofmap``
(P1/P2, any dof numbering: never node·gdim + c); the cross-joint couplings in the matrix's
sparsity, reserved with explicit zeros so a final assembly does not drop them; joint residuals
added to the local ghosted vector before the reverse ghost update; joint Jacobian blocks added
before DOLFINx's matrix assembly (which flushes and inserts the Dirichlet diagonal), with the
rows and columns of supported dofs left out; the step shortened so no closure passes a fraction
of its remaining room to a law's maximum closure.
"""
from __future__ import annotations

from typing import Iterable, Mapping, Sequence

import numpy as np
from dolfinx import cpp as _dcpp
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc

from ...joint import joint_behaviours, symmetric_tangent
from ..compat import la_petsc
from ..mesh.distributed_mesh import DistributedJointMesh, JointPairs, names_of
from .interface import JointInterface
from .law_range import check_beyond_range, check_range, summarize

__all__ = ["JointCoupling", "joint_behaviours", "supported_dofs"]


def supported_dofs(V: fem.FunctionSpace, bcs: Iterable[fem.DirichletBC]) -> np.ndarray:
    """Mask (int8, 1 = supported) over the local unrolled dofs of V, ghosts included, of every dof
    a DirichletBC in `bcs` prescribes (whole-space or component bcs, V.sub(i))."""
    imap, bs = V.dofmap.index_map, V.dofmap.index_map_bs
    n = (imap.size_local + imap.num_ghosts) * bs
    mask = np.zeros(n, dtype=np.int8)
    for i, bc in enumerate(bcs):
        if not isinstance(bc, fem.DirichletBC):
            raise TypeError(f"bcs[{i}] must be a dolfinx.fem.DirichletBC, got {type(bc).__name__}")
        if not same_space(bc.function_space, V):
            raise ValueError(f"bcs[{i}] constrains a function space that is not the displacement space "
                             "V (or one of its components V.sub(i))")
        idx, _ = bc.dof_indices()
        idx = np.asarray(idx)
        if idx.size and (idx.min() < 0 or idx.max() >= n):
            raise ValueError(f"bcs[{i}]: dof indices in [{idx.min()}, {idx.max()}] lie outside the "
                             f"{n} local dofs of V")
        mask[idx] = 1
    return mask


def same_space(W, V) -> bool:
    """W (Python or C++ function space) is V or a component V.sub(i) of it."""
    return V._cpp_object.contains(getattr(W, "_cpp_object", W))


class JointCoupling:
    """The joints of a mesh bound to the user's displacement space V.

    :V: vector Lagrange space of degree 1 or 2 on the split mesh (block size = gdim).
    :joints: the DistributedJointMesh (pairs and joint names from it), or its JointPairs with
        `joint_tags` = {joint name: tag}.
    :laws: {joint name: law} for every joint (see rockjoint.joint.joint_behaviours); shear_stiffness,
        shear_stiffness_ratio, residual_stiffness, strength: as in joint_behaviours.
    :quadrature: "nodal" (default; smooth tractions for stiff joints) or "gauss" (P1 only).
    :bcs: the Dirichlet conditions of the problem; their dofs' rows and columns are left out of the
        joint Jacobian and rows out of the joint residual (see set_supports).
    :beyond_range: "warn" (default) or "raise": what check_range does when a joint law answered
        past its range (a table beyond its last knot): a RangeWarning on rank 0, or
        BeyondRangeError on every rank (law_range.py).
    :Arrays: "local" means this rank's unrolled dofs of V, ghosts included (u.x.array layout).
    """

    def __init__(self, V: fem.FunctionSpace, joints: DistributedJointMesh | JointPairs,
                 laws: Mapping[str, object], *, joint_tags: Mapping[str, int] | None = None,
                 shear_stiffness=0.0, shear_stiffness_ratio=None, residual_stiffness=0.0,
                 strength=None, quadrature: str = "nodal", bcs: Sequence[fem.DirichletBC] = (),
                 beyond_range: str = "warn"):
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
        #: the DistributedJointMesh (block names in failure messages), None for bare JointPairs
        self.dmesh = joints if isinstance(joints, DistributedJointMesh) else None
        self.behaviours = joint_behaviours(names, laws, shear_stiffness=shear_stiffness,
                                           shear_stiffness_ratio=shear_stiffness_ratio,
                                           residual_stiffness=residual_stiffness, strength=strength)
        self.interface = JointInterface(V, pairs, self.behaviours, quadrature)
        self.beyond_range = check_beyond_range(beyond_range)
        self._evaluated = self._checked = 0  # point-state evaluations: all, and at the last check
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
        if a.rank != 2 or any(W.component() or not same_space(W, self.V) for W in a.function_spaces):
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
        self._evaluated += 1
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

    def commit_state(self, check_range: bool = True) -> None:
        """Accept the joints' trial state (slip history) after a converged solve or load step.
        check_range: first check_range() on the state of the last residual (unless checked since);
        collective then. JointedRockModel passes False and checks once per stage."""
        if check_range and self._checked != self._evaluated:
            self.check_range()
        self.interface.commit_state()

    def revert_state(self) -> None:
        """Discard the joints' trial state after a failed solve."""
        self.interface.revert_state()

    def reset_state(self) -> None:
        """Virgin point state everywhere (no slip, no dilation, bonds intact): a new analysis."""
        self.interface.reset_state()

    def state(self, u=None) -> dict:
        """Joint point state at u on this rank: coordinates, tag, closure [m], normal_stress [Pa,
        compression +], shear_traction [Pa], status (rockjoint.Status codes), normal (see
        JointInterface.state). u None: the state of the last residual evaluated."""
        if u is not None:
            self.interface.update_state(self._local(u, "u"))
            self._evaluated += 1
        return self.interface.state()

    def summary(self, u=None) -> dict:
        """{joint name: law_range.JointSummary} at u (None: the last residual's state) over all
        ranks, the same on every rank: points, min/max closure [m] and normal stress [Pa], the
        largest shear traction magnitude [Pa], points per status. Collective."""
        return summarize(self.V.mesh.comm, self.state(u), self.joint_tags)

    def check_range(self, u=None, where: str = "") -> list:
        """After a solve: the joints whose law answered past its range at u (None: the last
        residual's state) are reported as `beyond_range` says (a RangeWarning on rank 0, or
        BeyondRangeError on every rank); returns the messages (empty: all inside). Collective."""
        summaries = self.summary(u)
        self._checked = self._evaluated
        laws = {name: self.behaviours[tag] for name, tag in self.joint_tags.items()}
        return check_range(self.V.mesh.comm, summaries, laws, self.beyond_range, where)

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
            if v.function_space.component() or not same_space(v.function_space, self.V):
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
