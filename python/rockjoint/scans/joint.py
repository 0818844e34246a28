# SPDX-License-Identifier: MIT
"""Two scanned walls -> one joint: flip the upper wall, level both, resample the lower wall,
register the upper one onto it, resample the upper wall once at the registered positions (one
interpolation, so the error bound of lattice.py holds), cut the largest overlap rectangle,
apply the hole policy and form the contact state (rockjoint.topography)."""
from __future__ import annotations

import dataclasses
import logging
from typing import Optional

import numpy as np
from scipy.ndimage import binary_fill_holes

from .._rockjoint import topography as _cpp_topography
from .errors import NoOverlapError
from .frame import Levelling, flip, level, plane_removal_mode
from .lattice import ScanGrid, apply_fill, resample
from .points import ScanPoints
from .registration import Registration, register

log = logging.getLogger(__name__)


@dataclasses.dataclass
class RegisteredJoint:
    """The two walls on one lattice of the lower wall's levelled frame, and how they got
    there. ``upper``/``lower`` are ScanGrids with a common origin; ``composite`` is the
    rockjoint.topography contact state (aperture and composite topography)."""

    upper: ScanGrid
    lower: ScanGrid
    composite: object
    registration: Registration
    lower_levelling: Levelling
    upper_levelling: Levelling
    masked_count: int        # holes in the overlap: NaN (fill="none") or filled
    fill: str

    def scanner_coordinates(self) -> np.ndarray:
        """Lattice nodes (rows, cols, 3) [m] in the lower wall's scanner frame, on its mean
        plane: where each node of the joint is on the lower scan."""
        x, y = self.lower.node_coordinates()
        q = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
        return self.lower_levelling.to_scanner(q).reshape(x.shape + (3,))

    def report(self) -> str:
        """A one-paragraph summary of the registration (rotation, shift, overlap, misfit)."""
        r = self.registration
        return (f"registration: rotation {np.degrees(r.rotation):.4f}°, shift "
                f"({r.translation[0] * 1e3:.4g}, {r.translation[1] * 1e3:.4g}) mm, overlap "
                f"{100 * r.overlap_fraction:.0f}% of the smaller wall, residual misfit (rms of "
                f"the aperture's variation) {r.residual_rms * 1e3:.4g} mm; joint lattice "
                f"{self.lower.heights.shape[0]} x {self.lower.heights.shape[1]} at "
                f"{self.lower.spacing_x * 1e3:.4g} mm, {self.masked_count} hole node(s) "
                f"({'masked' if self.fill == 'none' else 'filled: ' + self.fill})")


def joint_from_scans(upper: ScanPoints, lower: ScanPoints, *, spacing: Optional[float] = None,
                     flip_upper: bool = True, fill: str = "none", plane_removal: str = "common",
                     hole_factor: float = 3.0, angle_step: float = np.radians(2.0),
                     max_rotation: float = np.pi, min_overlap: float = 0.5,
                     min_correlation: float = 0.5, max_misfit: float = 0.5
                     ) -> RegisteredJoint:
    """The joint of two walls each scanned in its own frame (see the module doc).

    ``spacing`` [m]: lattice step (default: the coarser wall's median sample spacing);
    ``flip_upper``: the upper scan looks at the joint face from above (default) - set False if
    its heights are already in the joint frame; ``fill``: "none" (holes stay NaN, masked by
    the analysis), "nearest" or "refuse" (MaskedNodesError); the hole count is logged.
    ``angle_step``, ``max_rotation``, ``min_overlap``, ``min_correlation``, ``max_misfit``:
    see registration.register (NoOverlapError when the walls do not face each other)."""
    up = flip(upper.points) if flip_upper else upper.points
    up, up_level = level(up)
    low, low_level = level(lower.points)
    h = spacing or max(upper.sample_spacing(), lower.sample_spacing())
    low_grid = resample(low, h, hole_factor=hole_factor, path=lower.path,
                        sample_spacing=lower.sample_spacing())
    up_grid = resample(up, h, hole_factor=hole_factor, path=upper.path,
                       sample_spacing=upper.sample_spacing())
    reg = register(low_grid, up_grid, angle_step=angle_step, max_rotation=max_rotation,
                   min_overlap=min_overlap, min_correlation=min_correlation,
                   max_misfit=max_misfit,
                   path=upper.path)
    up_on_low = resample(reg.apply(up), h, origin=low_grid.origin,
                         shape=low_grid.heights.shape, hole_factor=hole_factor,
                         path=upper.path, sample_spacing=upper.sample_spacing())
    box = _overlap_rectangle(~np.isnan(up_on_low.heights) & ~np.isnan(low_grid.heights))
    if box is None:
        raise NoOverlapError(upper.path, "the registered walls have no common rectangle of "
                             "3 x 3 nodes")
    (i0, i1), (j0, j1) = box
    origin = (low_grid.origin[0] + j0 * h, low_grid.origin[1] + i0 * h)
    zu = up_on_low.heights[i0:i1, j0:j1]
    zl = low_grid.heights[i0:i1, j0:j1]
    holes = np.isnan(zu) | np.isnan(zl)
    where = f"{upper.path or 'upper'} + {lower.path or 'lower'}"
    if fill == "nearest":
        zu, _ = apply_fill(zu, fill, where)
        zl, _ = apply_fill(zl, fill, where)
        count = int(np.count_nonzero(holes))
    else:
        zu, count = apply_fill(np.where(holes, np.nan, zu), fill, where)
        zl = np.where(holes, np.nan, zl)
    ug = ScanGrid(zu, h, h, origin, upper.path)
    lg = ScanGrid(zl, h, h, origin, lower.path)
    composite = _cpp_topography.composite_topography(ug.surface(), lg.surface(), 0, 0,
                                                     plane_removal_mode(plane_removal))
    joint = RegisteredJoint(ug, lg, composite, reg, low_level, up_level, count, fill)
    log.info("%s", joint.report())
    return joint


def _overlap_rectangle(covered: np.ndarray):
    """Rows and columns [i0, i1) x [j0, j1) of the largest axis-aligned rectangle of nodes
    that both walls cover, holes inside the overlap counted as covered (they are the fill
    policy's business, the overlap's outline is not); None if smaller than 3 x 3."""
    inside = binary_fill_holes(covered)
    best, box = 0, None
    heights = np.zeros(inside.shape[1], dtype=int)
    for i in range(inside.shape[0]):
        heights = np.where(inside[i], heights + 1, 0)
        stack = []    # largest rectangle under the histogram of column heights
        for j in range(inside.shape[1] + 1):
            hj = heights[j] if j < inside.shape[1] else 0
            start = j
            while stack and stack[-1][1] >= hj:
                start, top = stack.pop()
                w = j - start
                if top >= 3 and w >= 3 and top * w > best:
                    best, box = top * w, ((i - top + 1, i + 1), (start, j))
            stack.append((start, hj))
    return box
