# SPDX-License-Identifier: MIT
"""A slope's mechanism at its critical factor of safety (mechanism.png): at the largest stable F
of the search, ``|u|`` on the deformed mesh (filled triangles, every block's outline, the joints by
state: stick, slip, open; pictures.field_view) with the moving blocks hatched and named; beside
it the slip and the opening along each joint that slips or opens, against the distance along it.
"""
from __future__ import annotations

import numpy as np

from . import pictures


def draw(safety, jm, scene, path: str) -> list:
    """The mechanism picture of `safety` (slope_run.SlopeSafety) on the serial mesh `jm` (rank 0);
    [] when the search found no stable F. Collective; rank 0 writes `path`."""
    from ..fem.output.fields import gather_triangles, section_triangles  # FE stack: optional
    if not safety.stable_models or safety.found.stable is None:
        return []
    model = safety.stable_models[safety.found.stable]
    if model.degree != 1:
        return []
    length = scene.data["geometry"].get("length") if model.gdim == 3 else None
    # 3D: the section through the middle of the length (x, z), its joints' points within half an
    # element of it; the blocks' outlines are the section's (the extrusion keeps them)
    tri, u = section_triangles(model.u, 0.5 * length) if length else gather_triangles(model.u)
    state = model.solution.gather_joints()
    joints = pictures.joint_states(model) if not length else None
    if length:
        state = _on_section(state, 0.5 * length, model)
    if model.comm.rank != 0:
        return [path]
    if length:
        u = u[..., :2]   # the section's in-plane displacement (x, z)
    plt = pictures.plt_module()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13.0, 5.2))
    top = float(np.linalg.norm(u, axis=2).max()) or 1.0
    scale = 0.05 * float(np.ptp(tri.reshape(-1, 2), axis=0).max()) / top
    pictures.field_view(ax, tri, u, scale, top, joints)
    _mark_moving(ax, jm, safety.moving, 0.5 * length if length else None)
    f = safety.found
    ax.set_title(f"{scene.data['name']}: F = {f.factor:.3g}; at F = {f.stable:.4g} (u x {scale:.3g})\n"
                 f"hatched: the moving blocks ({', '.join(safety.moving) or 'none'})", fontsize=9)
    _along_joints(bx, state, jm.names["joints"])
    pictures.save(fig, path)
    return [path]


def _on_section(state: dict, y: float, model) -> dict:
    """The gathered joint state of a 3D slope on the section y (the points within the slab
    |y' - y| <= 5 % of the extent across), coordinates in the section's (x, z)."""
    x = np.asarray(state["coordinates"], float).reshape(-1, 3)
    width = 0.05 * float(np.ptp(x[:, 1])) if len(x) else 0.0
    near = np.abs(x[:, 1] - y) <= width
    out = {k: np.asarray(state[k]).reshape(len(x), -1)[near].squeeze(axis=1) if k != "slip"
           else np.asarray(state[k]).reshape(len(x), -1)[near] for k in ("tag", "slip", "closure")}
    out["coordinates"] = x[near][:, [0, 2]]
    return out


def _mark_moving(ax, jm, moving: list, y: float | None = None) -> None:
    """Hatch the moving blocks' cells (undeformed) and write each name at its centroid; 3D (the
    section y): the faces, in (x, z), of the tetrahedra the section cuts."""
    from matplotlib.collections import PolyCollection  # slow: only when drawing
    tags = {name: tag for tag, name in jm.names["blocks"].items()}
    for name in moving:
        cells = jm.cells[jm.cell_blocks == tags[name]]
        if y is None:
            tri = jm.points[cells][:, :, :2]
        else:
            tet = jm.points[cells]
            cut = tet[:, :, 1]
            tet = tet[(cut.min(axis=1) <= y) & (cut.max(axis=1) >= y)][:, :, [0, 2]]
            tri = tet[:, [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]].reshape(-1, 3, 2)
        ax.add_collection(PolyCollection(tri, facecolors=(0.69, 0.0, 0.13, 0.1), edgecolors="#b00020",
                                         linewidths=0.0, hatch="//"))
        a, b = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        area = 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
        c = (tri.mean(axis=1) * area[:, None]).sum(axis=0) / area.sum()
        ax.text(c[0], c[1], name, fontsize=7, ha="center", va="center", color="#b00020",
                bbox=dict(fc="w", alpha=0.8, lw=0))


def along(x: np.ndarray) -> tuple:
    """(order, distance [m]) of joint points x (n, 2) along their straight trace, from its lower end."""
    centre = x.mean(axis=0)
    direction = np.linalg.svd(x - centre, full_matrices=False)[2][0]
    direction = direction if direction[1] >= 0 else -direction
    t = (x - centre) @ direction
    order = np.argsort(t)
    return order, t[order] - t[order][0]


def _along_joints(ax, state: dict, names: dict) -> None:
    """Slip (solid) and opening (dashed) [mm] along each joint that slips or opens by more than
    1 % of the largest of them."""
    x = np.asarray(state["coordinates"], float).reshape(-1, 2)
    tags = np.asarray(state["tag"])
    slip = np.linalg.norm(np.asarray(state["slip"], float).reshape(len(tags), -1), axis=1) * 1e3
    opening = np.maximum(-np.asarray(state["closure"], float), 0.0) * 1e3
    largest = max(float(slip.max(initial=0.0)), float(opening.max(initial=0.0)))
    for k, tag in enumerate(np.unique(tags)):
        at = tags == tag
        if at.sum() < 2 or max(slip[at].max(), opening[at].max()) <= 0.01 * largest:
            continue
        order, s = along(x[at])
        line, = ax.plot(s, slip[at][order], lw=1.2, label=f"{names[int(tag)]}: slip")
        ax.plot(s, opening[at][order], lw=1.0, ls="--", color=line.get_color(), label=f"{names[int(tag)]}: opening")
    ax.set_xlabel("distance along the joint from its lower end [m]")
    ax.set_ylabel("slip, opening [mm]")
    ax.set_title("along each joint that slips or opens", fontsize=9)
    if ax.lines:
        ax.legend(fontsize=6.5, ncol=2)
