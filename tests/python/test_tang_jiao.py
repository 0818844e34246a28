# SPDX-License-Identifier: MIT
"""Tang & Jiao (2018) from Python: numpy in/out, references written here, errors as ValueError."""
import math

import numpy as np
import pytest

import rockjoint

E_STAR = 50e9 / (2 * (1 - 0.25**2))  # Pa, theory §7 rock
BETA, SIGMA_S = 2.5e-3, 0.05e-3  # m


def q_ref(s):
    """Q(s) = (2/π)[arccos s + s√(1-s²)] written out (numpy, s >= 1e-2)."""
    s = np.asarray(s, dtype=float)
    return 2 / np.pi * (np.arccos(s) + s * np.sqrt(1 - s * s))


def overlap(length=0.2e-3, n=801, top=1e-3, seated=0.0):
    """Samples of 0.5 (1 - e^{-Δ/L}), plus a seating area ratio `seated` at Δ = 0."""
    x = np.linspace(0.0, top, n)
    return x, seated + (0.5 - seated) * (1 - np.exp(-x / length))


def make_law(seated=0.0, **kw):
    base = rockjoint.LogarithmicLaw(0.05e-3, 0.1e6)
    x, y = overlap(seated=seated)
    opts = dict(overlap_closure=x, overlap_area_ratio=y, maximum_area_root=0.6)
    opts.update(kw)
    return base, rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S, **opts)


def test_i1_is_base_stress_over_q_on_arrays():
    base, law = make_law()
    d = np.array([[2e-5, 5e-5], [1e-4, 2e-4]])
    s, k, a, status = law.evaluate(d)
    assert s.shape == d.shape and status.shape == d.shape
    ratio = 0.5 * (1 - np.exp(-d / 0.2e-3))
    # Consistent seating (theory §5): F = σ_model/Q(s) - σ_seat/Q(s0), here s0 = 0.
    seat = base.seating_stress
    expected = (base.normal_stress(d) + seat) / q_ref(np.sqrt(ratio)) - seat
    np.testing.assert_allclose(s, expected, rtol=1e-5)  # interpolated overlap curve
    np.testing.assert_allclose(a, ratio, rtol=1e-4)
    assert np.all(status == int(rockjoint.Status.contact))
    assert np.all(k > 0)
    # Tangent against central differences.
    h = 1e-7 * d
    fd = (law.normal_stress(d + h) - law.normal_stress(d - h)) / (2 * h)
    np.testing.assert_allclose(k, fd, rtol=1e-6)
    # Inverse.
    np.testing.assert_allclose(law.closure_at_stress(s), d, rtol=1e-10)
    assert law.variant == "I1" and law.name == "tang_jiao"
    assert law.contact_radius == pytest.approx(0.75 * math.sqrt(math.pi * BETA * SIGMA_S))


def test_validity_limit_frozen_and_inverse_raises():
    _, law = make_law()
    dmax = law.maximum_closure
    assert dmax == pytest.approx(-0.2e-3 * math.log(1 - 2 * 0.36), rel=1e-5)
    assert law.limit == rockjoint.TangJiaoLimit.area_root
    s, k, a, status = law.evaluate(np.array([dmax, 2 * dmax, 1.0]))
    assert np.all(status == int(rockjoint.Status.validity_limit))
    assert np.all(np.isfinite(s)) and np.all(np.isfinite(k))
    assert np.all(s == s[0])
    with pytest.raises(ValueError, match="validity limit"):
        law.closure_at_stress(2 * s[0])


def test_i2_needs_a_seated_area_and_shifts_closure():
    # Area vanishing at Δ = 0 under a stress linear in Δ: ε ~ √Δ, I2 has no monotone branch.
    with pytest.raises(ValueError, match="no monotone branch"):
        make_law(variant="I2")
    # With a seating contact area (A/A0 = s0² = 1e-4 at Δ = 0, as a GW reference gives) it
    # works. Near Δ = 0, F ≈ F'(0) ξ and ξ ≈ Δ/(1 - ε'(0)) with
    # ε'(0) = (2a/E*) F'(0) √(1-s0²)/s0, F'(0) = k3(0)/Q(s0) - σ0 Q_Δ(0)/Q(s0)² with
    # k3(0) = σ0/B, Q_Δ = -(2/π) s0 A'(0)/√(1-s0²), A'(0) = (0.5 - s0²)/L:
    # σ_I2/σ_I1 - 1 → ε'(0)/(1 - ε'(0)).
    base, i1 = make_law(seated=1e-4)
    _, i2 = make_law(seated=1e-4, variant="I2")
    assert i2.variant == "I2"
    s0 = 1e-2
    q0 = float(q_ref(s0))
    dq0 = -2 / math.pi * s0 * (0.5 - s0 * s0) / 0.2e-3 / math.sqrt(1 - s0 * s0)
    slope = 0.1e6 / 0.05e-3 / q0 - 0.1e6 * dq0 / q0**2
    rate = 2 * i2.contact_radius / E_STAR * slope * math.sqrt(1 - s0 * s0) / s0
    rel = i2.normal_stress(1e-12) / i1.normal_stress(1e-12) - 1
    assert rel == pytest.approx(rate / (1 - rate), rel=1e-4)
    # Parametric reference: Δ = ξ - ε(ξ), ε = (2F/E*)√(b²-a²) with b = a/s.
    xi = 1e-4
    st = i2.state(xi)
    a = i2.contact_radius
    b = a / st["area_root"]
    eps = 2 * st["normal_stress"] / E_STAR * math.sqrt(b * b - a * a)
    assert st["closure_shift"] == pytest.approx(eps, rel=1e-12)
    assert i2.normal_stress(xi - eps) == pytest.approx(st["normal_stress"], rel=1e-11)
    assert i2.internal_closure(xi - eps) == pytest.approx(xi, rel=1e-12)


def test_interaction_cell_closed_form_and_papers_algorithm():
    a = 0.75 * math.sqrt(math.pi * BETA * SIGMA_S)
    for s in (1e-3, 0.1, 0.5, 0.9):
        cell = rockjoint.InteractionCell(E_STAR, BETA, a, s)
        b = a / s
        pbar = 4 * E_STAR * a / (3 * math.pi * BETA) * s * s / float(
            rockjoint._cpp_constitutive.load_fraction(s))
        assert cell.mean_pressure == pytest.approx(pbar, rel=1e-14)
        assert cell.load == pytest.approx(pbar * math.pi * b * b, rel=1e-13)
        num = rockjoint.NumericInteractionCell(E_STAR, BETA, a, s, quadrature_order=32)
        assert num.converged
        assert num.mean_pressure == pytest.approx(cell.mean_pressure, rel=1e-6)
        assert num.load == pytest.approx(cell.load, rel=1e-6)
        r = np.linspace(0, 0.99 * a, 7)
        np.testing.assert_allclose(num.pressure(r), cell.pressure(r), rtol=1e-6)
        assert cell.pressure(np.array([a]))[0] == 0.0
    q = rockjoint._cpp_constitutive.load_fraction(np.array([0.0, 1.0]))
    np.testing.assert_allclose(q, [1.0, 0.0], atol=1e-16)
    small = rockjoint._cpp_constitutive.interaction_fraction(1e-4)
    assert small == pytest.approx(4e-12 / (3 * math.pi), rel=1e-7)


def test_bad_input_is_value_error_naming_the_parameter():
    base = rockjoint.LogarithmicLaw(0.05e-3, 0.1e6)
    x, y = overlap()
    with pytest.raises(ValueError, match="composite_modulus"):
        rockjoint.TangJiao(base, -1.0, BETA, SIGMA_S, overlap_closure=x, overlap_area_ratio=y)
    with pytest.raises(ValueError, match="summit_height_std"):
        rockjoint.TangJiao(base, E_STAR, BETA, math.nan, overlap_closure=x, overlap_area_ratio=y)
    with pytest.raises(ValueError, match="provides no contact area"):
        rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S)
    with pytest.raises(ValueError, match="not an asperity law"):
        rockjoint.TangJiao(base)
    with pytest.raises(ValueError, match="variant"):
        rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S, variant="I3",
                           overlap_closure=x, overlap_area_ratio=y)
    with pytest.raises(ValueError, match="maximum_area_root"):
        rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S, overlap_closure=x,
                           overlap_area_ratio=y, maximum_area_root=1.0)
    with pytest.raises(ValueError, match="overlap_area_ratio"):
        rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S, overlap_closure=x,
                           overlap_area_ratio=y[::-1])
    with pytest.raises(ValueError, match="at least 2"):
        rockjoint.TangJiao(base, E_STAR, BETA, SIGMA_S, overlap_closure=[0.0],
                           overlap_area_ratio=[0.0])
    _, law = make_law()
    with pytest.raises(ValueError, match="closure contains NaN"):
        law.normal_stress(np.array([1e-5, math.nan]))
    with pytest.raises(ValueError):
        rockjoint.InteractionCell(E_STAR, BETA, 1e-4, 1.0)


def test_over_tang_substrate_from_asperity_parameters():
    base = rockjoint.TangSubstrate(E_STAR, 0.3e6, BETA, SIGMA_S)   # an API change fails here
    law = rockjoint.TangJiao(base)  # E*, β, σ_s from the asperity law
    d = np.array([1e-5, 5e-5])
    f3 = base.normal_stress(d)
    s = np.sqrt(base.contact_area_ratio(d))
    # On the models' total stresses: F_model/σ_model - 1 = 1/Q - 1 ≈ 4s³/(3π).
    total = (law.normal_stress(d) + law.seating_stress) / (f3 + base.seating_stress)
    np.testing.assert_allclose(total - 1, 4 * s**3 / (3 * np.pi), rtol=1e-2)
