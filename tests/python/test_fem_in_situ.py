# SPDX-License-Identifier: MIT
"""In-situ stress: the initial state is an equilibrium (u = 0, zero residual), releasing in-situ
tractions gives the closed-form relative displacement, an excavated hole converges like Lamé.

References: uniform stress release in plane strain, ε = [(1-ν²) Δσ_a - ν(1+ν) Δσ_b] / E; a hole of
radius a in a thick cylinder b under isotropic p0 whose wall traction is released moves like the
Lamé cylinder under an internal pressure -p0 (superposition).
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import InSituStress, JointedRockModel, distribute  # noqa: E402
from staged_cases import (E, E_PLANE, KNI, NU, QUIET, VM, bb_closure, column,  # noqa: E402
                          lame_radial_displacement, quarter_annulus, radial_displacement_at)

H = 2.0  # height of staged_cases.column [m]

RHO, G = 2700.0, 9.81
WIDTH, HEIGHT = 2.0, 3.0


@pytest.fixture(scope="module")
def block():
    jm = meshes.jointed_block((WIDTH, HEIGHT), [], dim=2, mesh_size=0.5, comm=MPI.COMM_WORLD)
    return distribute(jm, MPI.COMM_WORLD)


def intact(dmesh, **kw):
    model = JointedRockModel(dmesh, rock=(E, NU), newton=QUIET, **kw)
    model.fix("bottom", "y")
    model.fix("left", "x")
    return model


def test_depth_dependent_initial_state_is_in_equilibrium(block):
    """σ_v = ρ g (z_s - y), σ_h = K0 σ_v with gravity ρ g: nothing moves, the residual is zero, and
    the supports carry the in-situ stress: bottom ρ g z_s × width, left ∫ K0 σ_v dy."""
    surface, k0 = 100.0, 0.5
    model = intact(block, density=RHO)
    model.set_in_situ_stress(InSituStress.depth_dependent(surface, RHO, k0))
    res = model.solve(name="in-situ")
    assert np.abs(model.u.x.array).max() == 0.0
    problem = model.problem()
    problem.load_factor = 1.0
    assert problem.residual_norm() < 1e-12 * RHO * G * surface * WIDTH
    assert res.reactions[("bottom", "y")] == pytest.approx(RHO * G * surface * WIDTH, rel=1e-12)
    left = k0 * RHO * G * (surface * HEIGHT - HEIGHT**2 / 2)
    assert res.reactions[("left", "x")] == pytest.approx(left, rel=1e-12)
    # total stress = σ0 + σ(0): the depth profile, at the cell midpoints (DG0)
    stress = model.total_stress().x.array.reshape(-1, 2, 2)
    x = model.total_stress().function_space.tabulate_dof_coordinates()
    np.testing.assert_allclose(stress[:, 1, 1], -RHO * G * (surface - x[:, 1]), rtol=1e-12)
    np.testing.assert_allclose(stress[:, 0, 0], -k0 * RHO * G * (surface - x[:, 1]), rtol=1e-12)


def test_depth_dependent_in_3d_with_two_horizontal_ratios():
    """3D box 1 × 1 × 2 m, z vertical, K0 = (0.5, 0.8): u = 0 and the rollers carry ρ g z_s (bottom)
    and K0_i ρ g (z_s H - H²/2) (sides), per metre of width."""
    surface, k0, h = 50.0, (0.5, 0.8), 2.0
    jm = meshes.jointed_block((1.0, 1.0, h), [], dim=3, mesh_size=0.5, comm=MPI.COMM_WORLD)
    model = JointedRockModel(distribute(jm, MPI.COMM_WORLD), rock=(E, NU), density=RHO, newton=QUIET)
    for side, comp in (("bottom", "z"), ("left", "x"), ("front", "y")):
        model.fix(side, comp)
    model.set_in_situ_stress(InSituStress.depth_dependent(surface, RHO, k0))
    res = model.solve()
    assert np.abs(model.u.x.array).max() == 0.0
    assert res.reactions[("bottom", "z")] == pytest.approx(RHO * G * surface, rel=1e-12)
    side = RHO * G * (surface * h - h**2 / 2)
    assert res.reactions[("left", "x")] == pytest.approx(k0[0] * side, rel=1e-12)
    assert res.reactions[("front", "y")] == pytest.approx(k0[1] * side, rel=1e-12)


def test_gravity_and_in_situ_gradient_must_agree(block):
    model = intact(block, density=RHO)
    with pytest.raises(ValueError, match="density 2600 kg/m³ but block 'block_1' has density 2700"):
        model.set_in_situ_stress(InSituStress.depth_dependent(100.0, 2600.0, 0.5))
    no_gravity = intact(block)
    with pytest.raises(ValueError, match="needs gravity in the model"):
        no_gravity.set_in_situ_stress(InSituStress.depth_dependent(100.0, RHO, 0.5))
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-1e6, -2e6])))  # no gradient, gravity on
    with pytest.raises(ValueError, match="not in equilibrium"):
        model.solve()
    with pytest.raises(ValueError, match="symmetric"):
        InSituStress.uniform([[0.0, 1.0], [2.0, 0.0]])
    with pytest.raises(ValueError, match="k0"):
        InSituStress.depth_dependent(100.0, RHO, -0.5)
    with pytest.raises(ValueError, match="2x2 or 3x3"):
        InSituStress.uniform([1.0, 2.0])
    with pytest.raises(ValueError, match="model is 2D"):
        no_gravity.set_in_situ_stress(InSituStress.uniform(-np.eye(3)))


def test_an_unbalanced_field_is_refused_unless_a_tolerance_is_given(block):
    """σ0_xx = -(1 + x²) MPa has div σ0 ≠ 0 with no body force: refused by default; with a
    tolerance the first stage moves u to restore equilibrium."""
    def field(x):
        zero = 0.0 * x[0]
        return np.array([[-1e6 * (1 + x[0] ** 2), zero], [zero, -1e6 + zero]])

    model = intact(block)
    model.set_in_situ_stress(InSituStress.from_function(field))
    with pytest.raises(ValueError, match=r"not in equilibrium.*equilibrium_tolerance"):
        model.solve()
    with pytest.raises(ValueError, match="equilibrium_tolerance"):
        model.set_in_situ_stress(InSituStress.from_function(field), equilibrium_tolerance=-1.0)
    relaxed = intact(block)
    relaxed.set_in_situ_stress(InSituStress.from_function(field), equilibrium_tolerance=1.0)
    relaxed.solve()
    assert np.abs(relaxed.u.x.array).max() > 0.0


@pytest.mark.parametrize("field", ["uniform", "function"])
def test_releasing_uniform_in_situ_tractions_matches_the_closed_form(block, field):
    """σ0 = diag(-1, -2) MPa; the right and top tractions released (excavate): the block expands by
    the plane-strain strains of Δσ = (+1, +2) MPa and the total stress vanishes."""
    sx, sy = -1e6, -2e6
    model = intact(block)
    if field == "uniform":
        model.set_in_situ_stress(InSituStress.uniform(np.diag([sx, sy])))
    else:
        model.set_in_situ_stress(InSituStress.from_function(
            lambda x: np.array([[sx + 0 * x[0], 0 * x[0]], [0 * x[0], sy + 0 * x[0]]])))
    initial = model.solve()
    assert np.abs(initial.displacement.x.array).max() == 0.0
    model.excavate("top")
    model.excavate("right")
    released = model.solve(load_steps=2)
    exx = ((1 - NU**2) * -sx - NU * (1 + NU) * -sy) / E
    eyy = ((1 - NU**2) * -sy - NU * (1 + NU) * -sx) / E
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(eyy * HEIGHT, rel=1e-10)
    assert model.boundary_mean_displacement("right")[0] == pytest.approx(exx * WIDTH, rel=1e-10)
    assert np.abs(model.total_stress().x.array).max() < 1e-8 * abs(sy)
    assert max(abs(r) for r in released.reactions.values()) < 1e-8 * abs(sy)
    model.excavate("top").remove()  # the top traction comes back: only Δσ_x = -sx is left
    model.solve()
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(-NU * (1 + NU) * -sx / E * HEIGHT,
                                                                        rel=1e-10)


def test_excavating_a_hole_matches_lame_and_a_negative_pressure():
    """Isotropic p0 = 10 MPa; excavating the hole (its wall traction ramped to zero) equals an
    internal pressure -p0 on the unstressed cylinder to round-off, and Lamé within 3e-4 (P2)."""
    a, b, p0 = 1.0, 3.0, 10e6
    dmesh = quarter_annulus(a, b, 16, 48)

    def model_of():
        m = JointedRockModel(dmesh, element_degree=2, rock=(E, NU), newton=QUIET)
        m.fix("left", "x")
        m.fix("bottom", "y")
        return m

    excavated = model_of()
    excavated.set_in_situ_stress(InSituStress.uniform(-p0 * np.eye(2)))
    initial = excavated.solve(name="in-situ")
    # the symmetry supports carry σ0 over their length b - a
    assert initial.reactions[("bottom", "y")] == pytest.approx(p0 * (b - a), rel=1e-12)
    excavated.excavate("inner")
    excavated.solve(load_steps=3, name="excavation")
    pressure = model_of()
    pressure.add_pressure("inner", -p0)
    pressure.solve()
    assert np.abs(excavated.u.x.array - pressure.u.x.array).max() < 1e-10 * np.abs(pressure.u.x.array).max()
    _, ur = radial_displacement_at(excavated, a)
    ref = lame_radial_displacement(a, a, b, -p0)
    assert ref < 0  # the wall converges into the opening
    assert np.abs(ur / ref - 1).max() < 3e-4
    # a lining pressure p0 in a later stage brings the wall back (superposition)
    excavated.add_pressure("inner", p0)
    excavated.solve(name="lining")
    assert np.abs(excavated.u.x.array).max() < 1e-9 * abs(ref)


def test_a_joint_follows_its_law_through_in_situ_unloading_and_reloading():
    """Column, horizontal Barton-Bandis joint at mid-height, σ0 = diag(-σh, -σv). At every stage
    the joint's closure is the law's closed-form Δ(σ_n) at the normal stress the applied load
    gives (top traction fraction f of σv, plus added load), and the top moves by the rock's
    plane-strain strain plus the change of closure:
        in-situ σ_n = σv (u = 0) → excavation-like unloading to σv/4 → reloading to 1.25 σv →
        complete unloading (σ_n = 0, the joint at its zero-stress closure 0)."""
    sh, sv = 2e6, 5e6
    model = column()
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-sh, -sv])))
    stages = []

    def check(normal_stress):
        res = model.solve(load_steps=2)
        joints = res.gather_joints()
        np.testing.assert_allclose(joints["normal_stress"], normal_stress, rtol=1e-8, atol=1e-6)
        np.testing.assert_allclose(joints["closure"], bb_closure(normal_stress), rtol=1e-8, atol=1e-15)
        expected_top = (sv - normal_stress) * H / E_PLANE + bb_closure(sv) - bb_closure(normal_stress)
        assert model.boundary_mean_displacement("top")[1] == pytest.approx(expected_top, rel=1e-8, abs=1e-15)
        assert res.reactions[("bottom", "y")] == pytest.approx(normal_stress * 1.0, rel=1e-8, abs=1e-3)
        stages.append(res)

    check(sv)                                # in-situ: nothing moves
    assert np.abs(model.u.x.array).max() == 0.0
    release = model.excavate("top", fraction_left=0.25)
    check(0.25 * sv)                         # unloading
    reload = model.add_traction("top", (0.0, -sv))
    check(1.25 * sv)                         # reloading past the in-situ stress
    release.value = 0.0
    reload.remove()
    check(0.0)                               # unloaded: the joint back at zero closure


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("field", ["uniform", "depth"])
def test_an_inclined_joint_carries_the_in_situ_shear_at_u_zero(dim, field):
    """Joint dipping θ = 30° through the centre of the unit block under σ0 = -s diag(K0[, K0], 1):
    at u = 0 the residual is zero (the pre-closure Δ0 = Δ(σ_n0) and the shear offset τ0/k_s balance
    the bulk), and the joint carries σ_n0 = s (K0 sin²θ + cos²θ), |τ0| = s (1 - K0) sin θ cos θ
    (σ0 n with n = (sin θ, [0,] cos θ)): pointwise for a uniform σ0 (s = 6 MPa, K0 = 1/3); as the
    resultant over the joint (area 1/cos θ, centroid at the centre) for the lithostatic state
    (s = ρ g (z_s - z), K0 = 0.6), whose gradient along the joint the vertex rule lumps per facet."""
    comm = MPI.COMM_WORLD
    jm = meshes.jointed_block((1.0,) * dim, [meshes.Joint((0.5,) * dim, 30.0, 90.0, "inclined")], dim=dim,
                              mesh_size=0.25 if dim == 2 else 0.4, comm=comm)
    law = rockjoint.BartonBandis(KNI, VM)
    density = RHO if field == "depth" else None
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU), joints={"inclined": law}, density=density,
                             shear_stiffness=2e9, plane="strain" if dim == 2 else None, newton=QUIET)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    if field == "uniform":
        s, k0 = 6e6, 1.0 / 3.0
        model.set_in_situ_stress(InSituStress.uniform(-s * np.diag([k0] * (dim - 1) + [1.0])))
    else:
        surface, k0 = 200.0, 0.6
        s = RHO * G * (surface - 0.5)
        model.set_in_situ_stress(InSituStress.depth_dependent(surface, RHO, k0))
    res = model.solve()
    theta = np.radians(30.0)
    sn = s * (k0 * np.sin(theta) ** 2 + np.cos(theta) ** 2)
    tau = s * (1 - k0) * np.sin(theta) * np.cos(theta)
    assert np.abs(model.u.x.array).max() == 0.0
    problem = model.problem()
    problem.load_factor = 1.0
    assert problem.residual_norm() < 1e-9 * s
    joints = res.gather_joints()
    np.testing.assert_allclose(joints["closure"], [bb_closure(x) for x in joints["normal_stress"]], rtol=1e-10)
    if field == "uniform":
        np.testing.assert_allclose(joints["normal_stress"], sn, rtol=1e-10)
        np.testing.assert_allclose(np.linalg.norm(joints["shear_traction"], axis=1), tau, rtol=1e-10)
    else:
        weights = np.repeat(model.interface._cpp.measures / dim, dim)  # vertex rule: |f| / gdim
        state = model.interface.state()
        normal_force = comm.allreduce(np.sum(weights * state["normal_stress"]))
        shear_force = comm.allreduce(np.sum(weights[:, None] * state["shear_traction"], axis=0))
        area = 1.0 / np.cos(theta)
        assert normal_force == pytest.approx(sn * area, rel=1e-10)
        assert np.linalg.norm(shear_force) == pytest.approx(tau * area, rel=1e-10)


def test_in_situ_tension_across_a_joint_is_refused():
    model = column()
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-1e6, 1e6])))
    with pytest.raises(ValueError, match="pulls joint 'joint_1' apart"):
        model.solve()


def test_a_joint_with_residual_stiffness_is_pre_closed_to_the_quadratic_root():
    """With a residual stiffness k_r the in-situ pre-closure Δ0 solves K_ni Δ/(1 - Δ/V_m) + k_r Δ = σv,
    i.e. k_r Δ² - b Δ + σv V_m = 0 with b = K_ni V_m + k_r V_m + σv (root below V_m, cancellation-free
    form); the initial state is an equilibrium (nothing moves) and the joint carries σv."""
    sh, sv, kr = 2e6, 5e6, 5e9
    model = column(residual_stiffness=kr)
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-sh, -sv])))
    joints = model.solve().gather_joints()
    b = KNI * VM + kr * VM + sv
    expected = 2.0 * sv * VM / (b + np.sqrt(b * b - 4.0 * kr * sv * VM))
    assert expected < bb_closure(sv)  # k_r carries part of σv
    np.testing.assert_allclose(joints["closure"], expected, rtol=1e-10)
    np.testing.assert_allclose(joints["normal_stress"], sv, rtol=1e-10)
    assert np.abs(model.u.x.array).max() == 0.0


def test_closure_at_normal_stress_keeps_the_shape_and_names_a_refused_entry():
    from rockjoint.fem import JointBehaviour, closure_at_normal_stress
    behaviour = JointBehaviour(rockjoint.BartonBandis(KNI, VM))  # k_r = 0: the law's closed form
    stress = np.array([[0.0, 1e6], [5e6, 20e6]])
    closure = closure_at_normal_stress(behaviour, stress)
    assert closure.shape == stress.shape
    np.testing.assert_allclose(closure, bb_closure(stress), rtol=1e-14, atol=0.0)
    assert isinstance(closure_at_normal_stress(behaviour, 1e6), float)
    assert closure_at_normal_stress(behaviour, np.empty(0)).shape == (0,)
    with pytest.raises(ValueError, match=r"entry 2: joint normal stress -1 Pa .*finite and >= 0"):
        closure_at_normal_stress(behaviour, np.array([1e6, 2e6, -1.0]))
    with pytest.raises(ValueError, match=r"entry 0: joint normal stress nan Pa"):
        closure_at_normal_stress(behaviour, np.array([np.nan]))
