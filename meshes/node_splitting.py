# SPDX-License-Identifier: MIT
"""Node splitting per block (MOOSE BreakMeshByBlock style) and joint-facet pairing.

A node touched by cells of k blocks keeps its id in the block with the lowest tag and gets k-1 copies,
one per further block (a T-junction node of 3 blocks gets 2 copies). The glue map remembers the
original node of every copy. A facet shared by cells of two different blocks is a joint facet; after
splitting its two sides are distinct facets, paired here with the plus nodes permuted to the minus
order. Requires every interface between two blocks to be a joint (the builders guarantee it).
"""
from __future__ import annotations

import numpy as np

from .jointed_mesh import JointedMesh

_NV = {"triangle": 3, "tetrahedron": 4}


def facet_keys(sorted_rows: np.ndarray, n_nodes: int) -> np.ndarray:
    """One int64 per facet from its sorted node ids: equal rows get equal keys, and keys order
    the rows lexicographically. Keys are comparable within one call only (see common_facet_keys)."""
    return common_facet_keys([sorted_rows], n_nodes)[0]


def common_facet_keys(row_arrays, n_nodes: int) -> list:
    """Keys of several (m_i, k) arrays of sorted node ids in [0, n_nodes), comparable across them.

    Exact and uncapped: the key of the first j columns is multiplied by n_nodes and the next column
    added (mixed radix, no sort) while that fits in int64; when it would not (n_nodes^k >= 2^63,
    e.g. tetrahedron facets beyond 2.1 M nodes), the partial keys are first replaced by their dense
    rank among all rows (np.unique), which keeps the order and is at most the number of rows.
    """
    arrays = [np.asarray(r, dtype=np.int64) for r in row_arrays]
    if not arrays:
        return []
    k = arrays[0].shape[1] if arrays[0].ndim == 2 else -1
    for i, r in enumerate(arrays):
        if r.ndim != 2 or r.shape[1] != k or k < 1:
            raise ValueError(f"facet keys: array {i} must be (m, {k}) node ids, got shape {r.shape}")
        if r.size and (r.min() < 0 or r.max() >= n_nodes):
            raise ValueError(f"facet keys: array {i} has node ids in [{r.min()}, {r.max()}], "
                             f"outside [0, n_nodes={n_nodes})")
    rows = np.concatenate(arrays) if len(arrays) > 1 else arrays[0]
    key = rows[:, 0].copy()
    bound = int(n_nodes)  # key < bound
    for j in range(1, k):
        if bound * int(n_nodes) >= 2 ** 63:
            _, key = np.unique(key, return_inverse=True)
            key = key.astype(np.int64).reshape(-1)
            bound = int(key.max()) + 1 if key.size else 1
            if bound * int(n_nodes) >= 2 ** 63:  # more distinct partial rows than int64 can scale
                raise ValueError(f"facet keys: {bound} distinct partial facets x {n_nodes} nodes "
                                 "exceed int64")
        key = key * n_nodes + rows[:, j]
        bound *= int(n_nodes)
    return np.split(key, np.cumsum([r.shape[0] for r in arrays])[:-1])


def cell_facets(cells: np.ndarray) -> np.ndarray:
    """(n_cells, nv, nv-1) facets of linear simplices; facet i is opposite vertex i (DOLFINx numbering)."""
    nv = cells.shape[1]
    local = np.array([[j for j in range(nv) if j != i] for i in range(nv)])
    return cells[:, local]


def split_nodes(cells: np.ndarray, cell_blocks: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Split nodes per block. Returns (split cells, glue); new nodes are numbered n_nodes, n_nodes+1, ...

    The copy kept under the original id belongs to the lowest block tag touching the node.
    """
    blocks = np.unique(cell_blocks)
    bidx = np.searchsorted(blocks, cell_blocks).astype(np.int64)
    nb = blocks.size
    key = cells * nb + bidx[:, None]  # (node, block) per cell vertex, sorted by node then block tag
    uniq, inverse = np.unique(key.ravel(), return_inverse=True)
    node = uniq // nb
    first = np.ones(uniq.size, dtype=bool)
    first[1:] = node[1:] != node[:-1]
    new_id = node.copy()
    n_copies = int(np.count_nonzero(~first))
    new_id[~first] = n_nodes + np.arange(n_copies)
    glue = np.concatenate([np.arange(n_nodes, dtype=np.int64), node[~first]])
    return new_id[inverse].reshape(cells.shape), glue


def build_jointed_mesh(points: np.ndarray, cells: np.ndarray, cell_type: str, cell_blocks: np.ndarray,
                       joint_elements: np.ndarray, joint_element_tags: np.ndarray,
                       boundary_elements: np.ndarray, boundary_element_tags: np.ndarray,
                       names: dict) -> JointedMesh:
    """Split a conforming glued mesh by block and pair the joint facets.

    points (n, gdim), cells (n_cells, nv) glued node ids (0-based); joint_elements / boundary_elements:
    (m, nv-1) glued facets of the joint / boundary physical groups with their tags.
    Raises ValueError if a facet between two blocks lies on no joint, or a joint element is not
    a facet between two blocks (a dangling joint).
    """
    if cell_type not in _NV:
        raise ValueError(f"cell_type must be 'triangle' or 'tetrahedron', got {cell_type!r}")
    points = np.asarray(points, dtype=np.float64)
    cells = np.asarray(cells, dtype=np.int64)
    cell_blocks = np.asarray(cell_blocks, dtype=np.int32)
    # Keep only the nodes used by cells, numbered contiguously.
    used = np.unique(cells)
    remap = np.full(points.shape[0], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    points, cells = points[used], remap[cells]
    joint_elements = remap[np.asarray(joint_elements, dtype=np.int64).reshape(-1, cells.shape[1] - 1)]
    boundary_elements = remap[np.asarray(boundary_elements, dtype=np.int64).reshape(-1, cells.shape[1] - 1)]
    if np.any(joint_elements < 0) or np.any(boundary_elements < 0):
        raise ValueError("a joint or boundary element uses a node that belongs to no cell")
    n = points.shape[0]
    nc, nv = cells.shape

    split, glue = split_nodes(cells, cell_blocks, n)

    # Every cell facet, glued ids sorted, with the split ids carried in the same order.
    gf = cell_facets(cells).reshape(-1, nv - 1)
    sf = cell_facets(split).reshape(-1, nv - 1)
    order = np.argsort(gf, axis=1, kind="stable")
    gf = np.take_along_axis(gf, order, axis=1)
    sf = np.take_along_axis(sf, order, axis=1)
    fcell = np.repeat(np.arange(nc, dtype=np.int64), nv)
    fopp = np.tile(np.arange(nv), nc)  # local vertex opposite the facet
    # Glued facet keys, comparable with those of the joint and boundary groups.
    keys, jkeys, bkeys = common_facet_keys([gf, np.sort(joint_elements, axis=1),
                                            np.sort(boundary_elements, axis=1)], n)
    srt = np.argsort(keys, kind="stable")
    ks = keys[srt]
    same = ks[1:] == ks[:-1]
    a, b = srt[:-1][same], srt[1:][same]  # the two cells of every interior glued facet
    single = np.ones(keys.size, dtype=bool)
    single[a] = single[b] = False
    cross = cell_blocks[fcell[a]] != cell_blocks[fcell[b]]
    a, b = a[cross], b[cross]
    swap = cell_blocks[fcell[a]] > cell_blocks[fcell[b]]  # minus = lower block tag
    minus = np.where(swap, b, a)
    plus = np.where(swap, a, b)
    fm, fp = sf[minus].copy(), sf[plus].copy()

    # Orient the minus order so that its right-hand normal points from minus into plus.
    x = points
    xm = x[glue[fm]]
    opp = x[cells[fcell[minus], fopp[minus]]]
    if nv == 3:
        t = xm[:, 1] - xm[:, 0]
        normal = np.stack([t[:, 1], -t[:, 0]], axis=1)
    else:
        normal = np.cross(xm[:, 1] - xm[:, 0], xm[:, 2] - xm[:, 0])
    flip = np.einsum("ij,ij->i", normal, opp - xm[:, 0]) > 0.0  # points into the minus cell
    fm[flip, :2] = fm[flip, 1::-1]
    fp[flip, :2] = fp[flip, 1::-1]

    # Joint tags from the joint physical groups (glued keys).
    jorder = np.argsort(jkeys)
    pair_keys = keys[minus]
    pos = np.searchsorted(jkeys[jorder], pair_keys)
    pos = np.minimum(pos, max(jkeys.size - 1, 0))
    found = (jkeys.size > 0) & (jkeys[jorder][pos] == pair_keys) if jkeys.size else np.zeros(pair_keys.size, bool)
    if not np.all(found):
        bad = np.flatnonzero(~found)[0]
        raise ValueError("a facet between blocks "
                         f"{cell_blocks[fcell[minus[bad]]]} and {cell_blocks[fcell[plus[bad]]]} at "
                         f"{x[gf[minus[bad]]].mean(axis=0)} lies on no joint; every block interface must be a joint")
    joint_tags = np.asarray(joint_element_tags, dtype=np.int32)[jorder][pos]
    if jkeys.size != np.unique(pair_keys).size or not np.all(np.isin(jkeys, pair_keys)):
        raise ValueError("a joint element is not a facet between two blocks (a joint that ends inside a block?)")

    # Boundary facets: the split ids of the single cell owning each exterior facet.
    ext = np.flatnonzero(single)
    ext_order = np.argsort(keys[ext])
    ext_sorted = keys[ext][ext_order]
    bpos = np.searchsorted(ext_sorted, bkeys)
    bpos = np.minimum(bpos, max(ext_sorted.size - 1, 0))
    if bkeys.size and not np.all(ext_sorted[bpos] == bkeys):
        raise ValueError("a boundary element is not an exterior facet of the mesh")
    boundary_facets = sf[ext[ext_order][bpos]] if bkeys.size else np.empty((0, nv - 1), np.int64)

    points_split = points[glue]
    order_pairs = np.lexsort((fcell[minus], joint_tags))  # by joint, then minus cell
    return JointedMesh(points=points_split, cells=split, cell_type=cell_type, cell_blocks=cell_blocks,
                       glue=glue, joint_facets_minus=fm[order_pairs], joint_facets_plus=fp[order_pairs],
                       joint_facet_cells=np.stack([fcell[minus], fcell[plus]], axis=1)[order_pairs],
                       joint_tags=joint_tags[order_pairs], boundary_facets=boundary_facets,
                       boundary_tags=np.asarray(boundary_element_tags, dtype=np.int32), names=names)
