# SPDX-License-Identifier: MIT
"""Equivalent continuum in DOLFINx (serial): smeared Barton-Bandis sets against closed forms and
against the discrete joints they replace.

- Column under uniaxial stress σ: the smeared set of spacing L/N shortens by σL/E' + N Δ(σ), the
  same as N discrete joints (E' = E/(1-ν²) in plane strain, E in 3D; Δ the closed-form
  Barton-Bandis inverse), equal to solver tolerance.
- Mixed: discrete joints in the column plus a set smeared in one block.
- Staged: in-situ stress, unloading and reloading (the sets pre-closed by σ0).
- Biaxial block with two orthogonal sets: ε_xx = ((1+ν)/E)((1-ν)σ_xx - νσ_yy) - Δ(|σ_xx|)/s_x and
  alike for y.
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import InSituStress, JointedRockModel, distribute  # noqa: E402
from continuum_cases import (E, HEIGHT, NU, QUIET, bb_closure, column, material,  # noqa: E402
                             rock_strain, top_load, vertical)

JOINTS = (1.0, 2.0)
STRESS = 5e6  # σ/(K_ni V_m) = 0.5: well inside the nonlinear range


@pytest.mark.parametrize("dim", [2, 3])
def test_smeared_column_equals_the_discrete_column(dim):
    n = len(JOINTS)
    smeared = column(dim, smeared={"block_1": material(dim, [(vertical(dim), HEIGHT / n)])})
    top_load(smeared, dim, STRESS)
    res = smeared.solve()
    assert all(r.converged for r in res.reports)
    discrete = column(dim, JOINTS)
    top_load(discrete, dim, STRESS)
    discrete.solve()
    u_s = smeared.boundary_mean_displacement("top")[dim - 1]
    u_d = discrete.boundary_mean_displacement("top")[dim - 1]
    closed = -(rock_strain(dim, STRESS) * HEIGHT + n * bb_closure(STRESS))
    assert u_s == pytest.approx(closed, rel=1e-9)
    assert u_s == pytest.approx(u_d, rel=1e-9)
    # the smeared stress at every quadrature point is the uniaxial stress
    nv = smeared.smeared.nv
    stress = smeared.smeared.stress.x.array.reshape(-1, nv)
    np.testing.assert_allclose(stress[:, dim - 1], -STRESS, rtol=1e-8)
    # the joint jump of the set is the closure: opening -Δ
    jump = smeared.smeared.points[1].set_state(0)["jump"]
    np.testing.assert_allclose(jump[:, 0], -bb_closure(STRESS), rtol=1e-8)


@pytest.mark.parametrize("dim", [2, 3])
def test_mixed_discrete_joints_and_a_smeared_block(dim):
    """Two discrete joints, and a set of spacing 0.25 m smeared in the top block (height 1 m)."""
    s = 0.25
    model = column(dim, JOINTS, smeared={"block_3": material(dim, [(vertical(dim), s)])})
    top_load(model, dim, STRESS)
    model.solve()
    closed = -(rock_strain(dim, STRESS) * HEIGHT + (len(JOINTS) + 1.0 / s) * bb_closure(STRESS))
    assert model.boundary_mean_displacement("top")[dim - 1] == pytest.approx(closed, rel=1e-9)


def test_staged_in_situ_unloading_and_reloading_smeared_as_discrete():
    """σ0 = diag(-σh, -σv) with the set pre-closed to Δ(σv): the in-situ stage moves nothing;
    unloading to σv/4 and reloading to 1.25 σv move the top by (σv - σ)H/E' + N(Δ(σv) - Δ(σ)),
    for the smeared and the discrete column alike."""
    sh, sv, n = 2e6, 5e6, len(JOINTS)
    models = {"smeared": column(2, smeared={"block_1": material(2, [((0.0, 1.0), HEIGHT / n)])}),
              "discrete": column(2, JOINTS)}
    for model in models.values():
        model.set_in_situ_stress(InSituStress.uniform(np.diag([-sh, -sv])))

    def expected(sigma):
        return (sv - sigma) * HEIGHT / (E / (1 - NU**2)) + n * (bb_closure(sv) - bb_closure(sigma))

    tops = {}
    for name, model in models.items():
        model.solve(name="in-situ")
        assert np.abs(model.u.x.array).max() == 0.0
        release = model.excavate("top", fraction_left=0.25)
        model.solve(load_steps=2)
        tops[name] = [model.boundary_mean_displacement("top")[1]]
        reload = model.add_traction("top", (0.0, -sv))
        model.solve(load_steps=2)
        tops[name].append(model.boundary_mean_displacement("top")[1])
        release.value = 0.0
        reload.remove()
        model.solve(load_steps=2)
        tops[name].append(model.boundary_mean_displacement("top")[1])
    for name in models:
        np.testing.assert_allclose(tops[name], [expected(0.25 * sv), expected(1.25 * sv), expected(0.0)],
                                   rtol=1e-8, atol=1e-14)
    np.testing.assert_allclose(tops["smeared"], tops["discrete"], rtol=1e-8, atol=1e-14)


@pytest.mark.parametrize("dim", [2, 3])
def test_biaxial_block_with_two_sets(dim):
    width, height, sx, sy = 2.0, 3.0, 0.5, 0.3
    p, q = 8e6, 3e6  # σ_xx = -p, σ_yy (σ_zz in 3D) = -q
    size = (width, height) if dim == 2 else (width, width, height)
    jm = meshes.jointed_block(size, [], dim=dim, mesh_size=1.0, comm=MPI.COMM_WORLD)
    nx = (1.0, 0.0) if dim == 2 else (1.0, 0.0, 0.0)
    mat = material(dim, [(nx, sx), (vertical(dim), sy)])
    model = JointedRockModel(distribute(jm, MPI.COMM_WORLD), rock=(E, NU), joints={}, newton=QUIET,
                             plane="strain" if dim == 2 else None, continuum={"block_1": mat})
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    model.add_traction("right", [-p] + [0.0] * (dim - 1))
    top_load(model, dim, q)
    model.solve(load_steps=2)
    if dim == 2:  # plane strain
        exx = (1 + NU) / E * (-(1 - NU) * p + NU * q) - bb_closure(p) / sx
        eyy = (1 + NU) / E * (-(1 - NU) * q + NU * p) - bb_closure(q) / sy
    else:         # σ_yy = 0, free
        exx = (-p + NU * q) / E - bb_closure(p) / sx
        eyy = (-q + NU * p) / E - bb_closure(q) / sy
    assert model.boundary_mean_displacement("right")[0] == pytest.approx(exx * width, rel=1e-8)
    assert model.boundary_mean_displacement("top")[dim - 1] == pytest.approx(eyy * height, rel=1e-8)


def _bare_column(**kw):
    jm = meshes.column(1.0, HEIGHT, (), dim=2, mesh_size=1.0, comm=MPI.COMM_WORLD)
    return JointedRockModel(distribute(jm, MPI.COMM_WORLD), joints={}, **kw)


def test_bad_continuum_input():
    mat = material(2, [((0.0, 1.0), 1.0)])
    with pytest.raises(ValueError, match="differs from the block's rock"):
        _bare_column(rock=(2 * E, NU), continuum={"block_1": mat})
    with pytest.raises(ValueError, match="plane strain"):
        _bare_column(rock=(E, NU), plane="stress", continuum={"block_1": mat})
    with pytest.raises(ValueError, match="unknown block"):
        column(2, smeared={"block_9": mat})
    with pytest.raises(ValueError, match="spacing"):
        material(2, [((0.0, 1.0), 0.0)])
    with pytest.raises(ValueError, match="normal"):
        material(3, [((0.0, 1.0, 1.0), 1.0)])


def _inclined_set_column(dim, friction_deg, residual_stiffness=0.0):
    from rockjoint import continuum as rj_continuum, joint as rj_joint
    from continuum_cases import KNI, KS, VM
    import rockjoint
    th = np.radians(35.0)
    n = [-np.sin(th), np.cos(th)] if dim == 2 else [0.0, -np.sin(th), np.cos(th)]
    j = rj_joint
    b = j.JointBehaviour(rockjoint.BartonBandis(KNI, VM), shear_stiffness=KS, residual_stiffness=residual_stiffness,
                         strength=j.JointStrength(j.StrengthModel.coulomb, friction_angle=np.radians(friction_deg)))
    c = rj_continuum
    return column(dim, smeared={"block_1": c.EquivalentContinuum(dim, E, NU, [c.JointSet(n, 0.5, b)])}, mesh_size=1.0)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("state", ["stick", "slip", "open"])
def test_assembled_jacobian_matches_finite_differences(dim, state):
    """The Newton Jacobian of a smeared model (K + J_c) against central differences of the assembled
    residual, from a converged state: stick (φ = 60°), slip (φ = 20°, loaded 30 % past the converged
    step) and open (the converged displacement reversed: tension across the set; k_r = 1e6 Pa/m)."""
    from jacobian_checks import assert_jacobian_matches_fd
    model = _inclined_set_column(dim, 60.0 if state == "stick" else 20.0,
                                 residual_stiffness=1e6 if state == "open" else 0.0)
    top_load(model, dim, 2e6)
    model.solve(load_steps=2)
    factor = {"stick": 1.0, "slip": 1.3, "open": -1.0}[state]
    u0 = factor * model.u.x.array.copy()
    if state == "stick":
        u0 += 1e-7 * np.sin(np.arange(u0.size))  # off the converged point, still inside the strength
    model.u.x.array[:] = u0
    model.problem().residual_norm()
    counts = _shear_states(model, dim)
    assert counts[state] > 0, counts
    assert_jacobian_matches_fd(model, u0, 1e-6, tol=1e-5, label=f"{state} {dim}D: ")


def _shear_states(model, dim):
    """{stick, slip, open: number of points} of the smeared set's trial state (joint_response at the
    trial jump from the converged state)."""
    from rockjoint import continuum as rj_continuum, joint as rj_joint
    pts = model.smeared.points[1]
    b = pts.material.sets[0].behaviour
    trial, conv = pts.set_state(0, converged=False), pts.set_state(0, converged=True)
    names = {int(rj_joint.ShearState.stick): "stick", int(rj_joint.ShearState.slip): "slip",
             int(rj_joint.ShearState.open): "open"}
    out = {"stick": 0, "slip": 0, "open": 0}
    for jump, slip in zip(trial["jump"], conv["slip"]):
        state = rj_joint.JointPointState(slip=list(slip))
        r = rj_joint.joint_response(b, np.array(jump[:dim]), state)
        out[names[int(r["shear_state"])]] += 1
    return out


def test_restart_resets_the_smeared_state():
    """solve(restart=True) starts the smeared sets from the virgin state, as it does the discrete
    joints: the sliding column solved again from rest gives the first answer (its slip would
    otherwise start from the slip already accumulated)."""
    from continuum_cases import sliding_answer, sliding_column
    model = sliding_column()
    model.solve(load_steps=2)
    first = sliding_answer(model)
    assert first[2] > 1e-5  # the set slides
    model.solve(load_steps=2, restart=True)
    again = sliding_answer(model)
    np.testing.assert_allclose(again[0], first[0], rtol=1e-9)
    np.testing.assert_allclose(again[1], first[1], rtol=1e-9)
    assert again[2] == pytest.approx(first[2], rel=1e-9)
