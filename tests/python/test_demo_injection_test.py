# SPDX-License-Identifier: MIT
"""The injection demo (demos/demo_injection_test.py) runs as it is, serially and on 2 ranks, and its
injection pressures equal references computed here, independently of the FE model, the network
and the coupling: from the joint's own laws only (its closure Δ(σ') from the walls' exact contact
with the hysteretic branches, and the walls' T(Δ)).

Under a uniform total normal stress σ (the demo's soft halves; checked from its table), continuity
along the joint of length L with the rate Q per metre of width gives T dp/dx = -μ Q, so

* one way (the joint closed by σ alone, T uniform): p_in = p_out + μ Q L / T(Δ(σ));
* two ways on first loading (every point on the virgin curve: σ' = σ - p rises with σ at every
  point, as dσ'/dσ = T_out / T(x) > 0): ∫_{p_out}^{p_in} T(Δ_v(σ - p)) dp = μ Q L, solved for p_in
  by brentq on SciPy's quad;
* two ways on unloading: each point on its branch (H2) from its own largest closure, reached at the
  peak: Δ_m(x) = Δ_v(σ_pk - p_pk(x)), so Δ(x, p) = Δ_p + (Δ_m - Δ_p)((σ - p)/(σ_pk - p_pk(x)))^(1/m),
  Δ_p = r Δ_m; the profile is the ODE dp/dx = -μ Q / T(Δ(x, p)) integrated with the peak's
  dp_pk/dx = -μ Q / T(Δ_v(σ_pk - p_pk)) from p = p_pk = p_out at x = L (SciPy's DOP853).

Two ways needs less pressure than one way wherever the water opens the joint: σ - p <= σ, and on
the branches Δ grows with Δ_m when m > k_v Δ / σ_v (checked below), so T is larger everywhere.

Tolerances: one way, T is uniform and the P1 network exact: the FE closure's Newton tolerance
(1e-10) alone, 1e-10 of p_in - p_out (measured up to 1e-11). Two ways: the network's P1 error
with the element mean of T (second order: at twice the joint element size, --quick, the largest
error is 2.4e-5, 4 times the demo's) and σ_n uniform to the soft halves' 6e-6 (the table's
column); measured 2e-7 to 5.7e-6 of p_in - p_out: 5e-5.
"""
import importlib.util
import os

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402

PATH = os.path.join(demo_runner.SOURCE, "demos", "demo_injection_test.py")
_spec = importlib.util.spec_from_file_location("demo_injection_test", PATH)
demo = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(demo)          # its constants and its joint's laws, not its FE model
MU_Q = demo.FLUID.viscosity * demo.RATE  # μ Q [Pa m]
L, P_OUT = demo.LENGTH, demo.OUTLET_PRESSURE


def run(out, ranks, extra=()):
    demo_runner.run_demo("demo_injection_test.py", out, ranks, extra)
    for name in ("injection_test.png", "injection_test.txt"):
        assert (out / name).exists(), name
    # σ [MPa], leg, p_in one way, two ways [MPa], T one way, T two ways at inlet [m³], iterations,
    # max |σ_n/σ - 1|, outflow/Q + 1
    return np.loadtxt(out / "injection_test.txt", comments="#")


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    return run(tmp_path_factory.mktemp("serial"), 1)


@pytest.fixture(scope="module")
def laws():
    law, walls, virgin = demo.joint_laws(demo.WALLS["points"])
    return law, walls.transmissivity, virgin.closure_at_stress


def branch(law, closure, effective, largest_stress):
    """(H2) inverted: Δ on the branch from Δ_m = Δ_v(σ_m) at the effective stress σ'."""
    top = closure(largest_stress)
    r, m = law.permanent_fraction, law.unloading_exponent
    return r * top + (1 - r) * top * (effective / largest_stress) ** (1.0 / m)


def two_way_loading(t, closure, sigma):
    def passed(p_in):
        return quad(lambda p: t(closure(sigma - p)), P_OUT, p_in, epsabs=0, epsrel=1e-12, limit=200)[0] - MU_Q * L
    return brentq(passed, P_OUT, sigma * (1 - 1e-9), xtol=1e-9, rtol=1e-14)


def two_way_unloading(law, t, closure, sigma, peak):
    def slope(x, y):
        p_peak, p = y
        effective_peak = peak - p_peak
        return [-MU_Q / t(closure(effective_peak)), -MU_Q / t(branch(law, closure, sigma - p, effective_peak))]
    sol = solve_ivp(slope, (L, 0.0), [P_OUT, P_OUT], method="DOP853", rtol=1e-12, atol=1e-6)
    assert sol.success, sol.message
    return sol.y[1, -1]


def references(table, laws):
    """(one way, two ways) p_in [Pa] at every level of the table."""
    law, t, closure = laws
    sigma, leg = table[:, 0] * 1e6, table[:, 1]
    peak = sigma.max()
    one = np.where(leg > 0, P_OUT + MU_Q * L / t(closure(sigma)),
                   P_OUT + MU_Q * L / t(branch(law, closure, sigma, peak)))
    two = np.array([two_way_loading(t, closure, s) if g > 0 else two_way_unloading(law, t, closure, s, peak)
                    for s, g in zip(sigma, leg)])
    return one, two


def test_injection_pressures_equal_the_independent_references(table, laws):
    sigma, leg, p_one, p_two = table[:, 0] * 1e6, table[:, 1], table[:, 2] * 1e6, table[:, 3] * 1e6
    # the premises: σ_n uniform (the soft halves), all the water drains at the outlet, the first
    # level's effective stress above the dry seating (its points on the virgin curve)
    assert np.all(table[:, 7] < 1e-4) and np.all(np.abs(table[:, 8]) < 1e-9)
    assert sigma[0] - p_two[0] > demo.SEATING
    one, two = references(table, laws)
    e_one = np.abs(p_one - one) / (one - P_OUT)
    e_two = np.abs(p_two - two) / (two - P_OUT)
    for s, g, a, b, c, d, x, y in zip(sigma, leg, p_one, one, p_two, two, e_one, e_two):
        print(f"σ = {s * 1e-6:5.2f} MPa ({'loading' if g > 0 else 'unloading'}): one way {a * 1e-6:.6f} "
              f"(ref {b * 1e-6:.6f}, error {x:.1e}), two ways {c * 1e-6:.6f} (ref {d * 1e-6:.6f}, error {y:.1e}) MPa")
    assert np.max(e_one) < 1e-10
    assert np.max(e_two) < 5e-5
    # the coupling matters here: the two answers differ by far more than the reference's tolerance
    assert np.all((one - two) / (one - P_OUT) > 20 * 5e-5)


def test_the_two_way_error_is_the_networks_and_falls_at_second_order(table, laws, tmp_path):
    """--quick (joint elements twice as long): at every level both have, the error against the
    reference is about 4 times the demo's (P1 with the element mean of T), so what is left is the
    discretisation, not the coupling or a wrong branch."""
    quick = run(tmp_path, 1, ("--quick",))
    errors = []
    for rows in (table, quick):
        two = references(rows, laws)[1]
        errors.append({(r[0], r[1]): abs(r[3] * 1e6 - ref) / (ref - P_OUT) for r, ref in zip(rows, two)})
    common = sorted(set(errors[0]) & set(errors[1]))
    ratio = np.array([errors[1][k] / errors[0][k] for k in common])
    print("error ratios, --quick / demo:", np.round(ratio, 2))
    assert len(common) >= 6 and np.all(ratio > 3.0)


def test_the_water_opening_the_joint_lowers_the_injection_pressure(table, laws):
    """Two ways <= one way at every level: σ' = σ - p <= σ, and (unloading) a smaller largest
    closure gives a smaller closure on the branch where m > k_v Δ/σ_v over the stresses reached."""
    law, _, closure = laws
    stresses = np.geomspace(table[-1, 0] * 1e6 - table[-1, 3] * 1e6, table[:, 0].max() * 1e6, 50)
    d = closure(stresses)
    assert np.max(law.virgin.normal_stiffness(d) * d / stresses) < law.unloading_exponent
    assert np.all(table[:, 3] < table[:, 2])
    # the joint does not spring back: on unloading both need more pressure than at the same σ on loading
    peak = int(np.argmax(table[:, 0]))
    for column in (2, 3):
        loading = np.interp(table[peak + 1:, 0], table[:peak + 1, 0], table[:peak + 1, column])
        assert np.all(table[peak + 1:, column] > loading)


def test_two_ranks_give_the_serial_answer(table, tmp_path):
    parallel = run(tmp_path, 2)
    np.testing.assert_allclose(parallel[:, :6], table[:, :6], rtol=1e-7)
