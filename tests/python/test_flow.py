# SPDX-License-Identifier: MIT
"""Flow along a joint from Python (rockjoint.flow, docs/flow.md): the array axes (rows = y), the
closure curve with flow=True against independent checks (Wiener bounds, the closure's datum, the
field-by-field answer), the transmissivity laws against their closed forms, T along load cycles
of a law with history, bad input."""
import numpy as np
import pytest

import rockjoint
from rockjoint import contact, flow
from rockjoint import topography as topo

E_STAR = rockjoint.composite_modulus(50e9, 0.25)
STRESSES = np.array([0.5e6, 2e6, 8e6, 30e6])
H = 0.25e-3


def synthetic_joint(n=64, seed=3):
    """The granite-like mated pair of the benchmarks, n x n at h = 0.25 mm."""
    upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (n, n), H, 2.5e-3, seed=seed)
    return topo.composite_topography(upper, lower).aperture


def test_parallel_plates_from_an_array_and_from_a_surface():
    e = 1.3e-4
    field = np.full((12, 20), e)
    for t in (flow.transmissivity(field, (2e-4, 1e-4)), flow.transmissivity(topo.Surface(field, 2e-4, 1e-4))):
        np.testing.assert_allclose(t.tensor, np.diag([e ** 3 / 12] * 2), rtol=1e-10, atol=1e-12 * e ** 3)
        assert t.hydraulic_aperture == pytest.approx(e, rel=1e-10)
        np.testing.assert_allclose(t.principal_hydraulic_apertures, [e, e], rtol=1e-10)


@pytest.mark.parametrize("periodic", [True, False])
def test_columns_are_x_rows_are_y(periodic):
    """An aperture that changes from column to column (along x) is in series along x (harmonic
    mean of e³) and side by side along y (arithmetic mean): the numpy axes are (y, x)."""
    e_of_column = np.array([1e-4, 2e-4, 0.5e-4, 3e-4, 1.5e-4])
    field = np.tile(e_of_column, (7, 1))          # rows = y, columns = x
    t = flow.transmissivity(field, 1e-3, periodic=periodic)
    k = e_of_column ** 3 / 12
    assert t.tensor[0, 0] == pytest.approx(1 / np.mean(1 / k), rel=1e-10)   # harmonic along x
    assert t.tensor[1, 1] == pytest.approx(np.mean(k), rel=1e-10)           # arithmetic along y


@pytest.fixture(scope="module")
def curve():
    return contact.closure_curve(synthetic_joint(), E_STAR, STRESSES, keep_fields=True, flow=True)


def test_closure_curve_with_flow_matches_the_field_by_field_answer(curve):
    for g, txx, tyy, txy, f in zip(curve.gap, curve.transmissivity_xx, curve.transmissivity_yy,
                                   curve.transmissivity_xy, curve.flow_results):
        alone = flow.transmissivity(g, H, solver="simplicial_cholesky")   # another factorisation
        np.testing.assert_allclose([txx, tyy, txy], [alone.tensor[0, 0], alone.tensor[1, 1],
                                                     alone.tensor[0, 1]], rtol=1e-9)
        assert abs(f.tensor[0, 1] - f.tensor[1, 0]) <= 1e-9 * f.tensor[0, 0]   # periodic: symmetric


def test_flow_columns_obey_wiener_bounds_and_the_closure_datum(curve):
    """Independent of the solver: the effective transmissivity lies between the harmonic and the
    arithmetic means of e³/12 (Wiener bounds); the mean gap is mean(e) - Δ (the closure's datum,
    docs/contact.md); T and e_h fall as the joint closes, e_h below the mean aperture."""
    e0 = curve.initial_flow.mechanical_aperture
    np.testing.assert_allclose(curve.mechanical_aperture, e0 - curve.closure, rtol=1e-9)
    for g, f in zip(curve.gap, curve.flow_results):
        k = g ** 3 / 12
        lower = 0.0 if np.any(k == 0) else 1 / np.mean(1 / k)
        t1, t2 = f.principal
        assert lower <= t2 <= t1 <= np.mean(k)
    assert np.all(np.diff(curve.transmissivity_xx) < 0) and np.all(np.diff(curve.transmissivity_yy) < 0)
    ratio = curve.hydraulic_aperture / curve.mechanical_aperture
    assert np.all(ratio < 1) and np.all(np.diff(ratio) < 0), ratio
    assert curve.initial_flow.hydraulic_aperture > curve.hydraulic_aperture[0]


def test_sealed_sides_closure_curve_has_flow_too():
    c = contact.closure_curve(synthetic_joint(32, seed=5), E_STAR, STRESSES[:2], periodic=False, flow=True)
    assert c.transmissivity_xx.shape == (2,) and np.all(c.transmissivity_xx > 0)
    assert c.initial_flow.periodic is False


def test_existing_api_unchanged_without_flow():
    c = contact.closure_curve(synthetic_joint(32), E_STAR, STRESSES[:2])
    assert c.transmissivity_xx is None and c.initial_flow is None and c.gap is None


def test_walls_law_goes_through_the_curve_and_falls_monotonically(curve):
    law = flow.transmissivity_law("walls", curve=curve)
    t_mean = 0.5 * (curve.transmissivity_xx + curve.transmissivity_yy)
    np.testing.assert_allclose(law.transmissivity(curve.closure), t_mean, rtol=1e-12)
    assert law.transmissivity(0.0) == pytest.approx(curve.initial_flow.mean, rel=1e-12)
    fine = np.linspace(0, 1.5 * curve.closure[-1], 400)
    assert np.all(np.diff(law.transmissivity(fine)) < 0)
    np.testing.assert_allclose(law.mechanical_aperture(curve.closure), curve.mechanical_aperture, rtol=1e-9)
    xx = flow.transmissivity_law("walls", curve=curve, component="xx")
    np.testing.assert_allclose(xx.transmissivity(curve.closure), curve.transmissivity_xx, rtol=1e-12)


def test_parametric_laws_are_their_closed_forms():
    e0, jrc = 400e-6, 10.0
    d = np.array([0.0, 100e-6, 300e-6, 390e-6, 500e-6])
    e = np.maximum(e0 - d, 0)
    cubic = flow.transmissivity_law("cubic_law", initial_aperture=e0)
    np.testing.assert_allclose(cubic.transmissivity(d), e ** 3 / 12, rtol=1e-14)
    barton = flow.transmissivity_law("barton_jrc", initial_aperture=e0, jrc=jrc)
    e_um = e * 1e6
    e_h = np.minimum(e_um ** 2 / jrc ** 2.5, e_um) * 1e-6   # e ≥ e_h (Barton et al. 1985)
    np.testing.assert_allclose(barton.hydraulic_aperture(d), e_h, rtol=1e-12)
    # JRC 10: JRC^2.5 = 316.2 µm. e = 300 µm: e_h = 9e4/316.2 = 284.6 µm; e = 100 µm: 31.6 µm;
    # e = 400 µm: 506 µm > e, so e_h = e (the conversion holds for e >= e_h)
    assert barton.hydraulic_aperture(100e-6) == pytest.approx(284.6e-6, rel=1e-3)
    assert barton.hydraulic_aperture(300e-6) == pytest.approx(31.62e-6, rel=1e-3)
    assert barton.hydraulic_aperture(0.0) == pytest.approx(400e-6, rel=1e-12)


def test_transmissivity_follows_the_closure_of_a_law_with_history():
    """Load, unload, reload a hysteretic joint: T at a stress on the unloading branch is below T
    at the same stress on first loading (the permanent closure), and equals T(Δ) of the branch
    closure."""
    virgin = rockjoint.BartonBandis(initial_normal_stiffness=20e9, maximum_closure=0.2e-3)
    joint = rockjoint.NormalHysteresis(virgin, permanent_fraction=0.3, unloading_exponent=3.0)
    law = flow.transmissivity_law("cubic_law", initial_aperture=0.25e-3)
    path = np.array([1e6, 5e6, 10e6, 5e6, 1e6, 5e6, 10e6])
    t = flow.transmissivity_along(law, joint, path)
    np.testing.assert_allclose(t, law.transmissivity(joint.closure_path(path)), rtol=1e-14)
    assert t[3] < t[1] and t[4] < t[0]          # unloading: closed more than on first loading
    assert t[6] == pytest.approx(t[2], rel=1e-9)  # back to the largest closure
    assert t[5] == pytest.approx(t[3], rel=1e-9)  # reloading retraces the unloading branch
    # without history: the virgin curve
    np.testing.assert_allclose(flow.transmissivity_along(law, virgin, path[:3]),
                               law.transmissivity(virgin.closure_at_stress(path[:3])), rtol=1e-14)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match=r"row 1, column 2.*>= 0"):
        flow.transmissivity(np.array([[1e-4, 1e-4, 1e-4], [1e-4, 1e-4, -1e-6]]), 1e-4)
    with pytest.raises(ValueError, match="spacing_x"):
        flow.transmissivity(np.full((3, 3), 1e-4), float("nan"))
    with pytest.raises(ValueError, match="no scanned point"):
        flow.transmissivity(np.full((3, 3), np.nan), 1e-4)
    with pytest.raises(ValueError, match="2-D"):
        flow.transmissivity(np.full(9, 1e-4), 1e-4)
    with pytest.raises(ValueError, match="at least 2 rows"):
        flow.transmissivity(np.full((1, 9), 1e-4), 1e-4)
    with pytest.raises(ValueError, match="solver 'lu'"):
        flow.transmissivity(np.full((3, 3), 1e-4), 1e-4, solver="lu")
    with pytest.raises(ValueError, match="its own spacing"):
        flow.transmissivity(topo.Surface(np.full((3, 3), 1e-4), 1e-4), 1e-4)
    with pytest.raises(ValueError, match="must be a 4 x 4 array"):
        flow.ApertureFlow((4, 4), 1e-4)(np.full((4, 5), 1e-4))
    with pytest.raises(ValueError, match="unknown transmissivity law 'poiseuille'"):
        flow.transmissivity_law("poiseuille")
    with pytest.raises(ValueError, match="missing jrc"):
        flow.transmissivity_law("barton_jrc", initial_aperture=1e-4)
    with pytest.raises(ValueError, match="initial_aperture = -0.0001 m"):
        flow.transmissivity_law("cubic_law", initial_aperture=-1e-4)
    with pytest.raises(ValueError, match="flow=True"):
        flow.transmissivity_law("walls", curve=contact.closure_curve(synthetic_joint(16), E_STAR, [1e6]))
    with pytest.raises(ValueError, match="NaN"):
        flow.transmissivity_law("cubic_law", initial_aperture=1e-4).transmissivity([0.0, float("nan")])
