# SPDX-License-Identifier: MIT
"""The lagged preconditioner of the iterative linear solver: built once, reused while it serves,
rebuilt after a solve that needed more than rebuild_factor times the iterations per decade of the
solve that built it; per-solve tolerances (the forcing term of inexact Newton)."""
import pytest

from fe_stack import require  # noqa: E402
require("dolfinx")

from petsc4py import PETSc  # noqa: E402

from rockjoint.fem.solvers.linear_solver import LinearSolver, LinearSolveError  # noqa: E402


def laplacian(n, shift=0.0):
    """5-point Laplacian on an n x n grid (SPD), + `shift` on the diagonal of the right half."""
    A = PETSc.Mat().createAIJ([n * n, n * n], nnz=5, comm=PETSc.COMM_SELF)
    for i in range(n):
        for j in range(n):
            k = i * n + j
            A.setValue(k, k, 4.0 + (shift if j >= n // 2 else 0.0))
            for ii, jj in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
                if 0 <= ii < n and 0 <= jj < n:
                    A.setValue(k, ii * n + jj, -1.0)
    A.assemble()
    return A


def residual(A, x, b):
    r = b.duplicate()
    A.mult(x, r)
    r.axpy(-1.0, b)
    return r.norm() / b.norm()


def test_the_preconditioner_is_reused_while_it_serves_and_rebuilt_when_it_stops_serving():
    solver = LinearSolver(PETSc.COMM_SELF, "iterative", rtol=1e-10)
    A = laplacian(60, shift=1e3)  # a stiff right half
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    fresh = solver.solve(A, b, x)
    assert solver.setups == 1 and residual(A, x, b) <= 1e-10
    # A looser solve with the same (lagged) preconditioner: fewer iterations, no new set-up.
    assert solver.solve(A, b, x, rtol=1e-6) < fresh and solver.setups == 1
    assert 1e-8 < residual(A, x, b) <= 1e-6
    # The matrix softens (the plain Laplacian): the lagged preconditioner (its smoother's
    # eigenvalue bounds now too high) still converges, but more than rebuild_factor times slower
    # per decade than the solve that built it, so the next solve rebuilds it, with fewer
    # iterations than the stale one needed. (A fresh solver needs fewer still: 34 against 61 on
    # PETSc 3.22 and 3.25; the rebuilt GAMG hierarchy keeps something of the old matrix.)
    laplacian(60).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
    lagged = solver.solve(A, b, x)
    assert solver.setups == 1 and lagged > solver.rebuild_factor * fresh and residual(A, x, b) <= 1e-10
    x.set(0.0)
    rebuilt = solver.solve(A, b, x)
    assert solver.setups == 2 and rebuilt < lagged and residual(A, x, b) <= 1e-10
    x.set(0.0)
    assert solver.solve(A, b, x) == rebuilt and solver.setups == 2   # and kept while it serves
    # The KSP is left at the solver's own tolerance for whoever drives it next (SNES).
    assert solver.ksp.getTolerances()[0] == pytest.approx(1e-10)


def test_a_stale_preconditioner_on_a_stiffened_matrix_still_gives_the_answer():
    """Built on the Laplacian, reused after a half of the matrix stiffens 1000x: the smoother's
    eigenvalue bounds are now too low, so CG with the stale preconditioner either crawls (PETSc
    3.22) or stops at once on an indefinite preconditioner (PETSc 3.25, KSP reason -8): either way
    the solve returns the answer to its tolerance, and the preconditioner is rebuilt at the
    latest by the next solve."""
    solver = LinearSolver(PETSc.COMM_SELF, "iterative", rtol=1e-10)
    A = laplacian(60)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    solver.solve(A, b, x)
    laplacian(60, shift=1e3).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
    solver.solve(A, b, x)
    assert residual(A, x, b) <= 1e-10
    solver.solve(A, b, x)
    assert solver.setups == 2 and residual(A, x, b) <= 1e-10


def test_without_reuse_a_changed_matrix_gets_a_new_preconditioner_at_once():
    solver = LinearSolver(PETSc.COMM_SELF, "iterative", rtol=1e-10, reuse_preconditioner=False)
    A = laplacian(60)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    fresh = solver.solve(A, b, x)
    laplacian(60, shift=1e3).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
    assert solver.solve(A, b, x) < 2 * fresh and solver.setups == 2


def test_bad_tolerances_are_refused_with_their_range():
    solver = LinearSolver(PETSc.COMM_SELF, "iterative")
    A = laplacian(10)
    b = A.createVecLeft()
    b.set(1.0)
    for bad in (0.0, 1.0, float("nan")):
        with pytest.raises(ValueError, match=r"rtol must be in \(0, 1\)"):
            solver.solve(A, b, b.duplicate(), rtol=bad)
    with pytest.raises(ValueError, match="rebuild_factor must be >= 1, got 0.5"):
        LinearSolver(PETSc.COMM_SELF, "iterative", rebuild_factor=0.5)


def test_auto_picks_mumps_only_below_the_measured_crossover():
    """bench/results/direct_vs_iterative.md: in 3D GAMG wins from a few thousand dofs on, in 2D
    the two are comparable up to ~90k dofs."""
    from rockjoint.fem.solvers.linear_solver import DIRECT_DOF_LIMIT, resolve_kind

    assert resolve_kind("auto", 40_000, 2) == "direct"
    assert resolve_kind("auto", 40_000, 3) == "iterative"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[3], 3) == "direct"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[3] + 1, 3) == "iterative"
    assert resolve_kind("direct", 10**7, 3) == "direct"
    assert resolve_kind("lagged", 10**7, 3) == "lagged"
    with pytest.raises(ValueError, match="'direct', 'lagged', 'iterative' or 'auto'"):
        resolve_kind("lu", 100, 2)
    with pytest.raises(ValueError, match="gdim must be 2 or 3"):
        resolve_kind("auto", 100, 1)


def test_auto_keeps_a_nonsymmetric_2d_jacobian_on_mumps_further():
    """bench/results/tunnel_profile.md: on the 90k-dof slipping tunnel (a non-symmetric Jacobian)
    MUMPS LU took 0.22 s CPU per solve against 1.04 s for GMRES + GAMG; kept over several Newton
    iterations (lagged) from 60k dofs on, 8 factorisations did the work of 18 at the same answer."""
    from rockjoint.fem.solvers.linear_solver import (DIRECT_DOF_LIMIT, DIRECT_DOF_LIMIT_NONSYMMETRIC,
                                                      resolve_kind)

    assert resolve_kind("auto", 90_052, 2, symmetric=True) == "iterative"
    assert resolve_kind("auto", 90_052, 2, symmetric=False) == "lagged"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[2], 2, symmetric=False) == "direct"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[2] + 1, 2, symmetric=False) == "lagged"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT_NONSYMMETRIC[2], 2, symmetric=False) == "lagged"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT_NONSYMMETRIC[2] + 1, 2, symmetric=False) == "iterative"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[3], 3, symmetric=False) == "direct"
    assert resolve_kind("auto", DIRECT_DOF_LIMIT[3] + 1, 3, symmetric=False) == "iterative"


def convection_diffusion(n, velocity):
    """The 5-point Laplacian on an n x n grid plus an upwind convection term `velocity` along x:
    non-symmetric, same nonzero pattern for every velocity."""
    A = laplacian(n)
    for i in range(n):
        for j in range(n):
            k = i * n + j
            A.setValue(k, k, velocity, addv=PETSc.InsertMode.ADD_VALUES)
            if j > 0:
                A.setValue(k, k - 1, -velocity, addv=PETSc.InsertMode.ADD_VALUES)
    A.assemble()
    return A


def test_lagged_factorisation_preconditions_gmres_on_a_changed_nonsymmetric_matrix():
    """kind "lagged": the LU of the first matrix is kept while GMRES converges fast with it; the
    answer is held to the true residual whatever the preconditioner."""
    solver = LinearSolver(PETSc.COMM_SELF, "lagged", symmetric=False, rtol=1e-10)
    A = convection_diffusion(30, 0.5)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    assert solver.solve(A, b, x) <= 2 and solver.setups == 1   # an exact LU: one or two iterations
    assert residual(A, x, b) <= 1e-10
    convection_diffusion(30, 0.55).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
    x.set(0.0)
    its = solver.solve(A, b, x)
    assert solver.setups == 1 and 2 < its <= 20 and residual(A, x, b) <= 1e-10
    # a looser tolerance (inexact Newton) stops earlier on the same lagged factorisation
    x.set(0.0)
    assert solver.solve(A, b, x, rtol=1e-4) < its and 1e-10 < residual(A, x, b) <= 1e-4
    assert solver.setups == 1


def test_lagged_factorisation_costs_one_triangular_solve_per_krylov_iteration():
    """kind "lagged", non-symmetric: FGMRES applies the factorisation once per Krylov iteration and
    never again to build its solution (right-preconditioned GMRES would: one more triangular solve
    per linear solve, two for the one iteration of a fresh factorisation). PETSc's event log counts
    MUMPS's triangular solves (MatSolve)."""
    PETSc.Log.begin()
    mat_solve = PETSc.Log.Event("MatSolve")
    solver = LinearSolver(PETSc.COMM_SELF, "lagged", symmetric=False, rtol=1e-10)
    assert solver.ksp.getType() == "fgmres" and solver.ksp.getPCSide() == PETSc.PC.Side.RIGHT
    A = convection_diffusion(30, 0.5)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    total = 0
    for velocity in (0.5, 0.55, 0.6):
        convection_diffusion(30, velocity).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        x.set(0.0)
        before = mat_solve.getPerfInfo()["count"]
        its = solver.solve(A, b, x)
        assert mat_solve.getPerfInfo()["count"] - before == its and residual(A, x, b) <= 1e-10
        total += its
    assert solver.setups == 1 and total > 3   # lagged: the later solves needed several iterations


def test_direct_solver_factorises_symbolically_once_for_a_fixed_pattern():
    """PETSc reuses MUMPS's analysis (symbolic factorisation) while the nonzero pattern stays:
    new values give a numeric factorisation only (PETSc's event log counts them)."""
    PETSc.Log.begin()
    sym, num = PETSc.Log.Event("MatLUFactorSym"), PETSc.Log.Event("MatLUFactorNum")
    before = sym.getPerfInfo()["count"], num.getPerfInfo()["count"]
    solver = LinearSolver(PETSc.COMM_SELF, "direct", symmetric=False)
    A = convection_diffusion(20, 0.5)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    for velocity in (0.6, 0.7, 0.8):
        convection_diffusion(20, velocity).copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        solver.solve(A, b, x)
        assert residual(A, x, b) <= 1e-12
    assert (sym.getPerfInfo()["count"] - before[0], num.getPerfInfo()["count"] - before[1]) == (1, 3)


def gamg_view(solver, tmp_path):
    v = PETSc.Viewer().createASCII(str(tmp_path / "ksp.txt"), comm=PETSc.COMM_SELF)
    solver.ksp.view(v)
    v.destroy()
    return (tmp_path / "ksp.txt").read_text()


@pytest.mark.parametrize("threshold", [None, 0.05])
def test_gamg_gets_its_settings_without_the_options_database(tmp_path, threshold):
    """Our GAMG settings reach the preconditioner (set through the API, the threshold through
    one setFromOptions) and a user's option overrides ours; the level smoothers are GAMG's
    defaults, Chebyshev/Jacobi, which the solver relies on instead of setting them."""
    options = {} if threshold is None else {"pc_gamg_threshold": threshold}
    solver = LinearSolver(PETSc.COMM_SELF, "iterative", rtol=1e-10, options=options,
                          prefix=f"rockjoint_gamg_test_{len(options)}_")
    A = laplacian(60)
    b = A.createVecLeft()
    b.set(1.0)
    x = b.duplicate()
    solver.solve(A, b, x)
    assert residual(A, x, b) <= 1e-10
    pc = solver.ksp.getPC()
    assert pc.getMGLevels() >= 2
    for level in range(1, pc.getMGLevels()):
        smoother = pc.getMGSmoother(level)
        assert (smoother.getType(), smoother.getPC().getType()) == ("chebyshev", "jacobi")
    view = gamg_view(solver, tmp_path)
    assert "AGG specific options" in view and "Number smoothing steps to construct prolongation 0" in view
    expected = 0.01 if threshold is None else threshold
    line = next(line for line in view.splitlines() if "Threshold for dropping small values" in line)
    assert float(line.split("=")[1].split()[0]) == pytest.approx(expected), line
    for key in options:
        PETSc.Options().delValue(f"rockjoint_gamg_test_1_{key}")


def test_mumps_reports_the_null_pivot_of_a_singular_matrix():
    """ICNTL(24) (null-pivot detection) is set on the solver's own factor matrix: a pure-Neumann
    Laplacian (constants in its kernel) is refused as singular, with the number of null pivots."""
    n = 20
    A = PETSc.Mat().createAIJ([n, n], nnz=3, comm=PETSc.COMM_SELF)
    for i in range(n):
        A.setValue(i, i, 2.0 if 0 < i < n - 1 else 1.0)
        for j in (i - 1, i + 1):
            if 0 <= j < n:
                A.setValue(i, j, -1.0)
    A.assemble()
    b = A.createVecLeft()
    b.set(0.0)
    b.setValue(0, 1.0)
    b.setValue(n - 1, -1.0)
    b.assemble()
    x = b.duplicate()
    solver = LinearSolver(PETSc.COMM_SELF, "direct", prefix="rockjoint_mumps_test_",
                          options={"mat_mumps_icntl_14": 50})
    with pytest.raises(LinearSolveError, match=r"MUMPS found 1 null pivot"):
        solver.solve(A, b, x)
    factor = solver.ksp.getPC().getFactorMatrix()
    # ICNTL(24) was read from the solver's prefix, and so was the user's own MUMPS option; then
    # the solver's option left the database, the user's stays (it is the user's).
    assert factor.getMumpsIcntl(24) == 1 and factor.getMumpsIcntl(14) == 50
    options = PETSc.Options().getAll()
    assert "rockjoint_mumps_test_mat_mumps_icntl_24" not in options
    assert options.get("rockjoint_mumps_test_mat_mumps_icntl_14") == "50"
    PETSc.Options().delValue("rockjoint_mumps_test_mat_mumps_icntl_14")


def test_a_kept_factorisation_is_rebuilt_sooner_than_a_gamg_hierarchy():
    """LAGGED_REBUILD_FACTOR (bench/results/tunnel_profile.md, the discrete tunnel's solvers): a
    factorisation is rebuilt from 1.5 Krylov iterations per decade on, GAMG from 2; an explicit
    rebuild_factor wins."""
    from rockjoint.fem.solvers.linear_solver import LAGGED_REBUILD_FACTOR
    assert LAGGED_REBUILD_FACTOR == 1.5
    assert LinearSolver(PETSc.COMM_SELF, "lagged", symmetric=False).rebuild_factor == 1.5
    assert LinearSolver(PETSc.COMM_SELF, "iterative").rebuild_factor == 2.0
    assert LinearSolver(PETSc.COMM_SELF, "lagged", symmetric=False, rebuild_factor=3.0).rebuild_factor == 3.0
