# SPDX-License-Identifier: MIT
"""Calibration of closure laws to measured curves (rockjoint.calibration, `calibrate` CLI).

Synthetic curves are generated here from a known law (closure at 20-25 stresses from 0.2 to
30 MPa, plus Gaussian closure noise from a fixed seed at the level stated in each test), so
the true parameters are known independently of the fit.
"""
import math
from pathlib import Path

import numpy as np
import pytest

import rockjoint
from rockjoint.__main__ import main
from rockjoint.calibration import ClosureCurve, calibrate, read_closure_curve

E_STAR = rockjoint.composite_modulus(50e9, 0.25)  # Pa, theory §7 rock
BETA = 2.5e-3  # m
STRESS = np.geomspace(0.2e6, 30e6, 24)  # Pa

#: law -> (true law, true fitted parameters (SI, order of the fit), calibrate keywords)
CASES = {
    "barton_bandis": (lambda: rockjoint.BartonBandis(20e9, 0.3e-3),
                      {"initial_normal_stiffness": 20e9, "maximum_closure": 0.3e-3}, {}),
    "exponential": (lambda: rockjoint.ExponentialLaw(0.25e-3, 5e6),
                    {"maximum_closure": 0.25e-3, "characteristic_stress": 5e6}, {}),
    "greenwood_williamson": (
        lambda: rockjoint.GreenwoodWilliamson(E_STAR, 0.3e6, BETA, 0.05e-3),
        {"summit_density": 0.3e6, "summit_height_std": 0.05e-3, "closure_offset": 0.0},
        {"composite_modulus": E_STAR, "summit_radius": BETA}),
    "tang_jiao": (
        lambda: rockjoint.TangJiao(rockjoint.TangSubstrate(E_STAR, 0.3e6, BETA, 0.05e-3)),
        {"summit_density": 0.3e6, "summit_height_std": 0.05e-3, "closure_offset": 0.0},
        {"composite_modulus": E_STAR, "summit_radius": BETA}),
}


def synthetic(law_name, noise=0.0, seed=20261122):
    law = CASES[law_name][0]()
    closure = law.closure_at_stress(STRESS)
    rng = np.random.default_rng(seed)
    return ClosureCurve(STRESS.copy(), closure + noise * rng.standard_normal(STRESS.size))


@pytest.mark.parametrize("law_name", sorted(CASES))
def test_exact_curve_recovers_the_parameters(law_name):
    _, truth, kw = CASES[law_name]
    result = calibrate(synthetic(law_name), law_name, **kw)
    assert result.fit.converged, result.fit.message
    for p in result.parameters:
        if p.name == "closure_offset":
            assert abs(p.value) < 1e-10  # m, 1e-6 of the largest closure (see below)
        else:
            # Empirical laws: closed-form inverses, 1e-7. GW-type: σ(Δ) is a quadrature to
            # 1e-10 and η is ill-conditioned against the fitted offset (its uncertainty is
            # ~100 times the closure's relative noise in the noisy test below), so 1e-6.
            rel = 1e-7 if law_name in ("barton_bandis", "exponential") else 1e-6
            assert p.value == pytest.approx(truth[p.name], rel=rel), p.name
    assert result.residual_rms < 1e-12  # m


@pytest.mark.parametrize("law_name", sorted(CASES))
def test_noisy_curve_recovers_the_parameters_within_their_uncertainty(law_name):
    # Closure noise 0.5 µm (standard deviation), about 0.3 % of the largest closure.
    noise = 0.5e-6
    _, truth, kw = CASES[law_name]
    result = calibrate(synthetic(law_name, noise), law_name, **kw)
    assert result.fit.converged, result.fit.message
    assert [p.name for p in result.parameters] == list(truth)
    for p in result.parameters:
        assert p.standard_error > 0, p.name
        assert abs(p.value - truth[p.name]) <= 3 * p.standard_error, str(p)
        if p.name != "closure_offset":
            # Sane: a 0.3 % closure noise on 24 points cannot leave a parameter unknown.
            assert p.standard_error < 0.5 * p.value, str(p)
        else:
            assert p.standard_error < 20 * noise, str(p)
    # The residual scatter estimates the noise (24 points: within ±40 % at this seed).
    assert 0.6 * noise < result.residual_std < 1.4 * noise


def test_reported_uncertainty_matches_the_scatter_of_repeated_fits():
    # Monte Carlo (independent of the covariance formula): 200 curves with 0.3 µm noise; the
    # spread of the fitted K_ni and V_m must match the mean reported standard error within
    # 20 % (the Monte Carlo estimate of a std from 200 samples is good to ~5 %).
    fits = [calibrate(synthetic("barton_bandis", 0.3e-6, seed), "barton_bandis")
            for seed in range(200)]
    for j in range(2):
        values = np.array([f.parameters[j].value for f in fits])
        reported = np.mean([f.parameters[j].standard_error for f in fits])
        assert np.std(values, ddof=1) == pytest.approx(reported, rel=0.2), \
            fits[0].parameters[j].name


def test_intact_deformation_is_removed_from_the_specimen_displacement(tmp_path):
    # Displacement u = Δ + σL/E of a 100 mm specimen of E = 40 GPa (σL/E = 75 µm at 30 MPa,
    # a third of the joint's closure): calibrating from u with L, E gives the law of Δ.
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    closure = law.closure_at_stress(STRESS)
    length, young = 0.1, 40e9
    path = tmp_path / "specimen.csv"
    with open(path, "w") as f:
        f.write("normal_stress [MPa],displacement [um]\n")
        for s, u in zip(STRESS, closure + STRESS * length / young):
            f.write(f"{float(s * 1e-6)!r},{float(u * 1e6)!r}\n")
    curve = read_closure_curve(path, intact_length=length, young_modulus=young)
    np.testing.assert_allclose(curve.closure, closure, rtol=1e-12, atol=1e-18)
    result = calibrate(curve, "barton_bandis")
    assert result.parameter("initial_normal_stiffness").value == pytest.approx(20e9, rel=1e-7)
    assert result.parameter("maximum_closure").value == pytest.approx(0.3e-3, rel=1e-7)
    with pytest.raises(ValueError, match="intact-length"):
        read_closure_curve(path)


def test_empirical_law_with_a_closure_offset():
    # A Barton-Bandis curve read from its first point (0.2 MPa) on: the offset is the law's
    # closure there, Δ(0.2 MPa) = σV_m/(K_ni V_m + σ) = 9.68 µm, recovered with K_ni and V_m.
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    closure = law.closure_at_stress(STRESS)
    shifted = ClosureCurve(STRESS, closure - closure[0])
    result = calibrate(shifted, "barton_bandis", fit_offset=True)
    assert [p.name for p in result.parameters] == ["initial_normal_stiffness",
                                                   "maximum_closure", "closure_offset"]
    expected = 0.2e6 * 0.3e-3 / (20e9 * 0.3e-3 + 0.2e6)
    assert result.closure_offset == pytest.approx(expected, rel=1e-7)
    assert result.parameter("initial_normal_stiffness").value == pytest.approx(20e9, rel=1e-7)
    np.testing.assert_allclose(result.predicted_closure(STRESS), shifted.closure, atol=1e-12)


def test_closure_std_column_weights_the_fit(tmp_path):
    # Noise 0.2 µm on the first 12 points and 2 µm on the rest, declared per row: the
    # weighted fit brackets the truth within 3σ, and with weights 1/std² its χ²/(N-P) is a
    # chi-square variate over 22 degrees of freedom divided by 22 (95 % in [0.5, 1.6]).
    law = rockjoint.ExponentialLaw(0.25e-3, 5e6)
    std = np.where(np.arange(STRESS.size) < 12, 0.2e-6, 2e-6)
    rng = np.random.default_rng(5)
    closure = law.closure_at_stress(STRESS) + std * rng.standard_normal(STRESS.size)
    path = tmp_path / "weighted.csv"
    with open(path, "w") as f:
        f.write("closure [mm], normal_stress [kPa], closure_std [mm]\n")
        for d, s, e in zip(closure, STRESS, std):
            f.write(f"{float(d * 1e3)!r}, {float(s * 1e-3)!r}, {float(e * 1e3)!r}\n")
    curve = read_closure_curve(path)
    assert curve.closure_std is not None
    weighted = calibrate(curve, "exponential")
    plain = calibrate(ClosureCurve(curve.normal_stress, curve.closure), "exponential")
    truth = {"maximum_closure": 0.25e-3, "characteristic_stress": 5e6}
    for p in weighted.parameters:
        assert abs(p.value - truth[p.name]) <= 3 * p.standard_error, str(p)
    reduced = weighted.fit.chi_squared / weighted.fit.degrees_of_freedom
    assert 0.5 < reduced < 1.6
    # Unweighted, the same data leave χ² in closure units: the weights did enter.
    assert plain.fit.chi_squared / plain.fit.degrees_of_freedom < 1e-3


@pytest.mark.parametrize("content, message", [
    ("closure [mm]\n0.1\n0.2\n0.3\n0.4\n", "no normal stress column"),
    ("normal_stress [MPa], aperture [mm]\n1,0.1\n2,0.2\n3,0.3\n4,0.4\n", "closure"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.2,x2\n0.3,3\n0.4,4\n", "line 3"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.2,2\n0.3,nan\n0.4,4\n", "line 4: normal_stress is NaN"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.3,2\n0.2,3\n0.4,4\n", "line 4: closure"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.2,2\n0.3,1.5\n0.4,4\n", "line 4: normal stress"),
    ("closure [mm], normal_stress [MPa]\n0.1,-1\n0.2,2\n0.3,3\n0.4,4\n", "line 2: normal stress -1e+06 Pa is negative"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.2,2\n", "at least 4"),
    ("closure [furlong], normal_stress [MPa]\n0.1,1\n0.2,2\n0.3,3\n0.4,4\n", "unit 'furlong'"),
    ("closure [mm], normal_stress [MPa]\n0.1,1\n0.2\n0.3,3\n0.4,4\n", "line 3"),
    ("", "empty"),
])
def test_malformed_curve_files_give_errors_naming_file_and_line(tmp_path, content, message):
    path = tmp_path / "bad_curve.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match="bad_curve.csv") as err:
        read_closure_curve(path)
    assert message in str(err.value), str(err.value)


def test_bad_calibration_requests_are_named():
    curve = synthetic("barton_bandis")
    with pytest.raises(ValueError, match="unknown"):
        calibrate(curve, "hyperbolic_tangent")
    with pytest.raises(ValueError, match="composite_modulus"):
        calibrate(curve, "greenwood_williamson", summit_radius=BETA)
    with pytest.raises(ValueError, match="summit_radius"):
        calibrate(curve, "tang_jiao", composite_modulus=E_STAR, summit_radius=-1.0)
    short = ClosureCurve(STRESS[:4], curve.closure[:4])
    with pytest.raises(ValueError, match="too few"):
        calibrate(short, "greenwood_williamson", composite_modulus=E_STAR, summit_radius=BETA)
    with pytest.raises(ValueError, match="initial values"):
        calibrate(curve, "barton_bandis", initial=[1.0])
    with pytest.raises(ValueError, match="does not exist|cannot read"):
        read_closure_curve("/nonexistent/curve.csv")


def test_cli_runs_end_to_end_and_writes_plot_and_table(tmp_path, capsys):
    # GW law through the CLI (E* from E, ν; β in mm), 0.5 µm noise, as a user would call it.
    curve = synthetic("greenwood_williamson", 0.5e-6)
    path = tmp_path / "lab_curve.csv"
    with open(path, "w") as f:
        f.write("# granite-like joint, loading branch\nnormal_stress [MPa], closure [mm]\n")
        for s, d in zip(curve.normal_stress, curve.closure):
            f.write(f"{float(s * 1e-6)!r}, {float(d * 1e3)!r}\n")
    png, rjt = tmp_path / "fit.png", tmp_path / "fit.rjt"
    rc = main(["calibrate", str(path), "--law", "greenwood_williamson", "--young", "50",
               "--poisson", "0.25", "--summit-radius", "2.5", "--plot", str(png),
               "--table", str(rjt)])
    out = capsys.readouterr().out
    assert rc == 0
    assert "η =" in out and "σ_s =" in out and "1/mm²" in out and "residual: rms" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    table = rockjoint.TabulatedLaw.load(str(rjt))
    # The table is the fitted law: compare with a calibration through the API.
    result = calibrate(read_closure_curve(path), "greenwood_williamson",
                       composite_modulus=E_STAR, summit_radius=BETA)
    d = np.linspace(0.2, 1.0, 5) * result.law.closure_at_stress(30e6)
    np.testing.assert_allclose(table.normal_stress(d), result.law.normal_stress(d), rtol=1e-5)
    # Default output names beside the curve; errors are reported, not raised.
    assert main(["calibrate", str(path), "--law", "barton_bandis"]) == 0
    assert (tmp_path / "lab_curve_barton_bandis.png").exists()
    assert (tmp_path / "lab_curve_barton_bandis.rjt").exists()
    bad = tmp_path / "bad.csv"
    bad.write_text("closure [mm], normal_stress [MPa]\n0.1,1\n0.2,oops\n0.3,3\n0.4,4\n0.5,5\n")
    assert main(["calibrate", str(bad), "--law", "exponential"]) == 1
    assert "bad.csv: line 3" in capsys.readouterr().err
