# SPDX-License-Identifier: MIT
"""The coupling API in a user's own DOLFINx model (serial).

References: JointedRockModel on the same mesh (its own assembly and Newton: see user_model_case),
the DOLFINx 0.11 NonlinearProblem interface of JointedNonlinearProblem, and for the closure limiter the closed form of a
uniform closure. Malformed input must raise errors that name the problem.
"""
import math

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import gmsh  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem  # noqa: E402
from dolfinx.fem import petsc as fem_petsc  # noqa: E402
from mpi4py import MPI  # noqa: E402
from petsc4py import PETSc  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import (JointCoupling, JointedNonlinearProblem, NewtonSolverError, distribute,  # noqa: E402
                                    supported_dofs)
from rockjoint.meshes.builders import _ensure_gmsh  # noqa: E402

import user_model_case as case  # noqa: E402

COMM = MPI.COMM_SELF


@pytest.fixture(scope="module", autouse=True)
def gmsh_session():
    _ensure_gmsh(gmsh)
    gmsh.option.setNumber("General.Terminal", 0)


@pytest.fixture(scope="module")
def dmesh2():
    return case.distributed_case(gmsh, 2, 0.25, COMM)


def max_abs(a):
    return float(np.abs(a).max())


@pytest.mark.parametrize("dim,degree,mesh_size", [(2, 1, 0.25), (2, 2, 0.4), (3, 1, 0.6)])
def test_user_forms_with_joints_equal_jointed_rock_model(dim, degree, mesh_size, dmesh2):
    dmesh = dmesh2 if (dim, mesh_size) == (2, 0.25) else case.distributed_case(gmsh, dim, mesh_size, COMM)
    problem = case.user_problem(dmesh, degree)
    iterations = case.solve(problem)
    model = case.rock_model(dmesh, degree)
    reference = model.solution.displacement
    assert iterations > 2, "the joint must make the problem nonlinear (Barton-Bandis)"
    # Same space construction, same dof layout: compare dof by dof.
    scale = max_abs(reference.x.array)
    assert scale > 1e-5
    assert max_abs(problem.u.x.array - reference.x.array) <= 1e-8 * scale
    # The joint state seen by the user equals the model's.
    state = problem.coupling.state(problem.u)
    np.testing.assert_allclose(state["closure"], model.solution.joints["closure"], rtol=0,
                               atol=1e-9 * case.LAW.maximum_closure)
    assert state["closure"].max() > 0.1 * case.LAW.maximum_closure  # the joint really closes


def test_the_problem_has_the_nonlinear_problem_interface_of_dolfinx_0_11(dmesh2):
    """F and J are the compiled forms, A the joint-aware matrix, x the SNES vector (not u's), the
    solver a SNES under the given prefix; solve() returns u, and solving again from the converged
    u with an absolute tolerance from the load (load_norm) takes no iteration."""
    problem = case.user_problem(dmesh2, prefix="slope_")
    assert isinstance(problem.F, fem.Form) and problem.F.rank == 1
    assert isinstance(problem.J, fem.Form) and problem.J.rank == 2
    assert isinstance(problem.solver, PETSc.SNES) and problem.solver.getOptionsPrefix() == "slope_"
    assert problem.A.handle == problem.solver.getJacobian()[0].handle
    assert problem.x.handle != problem.u.x.petsc_vec.handle
    assert problem.solve() is problem.u
    assert problem.solver.getConvergedReason() > 0 and problem.solver.getIterationNumber() > 2
    np.testing.assert_array_equal(problem.x.array_r, problem.u.x.petsc_vec.array_r)
    first = problem.u.x.array.copy()
    problem.solver.setTolerances(atol=1e-10 * problem.load_norm())
    problem.solve()
    assert problem.solver.getIterationNumber() == 0
    np.testing.assert_array_equal(problem.u.x.array, first)


# DOLFINx's NewtonSolver.__del__ destroys self._A, which its __init__ never set once refused.
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_dolfinx_newton_solver_is_refused_with_a_clear_error(dmesh2):
    """JointedNonlinearProblem is not DOLFINx's NonlinearProblem (docs/user-model.md says why):
    dolfinx.nls.petsc.NewtonSolver (0.9's, and 0.11's deprecated one) would build its own matrix
    from problem.a without the cross-joint couplings. It gets a TypeError saying what to call,
    not a bare AttributeError from inside DOLFINx; hasattr still answers False."""
    import warnings
    from dolfinx.nls.petsc import NewtonSolver
    problem = case.user_problem(dmesh2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)   # 0.11 deprecates NewtonSolver
        with pytest.raises(NewtonSolverError, match=r"solved by PETSc SNES: call problem\.solve\(\)"):
            NewtonSolver(COMM, problem)
    assert issubclass(NewtonSolverError, TypeError)
    assert not hasattr(problem, "a") and not hasattr(problem, "L")
    assert problem.coupling.V is problem.u.function_space


def test_a_saved_table_is_read_by_path(dmesh2, tmp_path):
    """A .rjt path as the law gives the table's answer (the table approximates the law to 1e-6)."""
    path = tmp_path / "fault.rjt"
    table = rockjoint.tabulate(case.LAW, max_stress=20e6)
    table.save(str(path))
    from_file = case.user_problem(dmesh2, law=str(path))
    case.solve(from_file)
    direct = case.user_problem(dmesh2)
    case.solve(direct)
    scale = max_abs(direct.u.x.array)
    assert max_abs(from_file.u.x.array - direct.u.x.array) <= 1e-5 * scale


def test_supported_rows_and_columns_stay_out_of_the_joint_blocks(dmesh2):
    """After the user's J(), a supported dof's row and column hold only the unit diagonal, and the
    cross-joint couplings are present (the matrix has them in its pattern)."""
    problem = case.user_problem(dmesh2)
    case.solve(problem)
    A = problem.matrix()
    mask = problem.coupling.supported
    pair_dofs = problem.coupling.interface.pair_dofs()
    owned = dmesh2.mesh.topology.index_map(0).size_local  # serial: all local
    assert owned > 0
    joint_supported = np.intersect1d(pair_dofs.ravel(), np.flatnonzero(mask))
    assert joint_supported.size > 0, "the case must have joint dofs on a support"
    dense = A.convert("dense").getDenseArray()
    for d in joint_supported:
        row = dense[d].copy()
        col = dense[:, d].copy()
        assert row[d] == 1.0 and col[d] == 1.0
        row[d] = col[d] = 0.0
        assert not row.any() and not col.any()
    free = [p for p in pair_dofs if not mask[p].any()]
    k = free[0]
    half = k.size // 2
    assert np.abs(dense[np.ix_(k[:half], k[half:])]).max() > 0.0  # minus-plus coupling


def test_supported_dofs_of_whole_space_and_component_bcs(dmesh2):
    V = fem.functionspace(dmesh2.mesh, ("Lagrange", 1, (dmesh2.mesh.geometry.dim,)))
    bottom = fem.locate_dofs_topological(V, 1, dmesh2.boundary("bottom"))          # block dofs
    left = fem.locate_dofs_topological(V.sub(0), 1, dmesh2.boundary("left"))       # unrolled
    bcs = [fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType), bottom, V),
           fem.dirichletbc(PETSc.ScalarType(0.0), left, V.sub(0))]
    mask = supported_dofs(V, bcs)
    expected = np.zeros(mask.size, dtype=np.int8)
    expected[2 * bottom] = expected[2 * bottom + 1] = 1
    expected[left] = 1
    assert np.array_equal(mask, expected)
    # Every bottom node is supported in both components, and x = 0 nodes in x.
    x = V.tabulate_dof_coordinates()
    assert np.all(np.isclose(x[mask.reshape(-1, 2)[:, 1] == 1, 1], 0.0))
    assert np.all(np.isclose(x[mask.reshape(-1, 2)[:, 0] == 1][:, :2].min(axis=1), 0.0))


def test_admissible_step_is_the_fraction_to_the_boundary_of_a_uniform_closure():
    """Two blocks pressed together uniformly by a jump -d: Δ(α) = α d, so the largest step with
    Δ ≤ 0.95 V_m is α = 0.95 V_m / d (d > V_m); α = 1 when d stays inside."""
    jm = meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=0.5, comm=COMM)
    dmesh = distribute(jm, COMM)
    V = fem.functionspace(dmesh.mesh, ("Lagrange", 1, (dmesh.mesh.geometry.dim,)))
    vm = case.LAW.maximum_closure
    coupling = JointCoupling(V, dmesh, {"joint_1": case.LAW}, shear_stiffness=1e9)
    u, du = fem.Function(V), fem.Function(V)
    above = V.tabulate_dof_coordinates()[:, 1] > 1.0 + 1e-9
    plus_side = np.zeros(V.dofmap.index_map.size_local, dtype=bool)
    plus_nodes = np.unique(coupling.interface.pair_dofs()[:, 4:]) // 2  # plus facet nodes (2D P1: 2 nodes)
    plus_side[plus_nodes] = True
    moving = above | plus_side
    for d, expected in ((2.0 * vm, 0.95 * vm / (2.0 * vm)), (0.5 * vm, 1.0)):
        du.x.array.reshape(-1, 2)[:, 1] = np.where(moving, -d, 0.0)
        assert coupling.admissible_step(u, du) == pytest.approx(expected, rel=1e-12)
    assert coupling.admissible_step(u, du.x.petsc_vec) == pytest.approx(1.0)


# ---- malformed input -------------------------------------------------------------------------
def test_wrong_array_sizes_name_the_sizes(dmesh2):
    problem = case.user_problem(dmesh2)
    c, u = problem.coupling, problem.u
    n = c.num_local_dofs
    with pytest.raises(ValueError,
                       match=rf"b: expected a float64 array of the {n} local dofs of V .*got shape \({n - 1},\)"):
        c.add_residual(u, np.zeros(n - 1))
    with pytest.raises(ValueError, match=rf"u: expected a float64 array of the {n} local dofs.*shape \({n + 2},\)"):
        c.add_residual(np.zeros(n + 2), np.zeros(n))
    with pytest.raises(ValueError, match=r"du: expected a float64 array"):
        c.admissible_step(u, np.zeros((n, 1)))
    other = fem.functionspace(dmesh2.mesh, ("Lagrange", 2, (dmesh2.mesh.geometry.dim,)))
    w = fem.Function(other)  # kept alive: in DOLFINx 0.9 x.petsc_vec borrows the Function's memory
    with pytest.raises(ValueError, match=r"u: a PETSc Vec with \d+ owned entries on this rank; V has"):
        c.add_residual(w.x.petsc_vec, np.zeros(n))
    with pytest.raises(ValueError, match="u must be a Function of the coupling's space V"):
        c.add_residual(fem.Function(other), np.zeros(n))
    A = fem_petsc.create_matrix(fem.form(ufl.inner(ufl.TrialFunction(other), ufl.TestFunction(other)) * ufl.dx))
    with pytest.raises(ValueError, match=r"A is \(\d+, \d+\), expected \(\d+, \d+\) for the dofs of V"):
        c.add_jacobian(u, A)
    with pytest.raises(ValueError, match=r"fraction = 1.5 must be in \(0, 1\)"):
        c.admissible_step(u, u, fraction=1.5)


def test_unknown_or_missing_joint_names_and_bad_laws(dmesh2, tmp_path):
    V = fem.functionspace(dmesh2.mesh, ("Lagrange", 1, (dmesh2.mesh.geometry.dim,)))
    with pytest.raises(ValueError, match=r"unknown joint\(s\) \['bedding'\]; available joints: \['fault'\]"):
        JointCoupling(V, dmesh2, {"fault": case.LAW, "bedding": case.LAW})
    with pytest.raises(ValueError, match=r"no law for joint\(s\) \['fault'\]"):
        JointCoupling(V, dmesh2, {})
    with pytest.raises(ValueError, match=r"shear_stiffness: unknown joint\(s\) \['faults'\]"):
        JointCoupling(V, dmesh2, {"fault": case.LAW}, shear_stiffness={"faults": 1e9})
    with pytest.raises(ValueError, match=r"laws\['fault'\]: no table file .*missing.rjt"):
        JointCoupling(V, dmesh2, {"fault": str(tmp_path / "missing.rjt")})
    with pytest.raises(TypeError, match=r"laws\['fault'\] must be a rockjoint closure law or table"):
        JointCoupling(V, dmesh2, {"fault": 1e10})
    with pytest.raises(ValueError, match="shear"):
        JointCoupling(V, dmesh2, {"fault": case.LAW}, shear_stiffness=-1.0)
    with pytest.raises(ValueError, match="quadrature must be one of"):
        JointCoupling(V, dmesh2, {"fault": case.LAW}, quadrature="simpson")


def test_wrong_spaces_and_conditions(dmesh2):
    mesh = dmesh2.mesh
    scalar = fem.functionspace(mesh, ("Lagrange", 1))
    with pytest.raises(ValueError, match=r"V must be a vector Lagrange space of degree 1 or 2 with 2 components"):
        JointCoupling(scalar, dmesh2, {"fault": case.LAW})
    V = fem.functionspace(mesh, ("Lagrange", 1, (mesh.geometry.dim,)))
    foreign = fem.dirichletbc(PETSc.ScalarType(0.0), np.array([0], dtype=np.int32), scalar)
    with pytest.raises(ValueError, match=r"bcs\[0\] constrains a function space that is not the displacement space"):
        JointCoupling(V, dmesh2, {"fault": case.LAW}, bcs=[foreign])
    with pytest.raises(ValueError, match="joint_tags=.* is required when joints are JointPairs"):
        JointCoupling(V, dmesh2.pairs, {"fault": case.LAW})
    with pytest.raises(ValueError, match=r"the pairs carry tags \[\d+\] that no name maps to"):
        JointCoupling(V, dmesh2.pairs, {"fault": case.LAW}, joint_tags={"fault": 999})
    coupling = JointCoupling(V, dmesh2, {"fault": case.LAW})
    P2 = fem.functionspace(mesh, ("Lagrange", 2, (mesh.geometry.dim,)))
    with pytest.raises(ValueError, match=r"a must be a bilinear form on V × V"):
        coupling.create_matrix(fem.form(ufl.inner(ufl.TrialFunction(P2), ufl.TestFunction(P2)) * ufl.dx))
    F = ufl.inner(ufl.grad(fem.Function(P2)), ufl.grad(ufl.TestFunction(P2))) * ufl.dx
    with pytest.raises(ValueError, match="u must be a Function of the coupling's displacement space V"):
        JointedNonlinearProblem(F, fem.Function(P2), coupling, petsc_options_prefix="p2_")


def test_a_missing_physical_group_is_named_with_the_available_ones():
    case.build_gmsh_model(gmsh, 2, 0.5)
    try:
        with pytest.raises(ValueError, match=r"joints: no dimension-1 physical group named 'faults'; available: "
                                             r"\['bottom', 'fault', 'left', 'right', 'top'\]"):
            meshes.from_gmsh_model(joints=["faults"])
    finally:
        gmsh.model.remove()


def test_the_demo_docstring_promise_joint_faces_are_exterior_facets(dmesh2):
    """A bare ds integrates over the joint faces too: ∫ds = outer perimeter + 2 × joint length."""
    one = fem.Constant(dmesh2.mesh, 1.0)
    everything = fem.assemble_scalar(fem.form(one * ufl.ds(domain=dmesh2.mesh)))
    joint_length = case.SIZE / math.cos(case.DIP)
    assert everything == pytest.approx(4 * case.SIZE + 2 * joint_length, rel=1e-12)


def test_closure_limiter_lets_newton_and_snes_pass_a_stiffening_law():
    """A column under σ = 5 K_ni V_m: plain Newton from zero overshoots the maximum closure of a
    Barton-Bandis law (docs/fem.md, pitfall 7); with the limiter both solvers converge to the
    closed form Δ = σ V_m / (K_ni V_m + σ) (uniform uniaxial stress: rollers, free sides)."""
    kni, vm = 1e10, 1e-3
    law = rockjoint.BartonBandis(kni, vm)
    stress = 5 * kni * vm
    dmesh = distribute(meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=0.5, comm=COMM), COMM)
    closure = stress * vm / (kni * vm + stress)

    def problem():
        V = fem.functionspace(dmesh.mesh, ("Lagrange", 1, (dmesh.mesh.geometry.dim,)))
        u, v = fem.Function(V), ufl.TestFunction(V)
        eps = ufl.sym(ufl.grad(u))
        mu, lam = 20e9 / 2.5, 20e9 * 0.25 / (1.25 * 0.5)
        ds = ufl.Measure("ds", domain=dmesh.mesh, subdomain_data=dmesh.boundaries)
        top = {n: t for t, n in dmesh.names["boundaries"].items()}["top"]
        F = (ufl.inner(2 * mu * eps + lam * ufl.tr(eps) * ufl.Identity(2), ufl.sym(ufl.grad(v))) * ufl.dx
             - ufl.inner(fem.Constant(dmesh.mesh, (0.0, -stress)), v) * ds(top))
        bcs = [fem.dirichletbc(PETSc.ScalarType(0.0), fem.locate_dofs_topological(V.sub(i), 1, dmesh.boundary(b)),
                               V.sub(i)) for i, b in ((1, "bottom"), (0, "left"))]
        coupling = JointCoupling(V, dmesh, {"joint_1": law}, shear_stiffness=1e9, bcs=bcs)
        return JointedNonlinearProblem(F, u, coupling, bcs=bcs, petsc_options_prefix=case.unique_prefix("column"),
                                       petsc_options=dict(case.SNES_OPTIONS, snes_max_it=15))

    plain = problem()
    plain.closure_fraction = None  # no limiter: SNES's full Newton step
    plain.solve()
    # Past V_m the joint traction is infinite: SNES is told (function-domain error) and stops
    # without converging (PETSc 3.25 reports DIVERGED_FUNCTION_DOMAIN, 3.22 the line search's
    # failure on it).
    assert plain.solver.getConvergedReason() < 0
    assert plain.domain_errors > 0

    limited = problem()
    case.solve(limited)
    np.testing.assert_allclose(limited.coupling.state(limited.u)["closure"], closure, rtol=1e-8)


def test_snes_options_stay_with_their_problem(dmesh2):
    """petsc_options reach the SNES they were given to, not the next one; bad options and
    prefixes are refused with a message that names them."""
    first = case.user_problem(dmesh2, petsc_options={"snes_max_it": 3, "snes_type": "newtontr"}).solver
    second = case.user_problem(dmesh2, petsc_options={}).solver
    assert first.getType() == "newtontr" and first.getTolerances()[3] == 3
    assert second.getType() == "newtonls" and second.getTolerances()[3] != 3
    named = case.user_problem(dmesh2, prefix="mine_", petsc_options={"snes_max_it": 7}).solver
    assert named.getOptionsPrefix() == "mine_" and named.getTolerances()[3] == 7
    with pytest.raises(ValueError, match="give option names without the leading dash"):
        case.user_problem(dmesh2, petsc_options={"-snes_max_it": 3})
    with pytest.raises(ValueError, match="options_prefix '-x_': a string without a leading dash"):
        case.user_problem(dmesh2, prefix="-x_")
    with pytest.raises(ValueError, match="petsc_options_prefix must be a non-empty string"):
        case.user_problem(dmesh2, prefix="")
