# SPDX-License-Identifier: MIT
"""Tabulated laws from Python: the error bound against the source, numpy knots,
bit-exact save/load, clear errors, the plot helper and the `tabulate` CLI command."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import rockjoint
from rockjoint.tabulation import table_errors


def library_laws():
    """Every law of the library constructible from Python (all of them, always: a law missing
    from the bindings fails here instead of leaving the list):
    (law, σ_max [Pa], finest tolerance the source itself supports)."""
    laws = [(rockjoint.BartonBandis(20e9, 0.3e-3), 30e6, 1e-8),
            (rockjoint.LogarithmicLaw(0.05e-3, 0.1e6), 30e6, 1e-8),
            (rockjoint.ExponentialLaw(0.2e-3, 5e6), 30e6, 1e-8)]
    # docs/theory.md §7; Gaussian heights by quadrature (relative tolerance 1e-10): accurate to 1e-8
    e_star = rockjoint.composite_modulus(50e9, 0.25)
    asperity = (e_star, 0.3e6, 2.5e-3, 0.05e-3)
    ts = rockjoint.TangSubstrate(*asperity, deflection_coefficient=8 / (3 * math.pi),
                                 base_radius=1e-3)
    laws += [(rockjoint.GreenwoodWilliamson(*asperity), 30e6, 1e-8),
             (rockjoint.GreenwoodWilliamson(*asperity, distribution="exponential"), 30e6,
              1e-8),
             (ts, 30e6, 1e-8),
             (rockjoint.TangJiao(ts), 30e6, 1e-8)]
    return laws


def random_closures(top, n=10_000, seed=0):
    rng = np.random.default_rng(seed)
    u = rng.random(n)
    # half uniform in Δ, half log-uniform over 12 decades (the first interval)
    return np.where(np.arange(n) % 2 == 0, top * np.maximum(u, 1e-16), top * 10.0 ** (-12 * u))


@pytest.mark.parametrize("tolerance", [1e-3, 1e-6, 1e-8])
def test_error_bound_holds_on_random_points(tolerance):
    for law, smax, finest in library_laws():
        if tolerance < finest:
            continue
        table = rockjoint.tabulate(law, max_stress=smax, tolerance=tolerance)
        d = random_closures(table.table_maximum_closure)
        s_tab, k_tab, _, status = table.evaluate(d)
        s_src, k_src, _, _ = law.evaluate(d)
        assert np.all(status == int(rockjoint.Status.contact))
        assert np.max(np.abs(s_tab / s_src - 1)) <= tolerance, law.name
        assert np.max(np.abs(k_tab / k_src - 1)) <= tolerance, law.name
        # the helper samples between the knots: same bound
        _, es, ek = table_errors(table, law)
        assert es.max() <= tolerance and ek.max() <= tolerance


def test_knots_are_numpy_arrays_consistent_with_the_source():
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    table = rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-6)
    d, s, k = table.knot_closure, table.knot_stress, table.knot_stiffness
    assert isinstance(d, np.ndarray) and d.shape == (table.knot_count,)
    assert d[0] == 0 and s[0] == 0 and np.all(np.diff(d) > 0) and np.all(np.diff(s) > 0)
    # knot values are the source's own σ and k (k limited only where monotonicity needs it,
    # which is nowhere for this smooth law); k_0 = k(0+) = K_ni
    np.testing.assert_array_equal(s[1:], law.normal_stress(d[1:]))
    np.testing.assert_array_equal(k[1:], law.normal_stiffness(d[1:]))
    assert table.initial_stiffness == k[0] == pytest.approx(20e9, rel=1e-10)
    assert table.table_maximum_stress == pytest.approx(30e6, rel=1e-12)
    assert table.source_model == "barton_bandis"
    assert {p.name for p in table.source_parameters} == {"initial_normal_stiffness",
                                                         "maximum_closure"}


def test_closure_range_form():
    law = rockjoint.ExponentialLaw(0.2e-3, 5e6)
    table = rockjoint.tabulate(law, max_closure=0.15e-3, tolerance=1e-5)
    assert table.table_maximum_closure == 0.15e-3  # the last knot is the range's end, exactly
    assert table.table_maximum_stress == law.normal_stress(0.15e-3)
    d = random_closures(0.15e-3, 2000, seed=4)
    np.testing.assert_allclose(table.normal_stress(d), law.normal_stress(d), rtol=1e-5)


def test_tangent_is_the_derivative_of_the_table():
    law = rockjoint.LogarithmicLaw(0.05e-3, 0.1e6)
    table = rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-3)
    d = random_closures(table.table_maximum_closure, 500, seed=3)
    s, k, _, _ = table.evaluate(d)
    h = 1e-5 * np.minimum(d, s / k)
    fd = (table.normal_stress(d + h) - table.normal_stress(d - h)) / (2 * h)
    np.testing.assert_allclose(k, fd, rtol=1e-6)


def test_save_load_round_trip_is_bit_exact(tmp_path):
    law = rockjoint.ExponentialLaw(0.2e-3, 5e6)
    table = rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-7, residual_stiffness=123.0)
    path = str(tmp_path / "law.rjt")
    table.save(path)
    back = rockjoint.TabulatedLaw.load(path)
    for name in ("knot_closure", "knot_stress", "knot_stiffness"):
        np.testing.assert_array_equal(getattr(back, name), getattr(table, name))
    for name in ("tolerance", "checked_error_stress", "checked_error_stiffness",
                 "residual_stiffness", "initial_stiffness", "source_model"):
        assert getattr(back, name) == getattr(table, name)
    assert back.residual_stiffness == 123.0
    d = np.concatenate([[-1e-4, 0.0], random_closures(1.2 * table.table_maximum_closure)])
    for a, b in zip(table.evaluate(d), back.evaluate(d)):
        np.testing.assert_array_equal(a, b)
    text = open(path).read()
    assert text.startswith("rockjoint-law-table 1\n") and "source_model exponential" in text


def test_malformed_file_is_a_value_error_naming_file_and_line(tmp_path):
    table = rockjoint.tabulate(rockjoint.BartonBandis(20e9, 0.3e-3), max_stress=30e6,
                               tolerance=1e-3)
    good = tmp_path / "good.rjt"
    table.save(str(good))
    lines = good.read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("knot 2 "))
    fields = lines[k].split()
    fields[3] = "nan"
    lines[k] = " ".join(fields)
    bad = tmp_path / "bad.rjt"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=rf"bad\.rjt.*line {k + 1}.*knot 2 normal_stress"):
        rockjoint.TabulatedLaw.load(str(bad))
    bad.write_text("\n".join(lines[:k]) + "\n")
    with pytest.raises(ValueError, match="truncated"):
        rockjoint.TabulatedLaw.load(str(bad))
    with pytest.raises(ValueError, match="cannot be opened"):
        rockjoint.TabulatedLaw.load(str(tmp_path / "missing.rjt"))


def test_bad_requests_are_clear_errors():
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    with pytest.raises(ValueError, match="exactly one"):
        rockjoint.tabulate(law)
    with pytest.raises(ValueError, match="exactly one"):
        rockjoint.tabulate(law, max_stress=1e6, max_closure=1e-4)
    with pytest.raises(ValueError, match="maximum_stress"):
        rockjoint.tabulate(law, max_stress=1e300)  # beyond the hyperbola's V_m
    with pytest.raises(ValueError, match="maximum_closure"):
        rockjoint.tabulate(law, max_closure=0.3e-3)  # = V_m
    with pytest.raises(ValueError, match="tolerance"):
        rockjoint.tabulate(law, max_stress=30e6, tolerance=0.5)
    with pytest.raises(RuntimeError, match="maximum_knots"):
        rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-12, maximum_knots=40)


def test_open_joint_uses_the_residual_stiffness():
    law = rockjoint.BartonBandis(20e9, 0.3e-3)
    table = rockjoint.tabulate(law, max_stress=30e6)
    kres = 1e-6 * table.table_maximum_stress / table.table_maximum_closure
    assert table.residual_stiffness == pytest.approx(kres, rel=1e-15)
    s, k, _, status = table.evaluate(np.array([-1e-3, 0.0]))
    np.testing.assert_array_equal(s, [-1e-3 * table.residual_stiffness, 0.0])
    np.testing.assert_array_equal(k, [table.residual_stiffness] * 2)
    assert set(status) == {int(rockjoint.Status.open)}
    strict = rockjoint.tabulate(law, max_stress=30e6, residual_stiffness=0.0)
    assert strict.normal_stress(-1e-3) == 0.0 and strict.normal_stiffness(-1e-3) == 0.0


def test_plot_writes_a_png(tmp_path):
    law = rockjoint.LogarithmicLaw(0.05e-3, 0.1e6)
    table = rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-4)
    path = tmp_path / "table.png"
    fig = rockjoint.plot_table(table, law, str(path))
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(fig.axes) == 4


def _cli(*args, cwd):
    env = dict(os.environ)
    # the package under test, wherever pytest imported it from (cwd changes below)
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(rockjoint.__file__)))
    env["PYTHONPATH"] = os.pathsep.join([package_root, env.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, "-m", "rockjoint", "tabulate", *args], cwd=cwd,
                          env=env, capture_output=True, text=True, timeout=120)


def test_cli_tabulates_a_toml_parameter_file(tmp_path):
    params = tmp_path / "bb.toml"
    params.write_text(
        "[law]\nmodel = \"barton_bandis\"\ninitial_normal_stiffness_MPa_per_mm = 20.0\n"
        "maximum_closure_mm = 0.3\n\n[table]\nmaximum_stress_MPa = 30.0\ntolerance = 1e-6\n")
    out = tmp_path / "bb.rjt"
    png = tmp_path / "bb.png"
    r = _cli(str(params), "-o", str(out), "--plot", str(png), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "knots" in r.stdout and png.exists()
    # the file is the table the API builds from the same law in SI units (bit-exact)
    table = rockjoint.TabulatedLaw.load(str(out))
    ref = rockjoint.tabulate(rockjoint.BartonBandis(20.0 * 1e9, 0.3 * 1e-3),
                             max_stress=30.0 * 1e6, tolerance=1e-6)
    np.testing.assert_array_equal(table.knot_stress, ref.knot_stress)
    np.testing.assert_array_equal(table.knot_closure, ref.knot_closure)
    np.testing.assert_array_equal(table.knot_stiffness, ref.knot_stiffness)


def test_cli_tabulates_tang_jiao_with_spec_parameters(tmp_path):
    params = tmp_path / "tj.toml"
    params.write_text(
        "[law]\nmodel = \"tang_jiao\"\nyoung_modulus_GPa = 50.0\npoisson_ratio = 0.25\n"
        "summit_density_per_mm2 = 0.3\nsummit_radius_mm = 2.5\nsummit_height_std_mm = 0.05\n"
        "base_radius_mm = 1.0\n[table]\nmaximum_stress_MPa = 30.0\ntolerance = 1e-4\n")
    out = tmp_path / "tj.rjt"
    r = _cli(str(params), "-o", str(out), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    table = rockjoint.TabulatedLaw.load(str(out))
    assert table.source_model == "tang_jiao"
    params_by_name = {p.name: p.value for p in table.source_parameters}
    assert params_by_name["composite_modulus"] == rockjoint.composite_modulus(50e9, 0.25)
    assert params_by_name["base.deflection_coefficient"] == pytest.approx(8 / (3 * math.pi))
    # the table reproduces the law built directly in SI units
    e_star = rockjoint.composite_modulus(50e9, 0.25)
    law = rockjoint.TangJiao(rockjoint.TangSubstrate(e_star, 0.3e6, 2.5e-3, 0.05e-3,
                                                     base_radius=1e-3))
    d = random_closures(table.table_maximum_closure, 2000, seed=9)
    np.testing.assert_allclose(table.normal_stress(d), law.normal_stress(d), rtol=1e-4)


def test_cli_reports_a_bad_parameter_file_in_one_line(tmp_path):
    params = tmp_path / "bad.toml"
    params.write_text("[law]\nmodel = \"barton_bandis\"\ninitial_normal_stiffness = 20.0\n"
                      "maximum_closure_mm = 0.3\n[table]\nmaximum_stress_MPa = 30\n")
    r = _cli(str(params), "-o", str(tmp_path / "x.rjt"), cwd=tmp_path)
    assert r.returncode == 1
    assert "initial_normal_stiffness_MPa_per_mm" in r.stderr and "bad.toml" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
