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


def _segment(half_chord: float, rise: float) -> tuple:
    """(radius R, half angle θ) of the circular arc over a chord 2 half_chord with its middle
    ``rise`` from the chord (0 < rise <= half_chord): R = (c² + f²) / (2 f), sin θ = c / R."""
    R = (half_chord ** 2 + rise ** 2) / (2.0 * rise)
    return R, math.asin(min(1.0, half_chord / R))


def _segment_area(R: float, theta: float) -> float:
    """Area of the circular segment of radius R and half angle θ: R² (θ - sin θ cos θ)."""
    return R * R * (theta - math.sin(theta) * math.cos(theta))


@dataclass(frozen=True)
class HorseshoeOpening:
    """The horseshoe and the D, one outline: a crown arc over the span 2 ``radius`` [m] from the
    springline, whose middle is ``centre``; straight vertical walls ``wall_height`` [m] below the
    springline; a floor that is flat (``invert_depth`` = 0: the **D**) or a circular invert arc sagging
    ``invert_depth`` [m] below the wall feet (the **horseshoe**).

    The crown is a semicircle of radius ``radius`` (``arch_radius`` None or equal to it, tangent to the
    walls) or, with ``arch_radius`` R > radius, a flatter segmental arch through the wall tops: its
    centre lies sqrt(R² - radius²) below the springline, its rise is R - sqrt(R² - radius²). An arch
    radius below half the span cannot reach both walls and is refused."""

    centre: tuple
    radius: float
    wall_height: float
    invert_depth: float = 0.0
    arch_radius: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "centre", tuple(_point(self.centre, "HorseshoeOpening.centre")))
        object.__setattr__(self, "radius", _positive("HorseshoeOpening.radius", self.radius))
        object.__setattr__(self, "wall_height", _positive("HorseshoeOpening.wall_height", self.wall_height))
        d = float(self.invert_depth)
        if not (math.isfinite(d) and 0.0 <= d <= self.radius):
            raise ValueError(f"HorseshoeOpening.invert_depth must be in [0, radius = {self.radius}] m, got {d!r}")
        object.__setattr__(self, "invert_depth", d)
        R = self.radius if self.arch_radius is None else _positive("HorseshoeOpening.arch_radius", self.arch_radius)
        if R < self.radius:
            raise ValueError(f"HorseshoeOpening.arch_radius ({R:g} m) is less than half the span ({self.radius:g} m): "
                             "the arch cannot reach both walls")
        object.__setattr__(self, "arch_radius", R)

    @property
    def rise(self) -> float:
        """Height of the crown above the springline [m]: R - sqrt(R² - a²) (a for a semicircle)."""
        R, a = self.arch_radius, self.radius
        return R - math.sqrt(max(R * R - a * a, 0.0))

    def _arcs(self) -> list:
        """[(centre, R, θ)] of the crown and (invert_depth > 0) the invert arc."""
        (x, y), a, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        R, th = _segment(a, self.rise)
        arcs = [((x, y + self.rise - R), R, th)]
        if s > 0.0:
            Ri, thi = _segment(a, s)
            arcs.append(((x, y - hw - s + Ri), Ri, thi))
        return arcs

    @property
    def area(self) -> float:
        """Area of the opening [m²]: the crown's circular segment, the walls' rectangle and the
        invert's circular segment."""
        return 2.0 * self.radius * self.wall_height + sum(_segment_area(R, th) for _, R, th in self._arcs())

    @property
    def perimeter(self) -> float:
        """Length of the outline [m]."""
        floor = 0.0 if self.invert_depth > 0.0 else 2.0 * self.radius
        return 2.0 * self.wall_height + floor + sum(2.0 * R * th for _, R, th in self._arcs())

    def bounds(self) -> tuple:
        """(x_min, y_min, x_max, y_max) [m]."""
        (x, y), a = self.centre, self.radius
        return (x - a, y - self.wall_height - self.invert_depth, x + a, y + self.rise)

    def outline(self, count: int = 720) -> np.ndarray:
        """(about count, 2) points [m] along the outline, counter-clockwise from the right springline."""
        return _outline_points(self.pieces(), count)

    def crossing(self, a, b) -> tuple | None:
        """(t_in, t_out): where the line a + t (b - a) enters and leaves the opening, or None if
        it misses it or only touches it. The opening is convex, so the line meets its outline
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

        arcs = self._arcs()
        arc(np.array(arcs[0][0]), arcs[0][1], lambda p: p[1] >= y - tol)
        segment(0, x - r, y - hw, y)
        segment(0, x + r, y - hw, y)
        if s > 0.0:
            arc(np.array(arcs[1][0]), arcs[1][1], lambda p: p[1] <= y - hw + tol)
        else:
            segment(1, y - hw, x - r, x + r)
        if len(hits) < 2 or max(hits) - min(hits) <= tol / max(np.linalg.norm(d), 1e-300):
            return None
        return (min(hits), max(hits))

    def pieces(self) -> list:
        """The outline counter-clockwise from the right springline: the crown's two arcs (to and
        from its top), the left wall, the invert (two arcs, or a line when flat), the right wall."""
        (x, y), a, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        arcs = self._arcs()
        c, right, top, left = arcs[0][0], (x + a, y), (x, y + self.rise), (x - a, y)
        left_foot, right_foot = (x - a, y - hw), (x + a, y - hw)
        out = [OutlinePiece(right, top, c), OutlinePiece(top, left, c), OutlinePiece(left, left_foot)]
        if s > 0.0:
            ci, bottom = arcs[1][0], (x, y - hw - s)
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
