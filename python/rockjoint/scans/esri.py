# SPDX-License-Identifier: MIT
"""ESRI ASCII grids (.asc): a header of "key value" lines, then nrows rows of ncols values
from the north (largest y) row down. Keys are case-insensitive and in any order: ncols,
nrows, xllcorner or xllcenter, yllcorner or yllcenter, cellsize or dx and dy, and an optional
NODATA_value. The value of cell (r, c) belongs to the cell's centre, which is
    x = xllcorner + (c + 1/2)·dx,  y = yllcorner + (nrows - r - 1/2)·dy   (corner header)
    x = xllcenter + c·dx,          y = yllcenter + (nrows - 1 - r)·dy      (centre header)
(ESRI "ASCII raster format"; GDAL AAIGrid driver for dx/dy). The grid comes back with row i
increasing in y, like every rockjoint lattice; NODATA and NaN cells are holes (NaN)."""
from __future__ import annotations

import math
import os
from typing import Dict, Optional

import numpy as np

from .errors import MalformedScanError, TruncatedScanError
from .lattice import ScanGrid
from .points import check_units, metres_per_unit

# Values that writers use for NODATA (ESRI/GDAL -9999, int16 -32768, float32 lowest): read
# as heights without a NODATA_value line they would be a cliff kilometres deep, so a grid
# without the key that holds one is refused rather than read silently wrong.
_SENTINELS = (-9999.0, -32768.0, -3.4028234663852886e38, -3.4028230607370965e38)

_KEYS = ("ncols", "nrows", "xllcorner", "xllcenter", "yllcorner", "yllcenter", "cellsize",
         "dx", "dy", "nodata_value")


def is_esri_ascii(path) -> bool:
    """True if the first non-blank line starts with an ESRI header key."""
    with open(path, "rb") as fh:
        for raw in fh:
            words = raw.decode("latin-1").split()
            if words:
                return words[0].lower() in _KEYS
    return False


def read_esri_ascii(path, unit: str = "mm", height_unit: Optional[str] = None) -> ScanGrid:
    """Read an ESRI ASCII grid, x, y and cellsize in ``unit``, heights in ``height_unit``
    (default ``unit``). Raises MalformedScanError (missing, repeated or conflicting keys,
    non-numbers, too many values), TruncatedScanError (fewer than nrows·ncols values) or
    ScanUnitError, naming the file and line."""
    path = os.fspath(path)
    with open(path, "r", encoding="latin-1") as fh:
        lines = fh.read().splitlines()
    header: Dict[str, float] = {}
    start = len(lines)
    for number, line in enumerate(lines, start=1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        if key not in _KEYS:
            if _number(words[0]) is None and not header:
                raise MalformedScanError(path, f"'{words[0]}' is not an ESRI ASCII header "
                                         f"key ({', '.join(_KEYS)})", line=number)
            start = number - 1
            break
        if len(words) != 2 or _number(words[1]) is None:
            raise MalformedScanError(path, f"header line '{line.strip()}' must be "
                                     "'<key> <number>'", line=number)
        if key in header:
            raise MalformedScanError(path, f"header key '{words[0]}' repeated", line=number)
        header[key] = _number(words[1])
    geometry = _geometry(path, header)
    rows, cols = geometry["nrows"], geometry["ncols"]
    values, where = [], []
    for number in range(start + 1, len(lines) + 1):
        for word in lines[number - 1].split():
            v = _number(word)
            if v is None:
                raise MalformedScanError(path, f"value '{word}' is not a number", line=number)
            values.append(v)
            where.append(number)
    if len(values) < rows * cols:
        raise TruncatedScanError(path, f"{len(values)} values for nrows {rows} x ncols {cols} = "
                                 f"{rows * cols}: the grid stops in row {len(values) // cols + 1}",
                                 line=len(lines))
    if len(values) > rows * cols:
        raise MalformedScanError(path, f"{len(values)} values, more than nrows {rows} x ncols "
                                 f"{cols}: the header does not describe the data",
                                 line=where[rows * cols])
    z = np.array(values, dtype=float).reshape(rows, cols)[::-1]   # north row first in file
    if "nodata_value" in header:
        z[z == header["nodata_value"]] = np.nan
    else:
        sentinel = np.isin(np.array(values[:rows * cols]), _SENTINELS)
        if sentinel.any():
            k = int(np.argmax(sentinel))
            raise MalformedScanError(path, f"value {values[k]:g} looks like a NODATA marker "
                                     "but the header has no NODATA_value line: add it (or "
                                     "write the missing cells as nan)", line=where[k])
    scale = metres_per_unit(unit)
    dx, dy = geometry["dx"] * scale, geometry["dy"] * scale
    grid = ScanGrid(z * metres_per_unit(height_unit or unit), dx, dy,
                    (geometry["x0"] * scale, geometry["y0"] * scale), path)
    check_units(path, min(dx, dy), max(dx * (cols - 1), dy * (rows - 1)), unit)
    return grid


def _geometry(path, h: Dict[str, float]) -> Dict[str, float]:
    """Counts, steps and the centre of the south-west cell from either header variant."""
    for key in ("ncols", "nrows"):
        if key not in h:
            raise MalformedScanError(path, f"header key '{key}' missing")
        if h[key] != int(h[key]) or h[key] < 2:
            raise MalformedScanError(path, f"{key} {h[key]:g} must be an integer >= 2")
    if "cellsize" in h and ("dx" in h or "dy" in h):
        raise MalformedScanError(path, "header has both cellsize and dx/dy")
    if "cellsize" in h:
        dx = dy = h["cellsize"]
    elif "dx" in h and "dy" in h:
        dx, dy = h["dx"], h["dy"]
    else:
        raise MalformedScanError(path, "header key 'cellsize' (or both 'dx' and 'dy') missing")
    if not (dx > 0 and dy > 0):
        raise MalformedScanError(path, f"cell size {dx:g} x {dy:g} must be > 0")
    out = {"ncols": int(h["ncols"]), "nrows": int(h["nrows"]), "dx": dx, "dy": dy}
    for axis, step in (("x", dx), ("y", dy)):
        corner, centre = f"{axis}llcorner", f"{axis}llcenter"
        if corner in h and centre in h:
            raise MalformedScanError(path, f"header has both {corner} and {centre}")
        if corner in h:
            out[f"{axis}0"] = h[corner] + 0.5 * step
        elif centre in h:
            out[f"{axis}0"] = h[centre]
        else:
            raise MalformedScanError(path, f"header key '{corner}' (or '{centre}') missing")
    return out


def _number(word: str) -> Optional[float]:
    try:
        v = float(word)
    except ValueError:
        return None
    return v if not math.isinf(v) else None


def write_esri_ascii(path, grid: ScanGrid, unit: str = "mm", *, centre: bool = False,
                     nodata: Optional[float] = -9999.0) -> str:
    """Write a ScanGrid (square or dx/dy cells) as ESRI ASCII in ``unit``."""
    s = 1.0 / metres_per_unit(unit)
    rows, cols = grid.heights.shape
    x0, y0 = grid.origin
    lines = [f"ncols {cols}", f"nrows {rows}"]
    if centre:
        lines += [f"xllcenter {x0 * s:.12g}", f"yllcenter {y0 * s:.12g}"]
    else:
        lines += [f"xllcorner {(x0 - grid.spacing_x / 2) * s:.12g}",
                  f"yllcorner {(y0 - grid.spacing_y / 2) * s:.12g}"]
    if grid.spacing_x == grid.spacing_y:
        lines.append(f"cellsize {grid.spacing_x * s:.12g}")
    else:
        lines += [f"dx {grid.spacing_x * s:.12g}", f"dy {grid.spacing_y * s:.12g}"]
    z = grid.heights[::-1] * s
    if nodata is not None:
        lines.append(f"NODATA_value {nodata:g}")
        z = np.where(np.isnan(z), nodata, z)
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
        np.savetxt(fh, z, fmt="%.9g")
    return os.fspath(path)
