# SPDX-License-Identifier: MIT
"""Linear solves of the Newton steps, with failures detected instead of accepted.

"direct": MUMPS Cholesky (symmetric Jacobian) or LU with null-pivot detection (ICNTL(24) = 1)
— for small problems (and 2D problems with a non-symmetric Jacobian up to 60k dofs).
"lagged": the same factorisation, kept as the preconditioner of CG / FGMRES over several Newton
iterations (rebuilt as GAMG is, below): fewer factorisations, each iteration a few triangular
solves — for 2D problems with a non-symmetric Jacobian from 60k to 250k dofs (LAGGED_DOF_RANGE).
"iterative": CG + GAMG with a rigid-body near-nullspace (per block through the aggregates,
see rigid_body_modes) — for large ones (SPD
Jacobians: constant shear stiffness). "auto" picks direct up to DIRECT_DOF_LIMIT[gdim] dofs.
The iterative solver lags its preconditioner: GAMG is built for the first Jacobian and reused for
the following ones (only the joint blocks change, so the old hierarchy stays a good
preconditioner), and rebuilt when a solve needs more than `rebuild_factor` times the Krylov
iterations per decade of residual reduction of the solve that built it, or when a solve with the
lagged preconditioner fails. solve(..., rtol=η) sets the relative tolerance of one solve (the
forcing term of an inexact Newton method); it is never tighter than the solver's own rtol.
A solve is rejected (LinearSolveError) if PETSc reports divergence, MUMPS reports an error or a
null pivot (a singular matrix: e.g. a block held only by an open joint), or the true residual
||J dx - b|| exceeds `check_tolerance` ||b|| (a loose solve: 10 times its own tolerance). docs/fem.md, pitfall 9: MUMPS silently returned |u| ≈ 1e11 on
a singular system; the residual check catches that class of garbage whatever the cause.
"""
from __future__ import annotations

import numpy as np
from petsc4py import PETSc

from ..compat import la_petsc


class LinearSolveError(RuntimeError):
    """A linear solve failed (singular or ill-posed system, Krylov divergence)."""


def rigid_body_modes(V):
    """Near-nullspace for GAMG: the 3 (2D) or 6 (3D) rigid-body modes evaluated at every node,
    orthonormalized. GAMG builds its tentative prolongator aggregate by aggregate from the
    restriction of these vectors, and split joint nodes are separate dofs, so every aggregate of a
    block gets that block's own rigid-body modes: this is the per-block rigid-body near-nullspace
    (one set of vectors per block instead would multiply the coarse dofs per aggregate by the
    number of blocks and raise the operator complexity for nothing: measured 3.4 vs 1.3)."""
    gdim = V.mesh.geometry.dim
    imap = V.dofmap.index_map
    bs = V.dofmap.index_map_bs
    n_local = imap.size_local
    x = V.tabulate_dof_coordinates()[:n_local, :gdim]
    vectors = []
    for k in range(3 if gdim == 2 else 6):
        v = la_petsc.create_vector([(imap, bs)])
        with v.localForm() as loc:
            a = loc.array.reshape(-1, bs)
            a[:] = 0.0
            if k < gdim:
                a[:n_local, k] = 1.0
            elif gdim == 2:
                a[:n_local, 0], a[:n_local, 1] = -x[:, 1], x[:, 0]
            else:
                i, j = [(0, 1), (1, 2), (0, 2)][k - 3]
                a[:n_local, i], a[:n_local, j] = -x[:, j], x[:, i]
        vectors.append(v)
    # Modified Gram-Schmidt with global dot products.
    basis = []
    for v in vectors:
        for b in basis:
            v.axpy(-v.dot(b), b)
        v.scale(1.0 / v.norm())
        basis.append(v)
    return PETSc.NullSpace().create(vectors=basis, comm=V.mesh.comm)


#: "auto" uses MUMPS up to this many dofs and CG/GMRES + GAMG above, per geometric dimension.
#: Measured with Debian's reference BLAS (bench/bench_direct_vs_iterative.py, results in
#: bench/results/direct_vs_iterative.md): in 3D GAMG is 9x faster than a MUMPS Cholesky at
#: 6.5k dofs and 17x at 14k-30k (the 3D factorisation grows much faster than N); in 2D the two
#: stay within 1.3x up to 93k dofs, so the direct solver (robust, exact null-pivot detection) is
#: kept there. Below 5k dofs in 3D both take well under 0.1 s.
DIRECT_DOF_LIMIT = {2: 60_000, 3: 5_000}
#: The same for a non-symmetric Jacobian (slipping joints, smeared sets): GMRES + GAMG does much
#: worse on it than CG + GAMG on an SPD one. Measured on the continuum bench's discrete tunnel
#: (90k dofs, 2D, bench/results/tunnel_profile.md): MUMPS LU 0.22 s CPU per solve (18 Newton
#: iterations), GMRES + GAMG 1.04 s (35 Krylov iterations per solve, 31 Newton iterations). A 2D
#: factorisation grows like N^1.5, GAMG like N: the 4.7x would last to ~2M dofs; 250k keeps the
#: factors to a few hundred MB (13.8M entries at 90k dofs).
DIRECT_DOF_LIMIT_NONSYMMETRIC = {2: 250_000, 3: 5_000}
#: "auto" keeps a non-symmetric 2D Jacobian's LU over several Newton iterations ("lagged") from
#: DIRECT_DOF_LIMIT[2] dofs up to DIRECT_DOF_LIMIT_NONSYMMETRIC[2] (range (lo, hi]), direct below.
#: Measured on the continuum bench's discrete tunnel (90k dofs; bench/bench_tunnel_profile.py →
#: bench/results/tunnel_profile.md, "Linear solver of the discrete tunnel"): 8 factorisations and
#: 38 triangular solves instead of 18 factorisations (0.25 s each against 0.03 s for a triangular
#: solve: the split mesh's LU has 13.5M entries), the same crown and sidewall. Below 60k dofs the
#: direct solver's exact Newton steps are kept: lagged is faster there too, by less than 0.3 s an
#: analysis (the same tunnel at s = 1 and 0.5 m, 11k and 26k dofs), but its inexact steps lose
#: knife-edge slipping cases that the exact ones get through (test_fem_joint_slip's direct shear
#: at σ_n = 1 MPa, c = 0, and at times the tunnel demo's --quick slip model: a singular Jacobian
#: on the way).
LAGGED_DOF_RANGE = {2: (DIRECT_DOF_LIMIT[2], DIRECT_DOF_LIMIT_NONSYMMETRIC[2])}
#: Krylov iterations allowed with a lagged factorisation before it is given up and rebuilt
LAGGED_MAX_ITERATIONS = 50
#: rebuild_factor of the lagged kind: a factorisation is rebuilt once a solve with it needs 1.5
#: Krylov iterations per decade of residual reduction (an exact one needs 1 in all). On the
#: discrete tunnel (bench/results/tunnel_profile.md) 1.5 gives the direct solver's crown and
#: sidewall with 8 factorisations; GAMG's 2.0 gives 6, 0.1 s less, and lands 0.1 % off at the
#: sidewall (another state within Newton's tolerance, reached by a longer inexact path).
LAGGED_REBUILD_FACTOR = 1.5


def resolve_kind(kind: str, num_dofs: int, gdim: int, symmetric: bool = True) -> str:
    """"direct", "lagged" or "iterative" for a requested kind ("direct", "lagged", "iterative" or
    "auto"; "auto" by the Jacobian's symmetry, DIRECT_DOF_LIMIT(_NONSYMMETRIC) and
    LAGGED_DOF_RANGE)."""
    if kind not in ("direct", "lagged", "iterative", "auto"):
        raise ValueError(f"linear solver must be 'direct', 'lagged', 'iterative' or 'auto', got {kind!r}")
    if kind != "auto":
        return kind
    if gdim not in DIRECT_DOF_LIMIT:
        raise ValueError(f"linear solver: gdim must be 2 or 3, got {gdim!r}")
    limit = (DIRECT_DOF_LIMIT if symmetric else DIRECT_DOF_LIMIT_NONSYMMETRIC)[gdim]
    if num_dofs > limit:
        return "iterative"
    lagged = None if symmetric else LAGGED_DOF_RANGE.get(gdim)
    return "lagged" if lagged is not None and lagged[0] < num_dofs <= lagged[1] else "direct"


class LinearSolver:
    """KSP wrapper. kind: "direct" | "lagged" | "iterative" | "auto" (resolved with `resolve_kind`)."""

    def __init__(self, comm, kind: str = "auto", num_dofs: int = 0, gdim: int = 3,
                 near_nullspace=None, rtol: float = 1e-10, check_tolerance: float = 1e-6,
                 symmetric: bool = True, options: dict | None = None, prefix: str | None = None,
                 reuse_preconditioner: bool = True, rebuild_factor: float | None = None):
        kind = resolve_kind(kind, num_dofs, gdim, symmetric)
        if rebuild_factor is None:  # GAMG's, or a factorisation's (LAGGED_REBUILD_FACTOR)
            rebuild_factor = LAGGED_REBUILD_FACTOR if kind == "lagged" else 2.0
        self.kind = kind
        self.symmetric = symmetric
        self.check_tolerance = check_tolerance
        self.near_nullspace = near_nullspace
        if not rebuild_factor >= 1.0:
            raise ValueError(f"rebuild_factor must be >= 1, got {rebuild_factor!r}")
        self.reuse_preconditioner = bool(reuse_preconditioner) and kind in ("iterative", "lagged")
        self.rebuild_factor = float(rebuild_factor)
        self._fresh_rate = None   # Krylov iterations per decade of the solve that built the PC
        #: number of preconditioner set-ups (GAMG hierarchies, factorisations)
        self.setups = 0
        self.ksp = PETSc.KSP().create(comm)
        self._prefix = prefix if prefix is not None else f"rockjoint_ls_{id(self)}_"
        self.ksp.setOptionsPrefix(self._prefix)
        # Our own settings go through the API where petsc4py has one; the others are put into
        # the global options database only while PETSc reads them (GAMG's threshold: this
        # setFromOptions; MUMPS's ICNTL(24): the solves, flag()/unflag()), then removed. Left
        # there, settings the solver never reads (MUMPS's on an iterative solver or one never
        # used, the level smoothers of a one-level GAMG) end every program with PETSc's
        # "options you set that were not used" warning (issue 30, item 7).
        self._flagged = None   # the option flag() put into the database, until unflag()
        internal = {}
        if kind in ("direct", "lagged"):
            if kind == "direct":
                self.ksp.setType("preonly")
            else:
                # The factorisation of an earlier Jacobian preconditions a Krylov method on the
                # current one (lagged as GAMG is, see the module docstring): one numeric
                # factorisation serves several Newton iterations, each then costing a few
                # triangular solves. Right preconditioning and the true residual's norm, as below.
                # Flexible GMRES, not GMRES: right-preconditioned GMRES builds its solution as
                # M⁻¹(V y), one more triangular solve per linear solve (2 for the 1 iteration of a
                # fresh factorisation); FGMRES keeps the preconditioned vectors and needs none
                # (the factorisation is a fixed operator, so both give the same iterates). On the
                # discrete tunnel 20 of its 61 triangular solves (bench/results/tunnel_profile.md).
                self.ksp.setType("cg" if symmetric else "fgmres")
                self.ksp.setTolerances(rtol=rtol, atol=1e-50, max_it=LAGGED_MAX_ITERATIONS)
                if not symmetric:
                    self.ksp.setPCSide(PETSc.PC.Side.RIGHT)
                self.ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
            pc = self.ksp.getPC()
            # A symmetric Jacobian (constant joint shear stiffness) is factorised by Cholesky
            # (LDLᵀ), about half the work and memory of LU.
            pc.setType("cholesky" if symmetric else "lu")
            pc.setFactorSolverType("mumps")
            # MUMPS null-pivot detection, ICNTL(24) = 1: put under the prefix by flag() for the
            # solve only.
        else:
            self.ksp.setType("cg" if symmetric else "gmres")
            pc = self.ksp.getPC()
            pc.setType("gamg")
            self.ksp.setTolerances(rtol=rtol, atol=1e-50, max_it=2000)
            if not symmetric:
                # Right preconditioning: GMRES then minimises the true residual, so the forcing
                # term of inexact Newton bounds ||J dx - b|| as it does with CG.
                self.ksp.setPCSide(PETSc.PC.Side.RIGHT)
            # Stop on the true residual ||b - A x||, not the preconditioned one: then one
            # solve meets Newton's residual tolerance (a linear, intact model: one iteration).
            self.ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
            pc.setGAMGType(PETSc.PC.GAMGType.AGG)
            # Plain (unsmoothed) aggregation: more CG iterations than smoothed aggregation but a
            # far cheaper set-up; measured on the 203k-dof benchmark block (CPU s, 1 rank): set-up
            # 1.1 + 58 iterations 3.3 = 4.3 s, against 8.8 + 20 iterations 1.8 = 10.6 s smoothed.
            pc.setGAMGSmooths(0)
            # Dropping weak graph edges: 16 CG iterations instead of 69 on the benchmark block
            # (48k dofs, 2 joints), 4x faster overall. (No petsc4py call for the threshold.)
            internal["pc_gamg_threshold"] = 0.01
            # The level smoothers are GAMG's defaults, Chebyshev/Jacobi (checked by
            # test_fem_linear_solver.py on both PETSc versions).
        options = dict(options or {})
        opts = PETSc.Options()
        for k, v in {**internal, **options}.items():   # the user's options win
            opts[f"{self._prefix}{k}"] = v
        self.ksp.setFromOptions()
        for k in internal.keys() - options.keys():
            opts.delValue(f"{self._prefix}{k}")
        self.rtol = self.ksp.getTolerances()[0]   # after the user's options (ksp_rtol)
        self.iterations = []

    def solve(self, A, b, x, rtol: float | None = None) -> int:
        """Solve A x = b to the relative residual max(rtol, the solver's rtol) (rtol=None: the
        solver's); raise LinearSolveError on any detected failure. Returns the Krylov iterations."""
        if rtol is not None and not (np.isfinite(rtol) and 0.0 < rtol < 1.0):
            raise ValueError(f"linear solve: rtol must be in (0, 1), got {rtol!r}")
        if self.kind != "direct":
            self.ksp.setTolerances(rtol=self.rtol if rtol is None else max(rtol, self.rtol))
        reuse = self.reuse_preconditioner and self._fresh_rate is not None
        try:
            return self._solve(A, b, x, reuse)
        except LinearSolveError:
            if not reuse:
                raise
            # The lagged preconditioner no longer suits the Jacobian: rebuild it and retry once.
            self._fresh_rate = None
            return self._solve(A, b, x, False)
        finally:
            # Others may drive this KSP (SNES): leave it at its own tolerance, rebuilding its PC.
            if self.kind != "direct":
                self.ksp.setTolerances(rtol=self.rtol)
            self.ksp.getPC().setReusePreconditioner(False)

    def flag(self, A) -> None:
        """Tell what a solve needs, whoever drives the KSP (this solver, or SNES in
        stages.snes_load_path): GAMG's near-nullspace and MUMPS Cholesky's symmetry on A, and
        MUMPS's null-pivot detection ICNTL(24) = 1 as an option under this solver's prefix unless
        the user gave one. MUMPS reads it when it factorises; petsc4py cannot set it on the factor
        matrix before then without losing the prefix (the user's -<prefix>mat_mumps_* would be
        ignored). unflag() removes it again."""
        if self.near_nullspace is not None and self.kind == "iterative":
            A.setNearNullSpace(self.near_nullspace)
        if self.kind != "iterative" and self.symmetric:
            A.setOption(PETSc.Mat.Option.SYMMETRIC, True)  # MUMPS Cholesky requires the flag
        pc = self.ksp.getPC()
        key = f"{self._prefix}mat_mumps_icntl_24"
        if (self._flagged is None and pc.getType() in ("lu", "cholesky")
                and pc.getFactorSolverType() == "mumps" and not PETSc.Options().hasName(key)):
            PETSc.Options()[key] = 1
            self._flagged = key

    def unflag(self) -> None:
        """Remove what flag() put into the options database (read, or not needed any more)."""
        if self._flagged is not None:
            PETSc.Options().delValue(self._flagged)
            self._flagged = None

    def _solve(self, A, b, x, reuse: bool) -> int:
        self.ksp.setOperators(A)
        self.ksp.getPC().setReusePreconditioner(reuse)
        if not reuse:
            self.setups += 1
        self.flag(A)
        try:
            self.ksp.solve(b, x)
        except PETSc.Error as e:
            raise LinearSolveError(f"linear solve failed in PETSc ({self.kind}): {e}") from e
        finally:
            self.unflag()
        reason = self.ksp.getConvergedReason()
        its = self.ksp.getIterationNumber()
        self.iterations.append(its)
        if reason < 0:
            raise LinearSolveError(f"linear solve diverged ({self.kind}, KSP reason {reason}); the "
                                   f"Jacobian may be singular (a block held only by an open joint?)")
        if self.kind != "iterative":
            F = self.ksp.getPC().getFactorMatrix()
            infog1, null_pivots = F.getMumpsInfog(1), F.getMumpsInfog(28)
            if infog1 < 0:
                raise LinearSolveError(f"MUMPS failed with INFOG(1) = {infog1}")
            if null_pivots > 0:
                raise LinearSolveError(
                    f"the Jacobian is singular: MUMPS found {null_pivots} null pivot(s). A rigid-body "
                    f"motion is free, e.g. a block held only by an open (zero-stiffness) joint or missing "
                    f"supports; add supports or a joint residual_stiffness")
        r = b.duplicate()
        A.mult(x, r)
        r.axpy(-1.0, b)
        bn, rn = b.norm(), r.norm()
        # A loose solve (inexact Newton) is held to 10 x its own tolerance, and must reduce ||b||.
        limit = self.check_tolerance
        rtol = self.ksp.getTolerances()[0]
        if self.kind != "direct" and 10.0 * rtol > limit:
            if self.ksp.getNormType() == PETSc.KSP.NormType.UNPRECONDITIONED:
                limit = min(10.0 * rtol, 0.99)
            else:
                # A loose solve on the preconditioned residual (e.g. the user's left-preconditioned
                # GMRES) says little about ||J dx - b||: only finiteness is checked; Newton's
                # true residual judges the step.
                limit = np.inf
        if not np.isfinite(rn) or rn > limit * max(bn, 1e-300):
            raise LinearSolveError(f"linear solve rejected ({self.kind}): ||J dx - b|| = {rn:.3e} > "
                                   f"{limit:g} ||b|| = {limit * bn:.3e}")
        r.destroy()
        if self.reuse_preconditioner:
            # Iterations per decade of reduction (at least one decade counted, so that loose
            # solves of an inexact Newton step do not look slow).
            rate = its / max(np.log10(bn / max(rn, 1e-300 * bn)) if bn > 0 else 1.0, 1.0)
            if not reuse:
                self._fresh_rate = max(rate, 1.0)
            elif rate > self.rebuild_factor * self._fresh_rate:
                self._fresh_rate = None   # rebuild at the next solve
        return its
