# SPDX-License-Identifier: MIT
"""The slope section extruded along the strike (issue 40; slope.slope_section(length=...)), as a
tunnel section is (tunnel._extrude): the section's outline fragmented by the joints' traces with
OCC, turned into the x-z plane (the section's y becomes z, up) and extruded along y from y = 0
("front") to y = length ("back"); the joints become planes, the blocks prisms (tetrahedra). The
boundary groups are the section's (bottom, right, top, face, toe, left) and front and back.
"""
from __future__ import annotations

import numpy as np

from .builders import (BOUNDARY_TAGS, _add_trace, _distance_threshold, _generate, _graded_size, _joint_names,
                       _uniform_size)
from .jointed_mesh import JointedMesh
from .tunnel import _extrude


def extruded_slope(gmsh, geometry, joints: list, segments: list, groups_2d: tuple, boundary_tags: dict, *,
                   length: float, mesh_size: float, joint_mesh_size: float | None, refine: float, intact: bool,
                   dangling: str) -> JointedMesh:
    """The 3D mesh of the slope section `geometry` cut by `joints` (their clipped `segments`, one
    list per joint: slope.slope_traces), extruded by `length` [m]; groups_2d: the names of the
    outline's pieces in order (SlopeGeometry.piece_groups()); boundary_tags: the section's tags (front and back
    are added). ValueError naming a joint that ends inside a block (`dangling`: what to do)."""
    occ = gmsh.model.occ
    pieces = geometry.pieces()
    points = [occ.addPoint(*p.start, 0.0) for p in pieces]
    loop = occ.addCurveLoop([occ.addLine(points[k], points[(k + 1) % len(points)]) for k in range(len(points))])
    rock = [(2, occ.addPlaneSurface([loop]))]
    owner = [i for i, segs in enumerate(segments) for _ in segs]
    tools = [(1, _add_trace(occ, seg, 2)) for segs in segments for seg in segs]
    out_map = occ.fragment(rock, tools)[1] if tools else [rock]
    occ.synchronize()
    for k, i in enumerate(owner):   # every piece of a joint between two blocks of the section
        for d, c in out_map[len(rock) + k]:
            if d == 1 and len(gmsh.model.getAdjacencies(1, c)[0]) != 2:
                raise ValueError(f"joint {joints[i].name!r} does not separate two blocks everywhere: {dangling}")
    surfaces = [t for d, t in gmsh.model.getEntities(2)]
    size = np.array([geometry.width, geometry.base + geometry.height])
    volumes, joint_faces, size3 = _extrude(gmsh, surfaces, joints, size, length)

    groups = {}
    for _, f in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True, oriented=False):
        groups.setdefault(_face_group(gmsh, abs(f), pieces, groups_2d, length, float(size3.max())), []).append(abs(f))
    faces = [f for fs in joint_faces for f in fs]
    if joint_mesh_size is not None and faces:
        field = _distance_threshold(gmsh, 3, faces, joint_mesh_size, mesh_size, refine, float(size3.max()))
        gmsh.model.mesh.field.setAsBackgroundMesh(field)
        _graded_size(gmsh, mesh_size)
    else:
        _uniform_size(gmsh, mesh_size)
    tags = {**boundary_tags, "front": BOUNDARY_TAGS["front"], "back": BOUNDARY_TAGS["back"]}
    if intact:
        return _generate(gmsh, 3, [], groups, tags, _joint_names([]), one_block=True)
    return _generate(gmsh, 3, joint_faces, groups, tags, _joint_names(joints), dangling=dangling)


def _face_group(gmsh, face: int, pieces, names, length: float, extent: float) -> str:
    """The boundary group of an outer face of the extruded section: front (y = 0), back (y =
    length), or the outline piece (in x, z) its centre lies on."""
    x, y, z = gmsh.model.occ.getCenterOfMass(2, face)
    tol = 1e-7 * extent + 1e-7
    if abs(y) <= tol:
        return "front"
    if abs(y - length) <= tol:
        return "back"
    c = np.array([x, z])
    for name, piece in zip(names, pieces):
        a, b = np.asarray(piece.start), np.asarray(piece.end)
        t = np.clip((c - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        if np.linalg.norm(a + t * (b - a) - c) <= tol:
            return name
    raise RuntimeError(f"internal: the outer face at {(x, y, z)} lies on no side of the slope section")
