# SPDX-License-Identifier: MIT
"""The Python layer of the closure laws: numpy in/out, scalars stay scalars, clear errors."""
import math

import numpy as np
import pytest

import rockjoint


def test_barton_bandis_matches_hyperbola_on_arrays():
    kni, vm = 20e9, 0.3e-3
    law = rockjoint.BartonBandis(kni, vm)
    d = np.linspace(-1e-4, 0.29e-3, 101)
    s, k, a, status = law.evaluate(d)
    ref = np.where(d > 0, kni * d / (1 - d / vm), 0.0)
    np.testing.assert_allclose(s, ref, rtol=1e-13, atol=0)
    assert np.all(k[d > 0] > 0) and np.all(k[d <= 0] == 0)
    assert set(status[d <= 0]) == {int(rockjoint.Status.open)}
    np.testing.assert_allclose(law.closure_at_stress(s[d > 0]), d[d > 0], rtol=1e-12)


def test_scalars_stay_scalars():
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    assert isinstance(law.normal_stress(1e-4), float)
    assert law.normal_stiffness(0.0) == 0.0


def test_nan_closure_is_a_clear_error():
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    with pytest.raises(ValueError, match="closure contains NaN"):
        law.normal_stress(np.array([1e-5, math.nan]))


def test_bad_parameters_name_the_parameter():
    with pytest.raises(ValueError, match="maximum_closure.*-1"):
        rockjoint.BartonBandis(20e9, -1.0)


def test_composite_modulus_of_one_rock():
    assert rockjoint.composite_modulus(50e9, 0.25) == pytest.approx(50e9 / (2 * (1 - 0.25**2)))
    with pytest.raises(ValueError, match="poisson"):
        rockjoint.composite_modulus(50e9, 0.7)
