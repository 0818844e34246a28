# SPDX-License-Identifier: MIT
"""Staged load paths of JointedRockModel against closed forms (serial).

Column (2D plane strain, rollers at the bottom and on the left, free right side, Barton-Bandis joints
in series with the rock): uniform uniaxial stress σ, top settlement σ H / E' + Σ Δ(σ), with Δ the
law's closed-form inverse. Gravity with lateral rollers (oedometer): u_top = ρ g H² / (2 M) + Δ(ρ g
(H - h)), M = λ + 2μ (the exact field is quadratic: P2 reproduces it). Pressure on a curved wall:
the Lamé thick-walled cylinder.
"""
import logging
import re

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

from rockjoint.fem import JointedRockModel, Stage  # noqa: E402
from staged_cases import (E, E_PLANE, M_OEDOMETER, NU, QUIET, bb_closure, column,  # noqa: E402
                          lame_radial_displacement, quarter_annulus, radial_displacement_at)

H = 2.0  # column height [m] (width 1 m)


def top_settlement(stress, joints=1):
    return -(stress * H / E_PLANE + joints * bb_closure(stress))


def test_restarting_equals_one_shot_when_loads_are_proportional():
    """0 → ½ → 1 in two stages (and three via run()) equals 0 → 1 in one, to Newton's tolerance."""
    staged = column()
    top = staged.add_traction("top", (0.0, -2.5e6))
    half = staged.solve(name="half")
    top.value = (0.0, -5e6)
    full = staged.solve(name="full")
    one_shot = column()
    one_shot.add_traction("top", (0.0, -5e6))
    one_shot.solve()
    scale = np.abs(one_shot.u.x.array).max()
    assert np.abs(staged.u.x.array - one_shot.u.x.array).max() < 1e-9 * scale
    # each stage kept its own answer: half the load gives the law's closure at half the stress
    assert [s.name for s in staged.stages] == ["half", "full"]
    np.testing.assert_allclose(half.gather_joints()["closure"], bb_closure(2.5e6), rtol=1e-8)
    np.testing.assert_allclose(full.gather_joints()["closure"], bb_closure(5e6), rtol=1e-8)
    assert half.displacement.x.array[1::2].min() == pytest.approx(top_settlement(2.5e6), rel=1e-8)

    declarative = column()
    load = declarative.add_traction("top", (0.0, 0.0))

    def to(stress):
        return lambda model: setattr(load, "value", (0.0, -stress))

    results = declarative.run([Stage("a", 1, to(1e6)), Stage("b", 2, to(3e6)), Stage("c", 1, to(5e6))])
    assert [r.name for r in results] == ["a", "b", "c"]
    assert np.abs(declarative.u.x.array - one_shot.u.x.array).max() < 1e-9 * scale


def test_restart_goes_back_to_the_initial_state():
    """solve(restart=True) after an unloading path applies the current loads from zero again."""
    model = column()
    top = model.add_traction("top", (0.0, -5e6))
    model.solve()
    top.value = (0.0, -1e6)
    model.solve()
    top.value = (0.0, -3e6)
    res = model.solve(restart=True)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(top_settlement(3e6), rel=1e-8)
    assert len(model.stages) == 3 and res is model.stages[-1]


def test_advance_continues_the_stage_to_any_load_factor():
    """advance(λ): the loads set now scaled along the stage: 0.5 and 1 give the law's closure at
    half and full stress, 1.5 overloads, 0 unloads (Barton-Bandis is reversible: u = 0); a solve()
    afterwards starts from the factor reached."""
    model = column()
    model.add_traction("top", (0.0, -4e6))
    for factor in (0.5, 1.0, 1.5):
        res = model.advance(factor, load_steps=2)
        np.testing.assert_allclose(res.gather_joints()["closure"], bb_closure(factor * 4e6), rtol=1e-8)
    model.advance(0.0, load_steps=3)
    assert np.abs(model.u.x.array).max() < 1e-12
    model.advance(0.25)
    model.solve()  # from 1 MPa (λ = 0.25) to the loads set now: 4 MPa
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(top_settlement(4e6), rel=1e-8)
    with pytest.raises(ValueError, match="load_steps"):
        model.advance(1.0, load_steps=0)


def test_loads_changed_and_removed_between_stages():
    """Unloading to zero gives back u = 0 (Barton-Bandis closes reversibly from Δ = 0), zero
    reactions; a load added in a later stage is ramped in from zero."""
    model = column()
    top = model.add_traction("top", (0.0, -5e6))
    model.solve()
    top.remove()
    unloaded = model.solve(load_steps=2)
    assert np.abs(model.u.x.array).max() < 1e-12
    assert max(abs(r) for r in unloaded.reactions.values()) < 1e-6
    with pytest.raises(RuntimeError, match="removed"):
        top.value = (0.0, 1.0)
    again = model.add_traction("top", (0.0, -3e6))
    model.solve()
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(top_settlement(3e6), rel=1e-8)
    assert again.value.tolist() == [0.0, -3e6]


def test_reactions_per_support_balance_the_applied_load():
    """Bottom roller: reaction +σ × width (upward, all of the load); the left roller carries none."""
    model = column()
    model.add_traction("top", (0.0, -5e6))
    res = model.solve()
    assert res.reactions[("bottom", "y")] == pytest.approx(5e6, rel=1e-10)
    assert abs(res.reactions[("left", "x")]) < 1e-6 * 5e6


def test_a_support_added_later_holds_the_current_position():
    """fix(value=None) after a first stage: the top stays where it is and carries all of the added
    load (reaction +added × width, upward)."""
    model = column()
    model.add_traction("top", (0.0, -2.5e6))
    model.solve()
    before = model.u.x.array.copy()
    model.fix("top", "y", value=None)
    model.add_traction("top", (0.0, -1e6))
    res = model.solve()
    assert np.abs(model.u.x.array - before).max() < 1e-12 * np.abs(before).max()
    assert res.reactions[("top", "y")] == pytest.approx(1e6, rel=1e-9)
    assert res.reactions[("bottom", "y")] == pytest.approx(2.5e6, rel=1e-9)


def test_traction_given_as_a_function_of_x():
    """t_y = -(a + b x) on the top: the bottom reaction equals its resultant a + b/2 (width 1)."""
    a, b = 2e6, 1e6
    model = column()
    model.add_traction("top", lambda x: np.vstack([0.0 * x[0], -(a + b * x[0])]))
    res = model.solve()
    assert res.reactions[("bottom", "y")] == pytest.approx(a + b / 2, rel=1e-10)


def test_gravity_on_a_column_matches_the_closed_form():
    """Self-weight, lateral rollers (oedometric), one joint at h: P2 reproduces the quadratic field."""
    rho, g, h = 2700.0, 9.81, 1.0
    model = column(height=H, joint_heights=(h,), degree=2, density=rho)
    model.fix("right", "x")
    res = model.solve()
    expected = -(rho * g * H**2 / (2 * M_OEDOMETER) + bb_closure(rho * g * (H - h)))
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(expected, rel=1e-9)
    assert res.reactions[("bottom", "y")] == pytest.approx(rho * g * H * 1.0, rel=1e-10)
    # the lateral stress of the oedometer: σ_x = ν/(1-ν) σ_y on each side, ∫ over the height
    lateral = NU / (1 - NU) * rho * g * H**2 / 2
    assert res.reactions[("left", "x")] == pytest.approx(lateral, rel=1e-9)
    assert res.reactions[("right", "x")] == pytest.approx(-lateral, rel=1e-9)
    np.testing.assert_allclose(res.gather_joints()["normal_stress"], rho * g * (H - h), rtol=1e-9)


def test_pressure_on_a_curved_hole_matches_lame():
    """Thick-walled cylinder a = 1, b = 3 m, internal pressure 2 MPa, P2 on straight-sided
    triangles: radial wall displacement within 3e-4 of Lamé on the finer mesh and converging at
    order > 1.8 (the polygonal wall is an O(h²) geometric error)."""
    a, b, p = 1.0, 3.0, 2e6
    errors = []
    for n in (4, 8):
        model = JointedRockModel(quarter_annulus(a, b, 2 * n, 6 * n), element_degree=2, rock=(E, NU),
                                 newton=QUIET)
        model.fix("left", "x")
        model.fix("bottom", "y")
        model.add_pressure("inner", p)
        res = model.solve()
        _, ur = radial_displacement_at(model, a)
        errors.append(np.abs(ur / lame_radial_displacement(a, a, b, p) - 1).max())
        # the pressure's resultant on the quarter wall, p × a per axis, goes to the symmetry supports
        assert res.reactions[("left", "x")] == pytest.approx(-p * a, rel=1e-9)
        assert res.reactions[("bottom", "y")] == pytest.approx(-p * a, rel=1e-9)
    assert errors[1] < 3e-4, errors
    assert np.log2(errors[0] / errors[1]) > 1.8, errors


def test_prescribed_displacement_gives_the_analytic_reaction():
    """Top pushed down by d: intact, σ = E' d / H; with a joint, d = σ H / E' + Δ(σ) solved for σ."""
    d = 1e-4
    intact = column(joint_heights=())
    intact.fix("top", "y", value=-d)
    res = intact.solve(load_steps=2)
    sigma = E_PLANE * d / H
    assert res.reactions[("bottom", "y")] == pytest.approx(sigma, rel=1e-9)
    assert res.reactions[("top", "y")] == pytest.approx(-sigma, rel=1e-9)
    jointed = column()
    support = jointed.fix("top", "y", value=-d)
    res = jointed.solve(load_steps=2)
    sigma = brentq(lambda s: s * H / E_PLANE + bb_closure(s) - d, 0.0, 1e9, xtol=1e-6)
    assert res.reactions[("top", "y")] == pytest.approx(-sigma, rel=1e-9)
    np.testing.assert_allclose(res.gather_joints()["closure"], bb_closure(sigma), rtol=1e-8)
    support.value = -2 * d  # displacement-controlled reloading, ramped from -d
    res = jointed.solve(load_steps=2)
    sigma = brentq(lambda s: s * H / E_PLANE + bb_closure(s) - 2 * d, 0.0, 1e9, xtol=1e-6)
    assert res.reactions[("bottom", "y")] == pytest.approx(sigma, rel=1e-9)


def test_snes_and_the_problem_object_agree_with_newton():
    newton = column()
    newton.add_traction("top", (0.0, -5e6))
    newton.solve()
    snes = column(petsc_options={"snes_linesearch_type": "basic"})
    snes.add_traction("top", (0.0, -5e6))
    res = snes.solve(solver="snes", load_steps=2)
    assert all(r.converged for r in res.reports)
    scale = np.abs(newton.u.x.array).max()
    assert np.abs(snes.u.x.array - newton.u.x.array).max() < 1e-9 * scale
    # F(x) = 0 at the converged x; J(x) is the model's Jacobian there
    problem = newton.problem()
    x = newton.u.x.petsc_vec.copy()
    b, A = problem.vector(), problem.matrix()
    problem.load_factor = 1.0
    problem.residual(x, b)
    assert b.norm() < 1e-9 * 5e6
    problem.jacobian(x, A)
    problem.update_jacobian()  # the project's Newton: at u into the problem's own J
    A.axpy(-1.0, problem.J)
    assert A.norm() < 1e-12 * problem.J.norm()


def test_progress_of_a_run_is_logged(caplog):
    model = column()
    load = model.add_traction("top", (0.0, 0.0))
    caplog.set_level(logging.INFO, logger="rockjoint.fem.mechanics.stages")
    model.run([Stage("load", 2, lambda m: setattr(load, "value", (0.0, -4e6))),
               Stage("unload", 1, lambda m: load.remove())])
    lines = [r.getMessage() for r in caplog.records if r.name == "rockjoint.fem.mechanics.stages"]
    assert any(re.match(r"stage 1/2 \(load\): λ = 0\.5 converged in \d+ Newton iteration", s) for s in lines), lines
    assert any(re.match(r"stage 2/2 \(unload\): λ = 1 converged .* s elapsed", s) for s in lines), lines


def test_bad_staged_input_is_refused_with_clear_errors():
    model = column()
    with pytest.raises(RuntimeError, match="set_in_situ_stress first"):
        model.excavate("top")
    with pytest.raises(ValueError, match="one finite number or 1"):
        model.fix("top", "y", value=[1.0, 2.0])
    with pytest.raises(ValueError, match="pressure on 'top' must be finite"):
        model.add_pressure("top", np.nan)
    with pytest.raises(ValueError, match="unknown boundary 'roof'"):
        model.add_pressure("roof", 1.0)
    with pytest.raises(ValueError, match="solver must be 'newton' or 'snes'"):
        model.solve(solver="gauss-seidel")
    with pytest.raises(ValueError, match="not a Stage"):
        model.run([("load", 1)])
    with pytest.raises(ValueError, match=r"density\['block_1'\] = -1"):
        column(density=-1.0)
    with pytest.raises(ValueError, match=r"density: no value for block\(s\) \['block_2'\]"):
        column(density={"block_1": 2700.0})
    with pytest.raises(ValueError, match="gravity = -9.81"):
        column(density=2700.0, gravity=-9.81)
