# SPDX-License-Identifier: MIT
"""gmsh builder of a rock-mass section around a tunnel opening, cut by joint sets (2D, or extruded to 3D).

Geometry (plane strain, y up): the section is the rectangle [0, width] x [0, height] minus the
opening (a CircularOpening or a HorseshoeOpening placed at its ``centre``, meshes.openings). Joints
(meshes.Joint, e.g. from meshes.joint_set) are clipped analytically to the rectangle (and to the
joints they are bounded by) and to the opening (its ``crossing``): no piece of a joint is ever made
inside the opening, so every joint ends on the opening, on the outer boundary or on another joint.
A 2D section (_build_planar) is then built without any boolean: the joints' crossings and the
outline's split points come from meshes.planar_section, and gmsh's built-in kernel meshes one
surface with the joint pieces embedded as mesh lines; the blocks are found on the mesh. The 3D
extrusion and the quarter section (_build) cut the section with OCC's ``fragment``.
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
from typing import Iterable

import numpy as np

from . import planar_section
from .builders import (BOUNDARY_TAGS, _add_trace, _block_face, _distance_threshold, _generate, _gmsh_model,
                       _graded_size, _joint_names, _normalise_joints, _one_element_curves, _resolve_bounds,
                       threshold_distances, threshold_size)
from .joint_geometry import _positive, joint_trace, unit_normal
from .jointed_mesh import JointedMesh
from .openings import CircularOpening, HorseshoeOpening

OPENING = "opening"
OPENING_TAG = 7  # after builders.BOUNDARY_TAGS (1..6)
#: what to do about a joint that does not separate two blocks (the end of its error message)
_DANGLING = "part of it runs along the opening's boundary or ends inside a block (dangling tip)"
SECTION_BOUNDARY_TAGS = {**{k: BOUNDARY_TAGS[k] for k in ("bottom", "top", "left", "right")}, OPENING: OPENING_TAG}


def tunnel_section(width: float, height: float, opening, joints: Iterable = (), *, mesh_size: float,
                   opening_mesh_size: float | None = None, opening_refine_distance: float | None = None,
                   joint_mesh_size: float | None = None, joint_refine_distance: float | None = None,
                   intact: bool = False, quarter: bool = False, length: float | None = None,
                   comm=None) -> JointedMesh | None:
    """The section [0, width] x [0, height] minus ``opening``, cut by ``joints``, meshed and split.

    :opening: CircularOpening or HorseshoeOpening, strictly inside the section (at least one element
        size from its sides).
    :joints: Joint objects, lists of them (meshes.joint_set) or (point, dip[, dip_direction]) tuples;
        2D dips toward +x (dip_direction 90) or -x (270).
    :mesh_size: element size [m] far from the opening and the joints.
    :opening_mesh_size: element size [m] on the opening (default mesh_size / 4);
        opening_refine_distance: distance [m] over which it grows to mesh_size (default 2 x the
        opening's largest half-dimension).
    :joint_mesh_size: element size [m] on the joints (default: no joint refinement);
        joint_refine_distance: growth distance [m] (default 2 mesh_size).
    :intact: the same mesh as one block without joints (see the module docstring).
    :quarter: mesh a quarter of a section symmetric about the opening's vertical and horizontal axes:
        a CircularOpening centred at the origin (0, 0), the rock [0, width] x [0, height] around it;
        "left" (x = 0) and "bottom" (y = 0) are then the symmetry planes (rollers there are exact for
        a symmetric load such as Kirsch's far field).
    :length: if given, the 3D extrusion of the section along the tunnel axis, ``length`` [m] long: the
        section's x stays x, its y becomes z (up) and the axis is y, from y = 0 ("front") to
        y = length ("back"); joints become planes, the opening a prism (tetrahedra, the same size
        fields on the opening's and the joints' faces).
    :comm: an mpi4py communicator; ranks != 0 return None (gmsh runs on rank 0).
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
        if length is None and not quarter:
            return _build_planar(gmsh, size, opening, joints, segments, mesh_size, opening_mesh_size,
                                 opening_refine_distance, joint_mesh_size, joint_refine_distance, intact)
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


def _build_planar(gmsh, size, opening, joints, segments, mesh_size, opening_mesh_size, opening_refine_distance,
                  joint_mesh_size, joint_refine_distance, intact) -> JointedMesh:
    """The 2D section with gmsh's built-in kernel and no boolean: the joints' crossings and the
    outline's split points from planar_section, ONE surface (the rectangle minus the opening) with
    every joint piece embedded in it as a mesh line, each given its node count up front.

    Against OCC's fragment into 11k block surfaces (the 3D and quarter sections still use it,
    _build), on the continuum bench's discrete tunnel: geometry 2.0 -> 0.1 s
    (bench/results/tunnel_profile.md). The node counts are gmsh's own rule on the same size fields
    (planar_section.line_node_counts, builders.threshold_size): gmsh finds them by integrating the
    field along every one of the 22k joint pieces, which was most of its 1D meshing time.
    """
    extent = float(size.max())
    tol = 1e-9 * extent
    owner = np.array([i for i, segs in enumerate(segments) for _ in segs], dtype=np.int64)
    segs = np.array([seg for segs in segments for seg in segs], dtype=float).reshape(-1, 2, 2)
    loops = [planar_section.rectangle(*size), opening.pieces()]
    outline = loops[0] + loops[1]
    nodes, chains, vertex = planar_section.arrange(segs, [joints[i].name for i in owner], tol,
                                                   np.array([p.start for p in outline]))
    starts, ends, line_owner, tips = planar_section.chain_lines(chains, owner)
    # A joint piece between two nodes on the outline may run along it (then it separates nothing).
    on_outline = np.zeros(len(nodes), dtype=bool)
    on_outline[tips[planar_section.outline_distance(nodes[tips], outline) <= tol] if tips.size else tips] = True
    both = np.flatnonzero(on_outline[starts] & on_outline[ends])
    if both.size:
        runs_along = planar_section.outline_distance(0.5 * (nodes[starts[both]] + nodes[ends[both]]), outline) <= tol
        if runs_along.any():
            raise ValueError(f"joint {joints[int(line_owner[both[np.argmax(runs_along)]])].name!r} does not separate "
                             f"two blocks everywhere: {_DANGLING}")

    geo = gmsh.model.geo
    point = planar_section.GeoPoints(geo, nodes)

    names = ("bottom", "right", "top", "left")
    splits = planar_section.split_outline(outline, nodes, tips, tol)
    groups, loop_tags, hole_longest, k = {}, [], 0.0, 0
    for loop in loops:
        curves = []
        for j, piece in enumerate(loop):
            seq = [vertex[k + j], *splits[k + j], vertex[k + (j + 1) % len(loop)]]
            centre = None if piece.centre is None else geo.addPoint(*piece.centre, 0.0)
            for a, b in zip(seq[:-1], seq[1:]):
                c = geo.addLine(point(a), point(b)) if centre is None else \
                    geo.addCircleArc(point(a), centre, point(b))
                curves.append(c)
                groups.setdefault(names[j] if loop is loops[0] else OPENING, []).append(c)
            if loop is loops[1]:   # the opening's longest curve, for its Distance field's sampling
                hole_longest = max(hole_longest, float(np.diff(piece.position(nodes[seq])[1]).max()))
        loop_tags.append(geo.addCurveLoop(curves))
        k += len(loop)
    lines = np.array([geo.addLine(point(a), point(b)) for a, b in zip(starts, ends)], dtype=np.int64)
    surface = geo.addPlaneSurface(loop_tags)
    geo.synchronize()
    if lines.size:
        gmsh.model.mesh.embed(1, lines.tolist(), 2, surface)
    pieces = [lines[line_owner == i].tolist() for i in range(len(joints))]

    segment_length = np.linalg.norm(nodes[ends] - nodes[starts], axis=1)
    _size_fields(gmsh, 2, groups[OPENING], lines.tolist(), mesh_size, opening_mesh_size, opening_refine_distance,
                 joint_mesh_size, joint_refine_distance, extent,
                 longest=(hole_longest, float(segment_length.max()) if lines.size else None))
    factor = gmsh.option.getNumber("Mesh.MeshSizeFactor")

    def size_at(p):
        h = np.minimum(mesh_size, threshold_size(planar_section.outline_distance(p, loops[1]), opening_mesh_size,
                                                 mesh_size, opening_refine_distance))
        return factor * (h if joint_mesh_size is None else np.minimum(h, joint_mesh_size))

    if lines.size:
        # Beyond the opening's field (DistMax, _distance_threshold) the size is uniform: the distance
        # is 1-Lipschitz, so a piece whose midpoint lies half its length farther is all there.
        far = factor * (mesh_size if joint_mesh_size is None else min(mesh_size, joint_mesh_size))
        counts = planar_section.node_count(segment_length / far)
        mid = 0.5 * (nodes[starts] + nodes[ends])
        near = np.flatnonzero(planar_section.outline_distance(mid, loops[1]) - 0.5 * segment_length
                              < threshold_distances(opening_mesh_size, opening_refine_distance)[1])
        counts[near] = planar_section.line_node_counts(segment_length[near], nodes[starts[near]], nodes[ends[near]],
                                                       size_at)
        _set_node_counts(gmsh, lines, counts)

    if intact:  # the same mesh lines, one block, no joints
        return _generate(gmsh, 2, [], groups, SECTION_BOUNDARY_TAGS, _joint_names([]), one_block=True,
                         blocks_are_volumes=False)
    return _generate(gmsh, 2, pieces, groups, SECTION_BOUNDARY_TAGS, _joint_names(joints), dangling=_DANGLING,
                     blocks_are_volumes=False)


def _size_fields(gmsh, dim, opening_entities, joint_entities, mesh_size, opening_mesh_size,
                 opening_refine_distance, joint_mesh_size, joint_refine_distance, extent,
                 longest=(None, None)) -> bool:
    """The mesh size: the finer of the opening's and (joint_mesh_size given) the joints' Threshold
    fields (builders._distance_threshold; longest: their longest curves [m] if known), graded
    (builders._graded_size). Returns whether the joints have a field of their own."""
    fields = [_distance_threshold(gmsh, dim, opening_entities, opening_mesh_size, mesh_size, opening_refine_distance,
                                  extent, longest=longest[0])]
    joint_field = joint_mesh_size is not None and len(joint_entities) > 0
    if joint_field:
        fields.append(_distance_threshold(gmsh, dim, joint_entities, joint_mesh_size, mesh_size, joint_refine_distance,
                                          extent, longest=longest[1]))
    field = gmsh.model.mesh.field
    finest = field.add("Min")
    field.setNumbers(finest, "FieldsList", fields)
    field.setAsBackgroundMesh(finest)
    _graded_size(gmsh, mesh_size)
    return joint_field


def _set_node_counts(gmsh, lines, counts) -> None:
    """Mesh each line with its count of nodes, equally spaced (a transfinite curve: gmsh then only
    integrates the curve's speed, not the size field)."""
    for c, n in zip(np.asarray(lines).tolist(), np.asarray(counts).tolist()):
        gmsh.model.mesh.setTransfiniteCurve(c, n)


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

    extent = float(size.max())
    joint_field = _size_fields(gmsh, dim, groups[OPENING], joint_facets, mesh_size, opening_mesh_size,
                               opening_refine_distance, joint_mesh_size, joint_refine_distance, extent)
    if dim == 2:
        # Far from the opening (beyond the DistMax = size_min / 2 + refine_distance of its
        # Threshold field, builders._distance_threshold) the size is mesh_size, unless the joints
        # have a field of their own.
        reach = threshold_distances(opening_mesh_size, opening_refine_distance)[1]
        x0, y0, x1, y1 = opening.bounds()
        big = 2.0 * extent
        far = [] if joint_field else [(-big, -big, x0 - reach, big), (x1 + reach, -big, big, big),
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
