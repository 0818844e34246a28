# SPDX-License-Identifier: MIT
"""GreenwoodWilliamson / TangSubstrate bindings: numpy in/out, keyword arguments in SI,
distributions by name or as an empirical list, ValueError naming the parameter."""
import math

import numpy as np
import pytest

import rockjoint

E_STAR = 50e9 / (2 * (1 - 0.25**2))  # E 50 GPa, ν 0.25 (theory §7)
ETA, BETA, SIGMA_S = 0.3e6, 2.5e-3, 0.05e-3  # 1/m², m, m


def test_gw_exponential_matches_closed_form_on_arrays():
    law = rockjoint.GreenwoodWilliamson(E_STAR, ETA, BETA, SIGMA_S, distribution="exponential")
    assert law.distribution == "exponential"
    assert law.reference_separation == pytest.approx(4.5 * SIGMA_S, rel=1e-15)
    d = np.array([[-1e-5, 0.0], [1e-6, 2e-4]])
    s, k, a, status = law.evaluate(d)
    assert s.shape == d.shape and status.shape == d.shape
    h = (law.reference_separation - d) / SIGMA_S
    total = math.sqrt(math.pi) * E_STAR * ETA * math.sqrt(BETA) * SIGMA_S**1.5 * np.exp(-h)
    contact = d > 0
    np.testing.assert_allclose(s[contact] + law.seating_stress, total[contact], rtol=1e-12)
    np.testing.assert_allclose(k[contact], total[contact] / SIGMA_S, rtol=1e-12)
    np.testing.assert_allclose(a[contact], math.pi * ETA * BETA * SIGMA_S * np.exp(-h[contact]),
                               rtol=1e-12)
    assert np.all(s[~contact] == 0) and set(status[~contact]) == {int(rockjoint.Status.open)}
    np.testing.assert_allclose(law.closure_at_stress(s[contact]), d[contact], rtol=1e-10)


def test_tang_section7_example_and_properties():
    law = rockjoint.TangSubstrate(E_STAR, ETA, BETA, SIGMA_S, base_radius=1e-3)
    assert law.deflection_coefficient == pytest.approx(8 / (3 * math.pi))
    assert law.base_radius == 1e-3
    p = law.asperity_parameters
    assert (p.composite_modulus, p.summit_density, p.summit_radius, p.summit_height_std) == (
        E_STAR, ETA, BETA, SIGMA_S)
    closure = law.closure_at_stress(10e6)
    assert isinstance(closure, float) and 0.12e-3 < closure < 0.13e-3
    assert 0.007 < law.contact_area_ratio(closure) < 0.009
    default = rockjoint.TangSubstrate(E_STAR, ETA, BETA, SIGMA_S)
    assert default.base_radius == pytest.approx(0.5 / math.sqrt(ETA))
    gw = rockjoint.GreenwoodWilliamson(E_STAR, ETA, BETA, SIGMA_S)
    plain = rockjoint.TangSubstrate(E_STAR, ETA, BETA, SIGMA_S, deflection_coefficient=0.0)
    d = np.linspace(1e-6, 3e-4, 7)
    np.testing.assert_array_equal(plain.normal_stress(d), gw.normal_stress(d))


def test_empirical_single_summit_is_hertz():
    radius, area = 2e-3, 1e-6
    law = rockjoint.GreenwoodWilliamson(E_STAR, distribution=([0.0], np.array([radius]), area))
    assert law.distribution == "empirical"
    w = np.array([1e-9, 1e-6])
    hertz = 4 / 3 * E_STAR * math.sqrt(radius) * w**1.5 / area
    np.testing.assert_allclose(law.normal_stress(w), hertz, rtol=1e-14)
    assert law.asperity_parameters.summit_density == pytest.approx(1 / area)


def test_seating_stress_reference():
    law = rockjoint.GreenwoodWilliamson(E_STAR, ETA, BETA, SIGMA_S, seating_stress=1e4)
    assert law.seating_stress == pytest.approx(1e4, rel=1e-12)
    s, _, _, _ = law.response_at_separation(law.reference_separation)
    assert s == pytest.approx(1e4, rel=1e-12)


@pytest.mark.parametrize("name, kwargs", [
    ("summit_height_std", dict(summit_height_std=-1.0)),
    ("summit_density", dict(summit_density=math.nan)),
    ("composite_modulus", dict(composite_modulus=math.inf)),
    ("seating_stress", dict(seating_stress=0.0)),
    ("quadrature_tolerance", dict(quadrature_tolerance=1.5)),
    ("base_radius", dict(base_radius=-1e-3)),
    ("deflection_coefficient", dict(deflection_coefficient=-0.1)),
])
def test_bad_parameters_name_the_parameter(name, kwargs):
    args = dict(composite_modulus=E_STAR, summit_density=ETA, summit_radius=BETA,
                summit_height_std=SIGMA_S)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        rockjoint.TangSubstrate(**args)


def test_bad_distributions_are_clear_errors():
    with pytest.raises(ValueError, match="distribution 'weibull'"):
        rockjoint.GreenwoodWilliamson(E_STAR, ETA, BETA, SIGMA_S, distribution="weibull")
    with pytest.raises(ValueError, match="summit_radius"):
        rockjoint.GreenwoodWilliamson(E_STAR, ETA, None, SIGMA_S)
    with pytest.raises(ValueError, match=r"radii\[1\]"):
        rockjoint.GreenwoodWilliamson(E_STAR, distribution=([0, 1e-6], [1e-3, 0.0], 1e-6))
    with pytest.raises(ValueError, match="heights"):
        rockjoint.GreenwoodWilliamson(E_STAR, distribution=([], [], 1e-6))
    with pytest.raises(ValueError, match="derived"):
        rockjoint.GreenwoodWilliamson(E_STAR, ETA, distribution=([0.0], [1e-3], 1e-6))
    with pytest.raises(ValueError, match="not both"):
        rockjoint.GreenwoodWilliamson(E_STAR, ETA, BETA, SIGMA_S, seating_stress=1.0,
                                      reference_separation=0.0)
