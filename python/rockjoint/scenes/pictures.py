# SPDX-License-Identifier: MIT
"""PNG pictures drawn on the mesh: ``|u|`` on filled triangles, the deformed outline of every block,
joints coloured by their state (stick, slip, open) with a legend, jointed beside intact.

The overview shows the whole scene (displacements magnified so that the largest is 5 % of it).
A tunnel adds the view a rock engineer reads first: the opening, four radii (a horseshoe's or D's
half-sizes: half its largest dimension) across, at a
magnification chosen so that the largest displacement there is 2-5 % of the radius and stated on
the plot (a magnification that fits the 80 m section turns a 4 m opening into a sliver). In 3D the
same views are drawn on the section through the opening at half its length. A scene with water
adds a row (2D): the jointed model's joints coloured by their water pressure (water_picture.py)."""
from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from .. import Status
from ..meshes import CircularOpening
from . import geometry as scene_geometry, water_picture
from .outline import block_outline

#: joint point states, drawn in this order and colour; "closed" is a joint without strength in
#: contact (it has no stick/slip distinction)
STATE_COLOURS = {"stick": "#1f3a93", "slip": "#e8112d", "open": "#ff9900", "closed": "#1f3a93"}
#: which state a node shared by two joint pairs shows when the pairs differ
_DRAW_FIRST = {"open": 0, "slip": 1, "stick": 2, "closed": 2}
#: the largest displacement in the opening view is drawn as at most this fraction of the radius
OPENING_FRACTION = 0.05


def nice_scale(raw: float) -> float:
    """The largest 1, 2 or 5 x 10^k not above `raw` (a magnification people can read)."""
    if not (raw > 0 and math.isfinite(raw)):
        return 1.0
    k = math.floor(math.log10(raw))
    return max(m * 10.0 ** k for m in (1, 2, 5) if m * 10.0 ** k <= raw * (1 + 1e-12))


def joint_states(model) -> dict:
    """The joint points of `model` (all ranks, on every rank): coordinates (n, gdim) [m], state
    names (n,) ('stick', 'slip', 'open'; 'closed' for joints without strength) and joint tags.
    Collective."""
    from ..fem import ShearState  # the FE stack is optional: imported when drawing
    from ..fem.water.coupled import gathered_pressure  # the FE stack, as above
    state = model.solution.gather_joints()
    x = np.asarray(state["coordinates"], dtype=float).reshape(-1, model.gdim)
    if "shear_state" in state:
        names = {int(ShearState.stick): "stick", int(ShearState.slip): "slip",
                 int(ShearState.open): "open"}
        labels = [names[int(v)] for v in np.asarray(state["shear_state"])]
    else:
        labels = ["open" if int(v) == int(Status.open) else "closed" for v in np.asarray(state["status"])]
    return {"x": x, "state": np.array(labels, dtype=object), "tag": np.asarray(state["tag"]),
            "pressure": gathered_pressure(model)}


def joint_segments(x: np.ndarray, labels: np.ndarray, tags: np.ndarray, u_at):
    """Deformed joint traces as short segments, each coloured by the point it belongs to: the
    points of one joint (a straight trace in the drawing plane) are ordered along it and each
    point owns half of the gap to each neighbour; gaps wider than 3 median gaps (an opening that
    cuts the joint) are not bridged. `u_at(points)` gives the drawn displacement there.
    Returns {state: array (m, 2, 2)}."""
    out = {}
    for tag in np.unique(tags):
        p = x[tags == tag][:, :2]
        s = labels[tags == tag]
        if len(p) < 2:
            continue
        centre = p.mean(axis=0)
        direction = np.linalg.svd(p - centre, full_matrices=False)[2][0]
        t = (p - centre) @ direction
        # a node once, not per pair: where the pairs on either side of a node differ, the state
        # that matters most is drawn (open, then slip, then stick or closed)
        rank = np.array([_DRAW_FIRST.get(v, len(_DRAW_FIRST)) for v in s])
        t_key = np.round(t / max(np.ptp(t), 1e-300), 9)
        order = np.lexsort((rank, t_key))
        p, s, t = p[order], s[order], t[order]
        keep = np.r_[True, np.diff(t_key[order]) > 0]
        p, s, t = p[keep], s[keep], t[keep]
        if len(p) < 2:
            continue
        gaps = np.diff(t)
        bridged = gaps <= 3.0 * np.median(gaps)
        half = 0.5 * np.median(gaps)
        moved = p + u_at(p)
        mid = 0.5 * (moved[1:] + moved[:-1])
        for i in np.flatnonzero(bridged):
            out.setdefault(s[i], []).append([moved[i], mid[i]])
            out.setdefault(s[i + 1], []).append([mid[i], moved[i + 1]])
        # A point with no bridged gap on either side (a short piece between an opening and a wide
        # gap) still shows its state: half a median gap each way along the joint.
        alone = ~(np.r_[False, bridged] | np.r_[bridged, False])
        for i in np.flatnonzero(alone):
            out.setdefault(s[i], []).append([moved[i] - half * direction, moved[i] + half * direction])
    return {k: np.array(v) for k, v in out.items()}


def _vertex_displacement(tri: np.ndarray, u: np.ndarray):
    """u at a point (mean over the mesh vertices at that place: on a joint, the mid-plane of its
    two faces), as a function of points (n, 2); nearest vertex."""
    xy = tri.reshape(-1, 2)
    key, inverse = np.unique(np.round(xy, 9), axis=0, return_inverse=True)
    inverse = inverse.ravel()
    total = np.zeros((len(key), 2))
    np.add.at(total, inverse, u.reshape(-1, 2))
    mean = total / np.bincount(inverse, minlength=len(key))[:, None]
    tree = cKDTree(key)
    return lambda p: mean[tree.query(p)[1]]


def draw(models: dict, scene, path: str) -> list:
    """One column per model (P1 only): the whole scene, and for a tunnel the opening below it.
    2D: filled triangles with block outlines; 3D: the boundary faces of the deformed mesh, and
    for a tunnel the section through the opening. Joints by state in every 2D view and section.
    Collective; rank 0 writes `path`."""
    from ..fem.output.fields import gather_triangles, section_triangles  # FE stack: optional
    if any(m.degree != 1 for m in models.values()):
        return []
    geometry = scene.data["geometry"]
    opening = scene_geometry.opening(geometry) if geometry["kind"] == "tunnel" else None
    joints = {label: joint_states(m) for label, m in models.items() if m.gdim == 2 or opening}
    if models["jointed"].gdim == 3:
        sections = ({label: section_triangles(m.u, 0.5 * geometry["length"])
                     for label, m in models.items()} if opening else None)
        return _draw_3d(models, scene, path, sections, joints)
    gathered = {label: gather_triangles(m.u) for label, m in models.items()}
    if models["jointed"].comm.rank != 0:
        return [path]
    plt = plt_module()
    wet = "water" in scene.data and "jointed" in joints
    rows = (2 if opening else 1) + wet
    fig, axes = plt.subplots(rows, len(models), figsize=(5.8 * len(models), 4.9 * rows), squeeze=False)
    top = max(float(np.linalg.norm(u, axis=2).max()) for _, u in gathered.values()) or 1.0
    for k, (label, (tri, u)) in enumerate(gathered.items()):
        extent = float(np.ptp(tri.reshape(-1, 2), axis=0).max())
        scale = 0.05 * extent / top
        field_view(axes[0][k], tri, u, scale, top, joints[label])
        axes[0][k].set_title(f"{scene.data['name']}: {label} (u x {scale:.3g})")
        if opening:
            axes[0][k].add_patch(_view_box(plt, opening))
    if opening:
        _opening_views(axes[1], gathered, joints, opening, scene.data["name"])
    if wet:   # the jointed model's water on its undeformed mesh; the row's other panels off
        for k, ax in enumerate(axes[-1]):
            if k == list(gathered).index("jointed"):
                water_picture.draw_pressure(ax, gathered["jointed"][0], joints["jointed"], joint_segments,
                                            f"{scene.data['name']}: water in the joints")
            else:
                ax.set_axis_off()
    save(fig, path)
    return [path]


def plt_module():
    """matplotlib.pyplot with the Agg backend (imported on first use: it is slow to import)."""
    import matplotlib  # slow to import: only when a picture is drawn
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path: str) -> None:
    """Write and close the figure (one place, so a test can look at the figure it writes)."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    fig.clf()
    plt_module().close(fig)


def _view(opening) -> tuple:
    """((cx, cy), r, word): the opening view's centre (the middle of the opening's box), its
    half-width r (a circle's radius, else the opening's half-size: half its largest dimension) and
    the word for r in the caption."""
    x0, y0, x1, y1 = opening.bounds()
    word = "radius" if isinstance(opening, CircularOpening) else "half-size"
    return (0.5 * (x0 + x1), 0.5 * (y0 + y1)), 0.5 * max(x1 - x0, y1 - y0), word


def _view_box(plt, opening):
    (cx, cy), r, _ = _view(opening)
    return plt.Rectangle((cx - 2 * r, cy - 2 * r), 4 * r, 4 * r, fill=False, ec="w", ls="--", lw=0.8)


def field_view(ax, tri, u, scale, top, joints, limits=None):
    """``|u|`` on the deformed triangles, block outlines, joints by state (legend of those drawn)."""
    from matplotlib.collections import LineCollection, PolyCollection  # slow: only when drawing
    mag = np.linalg.norm(u, axis=2).mean(axis=1) * 1e3
    # edges in the face colour: no white seams between filled triangles
    polys = PolyCollection(tri + scale * u, array=mag, cmap="viridis", edgecolors="face",
                           linewidths=0.2)
    polys.set_clim(0.0, top * 1e3)
    ax.add_collection(polys)
    ax.add_collection(LineCollection(block_outline(tri, u, scale), colors="k", linewidths=0.6))
    if joints is not None and len(joints["x"]):
        u_at = _vertex_displacement(tri, u)
        segments = joint_segments(joints["x"], joints["state"], joints["tag"], lambda p: scale * u_at(p))
        for state in STATE_COLOURS:
            if state in segments:
                ax.add_collection(LineCollection(segments[state], colors=STATE_COLOURS[state],
                                                 linewidths=2.0 if state in ("slip", "open") else 0.9,
                                                 label=f"joint: {state}"))
        if segments:
            ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    if limits is None:
        ax.autoscale()
    else:
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.figure.colorbar(polys, ax=ax, label="|u| [mm]")


def _opening_views(axes, gathered, joints, opening, name):
    """The opening four radii across, one magnification for all models: the largest displacement
    in the views drawn as 2-5 % of the radius (OPENING_FRACTION, rounded down to 1-2-5)."""
    (cx, cy), r, word = _view(opening)
    outline = opening.outline(200)
    limits = ((cx - 2 * r, cx + 2 * r), (cy - 2 * r, cy + 2 * r))
    largest = {}
    for label, (tri, u) in gathered.items():
        inside = _in_view(tri, limits)
        largest[label] = float(np.linalg.norm(u[inside], axis=2).max()) if inside.any() else 0.0
    top = max(largest.values()) or 1.0
    scale = nice_scale(OPENING_FRACTION * r / top)
    for ax, (label, (tri, u)) in zip(axes, gathered.items()):
        field_view(ax, tri, u, scale, top, joints.get(label), limits)  # the axes clip to the view
        x, y = np.vstack([outline, outline[:1]]).T
        ax.plot(x, y, "w--", lw=0.8, label="_opening before")
        ax.set_title(f"{name}: {label}, opening (4 {'radii' if word == 'radius' else 'half-sizes'} across)")
        ax.text(0.02, 0.02, opening_caption(scale, largest[label], r, word), transform=ax.transAxes,
                fontsize=7.5, va="bottom", bbox=dict(fc="w", alpha=0.85, lw=0))


def opening_caption(scale: float, largest: float, radius: float, word: str = "radius") -> str:
    """The stated magnification of an opening view (tests read it back); `word` names `radius`
    (a circle's radius, or a horseshoe's or D's half-size)."""
    return (f"displacements x {scale:g}: the largest, {largest * 1e3:.3g} mm,\n"
            f"is drawn as {100 * scale * largest / radius:.2g} % of the {word} ({radius:g} m);\n"
            "dashed: the opening before deformation")


def _in_view(tri, limits):
    """Triangles with a vertex inside the view (or, 3D sections, any point in it)."""
    (x0, x1), (y0, y1) = limits
    x, y = tri[..., 0], tri[..., 1]
    return ((x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)).any(axis=1)


def _draw_3d(models: dict, scene, path: str, sections, joints) -> list:
    from ..fem.output.fields import boundary_triangles  # FE stack: optional
    gathered = {label: boundary_triangles(m.u) for label, m in models.items()}
    if models["jointed"].comm.rank != 0:
        return [path]
    plt = plt_module()
    from matplotlib import cm, colors  # slow to import: only when drawing
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # matplotlib's: only when drawing
    top = max(float(np.linalg.norm(u, axis=2).max()) for _, u in gathered.values()) or 1.0
    norm = colors.Normalize(0.0, top * 1e3)
    rows = 2 if sections else 1
    fig = plt.figure(figsize=(5.8 * len(models), 5.0 * rows))
    for k, (label, (tri, u)) in enumerate(gathered.items()):
        ax = fig.add_subplot(rows, len(models), k + 1, projection="3d")
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
    if sections:
        y = 0.5 * scene.data["geometry"]["length"]
        axes = [fig.add_subplot(rows, len(models), len(models) + k + 1) for k in range(len(models))]
        # the section's own displacement: u_x and u_z (the axial u_y is across the picture)
        in_plane = {label: (tri, u[:, :, [0, 2]]) for label, (tri, u) in sections.items()}
        near = {label: _near_section(j, y, sections[label][0]) for label, j in joints.items()}
        _opening_views(axes, in_plane, near, scene_geometry.opening(scene.data["geometry"]), scene.data["name"])
        for ax in axes:
            ax.set_title(ax.get_title() + f"\nsection y = {y:g} m")
            ax.set_ylabel("z [m]")
    save(fig, path)
    return [path]


def _near_section(joints: dict, y: float, tri: np.ndarray) -> dict:
    """The joint points in the layer of mesh nodes closest to the section y (within half the
    section's typical edge), projected on it (x, z): the joints' traces in the section."""
    dz = np.abs(joints["x"][:, 1] - y)
    edge = float(np.median(np.linalg.norm(tri[:, 1] - tri[:, 0], axis=1))) if len(tri) else 0.0
    keep = dz <= dz.min() + 0.5 * edge if len(dz) else dz > 0
    return {"x": joints["x"][keep][:, [0, 2]], "state": joints["state"][keep], "tag": joints["tag"][keep]}
