# SPDX-License-Identifier: MIT
"""A JointedMesh from the user's own gmsh model (or a .msh file), marked by physical groups.

The user builds any geometry in gmsh (OCC ``fragment`` makes the blocks and joints conforming),
meshes it with linear simplices, and names physical groups:
- blocks: dimension-d groups (d = 2 or 3, the model's dimension), one or more volumes each;
- joints: dimension-(d-1) groups of surfaces (3D) or curves (2D) lying between two blocks;
- boundaries: dimension-(d-1) groups on the outer surface (supports, loads).
rockjoint reads the mesh of the groups, splits the nodes along the joints
(node_splitting.build_jointed_mesh) and returns the JointedMesh; ``rockjoint.fem.distribute``
then gives the DOLFINx mesh, the block and boundary tags and the joint pairs, serially or over MPI.

Tags are the physical tags of the groups: the minus side of a joint is the block with the lower
tag, and the pair normal points from it into the other block. After splitting, the two faces of
every joint are exterior facets of the mesh: a bare ``ds`` integrates over them too, so surface
loads must use the boundary tags (``ds(tag)`` with ``subdomain_data=dmesh.boundaries``).

Errors name the group and say what to do: a missing group name (the available ones listed), no
block, a joint that does not lie between two blocks, an interface between two blocks that is not
a joint, a named boundary inside the model, an unmeshed model, second-order or non-simplex elements.
"""
from __future__ import annotations

import os
from typing import Sequence

import numpy as np

from .builders import _ensure_gmsh
from .jointed_mesh import JointedMesh
from .node_splitting import build_jointed_mesh

_SIMPLEX = {2: 2, 3: 4}            # dim -> gmsh type of the linear simplex (3-node triangle, 4-node tet)
_FACET_SIMPLEX = {1: 1, 2: 2}      # facet dim -> gmsh type (2-node line, 3-node triangle)
_CELL_TYPE = {2: "triangle", 3: "tetrahedron"}


def from_gmsh_model(joints: Sequence[str], blocks: Sequence[str] | None = None,
                    boundaries: Sequence[str] | None = None, *, comm=None) -> JointedMesh | None:
    """Read the current gmsh model (already meshed) into a JointedMesh split along the joints.

    :joints: names of the joint groups (dimension d-1); [] for an intact model.
    :blocks: names of the block groups (dimension d); default: every dimension-d group.
    :boundaries: names of the boundary groups (dimension d-1); default: every dimension-(d-1)
        group that is not a joint.
    :comm: an mpi4py communicator; ranks other than 0 return None without touching gmsh (build the
        model on rank 0 only, as with dolfinx.io.gmsh.model_to_mesh).

    Raises ValueError naming the offending group or entity (see the module docstring).
    """
    if comm is not None and comm.rank != 0:
        return None
    import gmsh  # heavy, and only rank 0 reads the model: imported when used
    return _read(gmsh, joints, blocks, boundaries)


def from_msh_file(path: str | os.PathLike, joints: Sequence[str], blocks: Sequence[str] | None = None,
                  boundaries: Sequence[str] | None = None, *, comm=None) -> JointedMesh | None:
    """As from_gmsh_model, from a gmsh .msh file (physical names and entities included, e.g.
    written by gmsh.write after meshing). The current gmsh model, if any, is left as it was."""
    if comm is not None and comm.rank != 0:
        return None
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise ValueError(f"from_msh_file: no file {path!r}")
    import gmsh  # heavy, and only rank 0 reads the file: imported when used
    _ensure_gmsh(gmsh)
    previous = gmsh.model.getCurrent() if gmsh.model.list() else None
    gmsh.model.add("rockjoint_msh_file")
    try:
        gmsh.merge(path)
        return _read(gmsh, joints, blocks, boundaries)
    finally:
        gmsh.model.remove()
        if previous is not None:
            gmsh.model.setCurrent(previous)


def _groups(gmsh, dim: int) -> dict:
    """{name: physical tag} of the dimension-dim groups (unnamed ones as 'physical_<dim>_<tag>')."""
    out = {}
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        name = gmsh.model.getPhysicalName(d, tag) or f"physical_{d}_{tag}"
        if name in out:
            raise ValueError(f"two dimension-{dim} physical groups are named {name!r} (tags {out[name]} "
                             f"and {tag}); give each group its own name")
        out[name] = int(tag)
    return out


def _pick(names, available: dict, other: dict, kind: str, dim: int, other_dim: int) -> dict:
    """{name: tag} of the requested groups, with an error for each unknown name."""
    if isinstance(names, str):
        raise ValueError(f"{kind}: give a list of group names, got the string {names!r}")
    out = {}
    for name in names:
        if name in available:
            out[name] = available[name]
            continue
        hint = f"; {name!r} is a dimension-{other_dim} group" if name in other else ""
        raise ValueError(f"{kind}: no dimension-{dim} physical group named {name!r}{hint}; "
                         f"available: {sorted(available)}")
    return out


def _read(gmsh, joints, blocks, boundaries) -> JointedMesh:
    try:
        dim = gmsh.model.getDimension()
    except Exception as err:  # gmsh not initialised or no model
        raise ValueError(f"from_gmsh_model: no gmsh model to read ({err}); build and mesh one first") from err
    if dim not in (2, 3):
        raise ValueError(f"from_gmsh_model: the model has dimension {dim}; rockjoint meshes are 2D or 3D "
                         "(blocks are surfaces in 2D, volumes in 3D)")
    fd = dim - 1
    cell_groups, facet_groups = _groups(gmsh, dim), _groups(gmsh, fd)
    if blocks is None:
        blocks = list(cell_groups)
    if not len(blocks):
        raise ValueError(f"from_gmsh_model: no block: add dimension-{dim} physical groups for the blocks "
                         f"(gmsh.model.addPhysicalGroup({dim}, [entities]) and setPhysicalName)")
    block_tags = _pick(blocks, cell_groups, facet_groups, "blocks", dim, fd)
    joint_tags = _pick(joints, facet_groups, cell_groups, "joints", fd, dim)
    if boundaries is None:
        boundaries = [n for n in facet_groups if n not in joint_tags]
    boundary_tags = _pick(boundaries, facet_groups, cell_groups, "boundaries", fd, dim)
    both = set(joint_tags) & set(boundary_tags)
    if both:
        raise ValueError(f"groups {sorted(both)} are listed as joints and as boundaries; a group is one or the other")

    # Entities of every group, and the block of every volume (surface in 2D).
    block_of = {}
    for name, tag in block_tags.items():
        for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            if int(e) in block_of:
                raise ValueError(f"entity ({dim}, {e}) is in blocks {block_of[int(e)]!r} and {name!r}; "
                                 "a volume belongs to one block")
            block_of[int(e)] = name
    orphans = [int(t) for _, t in gmsh.model.getEntities(dim) if int(t) not in block_of]
    if orphans:
        raise ValueError(f"entities {[(dim, t) for t in orphans]} belong to no block group: add them to a block "
                         f"group (blocks: {sorted(block_tags)}) or remove them from the model")
    facet_owner = {}
    for kind, groups in (("joint", joint_tags), ("boundary", boundary_tags)):
        for name, tag in groups.items():
            for e in gmsh.model.getEntitiesForPhysicalGroup(fd, tag):
                if int(e) in facet_owner:
                    raise ValueError(f"entity ({fd}, {e}) is in groups {facet_owner[int(e)][1]!r} and {name!r}")
                facet_owner[int(e)] = (kind, name)

    # Topology checks on the gmsh entities: joints between two different blocks, every interface
    # between different blocks a joint, boundaries on the outer surface.
    for _, f in gmsh.model.getEntities(fd):
        f = int(f)
        up = [int(v) for v in gmsh.model.getAdjacencies(fd, f)[0] if int(v) in block_of]
        kind, name = facet_owner.get(f, (None, None))
        sides = sorted({block_of[v] for v in up})
        if kind == "joint":
            if len(up) != 2:
                raise ValueError(f"joint {name!r}: entity ({fd}, {f}) bounds {len(up)} block volume(s), not 2: "
                                 "a joint must lie between two blocks (not end inside a block or lie on the "
                                 "outer boundary); cut the blocks with it (gmsh.model.occ.fragment) so that it "
                                 "separates them")
            if len(sides) == 1:
                raise ValueError(f"joint {name!r}: entity ({fd}, {f}) lies between two volumes of the same block "
                                 f"{sides[0]!r}; a joint separates two different blocks: put the volumes on "
                                 "either side in different block groups")
        elif kind == "boundary":
            if len(up) != 1:
                raise ValueError(f"boundary {name!r}: entity ({fd}, {f}) bounds {len(up)} block volume(s); a named "
                                 "boundary must lie on the outer surface of the model")
        elif len(sides) == 2:
            raise ValueError(f"the interface entity ({fd}, {f}) between blocks {sides[0]!r} and {sides[1]!r} is in no "
                             f"joint group: add it to a joint group (dimension-{fd} physical group listed in "
                             "`joints`), or put both volumes in one block group if the rock is intact there")

    # Mesh: nodes (any tags) and linear simplices only.
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    if node_tags.size == 0:
        raise ValueError(f"from_gmsh_model: the model has no mesh: call gmsh.model.mesh.generate({dim}) first")
    node_tags = np.asarray(node_tags, dtype=np.int64)
    row = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
    row[node_tags] = np.arange(node_tags.size)
    points = np.asarray(coords, dtype=np.float64).reshape(-1, 3)
    if dim == 2:
        extent = np.ptp(points[:, :2], axis=0).max() if points.size else 1.0
        if np.abs(points[:, 2]).max() > 1e-9 * max(extent, 1e-300):
            raise ValueError("from_gmsh_model: a 2D model must lie in the z = 0 plane (largest |z| = "
                             f"{np.abs(points[:, 2]).max():.3e} m)")
    points = points[:, :dim]

    block_number = {name: tag for name, tag in block_tags.items()}
    cells, cell_blocks = [], []
    for e, name in sorted(block_of.items()):
        c = _elements(gmsh, dim, e, _SIMPLEX[dim], row, f"block {name!r}")
        cells.append(c)
        cell_blocks.append(np.full(c.shape[0], block_number[name], dtype=np.int32))
    jel, jtag, bel, btag = [], [], [], []
    for f, (kind, name) in sorted(facet_owner.items()):
        tag = (joint_tags if kind == "joint" else boundary_tags)[name]
        e = _elements(gmsh, fd, f, _FACET_SIMPLEX[fd], row, f"{kind} {name!r}")
        (jel if kind == "joint" else bel).append(e)
        (jtag if kind == "joint" else btag).append(np.full(e.shape[0], tag, dtype=np.int32))
    cells = np.concatenate(cells)
    if cells.shape[0] == 0:
        raise ValueError(f"from_gmsh_model: the blocks hold no elements: call gmsh.model.mesh.generate({dim}) first")
    empty_f, empty_t = np.empty((0, dim), dtype=np.int64), np.empty(0, dtype=np.int32)
    names = {"blocks": {t: n for n, t in block_tags.items()},
             "joints": {t: n for n, t in joint_tags.items()},
             "boundaries": {t: n for n, t in boundary_tags.items()}}
    return build_jointed_mesh(points, cells, _CELL_TYPE[dim], np.concatenate(cell_blocks),
                              np.concatenate(jel) if jel else empty_f, np.concatenate(jtag) if jtag else empty_t,
                              np.concatenate(bel) if bel else empty_f, np.concatenate(btag) if btag else empty_t,
                              names)


def _elements(gmsh, dim: int, entity: int, expected: int, row: np.ndarray, what: str) -> np.ndarray:
    """Rows (0-based) of the nodes of the elements of entity (dim, entity); only `expected` allowed."""
    types, _, nodes = gmsh.model.mesh.getElements(dim, entity)
    n_expected = dim + 1
    out = []
    for t, nd in zip(types, nodes):
        t = int(t)
        if t == expected:
            out.append(row[np.asarray(nd, dtype=np.int64)].reshape(-1, n_expected))
            continue
        name, edim, order, _, _, _ = gmsh.model.mesh.getElementProperties(t)
        if order > 1:
            raise ValueError(f"{what}: entity ({dim}, {entity}) has second-order (or higher) elements "
                             f"({name}); rockjoint reads linear meshes (set gmsh option Mesh.ElementOrder = 1; "
                             "use a P2 displacement space on the linear mesh instead)")
        raise ValueError(f"{what}: entity ({dim}, {entity}) has {name} elements; rockjoint needs linear "
                         f"{'triangles' if dim == 2 else 'tetrahedra' if dim == 3 else 'simplices'} "
                         "(no recombination into quadrangles/hexahedra, no prisms or pyramids)")
    if not out:
        return np.empty((0, n_expected), dtype=np.int64)
    return np.concatenate(out)
