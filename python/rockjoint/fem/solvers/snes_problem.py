# SPDX-License-Identifier: MIT
"""The one adapter between a jointed nonlinear problem and PETSc SNES.

Both routes by which joints enter a DOLFINx model use it: the user's UFL problem
(`coupling.JointedNonlinearProblem`, shaped as DOLFINx 0.11's SNES-based
``dolfinx.fem.petsc.NonlinearProblem``) and `JointedRockModel` (`stages.JointedProblem`). A
subclass says how to assemble; this class owns everything SNES needs around that:

- ``residual(x, b)`` and ``jacobian(x, A)`` evaluated at x: SNES hands trial vectors that are not
  ``u.x.petsc_vec``, so x is copied into u first (docs/fem.md, pitfalls);
- a non-finite joint traction (a closure at or past a law's maximum closure) makes b infinite
  and is reported to SNES as a function-domain error (SNESSetFunctionDomainError), so the line
  search or the load stepping cuts the step instead of continuing from garbage; the project's
  own Newton sees the same infinite residual norm and cuts the step alike;
- the closure limiter as a line-search pre-check: the step never moves a closure past a fraction
  of its remaining room to the law's maximum closure (docs/fem.md, pitfall 7).
"""
from __future__ import annotations

import logging
from typing import Mapping

import numpy as np
from petsc4py import PETSc

from ... import _rockjoint_fem_coupling
from .petsc_options import check_options_prefix, check_petsc_options

log = logging.getLogger(__name__)

_SNES_COUNT = [0]  # default SNES options prefixes, numbered per process (the same on every rank)


class JointedSNESProblem:
    """Base of the jointed nonlinear problems. Subclasses set ``self.u`` (the displacement
    Function), ``self.coupling`` (a JointCoupling), ``self.closure_fraction`` (in (0, 1), or None
    for no limiter) and implement:

    - ``assemble_residual(b) -> bool``: the residual at the current u into b (ghost-complete
      owned entries, supported rows set); False if a joint traction is not finite;
    - ``assemble_jacobian(A)``: the Jacobian at the current u into A;
    - ``matrix()`` and ``vector()``: a Jacobian matrix (joint-aware sparsity) and a residual vector.
    """

    u = None
    coupling = None
    closure_fraction: float | None = 0.95
    #: True if the last residual had a non-finite joint traction
    nonfinite: bool = False
    #: number of residuals evaluated with a non-finite joint traction (reported to SNES as
    #: function-domain errors)
    domain_errors: int = 0

    # ---- evaluation at a vector x -------------------------------------------------------
    def update_solution(self, x: PETSc.Vec) -> None:
        """x into u, ghosts refreshed (e.g. SNES's converged x before a state is committed)."""
        self._copy_into_u(x)

    def residual(self, x: PETSc.Vec, b: PETSc.Vec) -> None:
        """Residual at x. A non-finite joint traction makes b infinite (Newton then cuts the step
        instead of continuing from garbage)."""
        self._copy_into_u(x)
        finite = self.assemble_residual(b)
        self.nonfinite = not finite
        if not finite:
            self.domain_errors += 1
            b.set(np.inf)

    def jacobian(self, x: PETSc.Vec, A: PETSc.Mat) -> None:
        """Jacobian at x."""
        self._copy_into_u(x)
        self.assemble_jacobian(A)

    # ---- SNES callbacks ------------------------------------------------------------------
    def snes_F(self, snes, x: PETSc.Vec, b: PETSc.Vec) -> None:
        """SNES residual callback: F(x) into b; a non-finite residual is a domain error to SNES."""
        self.residual(x, b)
        if self.nonfinite:
            _rockjoint_fem_coupling.snes_set_function_domain_error(snes.handle)

    def snes_J(self, snes, x: PETSc.Vec, A: PETSc.Mat, P: PETSc.Mat) -> None:
        """SNES Jacobian callback: A (and P if different) at x."""
        self.jacobian(x, A)
        if P.handle != A.handle:
            self.assemble_jacobian(P)

    def snes_precheck(self, x: PETSc.Vec, y: PETSc.Vec) -> None:
        """SNES steps x ← x - λ y: shorten y so that -y respects the closure limiter."""
        if self.closure_fraction is None:
            return
        minus_y = y.copy()
        minus_y.scale(-1.0)
        alpha = self.coupling.admissible_step(x, minus_y, self.closure_fraction)
        minus_y.destroy()
        if alpha < 1.0:
            y.scale(alpha)

    def _copy_into_u(self, x: PETSc.Vec) -> None:
        u_vec = self.u.x.petsc_vec
        if x.handle != u_vec.handle:
            x.copy(u_vec)
        self.u.x.scatter_forward()

    # ---- solvers -------------------------------------------------------------------------
    def snes_solver(self, comm=None, petsc_options: Mapping[str, object] | None = None,
                    options_prefix: str | None = None, ksp: PETSc.KSP | None = None) -> PETSc.SNES:
        """A PETSc SNES on this problem: residual (non-finite → domain error), joint-aware
        Jacobian, and the closure limiter as a line-search pre-check. petsc_options: {option:
        value} without the leading dash, set under `options_prefix` (default: a prefix of its own,
        "rockjoint_snes_<n>_", so options never leak between problems; pass one to reach it from
        the command line) and read by setFromOptions, e.g. {"snes_rtol": 1e-10, "ksp_type":
        "preonly", "pc_type": "lu"}. ksp: a linear solver to use (its options prefix is kept).
        Solve with snes.solve(None, x), x = u.x.petsc_vec.copy(); then x.copy(u.x.petsc_vec) and
        u.x.scatter_forward()."""
        comm = comm or self.u.function_space.mesh.comm
        options_prefix = check_options_prefix(options_prefix)
        petsc_options = check_petsc_options(petsc_options)
        if options_prefix is None:
            _SNES_COUNT[0] += 1
            options_prefix = f"rockjoint_snes_{_SNES_COUNT[0]}_"
        snes = PETSc.SNES().create(comm)
        snes.setOptionsPrefix(options_prefix)
        opts = PETSc.Options()
        for key, value in petsc_options.items():
            opts[options_prefix + key] = value
        snes.setFunction(self.snes_F, self.vector())
        A = self.matrix()
        snes.setJacobian(self.snes_J, A, A)
        if ksp is not None:
            snes.setKSP(ksp)
        snes.setLineSearchPreCheck(self.snes_precheck)
        snes.setFromOptions()
        return snes
