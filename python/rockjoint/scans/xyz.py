# SPDX-License-Identifier: MIT
"""Unstructured XYZ point clouds: one sample per line, "x y z" separated by whitespace, commas
or semicolons; further columns (intensity, colour, normals) are ignored but must be there on
every line. Lines starting with '#', '//' or '%' are comments anywhere; text lines before the
first sample (a column header such as "X,Y,Z") are skipped. A point cloud has no missing
value: NaN or inf is an error (a hole is where there are no samples, and the lattice flags
it)."""
from __future__ import annotations

import math
import os
import re

import numpy as np

from .errors import MalformedScanError, NonFiniteScanError, TruncatedScanError
from .points import ScanPoints, finish, metres_per_unit

_SPLIT = re.compile(r"[\s,;]+")
_COMMENT = ("#", "//", "%")


def read_xyz_points(path, unit: str = "mm") -> ScanPoints:
    """Read an XYZ point cloud with coordinates in ``unit`` (files say nothing about units).
    Raises MalformedScanError (line not numbers, column count changes), NonFiniteScanError
    (NaN/inf), TruncatedScanError (last line cut), ScanUnitError; each names file and line."""
    path = os.fspath(path)
    rows = []
    columns = None
    with open(path, "rb") as fh:
        raw = fh.read()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise MalformedScanError(path, f"not a text XYZ file (byte {err.start} is not UTF-8); "
                                 "binary scan formats: use .stl") from None
    lines = text.splitlines()
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith(_COMMENT):
            continue
        fields = [f for f in _SPLIT.split(stripped) if f]
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if not rows:        # a column header before the first sample
                continue
            bad = next(f for f in fields if not _is_number(f))
            raise MalformedScanError(path, f"'{bad}' is not a number (expected x y z)",
                                     line=number) from None
        if len(values) < 3:
            cut = number == len(lines) and not text.endswith("\n")
            cls = TruncatedScanError if cut else MalformedScanError
            raise cls(path, f"{len(values)} value(s), expected x y z"
                      + (" (file ends inside this line)" if cut else ""), line=number)
        if columns is None:
            columns = len(values)
        elif len(values) != columns:
            raise MalformedScanError(path, f"{len(values)} columns, the lines before have "
                                     f"{columns}", line=number)
        if not all(math.isfinite(v) for v in values[:3]):
            raise NonFiniteScanError(path, f"non-finite coordinate in '{stripped}' (a point "
                                     "cloud has no missing value: drop the sample)",
                                     line=number)
        rows.append(values[:3])
    points = np.array(rows, dtype=float).reshape(-1, 3)
    return finish(points, path, unit)


def _is_number(field: str) -> bool:
    try:
        float(field)
        return True
    except ValueError:
        return False


def write_xyz_points(path, points: np.ndarray, unit: str = "mm", header: bool = True) -> str:
    """Write (N, 3) points [m] as "x y z" lines in ``unit`` (with a column-header line)."""
    scale = 1.0 / _metres(unit)
    with open(path, "w") as fh:
        if header:
            fh.write(f"# x y z [{unit}]\nX,Y,Z\n")
        np.savetxt(fh, np.asarray(points) * scale, fmt="%.9g", delimiter=",")
    return os.fspath(path)


def _metres(unit: str) -> float:
    return metres_per_unit(unit)
