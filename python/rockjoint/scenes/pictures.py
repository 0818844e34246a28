"""PNG pictures drawn on the mesh: |u| on filled triangles, the deformed outline of every block
(displacements magnified so that the largest is 5 % of the scene), jointed beside intact."""
from __future__ import annotations

import numpy as np


def draw(models: dict, scene, path: str) -> list:
    """One panel per model (2D P1 only). Collective; rank 0 writes `path`."""
    from rockjoint.fem_coupling.output import gather_triangles
    if any(m.degree != 1 for m in models.values()):
        return []
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
