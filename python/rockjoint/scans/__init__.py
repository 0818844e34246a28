# SPDX-License-Identifier: MIT
"""Real joint scans in: STL meshes and XYZ point clouds of each wall in its scanner's frame,
ESRI ASCII grids; resampling to a lattice with holes flagged; one frame for both walls
(flip, level, register for matedness); errors that name the file and the line or facet.

Files carry no units: ``unit`` (default mm) says what they are in; SI inside. Typical use::

    from rockjoint import scans, topography as topo
    upper = scans.read_scan("upper.stl")                 # or .xyz/.csv/.txt points, .asc
    lower = scans.read_scan("lower.stl")
    joint = scans.joint_from_scans(upper, lower, fill="none")
    print(joint.report())                                # rotation, shift, residual misfit
    result = topo.analyse(joint.composite.composite)     # holes stay masked
"""
from __future__ import annotations

import os
from typing import Optional

from .errors import (MalformedScanError, MaskedNodesError, NoOverlapError, NonFiniteScanError,
                     NonManifoldScanError, ScanError, ScanUnitError, TruncatedScanError)
from .esri import is_esri_ascii, read_esri_ascii, write_esri_ascii
from .frame import Levelling, flip, level
from .joint import RegisteredJoint, joint_from_scans
from .lattice import FILL_POLICIES, ScanGrid, apply_fill, resample
from .points import ScanPoints
from .registration import Registration, register
from .stl import read_stl, write_stl
from .xyz import read_xyz_points, write_xyz_points

SCAN_FORMATS = {"stl": (".stl",), "points": (".xyz", ".csv", ".pts"), "esri": (".asc",)}


def scan_format(path, format: Optional[str] = None) -> str:
    """The scan format of a file: ``format`` if given, else by extension (an .asc file is
    ESRI only if it starts with an ESRI header key). Raises ValueError otherwise."""
    if format is not None:
        if format not in SCAN_FORMATS:
            raise ValueError(f"scan format '{format}' is not one of {', '.join(SCAN_FORMATS)}")
        return format
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    for name, suffixes in SCAN_FORMATS.items():
        if suffix in suffixes:
            return name
    raise ValueError(f"{path}: no scan format for '{suffix}'; use .stl, .xyz/.csv/.pts "
                     "(point cloud) or .asc (ESRI ASCII), or pass format=")


def read_scan(path, format: Optional[str] = None, *, unit: str = "mm",
              height_unit: Optional[str] = None) -> ScanPoints:
    """Samples of one wall from an STL, XYZ point cloud or ESRI ASCII grid (its valid nodes)
    in the scanner's frame, SI. ``unit``: the file's length unit (``height_unit`` for ESRI
    heights if different)."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"no such scan file: '{path}'")
    kind = scan_format(path, format)
    if kind == "stl":
        return read_stl(path, unit)
    if kind == "points":
        return read_xyz_points(path, unit)
    grid = read_esri_ascii(path, unit, height_unit)
    return ScanPoints(grid.points(), path)


__all__ = ["ScanError", "MalformedScanError", "TruncatedScanError", "NonFiniteScanError",
           "NonManifoldScanError", "ScanUnitError", "NoOverlapError", "MaskedNodesError",
           "ScanPoints", "ScanGrid", "Registration", "RegisteredJoint", "FILL_POLICIES",
           "read_scan", "scan_format", "read_stl", "write_stl", "read_xyz_points",
           "write_xyz_points", "read_esri_ascii", "write_esri_ascii", "is_esri_ascii",
           "resample", "apply_fill", "flip", "level", "Levelling", "register", "joint_from_scans"]
