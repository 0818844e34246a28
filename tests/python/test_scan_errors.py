# SPDX-License-Identifier: MIT
"""Bad scan files get clear errors naming the file and the line or facet (ValueError
subclasses from rockjoint.scans.errors); nothing crashes, nothing is read silently wrong."""
import re
import struct

import numpy as np
import pytest

from rockjoint import scans


def _lattice_cloud(n=10, step=0.5):
    """n x n lattice points, step in file units, gentle heights (text lines)."""
    return [f"{i * step} {j * step} {0.01 * (i - j)}" for i in range(n) for j in range(n)]


def _binary_stl(path, facets):
    with open(path, "wb") as fh:
        fh.write(b"x" * 80 + struct.pack("<I", len(facets)))
        for f in facets:
            fh.write(struct.pack("<12fH", 0, 0, 1, *np.ravel(f), 0))


def _square_facets(n=6, step=0.5):
    out = []
    for i in range(n):
        for j in range(n):
            a, b = (i * step, j * step, 0), ((i + 1) * step, j * step, 0)
            c, d = (i * step, (j + 1) * step, 0), ((i + 1) * step, (j + 1) * step, 0)
            out += [(a, b, d), (a, d, c)]
    return out


def _ascii_stl(facets):
    lines = ["solid s"]
    for f in facets:
        lines += ["facet normal 0 0 1", "outer loop"]
        lines += [f"vertex {v[0]} {v[1]} {v[2]}" for v in f]
        lines += ["endloop", "endfacet"]
    return lines + ["endsolid s"]


def test_truncated_binary_stl(tmp_path):
    p = tmp_path / "cut.stl"
    _binary_stl(p, _square_facets())
    data = p.read_bytes()
    p.write_bytes(data[:-70])
    with pytest.raises(scans.TruncatedScanError,
                       match=rf"{re.escape(str(p))}: facet 70: binary STL header announces 72 "
                             r"facets .* truncated"):
        scans.read_scan(p)


def test_truncated_ascii_stl_names_the_last_line(tmp_path):
    p = tmp_path / "cut.stl"
    lines = _ascii_stl(_square_facets())[:40]
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(scans.TruncatedScanError,
                       match=rf"{re.escape(str(p))}:40: file ends while expecting"):
        scans.read_scan(p)


def test_ascii_stl_with_a_word_for_a_coordinate(tmp_path):
    p = tmp_path / "word.stl"
    lines = _ascii_stl(_square_facets())
    lines[4] = "vertex 0 zero 0"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(scans.MalformedScanError, match=rf"{re.escape(str(p))}:5: vertex "
                                                      r"coordinates .* are not numbers"):
        scans.read_scan(p)


def test_nan_vertex_in_binary_stl_names_the_facet(tmp_path):
    p = tmp_path / "nan.stl"
    facets = _square_facets()
    facets[17] = ((0, 0, float("nan")),) + facets[17][1:]
    _binary_stl(p, facets)
    with pytest.raises(scans.NonFiniteScanError, match=rf"{re.escape(str(p))}: facet 17: "
                                                      "non-finite vertex"):
        scans.read_scan(p)


def test_non_manifold_stl_is_refused(tmp_path):
    p = tmp_path / "fin.stl"
    facets = _square_facets()
    a, d = facets[0][0], facets[0][2]           # the diagonal of the first cell (2 facets)
    facets.append((a, d, (0.25, 0.25, 1.0)))    # a fin standing on it: 3 facets on one edge
    _binary_stl(p, facets)
    with pytest.raises(scans.NonManifoldScanError,
                       match=rf"{re.escape(str(p))}: facet \d+: non-manifold: the edge .* "
                             r"belongs to 3 facets"):
        scans.read_scan(p)


def test_folded_stl_is_not_a_height_field(tmp_path):
    """A Z-fold: panels at z = 0 (x 0..3), back to x = 2 at z = 0.5, forward to x = 5; the
    middle panel faces the other way, so (x, y) in 2..3 has three heights. Its share of the
    projected area is 3/21 = 14.3% on z = 0, a little less on the (slightly tilted) mean
    plane."""
    profile = [(0, 0), (1, 0), (2, 0), (3, 0), (2, 0.5), (3, 0.5), (4, 0.5), (5, 0.5)]
    facets = []
    for (x0, z0), (x1, z1) in zip(profile[:-1], profile[1:]):
        for y in range(3):
            a, b = (x0, y, z0), (x1, y, z1)
            c, d = (x0, y + 1, z0), (x1, y + 1, z1)
            facets += [(a, b, d), (a, d, c)]
    p = tmp_path / "fold.stl"
    _binary_stl(p, facets)
    with pytest.raises(scans.NonManifoldScanError,
                       match=rf"{re.escape(str(p))}: facet 18: not a height field: 6 facets "
                             r"\(1[34]\.\d% of the projected area\)"):
        scans.read_scan(p)


def test_degenerate_stl_facet_is_refused(tmp_path):
    p = tmp_path / "flat.stl"
    facets = _square_facets()
    facets[5] = (facets[5][0], facets[5][0], facets[5][2])
    p.write_text("\n".join(_ascii_stl(facets)) + "\n")
    with pytest.raises(scans.NonManifoldScanError, match=rf"{re.escape(str(p))}: facet 5: "
                                                        "degenerate facet"):
        scans.read_scan(p)


def test_xyz_line_with_two_values(tmp_path):
    p = tmp_path / "two.xyz"
    lines = _lattice_cloud()
    lines[6] = "1.0 2.0"
    p.write_text("\n".join(["x y z"] + lines) + "\n")
    with pytest.raises(scans.MalformedScanError,
                       match=rf"{re.escape(str(p))}:8: 2 value\(s\), expected x y z"):
        scans.read_scan(p)


def test_xyz_truncated_last_line(tmp_path):
    p = tmp_path / "cut.xyz"
    lines = _lattice_cloud()
    p.write_text("\n".join(lines) + "\n4.5 4.5")
    with pytest.raises(scans.TruncatedScanError,
                       match=rf"{re.escape(str(p))}:101: 2 value\(s\).*file ends inside"):
        scans.read_scan(p)


def test_xyz_nan_and_words_after_the_data(tmp_path):
    p = tmp_path / "nan.xyz"
    lines = _lattice_cloud()
    lines[20] = "1.0 nan 0.5"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(scans.NonFiniteScanError, match=rf"{re.escape(str(p))}:21: non-finite"):
        scans.read_scan(p)
    lines[20] = "1.0 two 0.5"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(scans.MalformedScanError,
                       match=rf"{re.escape(str(p))}:21: 'two' is not a number"):
        scans.read_scan(p)


def test_xyz_column_count_changes(tmp_path):
    p = tmp_path / "cols.csv"
    lines = [ln.replace(" ", ",") for ln in _lattice_cloud()]
    lines[30] += ",99"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(scans.MalformedScanError,
                       match=rf"{re.escape(str(p))}:31: 4 columns, the lines before have 3"):
        scans.read_scan(p)


@pytest.mark.parametrize("unit, file_step, what", [
    ("m", 0.5, "sample spacing 0.5 m"),          # a mm file read as metres
    ("mm", 500.0, "sample spacing 0.5 m"),       # a µm file read as mm
    ("mm", 0.00005, "sample spacing 5e-08 m"),   # a m file read as mm
])
def test_wrong_units_are_caught_by_spacing_and_extent(tmp_path, unit, file_step, what):
    p = tmp_path / "units.xyz"
    p.write_text("\n".join(_lattice_cloud(step=file_step)) + "\n")
    with pytest.raises(scans.ScanUnitError,
                       match=rf"{re.escape(str(p))}: {what} \(read in unit '{unit}'\) is "
                             "outside the plausible"):
        scans.read_scan(p, unit=unit)


def test_too_few_samples_and_unknown_formats(tmp_path):
    p = tmp_path / "few.xyz"
    p.write_text("0 0 0\n1 0 0\n0 1 0\n")
    with pytest.raises(scans.MalformedScanError, match=r"few\.xyz: 3 sample\(s\)"):
        scans.read_scan(p)
    q = tmp_path / "wall.ply"
    q.write_text("ply\n")
    with pytest.raises(ValueError, match=r"wall\.ply: no scan format for '\.ply'"):
        scans.read_scan(q)
    with pytest.raises(FileNotFoundError):
        scans.read_scan(tmp_path / "absent.stl")


ESRI_OK = ["ncols 3", "nrows 3", "xllcorner 0", "yllcorner 0", "cellsize 0.5"]
ESRI_DATA = ["1 2 3", "4 5 6", "7 8 9"]


@pytest.mark.parametrize("header, data, cls, message", [
    (ESRI_OK[1:], ESRI_DATA, scans.MalformedScanError, r": header key 'ncols' missing"),
    (ESRI_OK[:4], ESRI_DATA, scans.MalformedScanError, r": header key 'cellsize' \(or both"),
    (ESRI_OK + ["xllcenter 0.25"], ESRI_DATA, scans.MalformedScanError,
     r": header has both xllcorner and xllcenter"),
    (ESRI_OK + ["ncols 4"], ESRI_DATA, scans.MalformedScanError,
     r":6: header key 'ncols' repeated"),
    (ESRI_OK, ESRI_DATA[:2], scans.TruncatedScanError,
     r":7: 6 values for nrows 3 x ncols 3 = 9: the grid stops in row 3"),
    (ESRI_OK, ["1 2 3", "4 x 6", "7 8 9"], scans.MalformedScanError,
     r":7: value 'x' is not a number"),
    (ESRI_OK, ESRI_DATA + ["10"], scans.MalformedScanError,
     r":9: 10 values, more than nrows 3 x ncols 3"),
    (["cols 3"] + ESRI_OK[1:], ESRI_DATA, scans.MalformedScanError,
     r":1: 'cols' is not an ESRI ASCII header key"),
    (ESRI_OK[:4] + ["cellsize 500"], ESRI_DATA, scans.ScanUnitError,
     r": sample spacing 0.5 m \(read in unit 'mm'\)"),
    (ESRI_OK, ["1 2 3", "4 -9999 6", "7 8 9"], scans.MalformedScanError,
     r":7: value -9999 looks like a NODATA marker but the header has no NODATA_value"),
], ids=["no-ncols", "no-cellsize", "corner-and-centre", "repeated", "truncated", "word",
        "too-many", "bad-key", "units", "undeclared-nodata"])
def test_malformed_esri_grids(tmp_path, header, data, cls, message):
    p = tmp_path / "bad.asc"
    p.write_text("\n".join(header + data) + "\n")
    with pytest.raises(cls, match=re.escape(str(p)) + message):
        scans.read_esri_ascii(p)
