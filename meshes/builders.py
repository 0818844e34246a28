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
import math
from typing import Iterable, Sequence

import numpy as np

from .joint_geometry import Joint, joint_trace, _positive
from .jointed_mesh import JointedMesh
from .node_splitting import build_jointed_mesh

JOINT_TAG_OFFSET = 100
BOUNDARY_TAGS = {"bottom": 1, "top": 2, "left": 3, "right": 4, "front": 5, "back": 6}
_GMSH_CELL = {2: (2, "triangle"), 3: (4, "tetrahedron")}  # dim -> (gmsh element type, cell type)
_GMSH_FACET = {2: 1, 3: 2}  # dim -> gmsh facet element type (line, triangle)
_ALGORITHMS_3D = {"delaunay": 1, "hxt": 10}  # gmsh Mesh.Algorithm3D codes


def column(width: float, height: float, joint_heights: Sequence[float], dim: int = 2, mesh_size: float = None,
           joint_mesh_size: float | None = None, refine_distance: float | None = None, comm=None, *,
           algorithm_3d: str = "delaunay") -> JointedMesh | None:
    """A 2D rectangle width x height or a 3D box width x width x height cut by horizontal joints.

    joint_heights: heights [m] of the joints, strictly inside (0, height), distinct. Joint i (1-based,
    bottom first) is named ``joint_<i>``; blocks ``block_1`` (bottom) ... ``block_<N+1>`` (top).
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
    joints = [Joint(centre + (h,), 0.0, 90.0, f"joint_{i + 1}") for i, h in enumerate(hs)]
    return jointed_block(size, joints, dim, mesh_size, joint_mesh_size, refine_distance, comm=comm,
                         algorithm_3d=algorithm_3d)


def jointed_block(size: Sequence[float], joints: Iterable, dim: int | None = None, mesh_size: float = None,
                  joint_mesh_size: float | None = None, refine_distance: float | None = None, comm=None, *,
                  algorithm_3d: str = "delaunay") -> JointedMesh | None:
    """A rectangle/box [0, size] cut by planar joints, meshed, split by block, joint facets paired.

    joints: Joint objects (see joint_geometry.Joint), tuples (point, dip[, dip_direction]) or lists of
        them (e.g. from joint_set).
    mesh_size: target element size [m] away from the joints.
    joint_mesh_size: element size [m] on the joints (gmsh Distance + Threshold fields); None = uniform.
    refine_distance: distance [m] over which the size grows from joint_mesh_size to mesh_size
        (default 2 mesh_size).
    comm: an mpi4py communicator; ranks != 0 return None.
    algorithm_3d: "delaunay" (gmsh's default 3D algorithm; the same mesh on every run) or "hxt"
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
            "Mesh.Algorithm3D")


@contextlib.contextmanager
def _gmsh_model(name: str):
    """gmsh (initialised) with a new model `name`, quiet; afterwards the model is removed and the
    global options a builder sets (_OPTIONS) are restored, whatever happened."""
    import gmsh  # heavy, and only rank 0 meshes: imported when a mesh is built
    _ensure_gmsh(gmsh)
    saved = {o: gmsh.option.getNumber(o) for o in _OPTIONS}  # gmsh options are global: restore them
    gmsh.option.setNumber("General.Terminal", 0)
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
                         tuple(j.bounded_by)))
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
            up = set(gmsh.model.getAdjacencies(fd, p)[0].tolist())
            if len(up) != 2:
                raise ValueError(f"joint {j.name!r} does not separate two blocks everywhere: part of it ends "
                                 "inside a block (dangling tip) — joints must end on other joints or on the "
                                 "block boundary (use bounded_by with joints that reach it)")

    ordered, names = _block_and_joint_groups(gmsh, dim, volumes, joints, size.max())

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
    return _generate(gmsh, dim, ordered, pieces, groups, BOUNDARY_TAGS, names)


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


def _block_and_joint_groups(gmsh, dim: int, volumes, joints, extent: float):
    """The groups of the blocks (``block_<k>``, ordered by centre of mass, vertical coordinate
    first) and of the joints (tags JOINT_TAG_OFFSET + i). Returns (ordered volumes, names)."""
    occ = gmsh.model.occ
    com = {v: occ.getCenterOfMass(dim, v) for v in volumes}
    ordered = sorted(volumes, key=lambda v: tuple(round(c / extent, 9) for c in
                                                  (com[v][dim - 1],) + tuple(com[v][:dim - 1][::-1])))
    names = {"blocks": {}, "joints": {}, "boundaries": {}}
    # The groups live in `names` only: the gmsh model is removed after meshing, and gmsh physical
    # groups (one addPhysicalGroup + setPhysicalName per block) cost 1.2 s of CPU time for the
    # 11k blocks of the continuum bench's discrete tunnel, for nothing read afterwards.
    for k, v in enumerate(ordered, start=1):
        names["blocks"][k] = f"block_{k}"
    for i, j in enumerate(joints):
        names["joints"][JOINT_TAG_OFFSET + i] = j.name
    return ordered, names


def _uniform_size(gmsh, mesh_size: float) -> None:
    for option, value in (("Mesh.MeshSizeExtendFromBoundary", 0), ("Mesh.MeshSizeFromPoints", 0),
                          ("Mesh.MeshSizeFromCurvature", 0), ("Mesh.MeshSizeMin", mesh_size),
                          ("Mesh.MeshSizeMax", mesh_size)):
        gmsh.option.setNumber(option, value)


def _graded_size(gmsh, mesh_size: float) -> None:
    """Sizes from the background field, capped at mesh_size."""
    _uniform_size(gmsh, mesh_size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)


def _distance_threshold(gmsh, dim: int, entities, size_min: float, size_max: float, refine_distance: float,
                        extent: float) -> int:
    """gmsh Distance + Threshold field: size_min within size_min/2 of the facet entities (curves in 2D,
    surfaces in 3D), growing linearly to size_max over refine_distance. Returns the field tag."""
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
        longest = max(gmsh.model.occ.getMass(1, e) for e in entities)
        samples = min(samples, max(20, math.ceil(4.0 * longest / size_min)))
    field.setNumber(dist, "NumPointsPerCurve", samples)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", size_min)
    field.setNumber(thr, "SizeMax", size_max)
    field.setNumber(thr, "DistMin", 0.5 * size_min)
    field.setNumber(thr, "DistMax", 0.5 * size_min + refine_distance)
    return thr


def _generate(gmsh, dim: int, ordered, pieces, groups: dict, boundary_tags: dict, names: dict) -> JointedMesh:
    """Mesh the model (linear simplices), then split it by block and pair the joint facets.

    ordered: block volumes (block k = ordered[k-1], a tag or a list of tags); pieces: joint entities per joint (tags
    JOINT_TAG_OFFSET + i); groups: {boundary name: entities}, tagged boundary_tags[name].
    """
    fd = dim - 1
    for name in groups:
        names["boundaries"][boundary_tags[name]] = name
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.model.mesh.generate(dim)
    gmsh.model.mesh.renumberNodes()

    tags, coords, _ = gmsh.model.mesh.getNodes()
    points = np.empty((tags.size, 3))
    points[tags.astype(np.int64) - 1] = coords.reshape(-1, 3)
    points = points[:, :dim]
    cell_etype, cell_type = _GMSH_CELL[dim]
    _check_element_types(gmsh, dim, cell_etype)
    _check_element_types(gmsh, fd, _GMSH_FACET[dim])
    cells, blocks = [], []
    for k, entities in enumerate(ordered, start=1):
        for v in np.atleast_1d(entities):
            c = _elements(gmsh, dim, int(v), cell_etype)
            cells.append(c)
            blocks.append(np.full(c.shape[0], k, dtype=np.int32))
    jel, jtag = [], []
    for i, ps in enumerate(pieces):
        for p in ps:
            e = _elements(gmsh, fd, p, _GMSH_FACET[dim])
            jel.append(e)
            jtag.append(np.full(e.shape[0], JOINT_TAG_OFFSET + i, dtype=np.int32))
    bel, btag = [], []
    for name, ents in groups.items():
        for f in ents:
            e = _elements(gmsh, fd, f, _GMSH_FACET[dim])
            bel.append(e)
            btag.append(np.full(e.shape[0], boundary_tags[name], dtype=np.int32))
    empty = np.empty((0, dim), dtype=np.int64)
    return build_jointed_mesh(points, np.concatenate(cells), cell_type, np.concatenate(blocks),
                              np.concatenate(jel) if jel else empty,
                              np.concatenate(jtag) if jtag else np.empty(0, np.int32),
                              np.concatenate(bel), np.concatenate(btag), names)


def _elements(gmsh, dim: int, tag: int, etype: int) -> np.ndarray:
    """0-based node ids (m, nodes per element) of the elements of type etype on entity (dim, tag).
    By type: half the cost of getElements, which the 33k entities of the continuum bench's discrete
    tunnel call (0.9 s); _check_element_types makes sure no other type is there."""
    nodes = gmsh.model.mesh.getElementsByType(etype, tag)[1]
    return np.asarray(nodes, dtype=np.int64).reshape(-1, dim + 1) - 1


def _check_element_types(gmsh, dim: int, etype: int) -> None:
    """The mesh's elements of dimension dim are all of type etype (linear simplices)."""
    types = [int(t) for t in gmsh.model.mesh.getElementTypes(dim)]
    if types not in ([], [etype]):
        raise RuntimeError(f"internal: the {dim}D elements are of types {types}, expected {etype}")
