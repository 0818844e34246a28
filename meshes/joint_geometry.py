# SPDX-License-Identifier: MIT
"""Planar joints in a rectangular block: orientation (dip, dip direction) and clipping.

Axes: x east, y north, z up in 3D; in 2D the section is the x-z plane, written (x, y) with y up.
A joint is the plane through ``point`` with dip ``dip`` (degrees below horizontal, 0..90) toward the
azimuth ``dip_direction`` (degrees clockwise from north = +y; 90 = dipping toward +x). Its upward unit
normal is n = (sin(dip) sin(dd), sin(dip) cos(dd), cos(dip)) in 3D and (sin(dip) sin(dd), cos(dip))
in 2D, where only dd = 90 (dipping toward +x) or dd = 270 (toward -x) describe a section.

The joint trace inside the block is computed analytically (convex clipping of a large polygon
against the block's half-spaces and against the joints that bound it), so gmsh only receives exact
polygons/segments whose edges lie on the block faces or on the bounding joints.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np


@dataclass(frozen=True)
class Joint:
    """One planar joint.

    :point: a point of the joint plane [m], inside the block (for a bounded joint: on the kept side of
        every bounding joint).
    :dip: degrees below horizontal, in [0, 90].
    :dip_direction: degrees clockwise from +y (north); 2D accepts 90 (toward +x) or 270 (toward -x).
    :name: physical-group name of the joint (default ``joint_<i>``, 1-based).
    :bounded_by: names or 0-based indices of other joints on which this joint ends (T-junctions): the
        joint is kept on the side of each of them where ``point`` lies. Without it the joint crosses
        the whole block. Every joint must separate blocks completely: a joint whose edge ends inside
        a block (a dangling crack tip) is rejected by the builder.
    :joint_set: the name of the set the joint belongs to (``joint_set`` gives its own name; None: the
        joint is a set of its own). The mesh carries it as the group names["joint_sets"]
        ({joint tag: set name}), so that a model reads a joint's set from its mesh.
    """

    point: tuple
    dip: float = 0.0
    dip_direction: float = 90.0
    name: str | None = None
    bounded_by: tuple = field(default_factory=tuple)
    joint_set: str | None = None


def joint_set(spacing: float, dip: float = 0.0, dip_direction: float = 90.0, *, origin: Sequence[float],
              count: int, name: str = "set", bounded_by: tuple = ()) -> list[Joint]:
    """``count`` parallel joints ``spacing`` [m] apart along their normal, the first through ``origin``.

    Names are ``<name>_1`` ... ``<name>_<count>``; each joint's ``joint_set`` is ``name``.
    """
    spacing = _positive("spacing", spacing)
    if int(count) != count or count < 1:
        raise ValueError(f"joint_set: count must be an integer >= 1, got {count!r}")
    origin = np.asarray(origin, dtype=float)
    n = unit_normal(dip, dip_direction, origin.size)
    return [Joint(tuple(origin + k * spacing * n), dip, dip_direction, f"{name}_{k + 1}", tuple(bounded_by),
                  joint_set=name) for k in range(int(count))]


def unit_normal(dip: float, dip_direction: float, gdim: int) -> np.ndarray:
    """Upward unit normal of a joint plane (see the module docstring)."""
    if not (math.isfinite(dip) and 0.0 <= dip <= 90.0):
        raise ValueError(f"joint dip must be in [0, 90] degrees, got {dip!r}")
    if not (math.isfinite(dip_direction) and 0.0 <= dip_direction < 360.0):
        raise ValueError(f"joint dip_direction must be in [0, 360) degrees, got {dip_direction!r}")
    d, a = math.radians(dip), math.radians(dip_direction)
    if gdim == 3:
        return np.array([math.sin(d) * math.sin(a), math.sin(d) * math.cos(a), math.cos(d)])
    if gdim == 2:
        if dip > 0.0 and dip_direction not in (90.0, 270.0):
            raise ValueError("in 2D a joint's dip_direction must be 90 (dipping toward +x) or 270 "
                             f"(toward -x), got {dip_direction!r}")
        return np.array([math.sin(d) * math.sin(a), math.cos(d)])
    raise ValueError(f"gdim must be 2 or 3, got {gdim!r}")


def _positive(name: str, value) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return value


def _clip(polygon: np.ndarray, a: np.ndarray, b: float, closed: bool) -> np.ndarray:
    """Part of a convex polygon (closed) or a segment (not closed) in the half-space a.x <= b."""
    if len(polygon) == 0:
        return polygon
    s = polygon @ a - b
    out = []
    m = len(polygon)
    edges = range(m) if closed else range(m - 1)
    if not closed and s[0] <= 0.0:
        out.append(polygon[0])
    for i in edges:
        j = (i + 1) % m
        p, q, sp, sq = polygon[i], polygon[j], s[i], s[j]
        if (sp < 0.0 < sq) or (sq < 0.0 < sp):
            out.append(p + (q - p) * (sp / (sp - sq)))
        if sq <= 0.0:
            out.append(q)
    if not out:
        return np.empty((0, polygon.shape[1]))
    out = np.array(out)
    keep = np.ones(len(out), bool)  # drop consecutive duplicates created by vertices on the plane
    keep[1:] = np.linalg.norm(np.diff(out, axis=0), axis=1) > 1e-14 * (1.0 + np.abs(out).max())
    out = out[keep]
    if closed and len(out) > 1 and np.linalg.norm(out[0] - out[-1]) <= 1e-14 * (1.0 + np.abs(out).max()):
        out = out[:-1]
    return out


def joint_trace(joint: Joint, size: np.ndarray, bounding: Sequence[Joint], label: str) -> np.ndarray:
    """Vertices of the joint inside the block [0, size]: a segment (2, 2) in 2D, a convex polygon (k, 3) in 3D.

    Raises ValueError (naming ``label``) if the joint does not cut through the block interior.
    """
    gdim = size.size
    p = np.asarray(joint.point, dtype=float)
    if p.shape != (gdim,) or not np.all(np.isfinite(p)):
        raise ValueError(f"{label}: point must be {gdim} finite coordinates, got {joint.point!r}")
    n = unit_normal(joint.dip, joint.dip_direction, gdim)
    diag = float(np.linalg.norm(size))
    centre = 0.5 * size
    c = centre - n * float(n @ (centre - p))  # block centre projected onto the plane
    big = 2.0 * diag
    if gdim == 2:
        t = np.array([n[1], -n[0]])
        poly = np.array([c - big * t, c + big * t])
    else:
        e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        poly = np.array([c + big * (sx * e1 + sy * e2) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    closed = gdim == 3
    for axis in range(gdim):  # block faces: 0 <= x_axis <= size_axis
        a = np.zeros(gdim)
        a[axis] = 1.0
        poly = _clip(poly, a, float(size[axis]), closed)
        poly = _clip(poly, -a, 0.0, closed)
    for other in bounding:
        q = np.asarray(other.point, dtype=float)
        m = unit_normal(other.dip, other.dip_direction, gdim)
        side = float(m @ (p - q))
        if abs(side) <= 1e-12 * diag:
            raise ValueError(f"{label}: its point {tuple(p)} lies on the bounding joint {other.name!r}; "
                             "give a point on the side where the joint is kept")
        sgn = math.copysign(1.0, side)  # keep sgn * m.(x - q) >= 0
        poly = _clip(poly, -sgn * m, -sgn * float(m @ q), closed)
    tol = 1e-9 * diag
    measure = 0.0
    if len(poly) >= 2:
        if gdim == 2:
            measure = float(np.linalg.norm(poly[-1] - poly[0]))
        elif len(poly) >= 3:
            measure = 0.5 * float(np.linalg.norm(sum(np.cross(poly[i] - poly[0], poly[i + 1] - poly[0])
                                                    for i in range(1, len(poly) - 1))))
    centroid = poly.mean(axis=0) if len(poly) else p
    interior = len(poly) and np.all(centroid > tol) and np.all(centroid < size - tol)
    if measure <= (tol if gdim == 2 else tol * diag) or not interior:
        raise ValueError(f"{label} (point {tuple(p)}, dip {joint.dip}, dip direction {joint.dip_direction}) "
                         f"does not cut the block [0, {tuple(float(s) for s in size)}]: its trace inside the "
                         "block is empty, degenerate or lies on a block face")
    return poly
