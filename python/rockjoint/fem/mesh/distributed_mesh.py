# SPDX-License-Identifier: MIT
"""Distribute a JointedMesh over MPI as a DOLFINx mesh and pair the joint facets on every rank.

Partitioning (docs/fem.md, pitfalls 1-2):

1. owners from DOLFINx's default partitioner run on the *glued* cells (the split mesh has no facet
   adjacency across joints, so partitioning it directly could separate a joint's two sides);
2. the two cells of every joint facet (and chains of them: a cell with several joint facets) are
   forced onto one rank, the owner of the lowest-numbered cell of the chain;
3. ghost ranks from the facet adjacency of the *split* cells (never across the cut: ghosting across
   it segfaults, dolfinx#1991; returning owners only builds a wrong mesh).

So both cells of every pair are owned by the same rank and each pair is assembled there, once.

Pairing uses cell->facet connectivity (not exterior_facet_indices, which returns owned facets only)
and the glue map: two distinct local facets whose vertices have the same original (glued) nodes are
the two sides of one joint facet. The glue of each local node is fetched from rank 0 through the
node's original input index (``geometry.input_global_indices``).
"""
from __future__ import annotations

import os
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

import dolfinx
import dolfinx.cpp as _cpp
from dolfinx.graph import adjacencylist
from dolfinx.io.utils import distribute_entity_data
from dolfinx.mesh import GhostMode, create_mesh, meshtags, meshtags_from_entities

from ..compat import cpp_adjacency_list, create_cell_partitioner, create_serial_mesh, io_gmsh

from ...meshes.jointed_mesh import JointedMesh
from ...meshes.node_splitting import cell_facets, facet_keys

_GMSH_CELL_ID = {"triangle": 2, "tetrahedron": 4}
_ROOT = 0

#: A serial mesh of more blocks than this keeps its cells in the order given (block by block:
#: compat.create_serial_mesh) instead of DOLFINx's Gibbs-Poole-Stockmeyer reordering, which costs
#: a pass over the mesh per block: 2.4 ns per block and cell against 2.6 µs per cell for the rest of
#: create_mesh (the continuum bench's discrete tunnel, 11k blocks, 23k triangles: 0.66 s against
#: 0.06 s), so from 100 blocks on it would cost more than a tenth of the mesh creation. Fewer blocks
#: keep DOLFINx's order: the same factorisations as before, pivot for pivot.
KEEP_CELL_ORDER_BLOCKS = 100

# Reproducible partitions. PT-SCOTCH (DOLFINx's default partitioner) partitions with threads, and
# Debian 13's 7.0.7 then returns a different partition at every launch even with a fixed seed:
# the blocky benchmark on 2 ranks needed 85 to 121 Krylov iterations on one mesh, launch to launch
# (docs/fem.md, pitfall 17). With one thread the partition is the same at every launch. SCOTCH
# reads the variable when it partitions, so setting it here covers every mesh created after
# rockjoint.fem is imported, also the user's own; a value the user set is kept.
os.environ.setdefault("SCOTCH_PTHREAD_NUMBER", "1")


@dataclass
class JointPairs:
    """Joint facet pairs on this rank; each pair is held once, by the owner of its minus cell.

    :minus_cells, plus_cells: (n,) int32 local cell indices (both owned by this rank).
    :minus_local_facets, plus_local_facets: (n,) int32 local facet index within the cell
        (0..nv-1 as DOLFINx numbers them: facet i is opposite vertex i).
    :joint_tags: (n,) int32 joint tag (physical group of the joint).

    Minus side = the block with the lower block tag; the pair normal points from minus into plus.
    Pairs are sorted by (joint tag, minus cell).
    """

    minus_cells: np.ndarray
    minus_local_facets: np.ndarray
    plus_cells: np.ndarray
    plus_local_facets: np.ndarray
    joint_tags: np.ndarray

    def __len__(self) -> int:
        return int(self.minus_cells.size)


@dataclass
class DistributedJointMesh:
    """A distributed split mesh with block tags, named boundaries and local joint pairs.

    mesh: the DOLFINx mesh (split nodes: the two sides of a joint are not connected).
    cell_blocks: cell MeshTags (owned and ghost cells), values = block tags.
    boundaries: facet MeshTags of the named exterior groups, values = boundary tags.
    names: {"blocks": {tag: name}, "joints": {tag: name}, "boundaries": {tag: name}} (every rank).
    pairs: the joint facet pairs assembled on this rank.
    """

    mesh: dolfinx.mesh.Mesh
    cell_blocks: object
    boundaries: object
    names: dict
    pairs: JointPairs

    def boundary(self, name: str) -> np.ndarray:
        """Local facet indices (int32, possibly empty on some ranks) of the boundary group ``name``."""
        if not isinstance(name, str):
            raise ValueError(f"boundary name must be a string, got {name!r}")
        for tag, n in self.names["boundaries"].items():
            if n == name:
                return self.boundaries.indices[self.boundaries.values == tag].astype(np.int32)
        raise KeyError(f"no boundary group named {name!r}; available: {sorted(self.names['boundaries'].values())}")

    def block_tag(self, name: str) -> int:
        """Tag of the block ``name`` (KeyError listing the available blocks)."""
        return _tag(self.names, "blocks", name)

    def joint_tag(self, name: str) -> int:
        """Tag of the joint ``name`` (KeyError listing the available joints)."""
        return _tag(self.names, "joints", name)

    def boundary_tag(self, name: str) -> int:
        """Tag of the boundary ``name`` in ``boundaries`` (KeyError listing the available
        boundaries), e.g. for ``ufl.Measure("ds", subdomain_data=dmesh.boundaries)(tag)``."""
        return _tag(self.names, "boundaries", name)

    def partition_balance(self) -> dict:
        """How the work is shared (collective; the same dict on every rank): per rank the owned
        cells, owned vertices and joint pairs, and the imbalance max/mean of the owned cells
        (1 = perfect). Pairs are assembled by the rank owning their minus cell, so a partition
        that keeps both sides of the joints together may load ranks unevenly."""
        comm = self.mesh.comm
        tdim = self.mesh.topology.dim
        local = (self.mesh.topology.index_map(tdim).size_local,
                 self.mesh.topology.index_map(0).size_local, len(self.pairs))
        cells, vertices, pairs = (list(x) for x in zip(*comm.allgather(local)))
        return {"cells": cells, "vertices": vertices, "pairs": pairs,
                "cell_imbalance": max(cells) / (sum(cells) / len(cells))}

    def cell_owners(self):
        """The owning rank of every input cell, in the JointedMesh's cell order, on rank 0 (None
        elsewhere; collective): `distribute(jm, comm, owners=...)` rebuilds this partition."""
        comm = self.mesh.comm
        topology = self.mesh.topology
        n = topology.index_map(topology.dim).size_local
        mine = np.asarray(topology.original_cell_index[:n], dtype=np.int64)
        gathered = comm.gather(mine, root=_ROOT)
        if comm.rank != _ROOT:
            return None
        owners = np.full(sum(g.size for g in gathered), -1, dtype=np.int64)
        for rank, cells in enumerate(gathered):
            owners[cells] = rank
        return owners


_SINGULAR = {"blocks": "block", "joints": "joint", "boundaries": "boundary"}


def _tag(names: dict, kind: str, name: str) -> int:
    for tag, n in names[kind].items():
        if n == name:
            return int(tag)
    raise KeyError(f"no {_SINGULAR[kind]} named {name!r}; available: {sorted(names[kind].values())}")


def distribute(jointed_mesh: JointedMesh | None, comm, owners=None) -> DistributedJointMesh:
    """Build the distributed mesh. Collective: rank 0 passes the JointedMesh, other ranks None.

    owners: optional, on rank 0: the owning rank of every cell of the JointedMesh (int array of
    length jm.cells.shape[0], values in [0, comm.size)), e.g. `cell_owners` of an earlier
    distribution, to reproduce a partition exactly (across launches, machines, DOLFINx versions);
    default: DOLFINx's partitioner on the glued cells. Chains of paired cells still go with their
    lowest-numbered cell. Raises ValueError on every rank if rank 0 has no JointedMesh or the
    owners do not fit it.
    """
    rank = comm.rank
    _idle_barrier(comm)
    if rank == _ROOT:
        jm = jointed_mesh
        if not isinstance(jm, JointedMesh):
            header = {"error": f"distribute: rank 0 must pass a JointedMesh, got {type(jm).__name__}"}
        elif owners is not None and (error := _owners_error(owners, jm, comm.size)):
            header = {"error": error}
        else:
            header = {"cell_type": jm.cell_type, "gdim": jm.gdim, "names": jm.names,
                      "n_original": int(jm.glue.max()) + 1 if jm.glue.size else 0,
                      "n_pairs": int(jm.joint_tags.size)}
    else:
        jm, header = None, None
    header = comm.bcast(header, root=_ROOT)
    if "error" in header:
        raise ValueError(header["error"])
    cell_type, gdim, names = header["cell_type"], header["gdim"], header["names"]
    domain = io_gmsh.ufl_mesh(_GMSH_CELL_ID[cell_type], gdim, dtype=np.float64)
    dolfinx_cell = _cpp.mesh.to_type(str(domain.ufl_cell()))
    nv = 3 if cell_type == "triangle" else 4
    perm = io_gmsh.cell_perm_array(dolfinx_cell, nv)
    facet_type = _cpp.mesh.cell_entity_type(dolfinx_cell, nv - 2, 0)
    fperm = io_gmsh.cell_perm_array(facet_type, nv - 1)

    if rank == _ROOT:
        cells = jm.cells[:, perm]
        x = jm.points
        partitioner = _JointPartitioner(jm, cells, None if owners is None else np.asarray(owners, np.int64))
    else:
        cells = np.empty((0, nv), dtype=np.int64)
        x = np.empty((0, gdim))
        partitioner = _JointPartitioner(None, cells)
    if comm.size == 1 and len(jm.names["blocks"]) > KEEP_CELL_ORDER_BLOCKS:
        mesh = create_serial_mesh(comm, cells, domain, x)
    else:
        mesh = create_mesh(comm, cells, e=domain, x=x, partitioner=partitioner)
    topology = mesh.topology
    tdim = topology.dim

    # Block tag of every local cell, fetched from rank 0 through the original cell index.
    original_cells = np.asarray(topology.original_cell_index, dtype=np.int64)
    blocks = _fetch(comm, original_cells, jm.cell_blocks if rank == _ROOT else None)
    ncells_local = topology.index_map(tdim).size_local + topology.index_map(tdim).num_ghosts
    cell_blocks = meshtags(mesh, tdim, np.arange(ncells_local, dtype=np.int32), blocks.astype(np.int32))

    # Facet tags: named boundaries and (minus sides of) joints, as dolfinx.io.gmsh.model_to_mesh does.
    topology.create_connectivity(tdim - 1, tdim)
    topology.create_connectivity(tdim, tdim - 1)
    topology.create_connectivity(tdim - 1, 0)
    boundaries = _facet_tags(mesh, jm.boundary_facets[:, fperm] if rank == _ROOT else np.empty((0, nv - 1), np.int64),
                             jm.boundary_tags if rank == _ROOT else np.empty(0, np.int32))
    joint_facets = _facet_tags(mesh, jm.joint_facets_minus[:, fperm] if rank == _ROOT
                               else np.empty((0, nv - 1), np.int64),
                               jm.joint_tags if rank == _ROOT else np.empty(0, np.int32))

    # Glued (original) node of every local vertex, fetched through the node's input index.
    node_glue = _fetch(comm, np.asarray(mesh.geometry.input_global_indices, dtype=np.int64),
                       jm.glue if rank == _ROOT else None)
    c2v = topology.connectivity(tdim, 0).array.reshape(-1, nv)
    x_dofmap = mesh.geometry.dofmaps[0]  # P1: geometry dof i of a cell = vertex i
    vertex_glue = np.empty(topology.index_map(0).size_local + topology.index_map(0).num_ghosts, dtype=np.int64)
    vertex_glue[c2v] = node_glue[x_dofmap]

    pairs, error = _pair_facets(mesh, vertex_glue, blocks, joint_facets, header["n_original"])
    errors = [e for e in comm.allgather(error) if e]  # raise on every rank, never leave one waiting
    if errors:
        raise RuntimeError("; ".join(errors))
    return DistributedJointMesh(mesh=mesh, cell_blocks=cell_blocks, boundaries=boundaries, names=names, pairs=pairs)


def _idle_barrier(comm, interval: float = 0.005) -> None:
    """Barrier that sleeps while rank 0 is still meshing (MPI's busy wait would steal its core)."""
    request = comm.Ibarrier()
    while not request.Test():
        time.sleep(interval)


def _fetch(comm, indices: np.ndarray, values_on_root: np.ndarray | None) -> np.ndarray:
    """values_on_root[indices] for this rank's indices (rank 0 answers every rank)."""
    requests = comm.gather(indices, root=_ROOT)
    replies = [values_on_root[r] for r in requests] if comm.rank == _ROOT else None
    return comm.scatter(replies, root=_ROOT)


def _facet_tags(mesh, facets: np.ndarray, values: np.ndarray):
    """Facet MeshTags from facets given by input node indices (model_to_mesh's route)."""
    tdim = mesh.topology.dim
    local_entities, local_values = distribute_entity_data(mesh, tdim - 1,
                                                          np.ascontiguousarray(facets, dtype=np.int64),
                                                          np.ascontiguousarray(values, dtype=np.int32))
    adj = adjacencylist(np.ascontiguousarray(local_entities, dtype=np.int32).reshape(-1, tdim))
    return meshtags_from_entities(mesh, tdim - 1, adj, np.asarray(local_values, dtype=np.int32))


def _pair_facets(mesh, vertex_glue: np.ndarray, blocks: np.ndarray, joint_facets, n_original: int
                 ) -> tuple[JointPairs, str | None]:
    topology = mesh.topology
    tdim = topology.dim
    nv = tdim + 1
    n_owned_cells = topology.index_map(tdim).size_local
    f2v = topology.connectivity(tdim - 1, 0).array.reshape(-1, tdim)
    c2f = topology.connectivity(tdim, tdim - 1).array.reshape(-1, nv)
    f2c = topology.connectivity(tdim - 1, tdim)
    keys = facet_keys(np.sort(vertex_glue[f2v], axis=1), max(n_original, 1))
    order = np.argsort(keys, kind="stable")
    dup = keys[order][1:] == keys[order][:-1]
    fa, fb = order[:-1][dup], order[1:][dup]  # two local facets with the same original nodes
    # On the split mesh each side of a joint facet belongs to exactly one cell.
    f2c_first = np.asarray(f2c.array)[np.asarray(f2c.offsets)[:-1]]
    ca, cb = f2c_first[fa].astype(np.int64), f2c_first[fb].astype(np.int64)
    swap = blocks[ca] > blocks[cb]
    fm, fp = np.where(swap, fb, fa), np.where(swap, fa, fb)
    cm, cp = np.where(swap, cb, ca), np.where(swap, ca, cb)
    keep = cm < n_owned_cells
    fm, fp, cm, cp = fm[keep], fp[keep], cm[keep], cp[keep]

    tag_of = np.full(f2v.shape[0], -1, dtype=np.int64)
    tag_of[joint_facets.indices] = joint_facets.values
    tags = tag_of[fm]
    owned_joint = joint_facets.indices[np.isin(joint_facets.indices,
                                               c2f[:n_owned_cells].ravel())]
    error = None
    if np.any(tags < 0) or np.unique(owned_joint).size != fm.size:
        error = (f"distribute: rank {mesh.comm.rank} found {fm.size} joint pairs for {np.unique(owned_joint).size} "
                 "owned minus-side joint facets; a plus cell is not local (partitioner invariant broken)")
    elif np.any(cp >= n_owned_cells):
        error = f"distribute: rank {mesh.comm.rank}: a plus cell is a ghost; pairs must be owned by one rank"
    local_m = np.argmax(c2f[cm] == fm[:, None], axis=1)
    local_p = np.argmax(c2f[cp] == fp[:, None], axis=1)
    srt = np.lexsort((cm, tags))
    return JointPairs(minus_cells=cm[srt].astype(np.int32), minus_local_facets=local_m[srt].astype(np.int32),
                      plus_cells=cp[srt].astype(np.int32), plus_local_facets=local_p[srt].astype(np.int32),
                      joint_tags=tags[srt].astype(np.int32)), error


class _JointPartitioner:
    """Cell partitioner callable for dolfinx.mesh.create_mesh (see the module docstring).

    DOLFINx calls it as (comm, nparts, cell_types, cells) with one flat int64 array of cell
    vertices per cell type; the ghost mode is the default partitioner's (shared_facet here)."""

    def __init__(self, jm: JointedMesh | None, cells: np.ndarray, owners: np.ndarray | None = None):
        self._jm = jm
        self._cells = cells
        self._owners = owners   # given by the caller (rank 0), or None: DOLFINx's partitioner
        self._default = create_cell_partitioner(GhostMode.shared_facet)

    def __call__(self, comm, nparts, cell_types, cells):
        jm = self._jm
        mine = np.asarray(cells[0], dtype=np.int64)
        if jm is not None:
            nv = jm.cells.shape[1]
            if mine.size != self._cells.size or not np.array_equal(mine.reshape(-1, nv), self._cells):
                raise RuntimeError("distribute: the partitioner did not receive the input cells in input order")
            glued = [np.ascontiguousarray(jm.glue[self._cells], dtype=np.int64).ravel()]
        else:
            glued = cells
        # Every rank takes part in the collective default partitioner unless owners are given
        # (all ranks know which: the header check makes it rank 0's choice, broadcast below).
        given = comm.bcast(self._owners is not None if jm is not None else None, root=_ROOT)
        if given:
            if jm is None:
                return cpp_adjacency_list(np.empty(0, np.int32), np.zeros(1, np.int32))
            return _joint_destinations(jm, self._owners, nparts)
        dest = self._default(comm, nparts, cell_types, glued)
        if jm is None:
            return dest
        offsets = np.asarray(dest.offsets)
        owners = np.asarray(dest.array)[offsets[:-1]].astype(np.int64)
        return _joint_destinations(jm, owners, nparts)


def _owners_error(owners, jm: JointedMesh, size: int) -> str | None:
    """Why `owners` cannot partition jm over `size` ranks, or None."""
    try:
        a = np.asarray(owners)
    except Exception as exc:   # noqa: BLE001 - raised on rank 0 only, it would hang the others: report it
        return f"distribute: owners must be an integer array, got {type(owners).__name__} ({exc})"
    nc = jm.cells.shape[0]
    if a.ndim != 1 or a.shape[0] != nc or not np.issubdtype(a.dtype, np.integer):
        return f"distribute: owners must be an integer array of one rank per cell ({nc}), got shape {a.shape} dtype {a.dtype}"
    if nc and (a.min() < 0 or a.max() >= size):
        return f"distribute: owners must lie in [0, {size}) (the communicator's size), got [{a.min()}, {a.max()}]"
    return None


def _joint_destinations(jm: JointedMesh, owners: np.ndarray, nparts: int):
    nc, nv = jm.cells.shape
    pairs = jm.joint_facet_cells
    graph = sp.coo_matrix((np.ones(pairs.shape[0]), (pairs[:, 0], pairs[:, 1])), shape=(nc, nc))
    _, label = connected_components(graph, directed=False)
    first = np.full(label.max() + 1, nc, dtype=np.int64)
    np.minimum.at(first, label, np.arange(nc))
    owners = owners[first[label]]  # every chain of paired cells goes with its lowest-numbered cell

    # Ghosts: facet neighbours in the split mesh owned elsewhere.
    f = np.sort(cell_facets(jm.cells).reshape(-1, nv - 1), axis=1)
    keys = facet_keys(f, jm.points.shape[0])
    fcell = np.repeat(np.arange(nc, dtype=np.int64), nv)
    order = np.argsort(keys, kind="stable")
    same = keys[order][1:] == keys[order][:-1]
    a, b = fcell[order[:-1][same]], fcell[order[1:][same]]
    cross = owners[a] != owners[b]
    a, b = a[cross], b[cross]
    ghost_cell = np.concatenate([a, b])
    ghost_rank = np.concatenate([owners[b], owners[a]])
    g = np.unique(ghost_cell * nparts + ghost_rank)
    ghost_cell, ghost_rank = g // nparts, g % nparts
    counts = 1 + np.bincount(ghost_cell, minlength=nc)
    offsets = np.zeros(nc + 1, dtype=np.int32)
    np.cumsum(counts, out=offsets[1:])
    data = np.empty(offsets[-1], dtype=np.int32)
    data[offsets[:-1]] = owners
    # ghost ranks after the owner, in the order of np.unique (sorted by cell then rank)
    start = np.searchsorted(ghost_cell, ghost_cell)  # first ghost entry of each cell
    data[offsets[ghost_cell] + 1 + (np.arange(ghost_cell.size) - start)] = ghost_rank
    return cpp_adjacency_list(data, offsets)


def pair_vertex_positions(dmesh: DistributedJointMesh) -> tuple[np.ndarray, np.ndarray]:
    """Matched facet vertices of every local pair, as positions (0..nv-1) within the pair's cells.

    Returns (minus_positions, plus_positions), each (n_pairs, nv-1) int32: entry [k, i] of both arrays is
    the same point of the joint (coincident copies); the minus order is oriented so that its right-hand
    normal (3D: (x1-x0) x (x2-x0); 2D: (t_y, -t_x), t = x1-x0) points from the minus into the plus cell.
    For P1 spaces position p of a cell is its p-th cell dof (P1 dof p sits on vertex p), and for the
    geometry ``mesh.geometry.dofmaps[0][cell, p]``. A convenience on top of JointPairs; optional.
    """
    mesh, p = dmesh.mesh, dmesh.pairs
    tdim = mesh.topology.dim
    nv = tdim + 1
    x = mesh.geometry.x[:, :mesh.geometry.dim]
    dofs = mesh.geometry.dofmaps[0]
    others = np.array([[j for j in range(nv) if j != i] for i in range(nv)], dtype=np.int32)
    pos_m = others[p.minus_local_facets]  # facet i of a simplex: the other vertices
    pos_p = others[p.plus_local_facets]
    xm = x[np.take_along_axis(dofs[p.minus_cells], pos_m, axis=1)]
    xp = x[np.take_along_axis(dofs[p.plus_cells], pos_p, axis=1)]
    # plus vertex matching each minus vertex: the split copies have identical coordinates
    dist = np.linalg.norm(xm[:, :, None, :] - xp[:, None, :, :], axis=3)
    match = np.argmin(dist, axis=2)
    pos_p = np.take_along_axis(pos_p, match, axis=1)
    xp = np.take_along_axis(xp, match[..., None], axis=1)
    # orient: right-hand normal away from the minus cell's opposite vertex
    opp = x[dofs[p.minus_cells, p.minus_local_facets]]
    if tdim == 2:
        t = xm[:, 1] - xm[:, 0]
        normal = np.stack([t[:, 1], -t[:, 0]], axis=1)
    else:
        normal = np.cross(xm[:, 1] - xm[:, 0], xm[:, 2] - xm[:, 0])
    flip = np.einsum("ij,ij->i", normal, opp - xm[:, 0]) > 0.0
    pos_m[flip, :2] = pos_m[flip, 1::-1]
    pos_p[flip, :2] = pos_p[flip, 1::-1]
    return pos_m.astype(np.int32), pos_p.astype(np.int32)


def names_of(dmesh, kind: str) -> dict:
    """{name: tag} of the mesh's groups of `kind` ("blocks", "joints", "boundaries")."""
    return {str(n): int(t) for t, n in dmesh.names[kind].items()}


def lookup(dmesh, kind: str, name: str) -> int:
    """The tag of a named group, or ValueError listing the available names."""
    names = names_of(dmesh, kind)
    if name not in names:
        raise ValueError(f"unknown {_SINGULAR[kind]} {name!r}; available {kind}: {sorted(names)}")
    return names[name]
