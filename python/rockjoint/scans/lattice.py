# SPDX-License-Identifier: MIT
"""Scattered samples -> a regular lattice, with holes flagged, never filled silently.

Method: piecewise-linear interpolation on the Delaunay triangulation of the samples' (x, y)
(scipy.spatial.Delaunay + LinearNDInterpolator). At a lattice node inside a triangle whose
vertices lie on a smooth surface z(x, y) the error is at most R²/2 · max|∂²z/∂u²| (R the
radius of the smallest disc containing the triangle: its circumradius if no angle is obtuse,
half its longest edge otherwise; u any direction; Waldron 1998, SIAM J. Numer. Anal. 35,
1191): for samples on a lattice of step h split into right triangles, R = h/√2 and the bound
is h²/4 · max|curvature|; independent measurement noise of amplitude a adds at most a, because
a linear interpolant is a convex combination of its three samples.

A node is a hole (NaN, counted) if it lies outside the convex hull of the samples or in a
triangle with an edge longer than ``hole_factor`` times the median sample spacing: such a
triangle spans a gap in the scan and interpolating across it would invent topography."""
from __future__ import annotations

import dataclasses
import logging
from typing import Optional, Tuple

import numpy as np
from scipy.interpolate import LinearNDInterpolator
from scipy.ndimage import distance_transform_edt
from scipy.spatial import Delaunay

from .._rockjoint.topography import Surface
from .errors import MaskedNodesError

log = logging.getLogger(__name__)

FILL_POLICIES = ("none", "nearest", "refuse")


@dataclasses.dataclass
class ScanGrid:
    """Heights [m] on a regular lattice, NaN = hole. Node (i, j) sits at
    x = origin[0] + j·spacing_x, y = origin[1] + i·spacing_y [m] (row i increases with y)."""

    heights: np.ndarray
    spacing_x: float
    spacing_y: float
    origin: Tuple[float, float] = (0.0, 0.0)
    path: Optional[str] = None

    @property
    def masked_count(self) -> int:
        """Number of holes (NaN nodes)."""
        return int(np.count_nonzero(np.isnan(self.heights)))

    def node_coordinates(self) -> Tuple[np.ndarray, np.ndarray]:
        """(x, y) [m] of every node, each shaped like ``heights``."""
        rows, cols = self.heights.shape
        x = self.origin[0] + self.spacing_x * np.arange(cols)
        y = self.origin[1] + self.spacing_y * np.arange(rows)
        return np.meshgrid(x, y)

    def points(self) -> np.ndarray:
        """The valid nodes as (N, 3) samples [m]."""
        x, y = self.node_coordinates()
        ok = ~np.isnan(self.heights)
        return np.column_stack([x[ok], y[ok], self.heights[ok]])

    def surface(self):
        """As a rockjoint.topography.Surface (origin dropped; NaN stays a masked point)."""
        return Surface(self.heights, self.spacing_x, self.spacing_y)


def resample(points: np.ndarray, spacing: float, *, origin: Optional[Tuple[float, float]] = None,
             shape: Optional[Tuple[int, int]] = None, sample_spacing: Optional[float] = None,
             hole_factor: float = 3.0, path=None) -> ScanGrid:
    """Linear interpolation of (N, 3) samples [m] on their Delaunay triangulation at the nodes
    of a square lattice of step ``spacing`` [m] (default origin and shape: the samples'
    bounding box). Holes (see module doc) are NaN; their count is logged."""
    xy, z = points[:, :2], points[:, 2]
    if origin is None:
        origin = (float(xy[:, 0].min()), float(xy[:, 1].min()))
    if shape is None:
        top = xy.max(axis=0)
        shape = (int(np.floor((top[1] - origin[1]) / spacing + 1e-9)) + 1,
                 int(np.floor((top[0] - origin[0]) / spacing + 1e-9)) + 1)
    grid = ScanGrid(np.full(shape, np.nan), spacing, spacing, tuple(origin), path)
    gx, gy = grid.node_coordinates()
    nodes = np.column_stack([gx.ravel(), gy.ravel()])
    tri = Delaunay(xy)
    heights = LinearNDInterpolator(tri, z)(nodes)
    simplex = tri.find_simplex(nodes)
    if sample_spacing is None:
        sample_spacing = _median_edge(tri)
    corners = xy[tri.simplices]
    longest = np.max(np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2), axis=1)
    gap = np.zeros(nodes.shape[0], dtype=bool)
    inside = simplex >= 0
    gap[inside] = longest[simplex[inside]] > hole_factor * sample_spacing
    heights[gap | ~inside] = np.nan
    grid.heights = heights.reshape(shape)
    log.info("%s: resampled %d samples to %d x %d nodes at %.4g mm; %d holes (%d outside the "
             "scan, %d across gaps > %.3g mm)", path or "scan", len(z), shape[0], shape[1],
             spacing * 1e3, grid.masked_count, int(np.count_nonzero(~inside)),
             int(np.count_nonzero(gap)), hole_factor * sample_spacing * 1e3)
    return grid


def _median_edge(tri: Delaunay) -> float:
    c = tri.points[tri.simplices]
    return float(np.median(np.linalg.norm(c - np.roll(c, 1, axis=1), axis=2)))


def apply_fill(heights: np.ndarray, fill: str, path=None) -> Tuple[np.ndarray, int]:
    """The explicit policy for holes: "none" keeps NaN (the analysis masks them), "nearest"
    copies the nearest valid node's height, "refuse" raises MaskedNodesError. Returns the
    heights and the number of holes met; every count is logged."""
    if fill not in FILL_POLICIES:
        raise ValueError(f"fill '{fill}' is not one of {', '.join(FILL_POLICIES)}")
    holes = np.isnan(heights)
    count = int(np.count_nonzero(holes))
    if count == 0:
        return heights, 0
    if fill == "refuse":
        raise MaskedNodesError(path, f"{count} of {heights.size} lattice nodes are not covered "
                               "by the scan; choose fill='none' (mask) or 'nearest'")
    if fill == "none":
        log.warning("%s: %d of %d nodes masked (NaN), not filled", path or "joint", count,
                    heights.size)
        return heights, count
    _, (ii, jj) = distance_transform_edt(holes, return_indices=True)
    log.warning("%s: %d of %d nodes filled from their nearest valid node", path or "joint",
                count, heights.size)
    return heights[ii, jj], count
