"""gmsh (OCC) builder of a 2D rock-mass section around a tunnel opening, cut by joint sets.

Geometry (plane strain, y up): the section is the rectangle [0, width] x [0, height] minus the
opening (a CircularOpening or a HorseshoeOpening placed at its ``centre``). Joints (meshes.Joint,
e.g. from meshes.joint_set) are clipped analytically to the rectangle (and to the joints they are
bounded by) and to the opening (its ``crossing``), then ``occ.fragment`` cuts the section with what
is left: no piece of a joint is ever made inside the opening, so every joint ends on the opening,
on the outer boundary or on another joint.
Joints must separate blocks completely, as in meshes.builders; a joint that lies entirely inside the
opening, misses the section, touches the opening tangentially or runs along its boundary raises
ValueError naming it.

Physical groups (as in meshes.builders): blocks ``block_<k>`` (tags 1, 2, ... by centre of mass,
lowest first), joints by name (tags 100, 101, ... in input order), boundaries "bottom", "top",
"left", "right" (tags of builders.BOUNDARY_TAGS) and "opening" (tag OPENING_TAG, the hole's boundary).

Refinement (gmsh Distance + Threshold fields, combined with Min): opening_mesh_size on the opening
growing linearly to mesh_size over opening_refine_distance; joint_mesh_size on the joints growing to
mesh_size over joint_refine_distance.

``intact=True`` meshes the same geometry with the same refinement, the joint traces kept as mesh
lines (so the triangles are the very ones of the jointed section), but as one block without joints:
the jointed-vs-intact comparison then differs by the joints only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable

import numpy as np

from .builders import (BOUNDARY_TAGS, _add_trace, _block_face, _distance_threshold, _generate, _gmsh_model,
                       _graded_size, _joint_names, _normalise_joints, _one_element_curves, _resolve_bounds)
from .joint_geometry import _positive, joint_trace, unit_normal
from .jointed_mesh import JointedMesh

OPENING = "opening"
OPENING_TAG = 7  # after builders.BOUNDARY_TAGS (1..6)
#: what to do about a joint that does not separate two blocks (the end of its error message)
_DANGLING = "part of it runs along the opening's boundary or ends inside a block (dangling tip)"
SECTION_BOUNDARY_TAGS = {**{k: BOUNDARY_TAGS[k] for k in ("bottom", "top", "left", "right")}, OPENING: OPENING_TAG}


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
        return math.pi * self.radius ** 2

    @property
    def perimeter(self) -> float:
        return 2.0 * math.pi * self.radius

    def bounds(self) -> tuple:
        """(x_min, y_min, x_max, y_max) [m]."""
        (x, y), a = self.centre, self.radius
        return (x - a, y - a, x + a, y + a)

    def outline(self, count: int = 720) -> np.ndarray:
        """(count, 2) points [m] along the outline, counter-clockwise from the right springline."""
        t = np.linspace(0.0, 2.0 * math.pi, count, endpoint=False)
        return np.asarray(self.centre) + self.radius * np.stack([np.cos(t), np.sin(t)], axis=1)

    def add_to(self, occ) -> int:
        (x, y), a = self.centre, self.radius
        return occ.addDisk(x, y, 0.0, a, a)

    def crossing(self, a, b) -> tuple | None:
        """(t_in, t_out): where the line a + t (b - a) enters and leaves the disk, or None if it
        misses it or only touches it (the disk is convex: one interval)."""
        d, f = np.subtract(b, a), np.subtract(a, self.centre)
        # |f + t d|² = r²: d·d t² + 2 f·d t + f·f - r² = 0
        qa, qb, qc = d @ d, f @ d, f @ f - self.radius ** 2
        disc = qb * qb - qa * qc
        if not disc > 0.0:
            return None
        root = math.sqrt(disc)
        return ((-qb - root) / qa, (-qb + root) / qa)


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
        a = self.radius
        area = 0.5 * math.pi * a * a + 2.0 * a * self.wall_height
        if self.invert_depth > 0.0:
            R, th = self._invert_arc()
            area += R * R * (th - math.sin(th) * math.cos(th))  # circular segment
        return area

    @property
    def perimeter(self) -> float:
        a = self.radius
        invert = 2.0 * a
        if self.invert_depth > 0.0:
            R, th = self._invert_arc()
            invert = 2.0 * R * th
        return math.pi * a + 2.0 * self.wall_height + invert

    def bounds(self) -> tuple:
        (x, y), a = self.centre, self.radius
        return (x - a, y - self.wall_height - self.invert_depth, x + a, y + a)

    def outline(self, count: int = 720) -> np.ndarray:
        """(about count, 2) points [m] along the outline, counter-clockwise from the right springline."""
        (x, y), a, hw = self.centre, self.radius, self.wall_height
        step = self.perimeter / count
        crown = np.linspace(0.0, math.pi, max(2, int(math.pi * a / step)), endpoint=False)
        parts = [np.stack([x + a * np.cos(crown), y + a * np.sin(crown)], axis=1)]
        wall = np.linspace(0.0, hw, max(2, int(hw / step)), endpoint=False)
        parts.append(np.stack([np.full(wall.size, x - a), y - wall], axis=1))
        if self.invert_depth > 0.0:
            R, th = self._invert_arc()
            phi = np.linspace(-math.pi / 2 - th, -math.pi / 2 + th, max(2, int(2 * R * th / step)), endpoint=False)
            yc = y - hw - self.invert_depth + R
            parts.append(np.stack([x + R * np.cos(phi), yc + R * np.sin(phi)], axis=1))
        else:
            foot = np.linspace(-a, a, max(2, int(2 * a / step)), endpoint=False)
            parts.append(np.stack([x + foot, np.full(foot.size, y - hw)], axis=1))
        parts.append(np.stack([np.full(wall.size, x + a), y - hw + wall], axis=1))
        return np.concatenate(parts)

    def crossing(self, a, b) -> tuple | None:
        """(t_in, t_out): where the line a + t (b - a) enters and leaves the horseshoe, or None if
        it misses it or only touches it. The horseshoe is convex, so the line meets its outline
        (crown arc, walls, invert) at its first and last crossing of those pieces."""
        (x, y), r, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        a, d = np.asarray(a, float), np.subtract(b, a)
        tol = 1e-12 * r
        hits = []

        def arc(centre, radius, keep):  # circle crossings whose point passes `keep`
            f = a - centre
            qa, qb, qc = d @ d, f @ d, f @ f - radius ** 2
            disc = qb * qb - qa * qc
            if disc > 0.0:
                for t in ((-qb - math.sqrt(disc)) / qa, (-qb + math.sqrt(disc)) / qa):
                    if keep(a + t * d):
                        hits.append(t)

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

    def add_to(self, occ) -> int:
        (x, y), a, hw, s = self.centre, self.radius, self.wall_height, self.invert_depth
        c = occ.addPoint(x, y, 0.0)
        right, top, left = occ.addPoint(x + a, y, 0.0), occ.addPoint(x, y + a, 0.0), occ.addPoint(x - a, y, 0.0)
        left_foot, right_foot = occ.addPoint(x - a, y - hw, 0.0), occ.addPoint(x + a, y - hw, 0.0)
        curves = [occ.addCircleArc(right, c, top), occ.addCircleArc(top, c, left), occ.addLine(left, left_foot)]
        if s > 0.0:
            R, _ = self._invert_arc()
            ci = occ.addPoint(x, y - hw - s + R, 0.0)
            bottom = occ.addPoint(x, y - hw - s, 0.0)
            curves += [occ.addCircleArc(left_foot, ci, bottom), occ.addCircleArc(bottom, ci, right_foot)]
        else:
            curves.append(occ.addLine(left_foot, right_foot))
        curves.append(occ.addLine(right_foot, right))
        return occ.addPlaneSurface([occ.addCurveLoop(curves)])


def tunnel_section(width: float, height: float, opening, joints: Iterable = (), *, mesh_size: float,
                   opening_mesh_size: float | None = None, opening_refine_distance: float | None = None,
                   joint_mesh_size: float | None = None, joint_refine_distance: float | None = None,
                   intact: bool = False, quarter: bool = False, length: float | None = None,
                   comm=None) -> JointedMesh | None:
    """The section [0, width] x [0, height] minus ``opening``, cut by ``joints``, meshed and split.

    opening: CircularOpening or HorseshoeOpening, strictly inside the section (at least one element
        size from its sides).
    joints: Joint objects, lists of them (meshes.joint_set) or (point, dip[, dip_direction]) tuples;
        2D dips toward +x (dip_direction 90) or -x (270).
    mesh_size: element size [m] far from the opening and the joints.
    opening_mesh_size: element size [m] on the opening (default mesh_size / 4);
        opening_refine_distance: distance [m] over which it grows to mesh_size (default 2 x the
        opening's largest half-dimension).
    joint_mesh_size: element size [m] on the joints (default: no joint refinement);
        joint_refine_distance: growth distance [m] (default 2 mesh_size).
    intact: the same mesh as one block without joints (see the module docstring).
    quarter: mesh a quarter of a section symmetric about the opening's vertical and horizontal axes:
        a CircularOpening centred at the origin (0, 0), the rock [0, width] x [0, height] around it;
        "left" (x = 0) and "bottom" (y = 0) are then the symmetry planes (rollers there are exact for
        a symmetric load such as Kirsch's far field).
    length: if given, the 3D extrusion of the section along the tunnel axis, ``length`` [m] long: the
        section's x stays x, its y becomes z (up) and the axis is y, from y = 0 ("front") to
        y = length ("back"); joints become planes, the opening a prism (tetrahedra, the same size
        fields on the opening's and the joints' faces).
    comm: an mpi4py communicator; ranks != 0 return None (gmsh runs on rank 0).
    """
    if comm is not None and comm.rank != 0:
        return None
    size = np.array([_positive("width", width), _positive("height", height)])
    length = None if length is None else _positive("length", length)
    if not isinstance(opening, (CircularOpening, HorseshoeOpening)):
        raise ValueError(f"opening must be a CircularOpening or a HorseshoeOpening, got {type(opening).__name__}")
    mesh_size = _positive("mesh_size", mesh_size)
    if mesh_size > 0.5 * size.min():
        raise ValueError(f"mesh_size ({mesh_size:g} m) exceeds half the section size {tuple(size)}")
    x0, y0, x1, y1 = opening.bounds()
    if quarter:
        if not isinstance(opening, CircularOpening) or opening.centre != (0.0, 0.0):
            raise ValueError(f"quarter=True needs a CircularOpening centred at (0, 0), got {opening!r}")
        x0 = y0 = mesh_size  # the symmetry planes cut the opening
    if not (x0 >= mesh_size and y0 >= mesh_size and x1 <= size[0] - mesh_size and y1 <= size[1] - mesh_size):
        raise ValueError(f"the opening (extent x {x0:g}..{x1:g} m, y {y0:g}..{y1:g} m) is not inside the section "
                         f"[0, {size[0]:g}] x [0, {size[1]:g}] m with a margin of one mesh_size ({mesh_size:g} m)")
    half = 0.5 * max(np.subtract(opening.bounds()[2:], opening.bounds()[:2]))
    opening_mesh_size = mesh_size / 4.0 if opening_mesh_size is None else \
        _positive("opening_mesh_size", opening_mesh_size)
    opening_refine_distance = 4.0 * half if opening_refine_distance is None else \
        _positive("opening_refine_distance", opening_refine_distance)
    if joint_mesh_size is not None:
        joint_mesh_size = _positive("joint_mesh_size", joint_mesh_size)
    joint_refine_distance = 2.0 * mesh_size if joint_refine_distance is None else \
        _positive("joint_refine_distance", joint_refine_distance)
    for name, value in (("opening_mesh_size", opening_mesh_size), ("joint_mesh_size", joint_mesh_size)):
        if value is not None and value > mesh_size:
            raise ValueError(f"{name} ({value:g} m) must not exceed mesh_size ({mesh_size:g} m)")
    finest = min(opening_mesh_size, joint_mesh_size or mesh_size)
    if np.prod(size) / mesh_size ** 2 + (2 * opening_refine_distance + opening.perimeter) ** 2 / finest ** 2 > 5e7:
        raise ValueError(f"the mesh sizes (mesh_size {mesh_size:g} m, finest {finest:g} m) would give more than "
                         f"~5e7 elements in the section {tuple(size)}")

    joints = _normalise_joints(joints)
    if any(j.name == OPENING for j in joints):
        raise ValueError(f"a joint cannot be named {OPENING!r} (the opening's boundary group)")
    traces = [joint_trace(j, size, [joints[k] for k in bounds], f"joint {j.name!r}")
              for j, bounds in _resolve_bounds(joints)]
    outline = opening.outline()
    for j, t in zip(joints, traces):
        d = t[1] - t[0]
        side = (outline - t[0]) @ (np.array([d[1], -d[0]]) / np.linalg.norm(d))  # signed distances [m]
        if (np.all(side >= 0.0) or np.all(side <= 0.0)) and np.abs(side).min() <= 0.05 * opening_mesh_size:
            raise ValueError(f"joint {j.name!r} touches the opening's outline without crossing it (tangent: "
                             f"closest {np.abs(side).min():.3g} m); sliver blocks would follow, move the joint")

    segments = [_outside(opening, t, 1e-9 * float(size.max())) for t in traces]
    for j, segs in zip(joints, segments):
        if not segs:
            raise ValueError(f"joint {j.name!r} misses the rock section: its trace lies inside the opening")

    with _gmsh_model("rockjoint_tunnel_section") as gmsh:
        return _build(gmsh, size, opening, joints, segments, mesh_size, opening_mesh_size, opening_refine_distance,
                      joint_mesh_size, joint_refine_distance, intact, length)


def _outside(opening, trace: np.ndarray, shortest: float) -> list:
    """The parts of the segment trace[0]-trace[-1] outside the opening: none, one or two segments
    ((2, 2) arrays). The opening is convex, so its crossing (opening.crossing) is one interval of the
    segment's parameter; parts shorter than `shortest` [m] are dropped. Clipping here, before OCC
    sees the joints, means no joint piece is ever created inside the opening: removing such pieces
    from the fragmented model afterwards (occ.remove) cost 28 s of a 57 s tunnel analysis with
    11k blocks (bench/results/tunnel_profile.md)."""
    a, b = np.asarray(trace[0], float), np.asarray(trace[-1], float)
    cross = opening.crossing(a, b)
    if cross is None or cross[1] <= 0.0 or cross[0] >= 1.0:
        return [np.array([a, b])]
    length = float(np.linalg.norm(b - a))
    parts = []
    if cross[0] * length > shortest:
        parts.append(np.array([a, a + cross[0] * (b - a)]))
    if (1.0 - cross[1]) * length > shortest:
        parts.append(np.array([a + cross[1] * (b - a), b]))
    return parts


def _build(gmsh, size, opening, joints, segments, mesh_size, opening_mesh_size, opening_refine_distance,
           joint_mesh_size, joint_refine_distance, intact, length) -> JointedMesh:
    occ = gmsh.model.occ
    rock = occ.cut([(2, occ.addRectangle(0, 0, 0, *size))], [(2, opening.add_to(occ))])[0]
    owner = [i for i, segs in enumerate(segments) for _ in segs]  # the joint of every tool
    tools = [(1, _add_trace(occ, seg, 2)) for segs in segments for seg in segs]
    out_map = occ.fragment(rock, tools)[1] if tools else [rock]
    occ.synchronize()
    volumes = [t for d, t in gmsh.model.getEntities(2)]
    pieces, seen = [set() for _ in joints], {}
    for k, i in enumerate(owner):
        pieces[i].update(t for d, t in out_map[len(rock) + k] if d == 1)
    for j, ps in zip(joints, pieces):
        for p in ps:
            if seen.setdefault(p, j.name) != j.name:
                raise ValueError(f"joints {seen[p]!r} and {j.name!r} overlap")
    pieces = [sorted(ps) for ps in pieces]

    dim = 2
    if length is not None:  # the section in the x-z plane, extruded along y
        volumes, pieces, size = _extrude(gmsh, volumes, joints, size, length)
        dim = 3

    # Boundaries: the outer sides, and every other exterior curve (face) is the opening's.
    groups = {}
    for d, f in gmsh.model.getBoundary([(dim, v) for v in volumes], combined=True, oriented=False):
        name = _block_face(gmsh, d, abs(f), size) or OPENING
        groups.setdefault(name, []).append(abs(f))
    joint_facets = [p for ps in pieces for p in ps]
    exterior = {f for fs in groups.values() for f in fs}
    for j, ps in zip(joints, pieces):  # a joint piece inside a block is found on the mesh (_generate)
        if exterior.intersection(ps):
            raise ValueError(f"joint {j.name!r} does not separate two blocks everywhere: {_DANGLING}")

    # Sizes: the finer of the opening's and the joints' Threshold fields.
    extent = float(size.max())
    fields = [_distance_threshold(gmsh, dim, groups[OPENING], opening_mesh_size, mesh_size, opening_refine_distance,
                                  extent)]
    if joint_mesh_size is not None and joint_facets:
        fields.append(_distance_threshold(gmsh, dim, joint_facets, joint_mesh_size, mesh_size, joint_refine_distance,
                                          extent))
    field = gmsh.model.mesh.field
    finest = field.add("Min")
    field.setNumbers(finest, "FieldsList", fields)
    field.setAsBackgroundMesh(finest)
    _graded_size(gmsh, mesh_size)
    if dim == 2:
        # Far from the opening (beyond the DistMax = size_min / 2 + refine_distance of its
        # Threshold field, builders._distance_threshold) the size is mesh_size, unless the joints
        # have a field of their own.
        reach = 0.5 * opening_mesh_size + opening_refine_distance
        x0, y0, x1, y1 = opening.bounds()
        big = 2.0 * extent
        far = [] if len(fields) > 1 else [(-big, -big, x0 - reach, big), (x1 + reach, -big, big, big),
                                          (-big, -big, big, y0 - reach), (-big, y1 + reach, big, big)]
        _one_element_curves(gmsh, joint_facets, min(opening_mesh_size, joint_mesh_size or mesh_size), mesh_size, far)

    boundary_tags = {**SECTION_BOUNDARY_TAGS, "front": BOUNDARY_TAGS["front"], "back": BOUNDARY_TAGS["back"]}
    if intact:  # the same fragments and mesh lines, one block, no joints
        return _generate(gmsh, dim, [], groups, boundary_tags, _joint_names([]), one_block=True)
    return _generate(gmsh, dim, pieces, groups, boundary_tags, _joint_names(joints), dangling=_DANGLING)


def _extrude(gmsh, surfaces, joints, size, length):
    """Turn the meshed-to-be section (x-y plane) into the x-z plane and extrude it along y by length.
    Returns (volumes, joint faces per joint, 3D size (width, length, height))."""
    occ = gmsh.model.occ
    ents = [(2, v) for v in surfaces]
    occ.rotate(ents, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5 * math.pi)  # (x, y, 0) -> (x, 0, y)
    occ.extrude(ents, 0.0, length, 0.0)
    if len(ents) > 1:
        occ.removeAllDuplicates()  # one face between two prisms
    occ.synchronize()
    volumes = [t for d, t in gmsh.model.getEntities(3)]
    size3 = np.array([size[0], length, size[1]])
    pieces = [[] for _ in joints]
    for d, f in gmsh.model.getEntities(2):
        if len(gmsh.model.getAdjacencies(2, f)[0]) != 2:
            continue
        # the face's corners, back in section coordinates (x, z): all on one joint's plane
        corners = np.array([gmsh.model.getValue(0, abs(t), []) for _, t in
                            gmsh.model.getBoundary([(2, f)], combined=False, recursive=True)])[:, [0, 2]]
        owner = [i for i, j in enumerate(joints)
                 if np.all(np.abs((corners - np.asarray(j.point)) @ unit_normal(j.dip, j.dip_direction, 2))
                           <= 1e-6 * size.max() + 2e-7)]
        if len(owner) != 1:
            raise RuntimeError(f"internal: the face between two blocks at {corners.mean(axis=0)} lies on "
                               f"{len(owner)} joints")
        pieces[owner[0]].append(f)
    return volumes, [sorted(p) for p in pieces], size3
