# SPDX-License-Identifier: MIT
"""Joints into a mesh the user made with DOLFINx's own gmsh reader (docs/user-model.md).

A FEniCSx user meshes with gmsh and reads the model with DOLFINx 0.11's

    mesh_data = dolfinx.io.gmsh.model_to_mesh(gmsh.model, comm, 0, gdim=2)

(on DOLFINx 0.9, ``rockjoint.fem.compat.io_gmsh`` is that module).
That mesh is conforming: the two sides of a joint share their nodes. A zero-thickness joint needs
them split (one copy per side) and both cells of every joint facet on one rank, so

    dmesh = split_joints(mesh_data, joints={"fault": FAULT_TAG})

gathers the tagged mesh on rank 0 (in the input numbering of the gmsh reader, through
``geometry.input_global_indices``), splits the nodes along the joint facets by block
(meshes.node_splitting, the same code the gmsh builders use) and distributes the split mesh with
the joint-aware partitioner (distributed_mesh.distribute). The result is a DistributedJointMesh
for JointCoupling or JointedRockModel; the original mesh is no longer needed. Cost: one gather of
the mesh and one more mesh creation, as the gmsh reader itself does on rank 0.
"""
from __future__ import annotations

from typing import Mapping

import numpy as np
from dolfinx.mesh import entities_to_geometry

from ...meshes.node_splitting import build_jointed_mesh
from .distributed_mesh import DistributedJointMesh, distribute

_CELL_TYPE = {2: "triangle", 3: "tetrahedron"}


def split_joints(mesh, cell_tags=None, facet_tags=None, joints: Mapping[str, int] | None = None,
                 blocks: Mapping[str, int] | None = None,
                 boundaries: Mapping[str, int] | None = None) -> DistributedJointMesh:
    """The DistributedJointMesh of a gmsh-read mesh split along its joint facets. Collective.

    mesh: the MeshData that dolfinx.io.gmsh.model_to_mesh returns (DOLFINx 0.10+), or the mesh
    itself with cell_tags and facet_tags (P1 triangles or tetrahedra). joints: {joint name: facet tag} (physical groups of dimension d-1 between blocks).
    blocks: {block name: cell tag} (default: every cell tag, named "block_<tag>").
    boundaries: {name: facet tag} of the named outer boundaries (default: every facet tag that is
    not a joint, named "boundary_<tag>"). Raises ValueError naming a missing tag or an untagged cell.
    """
    if hasattr(mesh, "facet_tags") and hasattr(mesh, "mesh"):  # a MeshData
        if cell_tags is not None or facet_tags is not None:
            raise TypeError("split_joints: give a MeshData alone, or a mesh with cell_tags and facet_tags")
        mesh, cell_tags, facet_tags = mesh.mesh, mesh.cell_tags, mesh.facet_tags
    if cell_tags is None or facet_tags is None:
        raise ValueError("split_joints: the mesh has no cell tags or no facet tags (physical groups of "
                         "the blocks and of the joints are needed)")
    if joints is None:
        raise TypeError("split_joints: joints={name: facet tag} is required")
    comm = mesh.comm
    tdim = mesh.topology.dim
    if tdim not in _CELL_TYPE or mesh.geometry.cmaps[0].degree != 1:
        raise ValueError("split_joints: a P1 triangle or tetrahedron mesh is needed")
    cell_values = _gather_values(comm, cell_tags)
    facet_values = _gather_values(comm, facet_tags)
    joints = _check_names("joints", joints, facet_values)
    if blocks is None:
        blocks = {f"block_{t}": t for t in sorted(cell_values)}
    blocks = _check_names("blocks", blocks, cell_values)
    if boundaries is None:
        boundaries = {f"boundary_{t}": t for t in sorted(facet_values - set(joints.values()))}
    boundaries = _check_names("boundaries", boundaries, facet_values)
    both = sorted(set(joints.values()) & set(boundaries.values()))
    if both:
        names = "; ".join(f"tag {t}: joint {', '.join(n for n, v in joints.items() if v == t)}, boundary "
                          f"{', '.join(n for n, v in boundaries.items() if v == t)}" for t in both)
        raise ValueError(f"split_joints: a facet tag is named both as a joint and as a boundary ({names})")

    # Owned cells and tagged owned facets, as input (gmsh) node indices.
    x = mesh.geometry.x[:, :mesh.geometry.dim]
    inputs = np.asarray(mesh.geometry.input_global_indices, dtype=np.int64)
    n_cells = mesh.topology.index_map(tdim).size_local
    cells = inputs[mesh.geometry.dofmaps[0][:n_cells]]
    block_of = np.full(n_cells, -1, dtype=np.int64)
    owned = cell_tags.indices < n_cells
    block_of[cell_tags.indices[owned]] = cell_tags.values[owned]
    mesh.topology.create_connectivity(tdim - 1, tdim)
    n_facets = mesh.topology.index_map(tdim - 1).size_local
    keep = facet_tags.indices < n_facets
    facets, values = facet_tags.indices[keep], facet_tags.values[keep]
    facet_nodes = inputs[entities_to_geometry(mesh, tdim - 1, facets, False)] if facets.size \
        else np.empty((0, tdim), dtype=np.int64)
    nodes = inputs
    parts = comm.gather((nodes, x, cells, block_of, facet_nodes, values), root=0)
    jm, error = None, None
    if comm.rank == 0:
        try:
            jm = _split_on_root(parts, tdim, joints, blocks, boundaries)
        except ValueError as e:  # raised on every rank below, never leaving one waiting
            error = str(e)
    error = comm.bcast(error, root=0)
    if error:
        raise ValueError(error)
    return distribute(jm, comm)


def _split_on_root(parts, tdim: int, joints: dict, blocks: dict, boundaries: dict):
    n_nodes = max(int(p[0].max()) + 1 for p in parts if p[0].size)
    points = np.zeros((n_nodes, parts[0][1].shape[1]))
    for p in parts:
        points[p[0]] = p[1]
    cells = np.concatenate([p[2] for p in parts])
    block_of = np.concatenate([p[3] for p in parts])
    untagged = block_of < 0
    if untagged.any():
        raise ValueError(f"split_joints: {int(untagged.sum())} cells carry no cell tag; tag every "
                         "block (a physical group of dimension d per block)")
    unnamed = sorted(set(np.unique(block_of).tolist()) - set(blocks.values()))
    if unnamed:
        raise ValueError(f"split_joints: cells with tags {unnamed} belong to no named block")
    facet_nodes = np.concatenate([p[4] for p in parts])
    values = np.concatenate([p[5] for p in parts])
    jsel = np.isin(values, list(joints.values()))
    bsel = np.isin(values, list(boundaries.values()))
    names = {"blocks": {int(t): n for n, t in blocks.items()},
             "joints": {int(t): n for n, t in joints.items()},
             "boundaries": {int(t): n for n, t in boundaries.items()}}
    return build_jointed_mesh(points, cells, _CELL_TYPE[tdim], block_of.astype(np.int32),
                              facet_nodes[jsel], values[jsel].astype(np.int32),
                              facet_nodes[bsel], values[bsel].astype(np.int32), names)


def _gather_values(comm, tags) -> set:
    """The set of tag values on all ranks."""
    return set().union(*comm.allgather(set(np.unique(tags.values).tolist())))


def _check_names(kind: str, given: Mapping[str, int], available: set) -> dict:
    out = {}
    for name, tag in dict(given).items():
        if not isinstance(name, str):
            raise ValueError(f"split_joints: {kind} names must be strings, got {name!r}")
        if int(tag) not in available:
            raise ValueError(f"split_joints: {kind}[{name!r}] = {tag}: no entity carries tag {tag}; "
                             f"tags present: {sorted(available)}")
        out[name] = int(tag)
    return out
