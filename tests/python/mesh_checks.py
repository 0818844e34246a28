# SPDX-License-Identifier: MIT
"""Independent checks on distributed jointed meshes, shared by the serial and MPI tests.

Facet vertices are read through DOLFINx's cell->facet and facet->geometry connectivity, not
through the pairing code's own numbering; cell measures from the geometry alone.
"""
import numpy as np

import dolfinx


def facet_coordinates(mesh, cells, local_facets):
    """(n, tdim, gdim) coordinates of the facets local_facets[i] of cells[i]."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim, tdim - 1)
    c2f = mesh.topology.connectivity(tdim, tdim - 1)
    facets = np.array([c2f.links(c)[f] for c, f in zip(cells, local_facets)], dtype=np.int32)
    if facets.size == 0:  # DOLFINx 0.9's entities_to_geometry divides by zero on an empty list
        return np.empty((0, tdim, mesh.geometry.dim))
    nodes = dolfinx.mesh.entities_to_geometry(mesh, tdim - 1, facets, False)
    return mesh.geometry.x[nodes][..., :mesh.geometry.dim]


def sorted_rows(x):
    """Facet coordinates as canonical sorted tuples (order of vertices removed)."""
    return [tuple(map(tuple, np.round(f[np.lexsort(f.T[::-1])], 12))) for f in x]


def owned_block_measures(d):
    """{block tag: area/volume of the block's cells owned by this rank}."""
    mesh = d.mesh
    tdim = mesh.topology.dim
    n_owned = mesh.topology.index_map(tdim).size_local
    x = mesh.geometry.x[:, :mesh.geometry.dim]
    dofs = mesh.geometry.dofmaps[0][:n_owned]
    e = x[dofs[:, 1:]] - x[dofs[:, :1]]
    if tdim == 2:
        m = 0.5 * np.abs(e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0])
    else:
        m = np.abs(np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6.0
    blocks = np.empty(n_owned, dtype=np.int32)
    sel = d.cell_blocks.indices < n_owned
    blocks[d.cell_blocks.indices[sel]] = d.cell_blocks.values[sel]
    return {int(t): float(m[blocks == t].sum()) for t in d.names["blocks"]}
