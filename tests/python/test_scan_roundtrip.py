# SPDX-License-Identifier: MIT
"""Scan files in and out: STL (binary, ASCII) and XYZ point clouds keep their samples, ESRI
ASCII grids put every node where the header says (corner and centre conventions, any key
case and order, cellsize or dx/dy, NODATA optional), and the Delaunay resampling stays within
its stated error bound, converges at second order and flags holes instead of filling them."""
import logging

import numpy as np
import pytest

import scan_cases as sc
from rockjoint import scans
from rockjoint import topography as topo


def _sheet(n=12, step=0.5e-3):
    """A small scanned sheet: lattice points (n x n, step) with z = 1e-4 sin, and its
    triangles (two per cell)."""
    x, y = np.meshgrid(np.arange(n) * step, np.arange(n) * step)
    z = 1e-4 * np.sin(x / 2e-3) * np.cos(y / 3e-3)
    pts = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel()
    return pts, np.vstack([np.column_stack([a, b, d]), np.column_stack([a, d, c])])


@pytest.mark.parametrize("binary", [True, False])
def test_stl_round_trip_keeps_vertices_and_facets(tmp_path, binary):
    pts, tri = _sheet()
    path = scans.write_stl(tmp_path / "wall.stl", pts, tri, binary=binary)
    scan = scans.read_stl(path)
    assert scan.triangles.shape == tri.shape
    assert scan.points.shape == pts.shape, "shared vertices are merged back to one each"
    got = scan.points[np.lexsort(scan.points[:, :2].T)]
    want = pts[np.lexsort(pts[:, :2].T)]
    # binary STL stores float32: 6e-8 relative of a few mm
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 if binary else 1e-12)


def test_xyz_reads_headers_comments_separators_and_extra_columns(tmp_path):
    p = tmp_path / "cloud.txt"
    rows = [(x, y, 0.01 * x - 0.02 * y) for x in range(0, 8) for y in range(0, 8)]
    lines = ["// exported by a scanner", "X;Y;Z;intensity"]
    for i, (x, y, z) in enumerate(rows):
        sep = (" ", ",", ";", "\t")[i % 4]
        lines.append(sep.join(f"{v:.6g}" for v in (x * 0.5, y * 0.5, z, 17)))
        if i == 10:
            lines.append("# a comment in the middle")
    p.write_text("\n".join(lines) + "\n")
    scan = scans.read_scan(p, format="points", unit="mm")
    want = np.array([(x * 0.5e-3, y * 0.5e-3, z * 1e-3) for x, y, z in rows])
    np.testing.assert_allclose(scan.points, want, rtol=1e-6, atol=1e-12)
    assert scan.sample_spacing() == pytest.approx(0.5e-3)


def _esri_text(header):
    """ncols 4 x nrows 3 cells of 2 mm (or dx 2, dy 1.5), south-west cell centre at
    (11, 21) mm; every value is z = x/10 + y/100 [mm] of its cell centre, so the heights say
    where the reader put each node."""
    dy = 1.5 if any(h.lower().startswith("dy") for h in header) else 2.0
    rows = []
    for r in range(3):                      # file row 0 = north = largest y
        y = 21 + (2 - r) * dy
        rows.append(" ".join(f"{(11 + 2 * c) / 10 + y / 100:.6f}" for c in range(4)))
    return "\n".join(header) + "\n" + "\n".join(rows) + "\n", dy


@pytest.mark.parametrize("header", [
    ["ncols 4", "nrows 3", "xllcorner 10", "yllcorner 20", "cellsize 2"],
    ["NCOLS 4", "NROWS 3", "XLLCENTER 11", "YLLCENTER 21", "CELLSIZE 2", "NODATA_VALUE -9999"],
    ["cellsize 2", "yllcorner 20", "NODATA_value -1e30", "xllcorner 10", "nrows 3", "ncols 4"],
    ["ncols 4", "nrows 3", "xllcorner 10", "yllcorner 20.25", "dx 2", "dy 1.5"],
    ["Ncols 4", "Nrows 3", "XllCenter 11", "yllcorner 20.25", "DX 2", "DY 1.5"],
], ids=["corner", "centre-upper", "shuffled", "dxdy", "mixed"])
def test_esri_nodes_sit_where_the_header_says(tmp_path, header):
    text, dy = _esri_text(header)
    p = tmp_path / "grid.asc"
    p.write_text(text)
    grid = scans.read_esri_ascii(p, unit="mm")
    x, y = grid.node_coordinates()
    assert grid.heights.shape == (3, 4)
    assert (grid.spacing_x, grid.spacing_y) == pytest.approx((2e-3, dy * 1e-3))
    np.testing.assert_allclose(x[0], np.array([11, 13, 15, 17]) * 1e-3)
    np.testing.assert_allclose(y[:, 0], (21 + dy * np.arange(3)) * 1e-3)
    # z = x/10 + y/100 in mm at each node: the value landed on its own node
    np.testing.assert_allclose(grid.heights, (x * 1e3 / 10 + y * 1e3 / 100) * 1e-3, rtol=1e-9)


def test_esri_nodata_is_a_counted_hole_and_round_trips(tmp_path):
    p = tmp_path / "holes.asc"
    p.write_text("ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 0.5\n"
                 "NODATA_value -9999\n1 2 3\n4 -9999 6\n7 8 nan\n")
    grid = scans.read_esri_ascii(p)
    assert grid.masked_count == 2
    assert np.isnan(grid.heights[1, 1]) and np.isnan(grid.heights[0, 2])  # row 0 = south
    q = scans.write_esri_ascii(tmp_path / "back.asc", grid, centre=True)
    back = scans.read_esri_ascii(q)
    np.testing.assert_array_equal(np.isnan(back.heights), np.isnan(grid.heights))
    np.testing.assert_allclose(back.heights[~np.isnan(back.heights)],
                               grid.heights[~np.isnan(grid.heights)])
    assert back.origin == pytest.approx(grid.origin)


def test_read_surface_takes_esri_and_still_the_rockjoint_grid_as_asc(tmp_path):
    p = tmp_path / "esri.asc"
    text, _ = _esri_text(["ncols 4", "nrows 3", "xllcorner 10", "yllcorner 20", "cellsize 2"])
    p.write_text(text)
    s = topo.read_surface(p)
    assert s.shape == (3, 4) and s.spacing_x == pytest.approx(2e-3)
    assert s.heights[0, 0] == pytest.approx((1.1 + 0.21) * 1e-3)   # south-west node
    q = tmp_path / "own.asc"
    q.write_text("# spacing: 0.5\n# unit: mm\n1 2 3\n4 5 6\n")
    assert topo.read_surface(q).shape == (2, 3)


def _resampling_error(wall, step, rng):
    x, y = sc.jittered_samples(4e-3, 44e-3, 4e-3, 44e-3, step, 0.2 * step, rng)
    pts = np.column_stack([x, y, wall(x, y)])
    grid = scans.resample(pts, 0.5e-3, origin=(8e-3, 8e-3), shape=(64, 64))
    gx, gy = grid.node_coordinates()
    err = np.abs(grid.heights - wall(gx, gy))
    return float(np.max(err)), grid, np.column_stack([x, y])


def test_resampling_error_within_the_interpolation_bound_and_second_order():
    """Max error <= R²/2 max|∂²z/∂u²| (Waldron 1998, R from the samples' triangles, M from the
    wall's Fourier series), and halving the sample spacing divides it by about 4 (>= 3)."""
    wall = sc.joint(seed=7).lower
    rng = np.random.default_rng(5)
    m = wall.max_second_derivative((0, 48e-3, 0, 48e-3), sc.SPEC.cutoff_wavelength / 16)
    errors = []
    for step in (0.4e-3, 0.2e-3):
        err, grid, xy = _resampling_error(wall, step, rng)
        assert grid.masked_count == 0
        r = sc.max_enclosing_radius(xy)
        assert err <= r * r / 2 * m, (step, err, r * r / 2 * m)
        errors.append(err)
    assert errors[0] / errors[1] >= 3.0, errors


def test_holes_are_flagged_and_counted_not_filled(caplog):
    wall = sc.joint(seed=7).lower
    rng = np.random.default_rng(6)
    step, hole = 0.4e-3, (24e-3, 24e-3, 3e-3)
    x, y = sc.jittered_samples(4e-3, 44e-3, 4e-3, 44e-3, step, 0.1 * step, rng)
    keep = np.hypot(x - hole[0], y - hole[1]) > hole[2]
    pts = np.column_stack([x[keep], y[keep], wall(x[keep], y[keep])])
    with caplog.at_level(logging.INFO, logger="rockjoint.scans"):
        grid = scans.resample(pts, 0.5e-3, origin=(8e-3, 8e-3), shape=(64, 64), path="w.xyz")
    gx, gy = grid.node_coordinates()
    r = np.hypot(gx - hole[0], gy - hole[1])
    assert np.all(np.isnan(grid.heights[r < hole[2] - 2 * step])), "the hole's inside is a hole"
    assert not np.any(np.isnan(grid.heights[r > hole[2] + 2 * step])), "no holes elsewhere"
    assert f"{grid.masked_count} holes" in caplog.text


def test_fill_policies_are_explicit():
    z = np.arange(16.0).reshape(4, 4)
    z[1, 2] = z[3, 0] = np.nan
    kept, n = scans.apply_fill(z.copy(), "none", "j")
    assert n == 2 and np.isnan(kept).sum() == 2
    filled, n = scans.apply_fill(z.copy(), "nearest", "j")
    assert n == 2 and not np.isnan(filled).any()
    assert filled[3, 0] in (z[2, 0], z[3, 1]) and filled[1, 2] in (z[0, 2], z[1, 1], z[1, 3],
                                                                    z[2, 2])
    with pytest.raises(scans.MaskedNodesError, match="j: 2 of 16 lattice nodes"):
        scans.apply_fill(z.copy(), "refuse", "j")
    with pytest.raises(ValueError, match="fill 'zero' is not one of none, nearest, refuse"):
        scans.apply_fill(z.copy(), "zero")


def test_levelling_and_flip_are_rigid():
    rng = np.random.default_rng(1)
    xy = rng.uniform(0, 0.05, (500, 2))
    tilted = np.column_stack([xy, 0.1 * xy[:, 0] - 0.05 * xy[:, 1] + 0.3])
    flat, lev = scans.level(tilted)
    np.testing.assert_allclose(flat[:, 2], 0.0, atol=1e-15)
    np.testing.assert_allclose(np.linalg.det(lev.rotation), 1.0)
    np.testing.assert_allclose(lev.to_scanner(flat), tilted, atol=1e-15)
    assert lev.tilt == pytest.approx(np.arctan(np.hypot(0.1, 0.05)))
    f = scans.flip(tilted)
    np.testing.assert_allclose(f[:, 1], tilted[:, 1])
    np.testing.assert_allclose(f[:, [0, 2]], -tilted[:, [0, 2]])
