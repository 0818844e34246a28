"""PNG pictures drawn on the mesh: |u| on filled triangles, the deformed outline of every block
(displacements magnified so that the largest is 5 % of the scene), jointed beside intact."""
from __future__ import annotations

import numpy as np


def boundary_triangles(u):
    """The boundary faces of a 3D P1 displacement's mesh (the outer faces and both faces of every
    joint: split nodes make them boundaries), gathered on rank 0: (vertices (n, 3, 3) [m], u at
    them (n, 3, 3) [m]); None elsewhere. Collective."""
    from dolfinx import mesh as dmesh
    V = u.function_space
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    facets = dmesh.exterior_facet_indices(mesh.topology)
    nodes = dmesh.entities_to_geometry(mesh, tdim - 1, facets, False)
    # P1 on simplices: a cell's geometry nodes and its dofs follow the same vertex order
    n_cells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
    node_dof = np.zeros(mesh.geometry.x.shape[0], dtype=np.int64)
    node_dof[mesh.geometry.dofmaps[0][:n_cells].ravel()] = V.dofmap.list[:n_cells].ravel()
    x = mesh.geometry.x[nodes]
    values = u.x.array.reshape(-1, 3)[node_dof[nodes]]
    parts = [mesh.comm.gather(p, root=0) for p in (x, values)]
    if mesh.comm.rank != 0:
        return None, None
    return tuple(np.concatenate(p) for p in parts)


def draw(models: dict, scene, path: str) -> list:
    """One panel per model (P1 only): 2D filled triangles with block outlines; 3D the boundary
    faces (outer faces and joint faces) of the deformed mesh. Collective; rank 0 writes `path`."""
    from rockjoint.fem_coupling.output import gather_triangles
    if any(m.degree != 1 for m in models.values()):
        return []
    if models["jointed"].gdim == 3:
        return _draw_3d(models, scene, path)
    gathered = {label: gather_triangles(m.u) for label, m in models.items()}
    if models["jointed"].comm.rank != 0:
        return [path]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    fig, axes = plt.subplots(1, len(models), figsize=(5.5 * len(models), 4.6), squeeze=False)
    top = max(float(np.linalg.norm(u, axis=2).max()) for _, u in gathered.values()) or 1.0
    for ax, (label, (tri, u)) in zip(axes[0], gathered.items()):
        extent = float(np.ptp(tri.reshape(-1, 2), axis=0).max())
        scale = 0.05 * extent / top
        mag = np.linalg.norm(u, axis=2).mean(axis=1) * 1e3
        polys = PolyCollection(tri + scale * u, array=mag, cmap="viridis", edgecolors="none")
        polys.set_clim(0.0, top * 1e3)
        ax.add_collection(polys)
        edges = _outline(tri, u, scale)
        ax.add_collection(LineCollection(edges, colors="k", linewidths=0.6))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_title(f"{scene.data['name']}: {label} (u x {scale:.3g})")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        fig.colorbar(polys, ax=ax, label="|u| [mm]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return [path]


def _outline(tri: np.ndarray, u: np.ndarray, scale: float) -> np.ndarray:
    """Deformed edges that belong to one triangle only (the outline of every block: boundaries,
    openings and both faces of every joint), matched by their undeformed coordinates."""
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    moved = np.concatenate([(tri + scale * u)[:, [0, 1]], (tri + scale * u)[:, [1, 2]],
                            (tri + scale * u)[:, [2, 0]]])
    rounded = np.round(edges, 9)
    a = np.where((rounded[:, 0, 0] < rounded[:, 1, 0]) | ((rounded[:, 0, 0] == rounded[:, 1, 0])
                 & (rounded[:, 0, 1] <= rounded[:, 1, 1])), 0, 1)
    ordered = np.stack([rounded[np.arange(len(a)), a], rounded[np.arange(len(a)), 1 - a]], 1)
    _, inverse, counts = np.unique(ordered.reshape(-1, 4), axis=0, return_inverse=True, return_counts=True)
    single = counts[inverse.ravel()] == 1
    # on a joint both faces share coordinates (count 2) but move apart: draw edges whose two
    # copies move differently too
    moved_key = np.round(moved.reshape(-1, 4), 9)
    order = np.argsort(inverse.ravel(), kind="stable")
    split = np.zeros(len(a), bool)
    inv = inverse.ravel()[order]
    same = inv[1:] == inv[:-1]
    diff = np.abs(moved_key[order][1:] - moved_key[order][:-1][:, [0, 1, 2, 3]]).max(axis=1) > 0
    flip = np.abs(moved_key[order][1:] - moved_key[order][:-1][:, [2, 3, 0, 1]]).max(axis=1) > 0
    cut = same & diff & flip
    split[order[1:][cut]] = True
    split[order[:-1][cut]] = True
    return moved[single | split]


def _draw_3d(models: dict, scene, path: str) -> list:
    gathered = {label: boundary_triangles(m.u) for label, m in models.items()}
    if models["jointed"].comm.rank != 0:
        return [path]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    top = max(float(np.linalg.norm(u, axis=2).max()) for _, u in gathered.values()) or 1.0
    norm = colors.Normalize(0.0, top * 1e3)
    fig = plt.figure(figsize=(5.5 * len(models), 5.0))
    for k, (label, (tri, u)) in enumerate(gathered.items()):
        ax = fig.add_subplot(1, len(models), k + 1, projection="3d")
        extent = float(np.ptp(tri.reshape(-1, 3), axis=0).max())
        scale = 0.05 * extent / top
        mag = np.linalg.norm(u, axis=2).mean(axis=1) * 1e3
        faces = Poly3DCollection(tri + scale * u, facecolors=cm.viridis(norm(mag)),
                                 edgecolors="k", linewidths=0.1)
        ax.add_collection3d(faces)
        lo, hi = tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        ax.set_title(f"{scene.data['name']}: {label} (u x {scale:.3g})")
        fig.colorbar(cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, label="|u| [mm]", shrink=0.7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return [path]
