# SPDX-License-Identifier: MIT
"""A jointed rock slope section (issue 40): the rock under a slope face of height H at angle ψ_f,
cut by joints, meshed and split as tunnel sections are (planar_section: the traces' crossings in
closed form, one gmsh surface with every joint piece embedded, the blocks found on the mesh).

The section, x along the slope (toe side at x = 0), y up::

                           crest
              top  ________ ______________ (W, base + H)
                  /                       |
             face/  ψ_f                   | right
    ____________/ toe                     |
    toe floor   (toe_distance, base)      |
    | left                                |
    |_____________________________________| bottom  (W, 0)

Boundary groups: bottom, right, top (the ground behind the crest), face, toe (the floor in front
of the toe), left. Benches (``benches``: (elevation above the toe, width) pairs) break the face into
faces at ψ_f between horizontal bench floors; the face group is all of them (the slope's free
surface between toe and crest), and the overall slope angle is then below ψ_f. A joint is a line (meshes.Joint: a point and its dip, 2D dip direction 90 or
270) clipped to the section, which is not convex (the toe is a re-entrant corner), and to the
joints it is ``bounded_by``: a tension crack is a vertical joint bounded by the sliding plane, the
plane one bounded by the crack. Every joint must separate blocks completely (no dangling tip).
Lengths in metres, angles in degrees.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable

import numpy as np

from . import planar_section
from .builders import (BOUNDARY_TAGS, _distance_threshold, _generate, _gmsh_model, _graded_size,
                       _joint_names, _normalise_joints, _resolve_bounds, _uniform_size)
from .joint_geometry import _positive, unit_normal
from .jointed_mesh import JointedMesh
from .planar_section import OutlinePiece
from .slope_extruded import extruded_slope

FACE, TOE = "face", "toe"
#: boundary tags: builders' bottom, top, left, right; the face and the toe floor after the opening's 7
SLOPE_BOUNDARY_TAGS = {**{k: BOUNDARY_TAGS[k] for k in ("bottom", "right", "top", "left")}, FACE: 8, TOE: 9}
_DANGLING = "it ends inside a block (a dangling tip): bound it by the joint it should end on (bounded_by)"


@dataclass(frozen=True)
class SlopeGeometry:
    """A slope of face `height` H [m] at `face_angle` ψ_f [deg] above a `base` [m] of rock below
    the toe, with `toe_distance` [m] of floor in front of the toe and `crest_distance` [m] of
    ground behind the crest."""

    height: float
    face_angle: float
    base: float
    toe_distance: float
    crest_distance: float
    #: horizontal benches, ((elevation above the toe [m], width [m]), ...), elevations rising
    benches: tuple = ()

    def __post_init__(self):
        for name in ("height", "base", "toe_distance", "crest_distance"):
            _positive(f"slope {name}", getattr(self, name))
        if not (math.isfinite(self.face_angle) and 0.0 < self.face_angle <= 90.0):
            raise ValueError(f"slope face_angle = {self.face_angle!r} must be in (0, 90] degrees")
        benches = tuple((float(e), float(w)) for e, w in self.benches)
        below = 0.0
        for k, (e, w) in enumerate(benches):
            if not (math.isfinite(e) and below < e < self.height):
                raise ValueError(f"slope bench {k + 1}: elevation {e!r} m must be above the toe and the bench "
                                 f"below ({below:g} m) and below the crest ({self.height:g} m)")
            _positive(f"slope bench {k + 1} width", w)
            below = e
        object.__setattr__(self, "benches", benches)

    @property
    def toe(self) -> tuple:
        """The toe (x, y) [m]."""
        return (self.toe_distance, self.base)

    def face_points(self) -> list:
        """The face's corners from the toe up to the crest [(x, y), ...] (m): faces at ψ_f rising
        between the benches' horizontal floors."""
        cot = 1.0 / math.tan(math.radians(self.face_angle)) if self.face_angle < 90.0 else 0.0
        x, y0 = self.toe_distance, self.base
        out, below = [self.toe], 0.0
        for e, w in self.benches:
            x += (e - below) * cot
            out += [(x, y0 + e), (x + w, y0 + e)]
            x, below = x + w, e
        return out + [(x + (self.height - below) * cot, y0 + self.height)]

    @property
    def crest(self) -> tuple:
        """The crest (x, y) [m]."""
        return self.face_points()[-1]

    def piece_groups(self) -> list:
        """The boundary group of each outline piece (pieces()): bottom, right, top, the face's
        pieces (faces and bench floors: all ``face``), toe, left."""
        return ["bottom", "right", "top"] + [FACE] * (len(self.face_points()) - 1) + [TOE, "left"]

    @property
    def width(self) -> float:
        """The section's width W [m]."""
        return self.crest[0] + self.crest_distance

    def pieces(self) -> list:
        """The outline counter-clockwise from the origin: bottom, right, top, the face's pieces
        (crest down to the toe), toe, left (their groups: piece_groups())."""
        w, top = self.width, self.base + self.height
        corners = [(0.0, 0.0), (w, 0.0), (w, top), *self.face_points()[::-1], (0.0, self.base)]
        return [OutlinePiece(corners[k], corners[(k + 1) % len(corners)]) for k in range(len(corners))]

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Whether each point (n, 2) lies inside the section (even-odd rule on the outline)."""
        p = np.atleast_2d(points)
        inside = np.zeros(len(p), dtype=bool)
        for piece in self.pieces():
            (x0, y0), (x1, y1) = piece.start, piece.end
            crosses = (y0 > p[:, 1]) != (y1 > p[:, 1])
            with np.errstate(divide="ignore", invalid="ignore"):
                x_at = x0 + (p[:, 1] - y0) * (x1 - x0) / (y1 - y0)
            inside ^= crosses & (p[:, 0] < x_at)
        return inside


def slope_traces(geometry: SlopeGeometry, joints: list) -> list:
    """The segments ((k, 2, 2) [m]) of each joint inside the section and on the kept side of its
    bounding joints; ValueError naming a joint that misses the section."""
    pieces = geometry.pieces()
    extent = max(geometry.width, geometry.base + geometry.height)
    tol = 1e-9 * extent
    out = []
    for j, bounds in _resolve_bounds(joints):
        p = np.asarray(j.point, dtype=float)
        if p.shape != (2,) or not np.all(np.isfinite(p)):
            raise ValueError(f"joint {j.name!r}: point must be 2 finite coordinates, got {j.point!r}")
        n = unit_normal(j.dip, j.dip_direction, 2)
        d = np.array([n[1], -n[0]])
        cuts = [-4.0 * extent, 4.0 * extent]
        for piece in pieces:   # where the line p + t d crosses each outline piece
            a, e = np.asarray(piece.start), np.subtract(piece.end, piece.start)
            det = d[0] * -e[1] + d[1] * e[0]
            if abs(det) > 1e-14:
                t, s = np.linalg.solve(np.array([d, -e]).T, a - p)
                if -1e-12 <= s <= 1.0 + 1e-12:
                    cuts.append(float(t))
        for k in bounds:       # the bounding joints: keep the side where the point lies
            other = joints[k]
            m = unit_normal(other.dip, other.dip_direction, 2)
            side = float(m @ (p - np.asarray(other.point, float)))
            if abs(side) <= tol:
                raise ValueError(f"joint {j.name!r}: its point lies on the bounding joint {other.name!r}")
            if abs(m @ d) > 1e-14:
                cuts.append(float(m @ (np.asarray(other.point, float) - p) / (m @ d)))
        cuts = np.unique(cuts)
        mids = p + 0.5 * (cuts[:-1] + cuts[1:])[:, None] * d
        keep = geometry.contains(mids)
        for k in bounds:
            other = joints[k]
            m = unit_normal(other.dip, other.dip_direction, 2)
            q = np.asarray(other.point, float)
            keep &= np.sign((mids - q) @ m) == np.sign(m @ (p - q))
        segs = [(p + cuts[i] * d, p + cuts[i + 1] * d) for i in np.flatnonzero(keep)
                if (cuts[i + 1] - cuts[i]) > tol]
        if not segs:
            raise ValueError(f"joint {j.name!r} (point {tuple(p)}, dip {j.dip}) misses the slope section")
        out.append(np.array(segs))
    return out


def slope_section(geometry: SlopeGeometry, joints: Iterable = (), *, mesh_size: float,
                  joint_mesh_size: float | None = None, joint_refine_distance: float | None = None,
                  intact: bool = False, length: float | None = None, comm=None) -> JointedMesh | None:
    """The slope section of `geometry` cut by `joints` (meshes.Joint objects or lists of them),
    meshed with `mesh_size` [m] (joint_mesh_size on the joints, growing to mesh_size over
    joint_refine_distance, default 2 mesh_size) and split along the joints; intact: the same mesh
    lines, one block. length: the section extruded along the strike by `length` [m]
    (slope_extruded.py: x stays x, the section's y becomes z, the strike is y from "front" (y = 0)
    to "back"; joints become planes). comm: ranks != 0 return None (gmsh runs on rank 0)."""
    if comm is not None and comm.rank != 0:
        return None
    mesh_size = _positive("mesh_size", mesh_size)
    if mesh_size > 0.5 * min(geometry.height, geometry.base):
        raise ValueError(f"mesh_size ({mesh_size:g} m) exceeds half the slope's height or base")
    if joint_mesh_size is not None and _positive("joint_mesh_size", joint_mesh_size) > mesh_size:
        raise ValueError(f"joint_mesh_size ({joint_mesh_size:g} m) must not exceed mesh_size ({mesh_size:g} m)")
    length = None if length is None else _positive("slope length", length)
    refine = 2.0 * mesh_size if joint_refine_distance is None else _positive("joint_refine_distance",
                                                                               joint_refine_distance)
    joints = _normalise_joints(joints)
    if set(j.name for j in joints) & set(SLOPE_BOUNDARY_TAGS):
        raise ValueError(f"joint names must differ from the boundary names {sorted(SLOPE_BOUNDARY_TAGS)}")
    segments = slope_traces(geometry, joints)
    if length is not None:
        with _gmsh_model("rockjoint_slope_extruded") as gmsh:
            return extruded_slope(gmsh, geometry, joints, segments, geometry.piece_groups(), SLOPE_BOUNDARY_TAGS,
                                  length=length,
                                  mesh_size=mesh_size, joint_mesh_size=joint_mesh_size, refine=refine, intact=intact,
                                  dangling=_DANGLING)
    extent = max(geometry.width, geometry.base + geometry.height)
    tol = 1e-9 * extent
    owner = np.array([i for i, s in enumerate(segments) for _ in s], dtype=np.int64)
    segs = np.concatenate(segments).reshape(-1, 2, 2) if segments else np.empty((0, 2, 2))
    outline = geometry.pieces()
    nodes, chains, vertex = planar_section.arrange(segs, [joints[i].name for i in owner], tol,
                                                   np.array([p.start for p in outline]))
    starts, ends, line_owner, tips = planar_section.chain_lines(chains, owner)
    with _gmsh_model("rockjoint_slope_section") as gmsh:
        geo = gmsh.model.geo
        point = planar_section.GeoPoints(geo, nodes)

        splits = planar_section.split_outline(outline, nodes, tips, tol)
        groups, curves = {}, []
        for j, name in enumerate(geometry.piece_groups()):
            seq = [vertex[j], *splits[j], vertex[(j + 1) % len(outline)]]
            for a, b in zip(seq[:-1], seq[1:]):
                curves.append(geo.addLine(point(a), point(b)))
                groups.setdefault(name, []).append(curves[-1])
        lines = np.array([geo.addLine(point(a), point(b)) for a, b in zip(starts, ends)], dtype=np.int64)
        surface = geo.addPlaneSurface([geo.addCurveLoop(curves)])
        geo.synchronize()
        if lines.size:
            gmsh.model.mesh.embed(1, lines.tolist(), 2, surface)
        if joint_mesh_size is not None and lines.size:
            longest = float(np.linalg.norm(nodes[ends] - nodes[starts], axis=1).max())
            field = _distance_threshold(gmsh, 2, lines.tolist(), joint_mesh_size, mesh_size, refine, extent,
                                        longest=longest)
            gmsh.model.mesh.field.setAsBackgroundMesh(field)
            _graded_size(gmsh, mesh_size)
        else:
            _uniform_size(gmsh, mesh_size)
        pieces = [lines[line_owner == i].tolist() for i in range(len(joints))]
        if intact:
            return _generate(gmsh, 2, [], groups, SLOPE_BOUNDARY_TAGS, _joint_names([]), one_block=True,
                             blocks_are_volumes=False)
        return _generate(gmsh, 2, pieces, groups, SLOPE_BOUNDARY_TAGS, _joint_names(joints), dangling=_DANGLING,
                         blocks_are_volumes=False)
