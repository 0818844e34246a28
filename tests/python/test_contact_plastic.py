# SPDX-License-Identifier: MIT
"""Elastic-perfectly-plastic contact reference (pressure capped at the indentation hardness H,
docs/contact.md): infinite-like hardness equals the elastic solver, a flat punch carries H over
its area at full plasticity, a sphere past yield has a mean contact pressure that tends to H (the
definition of indentation hardness) while below yield it is Hertz's elastic answer, and a load
cycle leaves a permanent closure, unloads stiffer than it loaded and reloads along its unloading
curve up to the previous maximum."""
import math

import numpy as np
import pytest

import rockjoint
from rockjoint import contact
from rockjoint import topography as topo

from test_contact import band_limited_aperture

E_STAR = rockjoint.composite_modulus(50e9, 0.25)


def test_unreached_hardness_equals_the_elastic_solver():
    ap = band_limited_aperture(64)
    path = [2e6, 8e6, 20e6, 8e6, 2e6]
    elastic = contact.closure_curve(ap, E_STAR, path, tolerance=1e-12)
    capped = contact.closure_curve(ap, E_STAR, path, tolerance=1e-12, hardness=1e15)
    np.testing.assert_allclose(capped.closure, elastic.closure, rtol=1e-10)
    np.testing.assert_array_equal(capped.plastic_area_ratio, 0.0)
    assert capped.unloaded_closure == 0.0 and elastic.unloaded_closure == 0.0
    # elastic walls retrace: the same closure at the same stress up and down
    assert elastic.closure[1] == pytest.approx(elastic.closure[3], rel=1e-8)


def flat_punch(n=64, radius_points=8, side=8e-3):
    x = (np.arange(n) - n / 2) * side / n
    X, Y = np.meshgrid(x, x)
    e = np.where(np.hypot(X, Y) <= radius_points * side / n, 0.0, 10e-3)   # outside: never touches
    return topo.Surface(e, side / n), int(np.count_nonzero(e == 0.0))


def test_flat_punch_carries_the_hardness_over_its_area_at_full_plasticity():
    hardness = 2e9
    ap, n_disc = flat_punch()
    n = ap.shape[0] * ap.shape[1]
    limit = hardness * n_disc / n          # mean stress at which the whole flat top is at H
    elastic = contact.closure_curve(ap, E_STAR, [0.5 * limit], keep_fields=True)
    assert np.nanmax(elastic.pressure[0]) > hardness    # the punch's edge exceeds H elastically
    # 1e-3 below the limit load the whole top must press at H to within N_disc 1e-3 H (the
    # deficit Σ(H - p) is 1e-3 H N_disc and no point is above H): the hard case of the cap. (Closer
    # to the limit the punch sinks without bound and the surroundings, 10 mm away, come into play.)
    c = contact.closure_curve(ap, E_STAR, [0.5 * limit], keep_fields=True, hardness=hardness,
                              tolerance=1e-9)
    full = contact.closure_curve(ap, E_STAR, [(1 - 1e-3) * limit], keep_fields=True,
                                 hardness=hardness, tolerance=1e-9)
    c.pressure.append(full.pressure[0])
    c.stress = np.append(c.stress, full.stress)
    c.plastic_area_ratio = np.append(c.plastic_area_ratio, full.plastic_area_ratio)
    assert 0 < c.plastic_area_ratio[0] * n < n_disc        # the edge yields first
    top = c.pressure[1][ap.heights == 0.0]
    assert top.min() >= hardness * (1 - 1.01e-3 * n_disc)  # the whole flat top presses at H
    assert np.count_nonzero(c.pressure[1] > 0) == n_disc   # nothing outside the flat top touches


def paraboloid(n=128, side=4e-3, radius=5e-3):
    x = (np.arange(n) - n / 2) * side / n
    X, Y = np.meshgrid(x, x)
    return topo.Surface((X**2 + Y**2) / (2 * radius), side / n), radius


def test_sphere_below_yield_is_elastic_and_far_past_it_presses_at_the_hardness():
    ap, radius = paraboloid()
    n = ap.shape[0] * ap.shape[1]
    hardness = 0.3e9   # yield at a = π H R / (2 E*) = 0.09 mm; at 60 F_y the contact is ~0.5 mm wide
    # Hertz: p0 = (6 F E*² / (π³ R²))^(1/3); yield of the cap at p0 = H
    f_yield = (hardness ** 3) * math.pi ** 3 * radius ** 2 / (6 * E_STAR ** 2)
    low = 0.3 * f_yield / (n * ap.spacing_x ** 2)          # mean stresses [Pa] on the cell
    high = 60 * f_yield / (n * ap.spacing_x ** 2)
    elastic = contact.closure_curve(ap, E_STAR, [low], keep_fields=True)
    c = contact.closure_curve(ap, E_STAR, [low, high], keep_fields=True, hardness=hardness)
    assert c.closure[0] == pytest.approx(elastic.closure[0], rel=1e-9)   # below yield: elastic
    assert c.plastic_area_ratio[0] == 0.0
    p = c.pressure[1]
    in_contact = p > 0
    mean_contact_pressure = np.nansum(p) / np.count_nonzero(in_contact)
    assert np.nanmax(p) <= hardness * (1 + 1e-6)
    assert 0.85 * hardness < mean_contact_pressure <= hardness
    assert c.plastic_area_ratio[1] > 0.5 * np.count_nonzero(in_contact) / n


def test_load_cycle_leaves_a_permanent_closure_and_reloads_on_the_unloading_curve():
    ap = band_limited_aperture(64)
    path = [5e6, 20e6, 5e6, 20e6, 40e6]
    c = contact.closure_curve(ap, E_STAR, path, hardness=0.1e9, tolerance=1e-11)
    assert c.plastic_area_ratio[1] > 0 and c.mean_flattening[1] > 0
    assert c.closure[2] > c.closure[0]                   # unloading stays more closed
    assert c.closure[3] == pytest.approx(c.closure[1], rel=1e-6)   # reload to the maximum
    assert c.closure[4] > c.closure[3]                   # then further on first loading
    # stiffer unloading: closure recovered from 20 to 5 MPa < closure gained on first loading
    assert c.closure[1] - c.closure[2] < c.closure[1] - c.closure[0]
    assert 0 < c.unloaded_closure < c.closure[2]
