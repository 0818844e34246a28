# SPDX-License-Identifier: MIT
"""The transmissivity law with history (rockjoint.flow_history, docs/flow.md "Transmissivity with
history (issue 41)"): against its closed form written out here (T1-T3), the virgin law where no
unloading happened, the registry record, T along a load cycle of a hysteretic closure law, and
bad parameters named."""
import numpy as np
import pytest

import rockjoint
from rockjoint import flow

E0 = 0.3e-3                    # initial aperture [m]
LOSS = 0.3


def closed_form(closure, peak, e0=E0, loss=LOSS):
    """(T1-T2) over the cubic law, independently: e_v = e0 - Δ."""
    closure, peak = np.asarray(closure, float), np.maximum(np.asarray(peak, float), closure)
    e_now, e_peak = e0 - closure, e0 - peak
    e_h = e_peak + (1 - loss) * (e_now - e_peak)
    return e_h ** 3 / 12


def test_branch_against_the_closed_form_and_the_virgin_law():
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=LOSS)
    virgin = flow.transmissivity_law("cubic_law", initial_aperture=E0)
    closure = np.linspace(0.0, 0.2e-3, 21)
    peak = 0.2e-3
    np.testing.assert_allclose(law.transmissivity(closure, peak), closed_form(closure, peak), rtol=1e-13)
    # first loading (no Δ_m, or Δ_m <= Δ): the virgin law
    np.testing.assert_allclose(law.transmissivity(closure), virgin.transmissivity(closure), rtol=1e-13)
    np.testing.assert_allclose(law.transmissivity(closure, 0.0), virgin.transmissivity(closure), rtol=1e-13)
    # below the peak: under the virgin law, continuous at the peak, T3's ratio
    assert np.all(law.transmissivity(closure[:-1], peak) < virgin.transmissivity(closure[:-1]))
    assert law.transmissivity(peak, peak) == pytest.approx(virgin.transmissivity(peak), rel=1e-14)
    ratio = law.transmissivity(0.0, peak) / virgin.transmissivity(0.0)
    assert ratio == pytest.approx(((1 - LOSS) + LOSS * (E0 - peak) / E0) ** 3, rel=1e-13)
    # d = 0: no history at all
    none = flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=0.0)
    np.testing.assert_allclose(none.transmissivity(closure, peak), virgin.transmissivity(closure), rtol=1e-13)
    assert law.has_history and not getattr(virgin, "has_history", False)


def test_barton_virgin_and_the_registry_record():
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=LOSS,
                                  virgin="barton_jrc", jrc=8.0)
    e = lambda d: np.minimum(((E0 - d) / 1e-6) ** 2 / 8.0 ** 2.5, (E0 - d) / 1e-6) * 1e-6   # Barton, µm
    peak, d = 0.15e-3, np.array([0.0, 0.05e-3, 0.1e-3])
    e_h = e(peak) + (1 - LOSS) * (e(d) - e(peak))
    np.testing.assert_allclose(law.transmissivity(d, peak), e_h ** 3 / 12, rtol=1e-12)
    record = flow.TRANSMISSIVITY_LAWS["hydraulic_history"]
    assert "hydraulic_loss" in record.parameters and not flow.built_from_walls("hydraulic_history")
    assert flow.user_parameters("hydraulic_history", required=True) == ["initial_aperture", "hydraulic_loss"]


def test_along_a_load_cycle_of_a_hysteretic_closure_law():
    """Loading to 10 MPa, unloading to 0.5, reloading to 10 and on to 15 MPa: T on the branches
    from the closed form at the path's Δ and running Δ_m; reloading retraces unloading."""
    closure_law = rockjoint.NormalHysteresis(rockjoint.BartonBandis(5e10, 0.25e-3), 0.25, 3.0)
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=LOSS)
    path = np.array([2, 5, 10, 5, 0.5, 5, 10, 15]) * 1e6
    t = flow.transmissivity_along(law, closure_law, path)
    d = np.asarray(closure_law.closure_path(path))
    np.testing.assert_allclose(t, closed_form(d, np.maximum.accumulate(d)), rtol=1e-13)
    assert t[3] == pytest.approx(t[5], rel=1e-13) and t[4] > t[2]
    assert t[4] / flow.transmissivity_law("cubic_law", initial_aperture=E0).transmissivity(d[4]) < 0.9
    np.testing.assert_allclose(law.transmissivity_path(d), t, rtol=1e-14)


def test_bad_parameters_are_named():
    with pytest.raises(ValueError, match="hydraulic_loss = 1.0 must be in"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=1.0)
    with pytest.raises(ValueError, match="hydraulic_loss = -0.1"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=-0.1)
    with pytest.raises(ValueError, match="missing hydraulic_loss"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=E0)
    with pytest.raises(ValueError, match="virgin = 'walls'"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=0.2, virgin="walls")
    with pytest.raises(ValueError, match="missing jrc"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=0.2, virgin="barton_jrc")
    with pytest.raises(ValueError, match="initial_aperture = 0.0 m"):
        flow.transmissivity_law("hydraulic_history", initial_aperture=0.0, hydraulic_loss=0.2)
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=E0, hydraulic_loss=0.2)
    with pytest.raises(ValueError, match="maximum_closure contains NaN"):
        law.transmissivity([0.0], [np.nan])
