# SPDX-License-Identifier: MIT
"""The openings a tunnel section is cut around (meshes.tunnel_section), with what the builders
need of them: extent, area and perimeter (closed forms), outline points, where a line crosses
them, and the outline as pieces (lines and arcs, planar_section.OutlinePiece). Lengths in metres."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .joint_geometry import _positive
from .planar_section import OutlinePiece


def _line_circle(a, d, centre, radius) -> tuple | None:
    """(t1, t2), t1 < t2: where the line a + t d crosses the circle, or None if it misses or
    touches it. |a - c + t d|² = r²: d·d t² + 2 f·d t + f·f - r² = 0 with f = a - c."""
    f = np.subtract(a, centre)
    qa, qb, qc = d @ d, f @ d, f @ f - radius ** 2
    disc = qb * qb - qa * qc
    if not disc > 0.0:
        return None
    root = math.sqrt(disc)
    return ((-qb - root) / qa, (-qb + root) / qa)


def _outline_points(pieces, count: int) -> np.ndarray:
    """About `count` points [m] along the closed chain of outline pieces, equally spaced on each
    piece, from the first piece's start (each piece's end is the next one's start)."""
    step = sum(p.length for p in pieces) / count
    parts = []
    for p in pieces:
        s = np.linspace(0.0, 1.0, max(2, int(p.length / step)), endpoint=False)
        if p.centre is None:
            parts.append(np.asarray(p.start) + s[:, None] * np.subtract(p.end, p.start))
        else:
            a0 = math.atan2(p.start[1] - p.centre[1], p.start[0] - p.centre[0])
            phi = a0 + s * p.span()
            parts.append(np.asarray(p.centre) + p.radius * np.stack([np.cos(phi), np.sin(phi)], axis=1))
    return np.concatenate(parts)


def _point(value, label: str) -> np.ndarray:
    p = np.asarray(value, dtype=float)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"{label} must be 2 finite coordinates (x, y) [m], got {value!r}")
    return p


@dataclass(frozen=True)
class CircularOpening:
    """A circular opening of ``radius`` [m] centred at ``centre`` (x, y) [m]."""

    centre: tuple
    radius: float

    def __post_init__(self):
        object.__setattr__(self, "centre", tuple(_point(self.centre, "CircularOpening.centre")))
        object.__setattr__(self, "radius", _positive("CircularOpening.radius", self.radius))

    @property
    def area(self) -> float:
        """Area of the opening [m²]."""
        return math.pi * self.radius ** 2

    @property
    def perimeter(self) -> float:
        """Length of the outline [m]."""
        return 2.0 * math.pi * self.radius

    def bounds(self) -> tuple:
        """(x_min, y_min, x_max, y_max) [m]."""
        (x, y), a = self.centre, self.radius
        return (x - a, y - a, x + a, y + a)

    def outline(self, count: int = 720) -> np.ndarray:
        """(about count, 2) points [m] along the outline, counter-clockwise from the right springline."""
        return _outline_points(self.pieces(), count)

    def pieces(self) -> list:
        """The outline as four quarter arcs, counter-clockwise from the right springline."""
        (x, y), a = self.centre, self.radius
        ends = [(x + a, y), (x, y + a), (x - a, y), (x, y - a)]
        return [OutlinePiece(ends[k], ends[(k + 1) % 4], self.centre) for k in range(4)]

    def add_to(self, occ) -> int:
        """Add the disk to the gmsh OpenCASCADE kernel `occ`; returns its surface tag."""
        (x, y), a = self.centre, self.radius
        return occ.addDisk(x, y, 0.0, a, a)

    def crossing(self, a, b) -> tuple | None:
        """(t_in, t_out): where the line a + t (b - a) enters and leaves the disk, or None if it
        misses it or only touches it (the disk is convex: one interval)."""
        return _line_circle(a, np.subtract(b, a), self.centre, self.radius)


@dataclass(frozen=True)
class HorseshoeOpening:
    """A horseshoe: semicircular crown of ``radius`` [m] centred at ``centre`` (the springline's
    middle), straight vertical walls ``wall_height`` [m] below the springline, and an invert that is
    flat (invert_depth = 0) or a circular arc sagging ``invert_depth`` [m] below the wall feet."""

    centre: tuple
    radius: float
    wall_height: float
    invert_depth: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "centre", tuple(_point(self.centre, "HorseshoeOpening.centre")))
        object.__setattr__(self, "radius", _positive("HorseshoeOpening.radius", self.radius))
        object.__setattr__(self, "wall_height", _positive("HorseshoeOpening.wall_height", self.wall_height))
        d = float(self.invert_depth)
        if not (math.isfinite(d) and 0.0 <= d <= self.radius):
            raise ValueError(f"HorseshoeOpening.invert_depth must be in [0, radius = {self.radius}] m, got {d!r}")
        object.__setattr__(self, "invert_depth", d)

    def _invert_arc(self) -> tuple:
        """(radius R, half angle θ) of the invert arc through the wall feet with sag invert_depth."""
        a, s = self.radius, self.invert_depth
        R = (a * a + s * s) / (2.0 * s)
        return R, math.asin(a / R) if s <= a else math.pi - math.asin(a / R)

    @property
    def area(self) -> float:
        """Area of the opening [m²] (half disk, walls and the invert's circular segment)."""
        a = self.radius
        area = 0.5 * math.pi * a * a + 2.0 * a * self.wall_height
        if self.invert_depth > 0.0:
            R, th = self._invert_arc()
            area += R * R * (th - math.sin(th) * math.cos(th))  # circular segment
        return area

    @property
    def perimeter(self) -> float:
        """Length of the outline [m]."""
        a = self.radius
        invert = 2.0 * a
        if self.invert_depth > 0.0:
            R, th = self._invert_arc()
            invert = 2.0 * R * th
        return math.pi * a + 2.0 * self.wall_height + invert

    def bounds(self) -> tuple:
        """(x_min, y_min, x_max, y_max) [m]."""
        (x, y), a = self.centre, self.radius
        return (x - a, y - self.wall_height - self.invert_depth, x + a, y + a)

    def outline(self, count: int = 720) -> np.ndarray:
        """(about count, 2) points [m] along the outline, counter-clockwise from the right springline."""
        return _outline_points(self.pieces(), count)

    def crossing(self, a, b) -> tuple | None:
        """(t_in, t_out): where the line a + t (b - a) enters and leaves the horseshoe, or None if
        it misses it or only touches it. The horseshoe is convex, so the line meets its outline
        (crown arc, walls, invert) at its first and last crossing of those pieces."""
        (x, y), r, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        a, d = np.asarray(a, float), np.subtract(b, a)
        tol = 1e-12 * r
        hits = []

        def arc(centre, radius, keep):  # circle crossings whose point passes `keep`
            hits.extend(t for t in (_line_circle(a, d, centre, radius) or ()) if keep(a + t * d))

        def segment(axis, value, lo, hi):  # the line x (axis 0) or y (axis 1) = value, other in [lo, hi]
            if abs(d[axis]) > 0.0:
                t = (value - a[axis]) / d[axis]
                if lo - tol <= (a + t * d)[1 - axis] <= hi + tol:
                    hits.append(t)

        arc(np.array([x, y]), r, lambda p: p[1] >= y - tol)
        segment(0, x - r, y - hw, y)
        segment(0, x + r, y - hw, y)
        if s > 0.0:
            R, _ = self._invert_arc()
            arc(np.array([x, y - hw - s + R]), R, lambda p: p[1] <= y - hw + tol)
        else:
            segment(1, y - hw, x - r, x + r)
        if len(hits) < 2 or max(hits) - min(hits) <= tol / max(np.linalg.norm(d), 1e-300):
            return None
        return (min(hits), max(hits))

    def pieces(self) -> list:
        """The outline counter-clockwise from the right springline: the crown's two quarter arcs,
        the left wall, the invert (two arcs, or a line when flat), the right wall."""
        (x, y), a, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        c, right, top, left = (x, y), (x + a, y), (x, y + a), (x - a, y)
        left_foot, right_foot = (x - a, y - hw), (x + a, y - hw)
        out = [OutlinePiece(right, top, c), OutlinePiece(top, left, c), OutlinePiece(left, left_foot)]
        if s > 0.0:
            R, _ = self._invert_arc()
            ci, bottom = (x, y - hw - s + R), (x, y - hw - s)
            out += [OutlinePiece(left_foot, bottom, ci), OutlinePiece(bottom, right_foot, ci)]
        else:
            out.append(OutlinePiece(left_foot, right_foot))
        return out + [OutlinePiece(right_foot, right)]

    def add_to(self, occ) -> int:
        """Add the outline as a surface to the gmsh OpenCASCADE kernel `occ`; returns its tag."""
        return _add_outline(occ, self.pieces())


def _add_outline(occ, pieces) -> int:
    """An OCC plane surface bounded by the closed chain of outline pieces."""
    first = occ.addPoint(*pieces[0].start, 0.0)
    start, curves = first, []
    for k, piece in enumerate(pieces):
        end = first if k == len(pieces) - 1 else occ.addPoint(*piece.end, 0.0)
        if piece.centre is None:
            curves.append(occ.addLine(start, end))
        else:
            curves.append(occ.addCircleArc(start, occ.addPoint(*piece.centre, 0.0), end))
        start = end
    return occ.addPlaneSurface([occ.addCurveLoop(curves)])
