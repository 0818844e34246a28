# SPDX-License-Identifier: MIT
"""The geometry of a scene: its extent, joint sets and their normals; its meshes through
rockjoint.meshes (column, jointed_block, tunnel_section), and the intact mesh: the same mesh with
its split nodes glued back (no joints), so that jointed minus intact is the joints' share and
nothing else."""
from __future__ import annotations

import math

import numpy as np

from .. import meshes
from ..meshes.joint_geometry import unit_normal
from ..meshes.slope import slope_section
from . import slope_keys


def extent(g) -> np.ndarray:
    """The box of a scene's geometry section `g` [m] along the axes x, y(, z): a block's size; a
    column's width(s) and height; a tunnel's width and height, in 3D (width, length, height):
    its section lies in the x-z plane and its axis is y."""
    if g["kind"] == "block":
        return np.array(g["size"])
    if g["kind"] == "column":
        return np.array([g["width"]] * (g["dimension"] - 1) + [g["height"]])
    if g["kind"] == "slope":   # the section's width and its height above the bottom (3D: the length between)
        geo = slope_keys.section(g)
        return np.array([geo.width, *([g["length"]] if "length" in g else []), geo.base + geo.height])
    if "length" in g:
        return np.array([g["width"], g["length"], g["height"]])
    return np.array([g["width"], g["height"]])


def joint_sets(scene) -> list:
    """The scene's joint sets (a column's joints as one horizontal set named 'joint')."""
    g = scene.data["geometry"]
    if g["kind"] == "column":
        return [{"name": "joint", "dip": 0.0, "dip_direction": math.pi / 2}]
    if g["kind"] == "slope":
        return slope_keys.sets(g)
    return g.get("joint_sets", [])


def set_normal(joint_set: dict, dim: int) -> np.ndarray:
    """Upward unit normal of a joint set (dip and dip direction in radians): the mesh's own
    (meshes.joint_geometry.unit_normal), so the planner and the statics checks see the planes
    the mesh has."""
    return unit_normal(math.degrees(joint_set["dip"]), math.degrees(joint_set["dip_direction"]), dim)


def joint_objects(scene, exclude=()):
    """The scene's joint sets as rockjoint.meshes.Joint lists (names <set>_<i>), without the sets
    named in `exclude` (smeared ones)."""
    g = scene.data["geometry"]
    if g["kind"] == "slope":
        return slope_keys.joints(g, exclude)
    # A 3D tunnel is its section (x-z plane) extruded along y: its joint sets run along y (the
    # schema checks it), so each is the section's joint through (x, z), with the same dip and
    # spacing (the normal has no y component); meshes.tunnel_section extrudes them into planes.
    section = g["kind"] == "tunnel" and g["dimension"] == 3
    out = []
    for s in g.get("joint_sets", []):
        if s["name"] in exclude:
            continue
        point = (s["point"][0], s["point"][2]) if section else tuple(s["point"])
        dip_direction = 90.0 if section and s["dip"] == 0.0 else math.degrees(s["dip_direction"])
        out += meshes.joint_set(s["spacing"], math.degrees(s["dip"]), dip_direction,
                                origin=point, count=s["count"], name=s["name"])
    return out


def opening(g):
    """The opening of a tunnel's geometry section `g` as the mesh builder's object (meshes/openings.py):
    shape circle, a CircularOpening (centre, radius); shapes D and horseshoe, a HorseshoeOpening whose
    centre is the springline's middle, with half the span, the wall height, the invert's sag (0 for
    the D's flat floor) and the arch radius (None: a semicircular crown)."""
    o = g["opening"]
    centre = tuple(o["centre"][:2])
    if o["shape"] == "circle":
        return meshes.CircularOpening(centre, o["radius"])
    return meshes.HorseshoeOpening(centre, 0.5 * o["span"], o["wall_height"], o.get("invert_depth", 0.0),
                                   o.get("arch_radius"))


def opening_half_size(g) -> float:
    """Half the largest dimension of the opening [m] (a circle's radius): the length the opening's
    mesh size, refinement distance, picture and the planner's spacing ratio s/a scale with."""
    x0, y0, x1, y1 = opening(g).bounds()
    return 0.5 * max(x1 - x0, y1 - y0)


def jointed_mesh(scene, plan, comm):
    """The jointed mesh of the scene (a JointedMesh on rank 0, None elsewhere)."""
    g = scene.data["geometry"]
    h, hj = plan.mesh_size, plan.joint_size
    if g["kind"] == "column":
        return meshes.column(g["width"], g["height"], g["joint_heights"], dim=plan.dimension,
                             mesh_size=h, joint_mesh_size=hj, comm=comm)
    if g["kind"] == "block":
        return meshes.jointed_block(g["size"], joint_objects(scene, plan.smeared), dim=plan.dimension, mesh_size=h,
                                    joint_mesh_size=hj, comm=comm)
    if g["kind"] == "slope":
        return slope_section(slope_keys.section(g), joint_objects(scene, plan.smeared), mesh_size=h,
                             joint_mesh_size=hj, joint_refine_distance=h if hj else None,
                             length=g.get("length") if plan.dimension == 3 else None, comm=comm)
    return meshes.tunnel_section(g["width"], g["height"], opening(g), joint_objects(scene, plan.smeared), mesh_size=h,
                                 opening_mesh_size=plan.opening_size,
                                 opening_refine_distance=2 * opening_half_size(g) if plan.opening_size else None,
                                 joint_mesh_size=hj, joint_refine_distance=h if hj else None,
                                 length=g.get("length") if plan.dimension == 3 else None, comm=comm)


def glued(jm):
    """The intact mesh: `jm` with its split nodes glued back (one node where the joint had two),
    its blocks and boundaries kept, no joints."""
    if jm is None:
        return None
    n0, g = jm.num_original_nodes, jm.glue
    nf = jm.joint_facets_minus.shape[1]
    return meshes.JointedMesh(
        points=jm.points[:n0], cells=g[jm.cells], cell_type=jm.cell_type, cell_blocks=jm.cell_blocks,
        glue=np.arange(n0), joint_facets_minus=np.zeros((0, nf), np.int64),
        joint_facets_plus=np.zeros((0, nf), np.int64), joint_facet_cells=np.zeros((0, 2), np.int64),
        joint_tags=np.zeros(0, np.int32), boundary_facets=g[jm.boundary_facets],
        boundary_tags=jm.boundary_tags,
        names={"blocks": jm.names["blocks"], "joints": {}, "boundaries": jm.names["boundaries"]})
