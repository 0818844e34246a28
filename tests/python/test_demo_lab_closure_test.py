# SPDX-License-Identifier: MIT
"""The main demo (laboratory joint-closure test) runs as it is, serially and on 2 ranks, and its
FE joint closure (jointed minus intact cube) equals the closure law's own inverse; the flow through
the FE cube's joint equals the closed form (ρ g / μ) T Δh of the transmissivity at that closure.

Tolerance: the FE model uses the Tang & Jiao *table* (σ within 1e-6 relative of the law); for a
convex σ(Δ) with σ(0) = 0, σ <= kΔ, so the closure error is at most the same 1e-6 relative; the
Newton tolerance (1e-10) adds nothing visible. Serial and parallel agree to solver tolerance.
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402



def run_demo(out, ranks):
    demo_runner.run_demo("demo_lab_closure_test.py", out, ranks, ("--mesh-size", "0.05"))
    for name in ("lab_closure_test.png", "lab_closure_test_table.txt", "granite_joint.rjt",
                 "jointed_cube.xdmf", "jointed_cube_joints.xdmf", "intact_cube.xdmf",
                 "lab_closure_cycle.png", "lab_closure_cycle.txt", "lab_flow_cycle.png",
                 "lab_flow_cycle.txt"):
        assert (out / name).exists(), name
    # columns: σ [MPa], intact top, jointed top, closure FE, closure law [mm], rel. difference;
    # the cycle: σ [MPa], closure FE, closure law, closure BEM (elastic-plastic walls) [mm]
    # the flow: σ [MPa], closure [mm], T [m³], e_h, e [µm], e_h/e, Q FE, Q closed form [mL/min]
    return np.loadtxt(out / "lab_closure_test_table.txt", comments="#"), \
        np.loadtxt(out / "lab_closure_cycle.txt", comments="#"), \
        np.loadtxt(out / "lab_flow_cycle.txt", comments="#")


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def test_fe_closure_equals_the_law(serial):
    serial = serial[0]
    closure_fe, closure_law = serial[:, 3], serial[:, 4]
    assert np.all(closure_law > 0)
    np.testing.assert_allclose(closure_fe, closure_law, rtol=1e-6)
    # The jointed cube settles more than the intact one, by more at higher stress.
    assert np.all(serial[:, 2] > serial[:, 1]) and np.all(np.diff(closure_fe) > 0)


def test_cycle_fe_follows_the_hysteretic_law_and_keeps_closure_on_unloading(serial):
    """The FE cube loaded, unloaded to 0.5 MPa and reloaded: its joint closure equals the
    hysteretic law's (same tolerance argument as above), stays above the first loading's at the
    same stress while unloaded (the joint does not spring back), and is back on the first
    loading's closure at 30 MPa; the elastic-plastic contact reference never unloads below its
    loading curve (plastic flow only adds closure)."""
    cycle = serial[1]
    stress, fe, law, bem = cycle.T
    assert np.array_equal(serial[2][:, 0], stress)
    np.testing.assert_allclose(fe, law, rtol=1e-6)
    peak = int(np.argmax(stress))
    # first loading between its levels: the chord, below the concave Δ(σ), so "above it" is implied
    # by "above the curve" and tested without needing the levels to coincide
    first = np.interp(stress[peak + 1:], stress[:peak + 1], fe[:peak + 1])
    first_bem = np.interp(stress[peak + 1:], stress[:peak + 1], bem[:peak + 1])
    after = stress[peak + 1:] < stress[peak]
    assert np.all(fe[peak + 1:][after] > first[after])
    exact = np.isin(stress[peak + 1:], stress[:peak + 1])   # the BEM at the same levels: never below
    assert np.all(bem[peak + 1:][exact] >= first_bem[exact] * (1 - 1e-6))
    assert fe[-1] == pytest.approx(fe[peak], rel=1e-6)


def test_flow_through_the_cube_follows_its_closure(serial):
    """Q through the FE cube's joint (its points' T from their closures) equals (ρ g / μ) T Δh
    of the table's T at the law's closure (the cube's joint is uniform; solver tolerance); T
    falls on first loading, stays below the first loading's on unloading (the closure kept) and
    retraces on reloading; e_h <= e (a rough joint passes less than parallel plates at its mean
    aperture)."""
    stress, closure, t, e_h, e, ratio, q_fe, q_closed = serial[2].T
    np.testing.assert_allclose(q_fe, q_closed, rtol=1e-8)
    peak = int(np.argmax(stress))
    assert np.all(np.diff(t[:peak + 1]) < 0)
    first = np.interp(stress[peak + 1:], stress[:peak + 1], t[:peak + 1])
    after = stress[peak + 1:] < stress[peak]
    assert np.all(t[peak + 1:][after] < first[after])
    assert t[-1] == pytest.approx(t[peak], rel=1e-9)
    assert np.all(e_h < e) and np.all(ratio > 0)


def test_two_ranks_give_the_serial_answer(serial, tmp_path):
    parallel, parallel_cycle, parallel_flow = run_demo(tmp_path, 2)
    serial, serial_cycle, serial_flow = serial
    np.testing.assert_allclose(parallel[:, 1:5], serial[:, 1:5], rtol=1e-8)
    np.testing.assert_allclose(parallel_cycle, serial_cycle, rtol=1e-6)
    np.testing.assert_allclose(parallel_flow, serial_flow, rtol=1e-6)
