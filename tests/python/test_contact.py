# SPDX-License-Identifier: MIT
"""The boundary-element contact reference from Python: grid convergence on a band-limited
surface, masked points, bad input, and the exact elastic law as a table (docs/contact.md)."""
import numpy as np
import pytest

import rockjoint
from rockjoint import contact
from rockjoint import topography as topo

E_STAR = rockjoint.composite_modulus(50e9, 0.25)
STRESSES = np.array([1e6, 5e6, 20e6])


def band_limited_aperture(n: int, side: float = 8e-3) -> topo.Surface:
    """A smooth periodic aperture (a few long-wavelength cosines, amplitude ~10 µm), sampled
    on n x n points: the same surface at every n, so refining the grid must converge."""
    x = np.arange(n) * side / n
    X, Y = np.meshgrid(x, x)
    k = 2 * np.pi / side
    s = (6e-6 * np.cos(k * X) + 4e-6 * np.cos(2 * k * Y + 0.3)
         + 2e-6 * np.cos(k * (X + 2 * Y) + 1.1) + 1.5e-6 * np.sin(3 * k * X - k * Y))
    return topo.Surface(s - s.min(), side / n)


def test_closure_converges_under_grid_refinement():
    closures = [contact.closure_curve(band_limited_aperture(n), E_STAR, STRESSES).closure
                for n in (64, 128, 256)]
    d1 = np.max(np.abs(closures[1] - closures[0]) / closures[2])
    d2 = np.max(np.abs(closures[2] - closures[1]) / closures[2])
    assert d2 < 0.5 * d1, (d1, d2)   # the change halves at least with each refinement
    assert d2 < 5e-3


def test_load_balance_gap_and_complementarity_on_a_rough_joint():
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (128, 128), 0.25e-3, 2.5e-3, seed=4)
    ap = topo.composite_topography(u, l).aperture
    c = contact.closure_curve(ap, E_STAR, STRESSES, keep_fields=True)
    assert np.all(np.diff(c.closure) > 0) and np.all(np.diff(c.contact_area_ratio) > 0)
    for s, p, g, cmp in zip(STRESSES, c.pressure, c.gap, c.complementarity):
        assert np.mean(p) == pytest.approx(s, rel=1e-12)
        assert p.min() >= 0.0 and g.min() >= 0.0
        assert np.all(g[p > 0] == 0.0) or np.max(g[p > 0]) < 1e-9 * c.closure[-1]
        assert cmp < 1e-6 * s * c.closure[-1]
    assert np.array_equal(c.closure, c.approach)   # periodic: no bulk term


def test_non_periodic_closure_is_the_mean_aperture_change_and_the_kernel_is_boussinesq():
    ap = band_limited_aperture(64)
    c = contact.closure_curve(ap, E_STAR, STRESSES, periodic=False, keep_fields=True)
    solver = rockjoint._rockjoint.contact.ElasticContact(
        ap, E_STAR, contact.Kernel.non_periodic, rockjoint._rockjoint.contact.ContactOptions())
    # Independent bulk term: Boussinesq mean displacement of a uniformly loaded square of side
    # L is (σ L/E*) · (4/π)·[asinh(1) + (1 - √2)/3] (Johnson 1985, mean of Love's solution).
    side = 8e-3
    mean_square = side / E_STAR * 4.0 / np.pi * (np.arcsinh(1.0) + (1.0 - np.sqrt(2.0)) / 3.0)
    assert solver.bulk_compliance == pytest.approx(mean_square, rel=2e-3)
    # The closure is the change of the mean aperture, mean(e) - mean(g) (g the gap under load).
    e = ap.heights - np.nanmin(ap.heights)
    change = np.array([np.mean(e) - np.mean(g) for g in c.gap])
    np.testing.assert_allclose(c.closure, change, rtol=1e-6, atol=1e-9 * c.closure[-1])
    assert np.all(np.diff(c.closure) > 0)


def test_non_periodic_closure_rises_with_load_on_a_large_scan_with_few_contact_spots():
    """A 256² scan (51 mm) whose walls touch at four paraboloidal caps (R = 20 mm) near its
    corners only: the closure must rise with the load at every step, and the spots stay four."""
    n, h, radius = 256, 0.2e-3, 20e-3
    x = (np.arange(n) + 0.5) * h
    X, Y = np.meshgrid(x, x)
    e = np.full((n, n), np.inf)
    for cx, cy in ((0.1, 0.1), (0.9, 0.12), (0.12, 0.88), (0.9, 0.9)):
        e = np.minimum(e, ((X - cx * n * h) ** 2 + (Y - cy * n * h) ** 2) / (2 * radius))
    stresses = np.geomspace(0.05e6, 30e6, 12)
    c = contact.closure_curve(topo.Surface(e, h), E_STAR, stresses, periodic=False)
    assert np.all(np.diff(c.closure) > 0), c.closure
    assert np.all(c.contact_patches == 4), c.contact_patches


def test_non_periodic_closure_rises_with_load_where_the_uniform_load_datum_falls():
    """A large synthetic scan, 256 mm at 1 mm (256²), 0.1-30 MPa: the closure (mean aperture
    change) rises at every load, while the former datum d - σ·c (c the patch's compliance under
    a uniform load) falls over the top loads of the same scan (the bench joint's fault at
    1024², docs/contact.md)."""
    upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (256, 256), 1e-3, 2.5e-3, seed=1)
    ap = topo.composite_topography(upper, lower).aperture
    stresses = np.geomspace(0.1e6, 30e6, 15)
    c = contact.closure_curve(ap, E_STAR, stresses, periodic=False)
    assert np.all(np.diff(c.closure) > 0), c.closure
    solver = rockjoint._rockjoint.contact.ElasticContact(
        ap, E_STAR, contact.Kernel.non_periodic, rockjoint._rockjoint.contact.ContactOptions())
    former = c.approach - stresses * solver.bulk_compliance
    assert np.any(np.diff(former) < 0), former


def test_masked_points_carry_no_pressure_and_bad_input_is_named():
    ap = band_limited_aperture(64)
    h = ap.heights.copy()
    h[10:14, 20:30] = np.nan
    masked = topo.Surface(h, ap.spacing_x)
    c = contact.closure_curve(masked, E_STAR, [5e6], keep_fields=True)
    assert np.all(np.isnan(c.pressure[0][10:14, 20:30]))
    valid = ~np.isnan(h)
    assert np.nanmean(c.pressure[0]) == pytest.approx(5e6, rel=1e-12)
    assert valid.sum() == 64 * 64 - 40
    with pytest.raises(ValueError, match="stresses"):
        contact.closure_curve(ap, E_STAR, [1e6, -2e6])
    with pytest.raises(ValueError, match="composite_modulus"):
        contact.closure_curve(ap, -1.0, [1e6])
    nan = topo.Surface(np.full((8, 8), np.nan), 1e-4)
    with pytest.raises(ValueError, match="valid"):
        contact.closure_curve(nan, E_STAR, [1e6])


def test_exact_elastic_law_passes_through_the_curve_and_is_monotone():
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (128, 128), 0.25e-3, 2.5e-3, seed=2)
    ap = topo.composite_topography(u, l).aperture
    stresses = np.geomspace(0.1e6, 30e6, 15)
    c = contact.closure_curve(ap, E_STAR, stresses)
    law = contact.exact_elastic_law(c)
    assert isinstance(law, rockjoint.TabulatedLaw) and law.source_model == "bem_elastic_contact"
    np.testing.assert_allclose(law.normal_stress(c.closure), stresses, rtol=1e-12)
    d = np.linspace(1e-9, c.closure[-1], 2000)
    sigma, k, _, _ = law.evaluate(d)
    assert np.all(np.diff(sigma) > 0) and np.all(k > 0)
    # The tangent is the derivative of the interpolant (central differences).
    mid = d[1:-1]
    fd = (law.normal_stress(mid + 1e-10) - law.normal_stress(mid - 1e-10)) / 2e-10
    np.testing.assert_allclose(fd, law.normal_stiffness(mid), rtol=1e-4)
    for s in (0.5e6, 3e6, 12e6):
        assert law.normal_stress(law.closure_at_stress(s)) == pytest.approx(s, rel=1e-10)


def test_exact_elastic_law_takes_a_curve_whose_first_slope_reaches_the_quartics_bound():
    """The first segment (a quartic in √Δ with k(0+) = 0) is monotone for k1 <= 2 σ1/Δ1; this
    scan's curve has its data slope at the first load (0.1 MPa) far above that bound, so the
    bound is taken, and the table must accept it (rounding once put its cubic coefficient at
    -1e-16 σ1 and the table refused). The walls: the accuracy ladder's granite-like seed 1 on
    512² at 0.25 mm, scanned at every other point (0.5 mm)."""
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (512, 512), 0.25e-3, 2.5e-3, seed=1)
    scan = topo.composite_topography(topo.Surface(u.heights[::2, ::2], 0.5e-3),
                                     topo.Surface(l.heights[::2, ::2], 0.5e-3)).aperture
    stresses = np.unique(np.r_[np.geomspace(0.1e6, 1e6, 5), np.geomspace(1e6, 30e6, 11)])
    c = contact.closure_curve(scan, E_STAR, stresses)
    assert (c.stress[1] - c.stress[0]) / (c.closure[1] - c.closure[0]) > 2 * c.stress[0] / c.closure[0]
    law = contact.exact_elastic_law(c)
    np.testing.assert_allclose(law.normal_stress(c.closure), stresses, rtol=1e-12)
    d = np.linspace(1e-9, c.closure[1], 500)
    assert np.all(np.diff(law.normal_stress(d)) > 0)


def test_cli_prints_the_bem_reference_beside_the_laws(tmp_path):
    import subprocess
    import sys
    import os
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg")
    run = lambda *a: subprocess.run([sys.executable, "-m", "rockjoint", "topography", *a],  # noqa: E731
                                    cwd=tmp_path, env=env, capture_output=True, text=True)
    r = run("synth", "--rms", "1.0", "--shape", "64", "64", "--matedness", "2.5", "--upper",
            "u.txt", "--lower", "l.txt")
    assert r.returncode == 0, r.stderr
    r = run("analyse", "u.txt", "l.txt", "--young", "50", "--reference", "bem", "--bem-kernel",
            "periodic", "--figures", "figs", "--resample", "--json", "p.json")
    assert r.returncode == 0, r.stderr
    assert "exact elastic contact (BEM, periodic)" in r.stdout and "recommended:" in r.stdout
    assert (tmp_path / "figs" / "closure_curves.png").stat().st_size > 10_000
    import json
    report = json.loads((tmp_path / "p.json").read_text())
    # The printed BEM closure is the library's own closure_curve on the same aperture.
    u = topo.read_surface(tmp_path / "u.txt")
    l_ = topo.read_surface(tmp_path / "l.txt")
    ap = topo.composite_topography(u, l_).aperture
    ref = contact.closure_curve(ap, E_STAR, np.array([1, 3, 10, 30]) * 1e6).closure
    np.testing.assert_allclose(list(report["bem_closure_mm"].values()),
                               ref * 1e3, rtol=1e-10)


def test_elastic_walls_reload_along_the_same_curve_after_a_deep_unloading():
    """Elastic walls are path-independent: loading to 10 MPa, unloading to 0.1 MPa (few contact
    points left) and reloading gives the first loading's closures (a warm start from one contact
    point once gave no CG step and stopped at once, "converged" on that point)."""
    upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (128, 128), 0.25e-3, 2.5e-3, seed=1)
    ap = topo.composite_topography(upper, lower).aperture
    c = contact.closure_curve(ap, E_STAR, [2e6, 10e6, 0.1e6, 2e6, 10e6])
    np.testing.assert_allclose(c.closure[3:], c.closure[:2], rtol=1e-6)


def test_profile_times_the_phases_of_each_load_and_changes_no_answer():
    """profile=True (bench/bench_contact.py's efficiency report): per load the phases are laps of
    one clock, so they add up to the load's wall time; the transform pairs are at least one per
    iteration not carried, plus the final u; the answers are those of the untimed solver, bit for
    bit; and the elastic-plastic solver, which has no profile, says so."""
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (128, 128), 0.25e-3, 2.5e-3, seed=4)
    ap = topo.composite_topography(u, l).aperture
    for periodic in (True, False):
        plain = contact.closure_curve(ap, E_STAR, STRESSES, periodic=periodic)
        timed = contact.closure_curve(ap, E_STAR, STRESSES, periodic=periodic, profile=True)
        assert np.array_equal(plain.closure, timed.closure) and np.array_equal(plain.iterations, timed.iterations)
        assert plain.profile is None and timed.transform_pair > 0 and timed.setup_seconds >= timed.planning_seconds >= 0
        for its, p in zip(timed.iterations, timed.profile):
            phases = p.start + p.transforms + p.direct_sums + p.grid_passes + p.contact_set + p.final_state
            assert p.wall > 0 and phases == pytest.approx(p.wall, rel=0.02, abs=2e-5)
            assert its - p.carried_updates + 1 <= p.transform_pairs <= 2 * its + 1
    with pytest.raises(ValueError, match="profile"):
        contact.closure_curve(ap, E_STAR, STRESSES, hardness=5e9, profile=True)
