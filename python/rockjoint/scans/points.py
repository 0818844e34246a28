# SPDX-License-Identifier: MIT
"""A scanned wall as it comes from the scanner: 3D samples in the scanner's frame, SI units,
with the units sanity check every reader applies."""
from __future__ import annotations

import dataclasses
from typing import Optional

import numpy as np
from scipy.spatial import cKDTree

from .._rockjoint.topography import metres_per_unit as _cpp_metres_per_unit
from .errors import MalformedScanError, ScanUnitError

# Plausible sample spacings and extents of a rock-joint scan [m]: laser and structured-light
# scanners and profilometers sample at 1 µm to 2 mm, specimens and outcrop patches span 1 mm
# to 20 m. A file read in the wrong unit lands a factor 1000 outside (µm read as mm gives a
# 0.5 m spacing; mm read as m a 0.5 m spacing too), so these bounds catch it.
PLAUSIBLE_SPACING = (1e-7, 5e-3)
PLAUSIBLE_EXTENT = (1e-3, 20.0)


#: metres in one unit (m, cm, mm, um/µm, nm): the library's one unit table (topography/units.cpp)
metres_per_unit = _cpp_metres_per_unit


@dataclasses.dataclass
class ScanPoints:
    """Samples of one wall: ``points`` (N, 3) [m] in the scanner's frame (z = height as the
    scanner saw it), ``triangles`` (M, 3) vertex indices for an STL, ``path`` the file."""

    points: np.ndarray
    path: Optional[str] = None
    triangles: Optional[np.ndarray] = None

    def sample_spacing(self) -> float:
        """Median in-plane distance to the nearest other sample [m]: the scan's resolution,
        the default lattice spacing and the scale of the hole criterion."""
        xy = self.points[:, :2]
        d, _ = cKDTree(xy).query(xy, k=2)
        d = d[:, 1]
        d = d[d > 0]
        return float(np.median(d)) if d.size else 0.0


def check_units(path, spacing: float, extent: float, unit: str) -> None:
    """Refuse a scan whose spacing [m] or in-plane extent [m] is implausible (PLAUSIBLE_*):
    the unit argument is most probably wrong. The message says what was read and why."""
    lo, hi = PLAUSIBLE_SPACING
    if not lo <= spacing <= hi:
        raise ScanUnitError(path, f"sample spacing {spacing:.3g} m (read in unit '{unit}') is "
                            f"outside the plausible {lo:g}-{hi:g} m of a joint scan; is the "
                            "file in another unit? pass unit=")
    lo, hi = PLAUSIBLE_EXTENT
    if not lo <= extent <= hi:
        raise ScanUnitError(path, f"scan extent {extent:.3g} m (read in unit '{unit}') is "
                            f"outside the plausible {lo:g}-{hi:g} m of a joint scan; is the "
                            "file in another unit? pass unit=")


def finish(points: np.ndarray, path, unit: str, triangles=None, *, minimum: int = 9
           ) -> ScanPoints:
    """Scale to SI, check the count, the in-plane spread and the units."""
    if points.shape[0] < minimum:
        raise MalformedScanError(path, f"{points.shape[0]} sample(s): a wall needs at least "
                                 f"{minimum}")
    scan = ScanPoints(points * metres_per_unit(unit), None if path is None else str(path),
                      triangles)
    xy = scan.points[:, :2]
    extent = float(np.max(np.ptp(xy, axis=0)))
    check_units(path, scan.sample_spacing(), extent, unit)
    return scan
