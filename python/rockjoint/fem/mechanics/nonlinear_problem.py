# SPDX-License-Identifier: MIT
"""JointedNonlinearProblem: the user's UFL residual plus the joints, solved by PETSc SNES.

Not a subclass of DOLFINx 0.11's ``dolfinx.fem.petsc.NonlinearProblem``, by design: that class's
constructor builds the Jacobian matrix from the form's sparsity, without the cross-joint
couplings (docs/fem.md, pitfall 4), and binds SNES to DOLFINx's own residual and Jacobian
callbacks; a subclass would build that matrix and the bindings only to replace them through
private attributes (``_A``), and on DOLFINx 0.9 the class of that name is another one (the
NewtonSolver's problem, with ``L``, ``a``, ``F(x, b)``, ``form``). So the class shares 0.11's
constructor keywords and attributes instead (``F``, ``J``, ``A``, ``b``, ``x``, ``u``, ``solver``,
``solve()``) on both versions, and adds the joints (``coupling``), the closure limiter
(``closure_fraction``) and the range check after every solve. docs/user-model.md lists where it
differs. DOLFINx's deprecated ``dolfinx.nls.petsc.NewtonSolver`` cannot drive it (it builds its
own matrix from ``problem.a``, without the joint couplings): asking for ``a`` or ``L`` raises
NewtonSolverError saying so.
"""
from __future__ import annotations

import logging
from typing import Mapping, Sequence

import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from ..compat import create_vector
from .coupling import JointCoupling, same_space
from ..solvers.snes_problem import JointedSNESProblem

log = logging.getLogger(__name__)


class NewtonSolverError(TypeError, AttributeError):
    """A JointedNonlinearProblem handed to dolfinx.nls.petsc.NewtonSolver (a TypeError; an
    AttributeError too, so that hasattr(problem, "a") stays False)."""


def _no_newton_solver(self):
    raise NewtonSolverError(
        "JointedNonlinearProblem is solved by PETSc SNES: call problem.solve() (or drive "
        "problem.solver, the SNES); dolfinx.nls.petsc.NewtonSolver cannot drive it, as it builds "
        "its own Jacobian matrix from problem.a without the cross-joint couplings and has no "
        "closure limiter (docs/user-model.md)")


class JointedNonlinearProblem(JointedSNESProblem):
    """The user's nonlinear problem F(u; v) = 0 plus the joints, solved by PETSc SNES, with the
    constructor keywords and attributes of DOLFINx 0.11's ``dolfinx.fem.petsc.NonlinearProblem``;
    the joint-aware Jacobian matrix, joint forces in the residual, a non-finite joint traction
    reported to SNES as a function-domain error, and the closure limiter as a line-search
    pre-check (snes_problem.JointedSNESProblem), and the range check after every solve. The same
    on DOLFINx 0.9. Not a subclass of DOLFINx's class (the module docstring says why). For
    example::

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

    Attributes besides 0.11's: ``coupling`` (the JointCoupling: ``coupling.state(u)``,
    ``coupling.summary(u)``, ``commit_state()``), ``bcs``, ``closure_fraction``, ``nonfinite``,
    ``domain_errors``; methods ``residual(x, b)``, ``jacobian(x, A)``, ``matrix()``, ``vector()``,
    ``load_norm()`` for a solver of one's own.
    """

    # dolfinx.nls.petsc.NewtonSolver asks for these first: a clear error instead of a bare
    # AttributeError from deep inside DOLFINx.
    a = property(_no_newton_solver, doc="not available: NewtonSolver cannot drive this problem")
    L = property(_no_newton_solver, doc="not available: NewtonSolver cannot drive this problem")

    def __init__(self, F: ufl.Form, u: fem.Function, coupling: JointCoupling, *,
                 petsc_options_prefix: str, bcs: Sequence[fem.DirichletBC] | None = None,
                 J: ufl.Form | None = None, petsc_options: Mapping[str, object] | None = None,
                 closure_fraction: float = 0.95, form_compiler_options: dict | None = None,
                 jit_options: dict | None = None):
        if not isinstance(coupling, JointCoupling):
            raise TypeError(f"coupling must be a JointCoupling, got {type(coupling).__name__}")
        if not isinstance(u, fem.Function) or u.function_space.component() \
                or not same_space(u.function_space, coupling.V):
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
        ``solver.getConvergedReason() > 0``, or set ``snes_error_if_not_converged``). Then the
        joints' range is checked at u (coupling.check_range: a RangeWarning on rank 0, or
        BeyondRangeError on every rank with the coupling's beyond_range="raise")."""
        self.u.x.petsc_vec.copy(self._x)
        self._snes.solve(None, self._x)
        self._copy_into_u(self._x)
        self.coupling.check_range(self.u, "after JointedNonlinearProblem.solve()")
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
