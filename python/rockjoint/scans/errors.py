# SPDX-License-Identifier: MIT
"""Errors of the scan readers and the wall registration. Every one is a ValueError (the CLI
turns ValueError into a one-line message) and names the file and, where there is one, the
line or record, so a user can open the file at the fault."""
from __future__ import annotations

from typing import Optional


class ScanError(ValueError):
    """A scan file or a pair of scans that cannot give a trustworthy height map.

    ``path`` is the file, ``line`` the 1-based text line or ``record`` the 0-based binary
    record (STL facet) where the fault was found, if any."""

    def __init__(self, path, message: str, *, line: Optional[int] = None,
                 record: Optional[int] = None):
        self.path = None if path is None else str(path)
        self.line = line
        self.record = record
        where = "" if self.path is None else self.path
        if line is not None:
            where += f":{line}"
        elif record is not None:
            where += f": facet {record}"
        super().__init__(f"{where}: {message}" if where else message)


class MalformedScanError(ScanError):
    """Text that is not what the format says (non-numbers, missing keys, wrong counts)."""


class TruncatedScanError(ScanError):
    """The file ends before the data its header or format promises."""


class NonFiniteScanError(ScanError):
    """A coordinate or height is NaN or infinite where the format has no missing value."""


class NonManifoldScanError(ScanError):
    """An STL whose facets do not form one surface sheet (an edge shared by more than two
    facets, or degenerate facets): a scanned wall is a 2-manifold with boundary."""


class ScanUnitError(ScanError):
    """The sample spacing or extent in the stated unit is implausible for a joint scan
    (most often a file in µm read as mm, or in mm read as m)."""


class NoOverlapError(ScanError):
    """The two walls share too little area to register or to form an aperture."""


class MaskedNodesError(ScanError):
    """Lattice nodes not covered by the scan, with ``fill="refuse"``."""
