# SPDX-License-Identifier: MIT
"""gmsh (OCC) builders of rectangular blocks cut by planar joints, split by block.

Geometry: the block is [0, Lx] x [0, Ly] (2D, y up) or [0, Lx] x [0, Ly] x [0, Lz] (3D, z up). Joints are
clipped analytically to the block (and to the joints they end on), then ``occ.fragment`` makes the
mesh conforming. Physical groups:
- blocks: one per fragment volume, ``block_<k>`` with tag k = 1, 2, ... in order of the centre of mass,
  lowest first (vertical coordinate, then y, then x): in a column of horizontal joints block 1 is the
  bottom one, so the minus side (lower block tag) of each joint is below it and the normal points up.
- joints: ``joint_<i>`` (or the joint's name) with tags 100, 101, ... in input order.
- boundaries: "bottom", "top", "left" (x = 0), "right" (x = Lx), and in 3D "front" (y = 0) and "back"
  (y = Ly); tags 1..6 in that order.
Joints must separate blocks completely (each joint piece has a block on each side); a joint that ends
inside a block (dangling crack tip) or does not cut the block raises ValueError.

gmsh runs on one process: with ``comm`` given, ranks other than 0 return None without touching gmsh.
"""
from __future__ import annotations

import atexit
import contextlib
import logging
import math
from typing import Iterable, Sequence

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from .joint_geometry import Joint, joint_trace, _positive
from .jointed_mesh import JointedMesh
from .node_splitting import build_jointed_mesh, cell_facets, common_facet_keys

log = logging.getLogger(__name__)

JOINT_TAG_OFFSET = 100
BOUNDARY_TAGS = {"bottom": 1, "top": 2, "left": 3, "right": 4, "front": 5, "back": 6}
_GMSH_CELL = {2: (2, "triangle"), 3: (4, "tetrahedron")}  # dim -> (gmsh element type, cell type)
_GMSH_FACET = {2: 1, 3: 2}  # dim -> gmsh facet element type (line, triangle)
_GMSH_POINT = 15  # gmsh's point element (the mesh node on a model point)
_ALGORITHMS_3D = {"delaunay": 1, "hxt": 10}  # gmsh Mesh.Algorithm3D codes
_DANGLING = ("part of it ends inside a block (dangling tip) — joints must end on other joints or on the block "
             "boundary (use bounded_by with joints that reach it)")


def column(width: float, height: float, joint_heights: Sequence[float], dim: int = 2, mesh_size: float = None,
           joint_mesh_size: float | None = None, refine_distance: float | None = None, comm=None, *,
           algorithm_3d: str = "delaunay") -> JointedMesh | None:
    """A 2D rectangle width x height or a 3D box width x width x height cut by horizontal joints.

    joint_heights: heights [m] of the joints, strictly inside (0, height), distinct. Joint i (1-based,
    bottom first) is named ``joint_<i>``, all in the set ``joint``; blocks ``block_1`` (bottom) ...
    ``block_<N+1>`` (top).
    """
    width, height = _positive("width", width), _positive("height", height)
    if dim not in (2, 3):
        raise ValueError(f"column: dim must be 2 or 3, got {dim!r}")
    hs = sorted(float(h) for h in joint_heights)
    for h in hs:
        if not (math.isfinite(h) and 0.0 < h < height):
            raise ValueError(f"column: joint height {h!r} is not strictly inside (0, height={height})")
    if any(b - a <= 1e-12 * height for a, b in zip(hs, hs[1:])):
        raise ValueError(f"column: joint heights must be distinct, got {sorted(joint_heights)}")
    size = (width, height) if dim == 2 else (width, width, height)
    centre = (0.5 * width,) * (dim - 1)
    joints = [Joint(centre + (h,), 0.0, 90.0, f"joint_{i + 1}", joint_set="joint") for i, h in enumerate(hs)]
    return jointed_block(size, joints, dim, mesh_size, joint_mesh_size, refine_distance, comm=comm,
                         algorithm_3d=algorithm_3d)


def jointed_block(size: Sequence[float], joints: Iterable, dim: int | None = None, mesh_size: float = None,
                  joint_mesh_size: float | None = None, refine_distance: float | None = None, comm=None, *,
                  algorithm_3d: str = "delaunay") -> JointedMesh | None:
    """A rectangle/box [0, size] cut by planar joints, meshed, split by block, joint facets paired.

    :joints: Joint objects (see joint_geometry.Joint), tuples (point, dip[, dip_direction]) or lists of
        them (e.g. from joint_set).
    :mesh_size: target element size [m] away from the joints.
    :joint_mesh_size: element size [m] on the joints (gmsh Distance + Threshold fields); None = uniform.
    :refine_distance: distance [m] over which the size grows from joint_mesh_size to mesh_size
        (default 2 mesh_size).
    :comm: an mpi4py communicator; ranks != 0 return None.
    :algorithm_3d: "delaunay" (gmsh's default 3D algorithm; the same mesh on every run) or "hxt"
        (about 5x faster on large boxes, but gmsh 4.8's HXT gives slightly different meshes run to run).
    """
    if comm is not None and comm.rank != 0:
        return None
    size = np.array([_positive(f"size[{i}]", s) for i, s in enumerate(np.atleast_1d(size))])
    if dim is None:
        dim = size.size
    if dim not in (2, 3) or size.size != dim:
        raise ValueError(f"jointed_block: dim must be 2 or 3 and size must have dim entries, got dim={dim!r}, "
                         f"size={tuple(size)}")
    if mesh_size is None:
        raise ValueError("jointed_block: mesh_size is required")
    mesh_size = _positive("mesh_size", mesh_size)
    if joint_mesh_size is not None:
        joint_mesh_size = _positive("joint_mesh_size", joint_mesh_size)
        if joint_mesh_size > mesh_size:
            raise ValueError(f"joint_mesh_size ({joint_mesh_size}) must not exceed mesh_size ({mesh_size})")
    refine_distance = 2.0 * mesh_size if refine_distance is None else _positive("refine_distance", refine_distance)
    if mesh_size > size.max():
        raise ValueError(f"mesh_size ({mesh_size}) exceeds the block size {tuple(size)}")
    if np.prod(size / (joint_mesh_size or mesh_size)) > 5e7:
        raise ValueError(f"mesh_size {mesh_size} would give more than ~5e7 elements in the block {tuple(size)}")
    if algorithm_3d not in _ALGORITHMS_3D:
        raise ValueError(f"algorithm_3d must be one of {sorted(_ALGORITHMS_3D)}, got {algorithm_3d!r}")
    joints = _normalise_joints(joints)
    traces = [joint_trace(j, size, [joints[k] for k in bounds], f"joint {j.name!r}")
              for j, bounds in _resolve_bounds(joints)]

    with _gmsh_model("rockjoint_jointed_block") as gmsh:
        gmsh.option.setNumber("Mesh.Algorithm3D", _ALGORITHMS_3D[algorithm_3d])
        return _build(gmsh, size, dim, joints, traces, mesh_size, joint_mesh_size, refine_distance)


_OPTIONS = ("General.Terminal", "Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
            "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeMin", "Mesh.MeshSizeMax", "Mesh.ElementOrder",
            "Mesh.Algorithm3D", "Mesh.RecombineAll")


@contextlib.contextmanager
def _gmsh_model(name: str):
    """gmsh (initialised) with a new model `name`, quiet; afterwards the model is removed and the
    global options a builder sets (_OPTIONS) are restored, whatever happened. One thread: gmsh's
    1D meshing on two (General.NumThreads, Mesh.MaxNumThreads1D) was 0.3 s faster on the
    continuum bench's tunnel section but gave different meshes from run to run (the intact
    variant of test_meshes_tunnel's section lost 2 of its 1128 nodes in 3 of 4 runs)."""
    import gmsh  # heavy, and only rank 0 meshes: imported when a mesh is built
    _ensure_gmsh(gmsh)
    saved = {o: gmsh.option.getNumber(o) for o in _OPTIONS}  # gmsh options are global: restore them
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.RecombineAll", 0)  # simplices, whatever the caller's model asked for
    gmsh.model.add(name)
    try:
        yield gmsh
    finally:
        gmsh.model.remove()
        for o, v in saved.items():
            gmsh.option.setNumber(o, v)


_OWN_GMSH = []


def _ensure_gmsh(gmsh) -> None:
    """Initialise gmsh once per process unless the caller already did (gmsh 4.8 has no isInitialized)."""
    if _OWN_GMSH:
        return
    if hasattr(gmsh, "isInitialized"):
        initialised = bool(gmsh.isInitialized())
    else:
        try:
            initialised = len(gmsh.model.list()) > 0  # [] before the first initialize
        except Exception:
            initialised = False
    if not initialised:
        gmsh.initialize()
        _OWN_GMSH.append(True)
        atexit.register(gmsh.finalize)


def _normalise_joints(joints) -> list[Joint]:
    flat = []

    def add(j):
        if isinstance(j, Joint):
            flat.append(j)
        elif isinstance(j, (list, tuple)) and j and all(isinstance(k, Joint) for k in j):
            for k in j:
                add(k)
        elif isinstance(j, (list, tuple)) and 2 <= len(j) <= 3:
            flat.append(Joint(tuple(j[0]), *[float(v) for v in j[1:]]))
        else:
            raise ValueError(f"a joint must be a Joint, (point, dip[, dip_direction]) or a list of Joints, got {j!r}")

    for j in joints:
        add(j)
    out = []
    for i, j in enumerate(flat):
        name = j.name if j.name is not None else f"joint_{i + 1}"
        out.append(Joint(tuple(float(v) for v in j.point), float(j.dip), float(j.dip_direction), name,
                         tuple(j.bounded_by), j.joint_set))
    names = [j.name for j in out]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"joint names must be unique, duplicated: {dup}")
    if names and set(names) & set(BOUNDARY_TAGS):
        raise ValueError(f"joint names must differ from the boundary names {sorted(BOUNDARY_TAGS)}")
    return out


def _resolve_bounds(joints: list[Joint]):
    index = {j.name: i for i, j in enumerate(joints)}
    for i, j in enumerate(joints):
        bounds = []
        for b in j.bounded_by:
            k = index.get(b) if isinstance(b, str) else (int(b) if isinstance(b, (int, np.integer)) else None)
            if k is None or not 0 <= k < len(joints):
                raise ValueError(f"joint {j.name!r}: bounded_by entry {b!r} is not a joint name or index; "
                                 f"joints: {list(index)}")
            if k == i:
                raise ValueError(f"joint {j.name!r} cannot be bounded by itself")
            bounds.append(k)
        yield j, bounds


def _add_trace(occ, trace: np.ndarray, dim: int) -> int:
    pad = [0.0] if dim == 2 else []
    pts = [occ.addPoint(*(list(p) + pad)) for p in trace]
    if dim == 2:
        return occ.addLine(pts[0], pts[-1])
    lines = [occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
    return occ.addPlaneSurface([occ.addCurveLoop(lines)])


def _build(gmsh, size, dim, joints, traces, mesh_size, joint_mesh_size, refine_distance) -> JointedMesh:
    occ = gmsh.model.occ
    fd = dim - 1
    body = occ.addRectangle(0, 0, 0, *size) if dim == 2 else occ.addBox(0, 0, 0, *size)
    tools = [(fd, _add_trace(occ, t, dim)) for t in traces]
    out_map = occ.fragment([(dim, body)], tools)[1] if tools else [[(dim, body)]]  # no joints: intact block
    occ.synchronize()
    volumes = [t for d, t in gmsh.model.getEntities(dim)]
    pieces = [sorted({t for d, t in out_map[1 + i] if d == fd}) for i in range(len(joints))]
    seen = {}
    for j, ps in zip(joints, pieces):
        for p in ps:
            if p in seen:
                raise ValueError(f"joints {seen[p]!r} and {j.name!r} overlap")
            seen[p] = j.name
    names = _joint_names(joints)

    # Boundaries: exterior faces of the union, classified by the block face they lie on.
    groups = {}
    for d, f in gmsh.model.getBoundary([(dim, v) for v in volumes], combined=True, oriented=False):
        name = _block_face(gmsh, d, abs(f), size)
        if name is None:
            raise RuntimeError(f"internal: exterior entity {f} lies on no block face")
        groups.setdefault(name, []).append(abs(f))

    # Mesh sizes.
    if joint_mesh_size is None or not joints:
        _uniform_size(gmsh, mesh_size)
    else:
        field = _distance_threshold(gmsh, dim, sorted(seen), joint_mesh_size, mesh_size, refine_distance,
                                    size.max())
        gmsh.model.mesh.field.setAsBackgroundMesh(field)
        _graded_size(gmsh, mesh_size)
    return _generate(gmsh, dim, pieces, groups, BOUNDARY_TAGS, names, dangling=_DANGLING)


def _block_face(gmsh, fdim: int, entity: int, size) -> str | None:
    """Name of the face of the block [0, size] ("left", "right", "bottom", "top", "front", "back") on
    which the boundary entity (fdim, entity) lies, or None if it lies on none."""
    dim = len(size)
    side_names = [("left", "right"), ("bottom", "top")] if dim == 2 else \
        [("left", "right"), ("front", "back"), ("bottom", "top")]
    extent = float(np.max(size))
    tol = 1e-8 * extent
    # OCC pads bounding boxes by an absolute ~1e-7 m (Precision::Confusion) on each side, so a
    # flat face of a lab-scale (0.1 m) block looks ~2e-7 m thick: allow that absolute pad.
    flat = 1e-6 * extent + 1e-6
    lo, hi = np.array(gmsh.model.getBoundingBox(fdim, entity)).reshape(2, 3)[:, :dim]
    c = np.array(gmsh.model.occ.getCenterOfMass(fdim, entity))[:dim]
    for axis in range(dim):
        for end, value in ((0, 0.0), (1, size[axis])):
            if abs(c[axis] - value) <= tol and hi[axis] - lo[axis] <= flat:
                return side_names[axis][end]
    return None


def _joint_names(joints) -> dict:
    """The names of the groups: joints by name (tags JOINT_TAG_OFFSET + i); _generate adds the
    blocks and the boundaries. The groups live in `names` only: the gmsh model is removed after
    meshing, and gmsh physical groups (one addPhysicalGroup + setPhysicalName per block) cost 1.2 s
    of CPU time for the 11k blocks of the continuum bench's discrete tunnel, for nothing read
    afterwards. With them the joints' sets: {joint tag: set name} (a joint without a set is its own)."""
    return {"blocks": {}, "joints": {JOINT_TAG_OFFSET + i: j.name for i, j in enumerate(joints)}, "boundaries": {},
            "joint_sets": {JOINT_TAG_OFFSET + i: j.joint_set or j.name for i, j in enumerate(joints)}}


def _uniform_size(gmsh, mesh_size: float) -> None:
    for option, value in (("Mesh.MeshSizeExtendFromBoundary", 0), ("Mesh.MeshSizeFromPoints", 0),
                          ("Mesh.MeshSizeFromCurvature", 0), ("Mesh.MeshSizeMin", mesh_size),
                          ("Mesh.MeshSizeMax", mesh_size)):
        gmsh.option.setNumber(option, value)


def _graded_size(gmsh, mesh_size: float) -> None:
    """Sizes from the background field, capped at mesh_size."""
    _uniform_size(gmsh, mesh_size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)


def threshold_distances(size_min: float, refine_distance: float) -> tuple:
    """(DistMin, DistMax) [m] of _distance_threshold's field: size_min up to size_min / 2 from its
    entities, size_max from size_min / 2 + refine_distance on."""
    return 0.5 * size_min, 0.5 * size_min + refine_distance


def threshold_size(distance, size_min: float, size_max: float, refine_distance: float):
    """The size [m] _distance_threshold's field gives at `distance` [m] from its entities (gmsh's
    Threshold field: linear between threshold_distances)."""
    lo, hi = threshold_distances(size_min, refine_distance)
    w = np.clip((np.asarray(distance, float) - lo) / (hi - lo), 0.0, 1.0)
    return size_min + w * (size_max - size_min)


def _distance_threshold(gmsh, dim: int, entities, size_min: float, size_max: float, refine_distance: float,
                        extent: float, longest: float | None = None) -> int:
    """gmsh Distance + Threshold field: size_min within size_min/2 of the facet entities (curves in 2D,
    surfaces in 3D), growing linearly to size_max over refine_distance (threshold_size). Returns the
    field tag. longest: the longest curve's length [m] (default: asked of OCC)."""
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "FacesList" if dim == 3 else "EdgesList", list(entities))
    # Sampling of the entities for the distance: a few points per refined element.
    samples = int(min(400 if dim == 2 else 120, max(20, math.ceil(2.0 * extent / size_min))))
    if dim == 2 and len(entities):
        # The count is per curve: when joints cut the opening into hundreds of short arcs, the
        # count that suits a whole curve puts a point every 0.4 mm and makes the distance queries
        # most of the 1D meshing time (4.4 of 5.5 s CPU on the continuum bench's discrete tunnel,
        # 316 arcs). Four points per refined element on the longest curve are enough (the same
        # mesh there to 5 µm).
        if longest is None:
            longest = max(gmsh.model.occ.getMass(1, e) for e in entities)
        samples = min(samples, max(20, math.ceil(4.0 * longest / size_min)))
    field.setNumber(dist, "NumPointsPerCurve", samples)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", size_min)
    field.setNumber(thr, "SizeMax", size_max)
    dist_min, dist_max = threshold_distances(size_min, refine_distance)
    field.setNumber(thr, "DistMin", dist_min)
    field.setNumber(thr, "DistMax", dist_max)
    return thr


def _one_element_curves(gmsh, lines, smallest: float, size: float | None = None, boxes=()) -> int:
    """Give the straight curves `lines` (2D) that gmsh would mesh as one element that element up
    front, as a transfinite count of 2 nodes: those shorter than `smallest`, the smallest mesh size
    anywhere, and those shorter than `size` inside one of `boxes` ((x0, y0, x1, y1)), where the
    mesh size is `size` everywhere. gmsh meshes a curve in N = max(2, int(L / h + 1.99)) nodes (h the
    size along it; Mesh.MinimumLineNodes = 2), and finds L / h by integrating the size field over
    at least 64 intervals, a transfinite count by integrating the curve's speed only. The
    continuum bench's discrete tunnel: 16k of its 22k joint pieces, mesh generation 2.3 -> 1.4 s
    for 0.2 s of queries (bench/results/tunnel_profile.md), the same mesh node for node. Returns
    the number of curves so set."""
    try:
        if gmsh.option.getNumber("Mesh.MinimumLineNodes") > 2:
            return 0
    except Exception:  # a gmsh without the option: lines get at least one element
        pass
    factor = 0.99 * gmsh.option.getNumber("Mesh.MeshSizeFactor")  # 1 % from the rounding
    inside = set()
    for x0, y0, x1, y1 in boxes:
        inside.update(int(t) for _, t in gmsh.model.getEntitiesInBoundingBox(x0, y0, -1.0, x1, y1, 1.0, 1))
    count = 0
    for c in sorted(int(t) for t in lines):
        length = gmsh.model.occ.getMass(1, c)
        if length < factor * smallest or (c in inside and length < factor * size):
            gmsh.model.mesh.setTransfiniteCurve(c, 2)
            count += 1
    return count


def _generate(gmsh, dim: int, pieces, groups: dict, boundary_tags: dict, names: dict, *,
              one_block: bool = False, dangling: str = "", blocks_are_volumes: bool = True) -> JointedMesh:
    """Mesh the model (linear simplices), then split it by block and pair the joint facets.

    Blocks: every volume (surface in 2D) of the model is a block, ``block_<k>`` with k = 1, 2, ... in
    order of the centre of mass (vertical coordinate first, then y, then x; _block_labels), or
    one_block: the whole model is block 1; blocks_are_volumes=False: the model is one surface with
    the joints embedded (tunnel._build_planar), its blocks exist on the mesh only. pieces: joint
    entities per joint (tags JOINT_TAG_OFFSET + i, names in names["joints"]); groups: {boundary name: entities}, tagged
    boundary_tags[name]. A joint facet without a different block on each side raises ValueError
    naming the joint, followed by `dangling` (what to do).

    The cells and the facets come from one gmsh call each, not one per entity: the continuum bench's
    discrete tunnel has 33k entities (11k blocks, 22k joint pieces), and one call per entity, with
    the centres of mass the blocks were numbered by and the adjacencies the joints were checked
    with, took 1.0 s of its 10.1 s (0.2 s now). The blocks are found on the mesh instead
    (_block_labels), the facets' entities from the order gmsh lists them in (_facet_entities), and
    a joint that does not separate two blocks from its facets' cells.
    """
    fd = dim - 1
    for name in groups:
        names["boundaries"][boundary_tags[name]] = name
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.model.mesh.generate(dim)
    gmsh.model.mesh.renumberNodes()

    tags, coords, _ = gmsh.model.mesh.getNodes()
    n_nodes = tags.size
    points = np.empty((n_nodes, 3))
    points[tags.astype(np.int64) - 1] = coords.reshape(-1, 3)
    points = points[:, :dim]
    cell_etype, cell_type = _GMSH_CELL[dim]
    _check_element_types(gmsh, dim, cell_etype)
    _check_element_types(gmsh, fd, _GMSH_FACET[dim])
    cells = _elements(gmsh, dim, -1, cell_etype)                 # every volume's, volume by volume
    facet_tags, facets = _elements(gmsh, fd, -1, _GMSH_FACET[dim], with_tags=True)
    facet_cells, joined = _adjacency(cells, facets, n_nodes)

    if one_block:
        blocks = np.ones(cells.shape[0], dtype=np.int32)
    else:
        blocks = _block_labels(cells, points, joined)
        volumes = len(gmsh.model.getEntities(dim))
        if blocks_are_volumes and int(blocks.max()) != volumes:
            raise RuntimeError(f"internal: the mesh splits into {int(blocks.max())} blocks, the model has "
                               f"{volumes} volumes")
    for k in range(1, int(blocks.max()) + 1):
        names["blocks"][k] = f"block_{k}"

    # The joint and the boundary of every facet element, through its entity (-1: none).
    entity = _facet_entities(gmsh, fd, facets, facet_tags, n_nodes)
    listed = [(boundary_tags[name], int(f)) for name, ents in groups.items() for f in ents]
    n_entities = 1 + max([int(entity.max(initial=0))] + [f for _, f in listed] + [int(p) for ps in pieces for p in ps])
    joint_of_entity = np.full(n_entities, -1, dtype=np.int64)
    for i, ps in enumerate(pieces):
        joint_of_entity[np.asarray(ps, dtype=np.int64)] = i
    joint_of = joint_of_entity[entity]
    on_joint = np.flatnonzero(joint_of >= 0)
    sides = np.where(facet_cells[on_joint] >= 0, blocks[np.maximum(facet_cells[on_joint], 0)], -1)
    bad = (sides[:, 0] < 0) | (sides[:, 1] < 0) | (sides[:, 0] == sides[:, 1])
    if bad.any():
        name = names["joints"][JOINT_TAG_OFFSET + int(joint_of[on_joint[np.argmax(bad)]])]
        raise ValueError(f"joint {name!r} does not separate two blocks everywhere: {dangling}")
    jorder = on_joint[np.argsort(joint_of[on_joint], kind="stable")]
    # Boundary facets group by group, entity by entity, in the order of `groups`.
    rank_of_entity = np.full(n_entities, -1, dtype=np.int64)
    rank_of_entity[np.array([f for _, f in listed], dtype=np.int64)] = np.arange(len(listed))
    rank = rank_of_entity[entity]
    border = np.flatnonzero(rank >= 0)
    border = border[np.argsort(rank[border], kind="stable")]
    border_tags = np.array([t for t, _ in listed], dtype=np.int32)[rank[border]]

    corder = np.argsort(blocks, kind="stable")  # cells block by block, as a per-block extraction gives
    return build_jointed_mesh(points, cells[corder], cell_type, blocks[corder], facets[jorder],
                              (JOINT_TAG_OFFSET + joint_of[jorder]).astype(np.int32), facets[border], border_tags,
                              names)


def _adjacency(elements: np.ndarray, separators: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Simplices (m, k) of one dimension and separators (s, k-1), elements of the dimension below:
    ((s, 2) the elements on either side of each separator, -1 where none; (p, 2) the pairs of
    elements that share a face carrying no separator)."""
    k = elements.shape[1]
    faces = np.sort(cell_facets(elements).reshape(-1, k - 1), axis=1)
    keys, skeys = common_facet_keys([faces, np.sort(separators, axis=1)], n_nodes)
    srt = np.argsort(keys, kind="stable")
    ks = keys[srt]
    same = np.flatnonzero(ks[1:] == ks[:-1])
    pairs = np.stack([srt[same], srt[same + 1]], axis=1) // k   # elements sharing a face
    # The elements of each separator: its first and (an inner face) second occurrence among the faces.
    pos = np.searchsorted(ks, skeys)
    first = (pos < ks.size) & (ks[np.minimum(pos, ks.size - 1)] == skeys)
    second = first & (pos + 1 < ks.size) & (ks[np.minimum(pos + 1, ks.size - 1)] == skeys)
    sides = np.full((skeys.size, 2), -1, dtype=np.int64)
    sides[first, 0] = srt[pos[first]] // k
    sides[second, 1] = srt[pos[second] + 1] // k
    return sides, pairs[~np.isin(ks[same], skeys)]


def _components(pairs: np.ndarray, count: int) -> np.ndarray:
    """Label (0, 1, ...) of each of `count` items joined by `pairs` (p, 2) into connected sets,
    numbered in order of their first item."""
    graph = sp.coo_matrix((np.ones(pairs.shape[0]), (pairs[:, 0], pairs[:, 1])), shape=(count, count))
    n, label = connected_components(graph, directed=False)
    first = np.full(n, count, dtype=np.int64)
    np.minimum.at(first, label, np.arange(count))
    rank = np.empty(n, dtype=np.int64)
    rank[np.argsort(first)] = np.arange(n)
    return rank[label]


def _block_labels(cells: np.ndarray, points: np.ndarray, joined: np.ndarray) -> np.ndarray:
    """Block tag (1, 2, ...) of every cell: the connected sets of cells through the facets of
    `joined` (the model's volumes: cells are joined across every facet but those on a curve in
    2D, a surface in 3D), numbered by centre of mass: vertical coordinate first, then y, then x,
    each rounded to 1e-9 of the model's extent, so that the blocks of a layer are numbered along
    it."""
    nc, dim = cells.shape[0], points.shape[1]
    label = _components(joined, nc)
    count = int(label.max()) + 1
    x = points[cells]
    d = x[:, 1:] - x[:, :1]
    measure = np.abs(d[:, 0, 0] * d[:, 1, 1] - d[:, 0, 1] * d[:, 1, 0]) if dim == 2 else \
        np.abs(np.einsum("ij,ij->i", d[:, 0], np.cross(d[:, 1], d[:, 2])))
    mass = np.bincount(label, measure, minlength=count)
    centre = np.stack([np.bincount(label, measure * x[:, :, k].mean(axis=1), minlength=count)
                       for k in range(dim)], axis=1) / mass[:, None]
    rounded = np.round(centre / float(np.ptp(points, axis=0).max()), 9)
    rank = np.empty(count, dtype=np.int32)
    rank[np.lexsort(rounded.T)] = np.arange(1, count + 1, dtype=np.int32)  # the last key sorts first
    return rank[label]


def _facet_entities(gmsh, fd: int, facets: np.ndarray, facet_tags: np.ndarray, n_nodes: int) -> np.ndarray:
    """The entity (curve in 2D, surface in 3D) of each facet element of the one-call extraction.

    gmsh lists the elements of all entities entity by entity, in the order of getEntities: so the
    facets of one entity, a connected set through the faces (nodes in 2D, edges in 3D) that carry
    no lower-dimensional element, are one run of the list, and the k-th run is the k-th entity.
    Checked: as many runs as entities, each set one run, and the first, middle and last entities'
    own elements those of their runs. Should gmsh list them otherwise, every entity is asked for
    its elements (one call each, _facet_entities_one_by_one) instead."""
    entities = np.array([t for _, t in gmsh.model.getEntities(fd)], dtype=np.int64)
    etype = _GMSH_FACET[fd + 1]
    if fd == 1:
        separators = _elements(gmsh, 0, -1, _GMSH_POINT)
    else:
        separators = _elements(gmsh, 1, -1, _GMSH_FACET[2])
    run = _components(_adjacency(facets, separators, n_nodes)[1], facets.shape[0])
    step = np.diff(run)
    if run.size and run[-1] + 1 == entities.size and np.all((step == 0) | (step == 1)):
        start = np.flatnonzero(np.r_[True, step != 0])
        end = np.r_[start[1:], run.size]
        if all(np.array_equal(facet_tags[start[k]:end[k]], gmsh.model.mesh.getElementsByType(etype, entities[k])[0])
               for k in sorted({0, entities.size // 2, entities.size - 1})):
            return entities[run]
    log.warning("gmsh did not list the %dD elements entity by entity: reading them entity by entity "
                "(one call each, slower)", fd)
    return _facet_entities_one_by_one(gmsh, fd, entities, facet_tags)


def _facet_entities_one_by_one(gmsh, fd: int, entities: np.ndarray, facet_tags: np.ndarray) -> np.ndarray:
    """The entity of each facet element (tags facet_tags), asking every entity for its elements."""
    order = np.argsort(facet_tags)
    entity = np.full(facet_tags.size, -1, dtype=np.int64)
    for e in entities:
        tags = gmsh.model.mesh.getElementsByType(_GMSH_FACET[fd + 1], int(e))[0]
        entity[order[np.searchsorted(facet_tags[order], tags)]] = e
    return entity


def _elements(gmsh, dim: int, tag: int, etype: int, with_tags: bool = False):
    """0-based node ids (m, nodes per element) of the elements of type etype on entity (dim, tag),
    or on every dimension-dim entity (tag -1), and with_tags: their element tags first. By type:
    half the cost of getElements; _check_element_types makes sure no other type is there."""
    tags, nodes = gmsh.model.mesh.getElementsByType(etype, tag)
    nodes = np.asarray(nodes, dtype=np.int64).reshape(-1, dim + 1) - 1
    return (np.asarray(tags, dtype=np.int64), nodes) if with_tags else nodes


def _check_element_types(gmsh, dim: int, etype: int) -> None:
    """The mesh's elements of dimension dim are all of type etype (linear simplices)."""
    types = [int(t) for t in gmsh.model.mesh.getElementTypes(dim)]
    if types not in ([], [etype]):
        raise RuntimeError(f"internal: the {dim}D elements are of types {types}, expected {etype}")
