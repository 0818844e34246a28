# SPDX-License-Identifier: MIT
"""The water in a scene picture (pictures.py): the jointed model's mesh in grey with its joints
coloured by the water pressure p [MPa] they hold at the end of the run (2D), undeformed (the
displacements are the rows above; here the water is the point), so that a rock engineer sees where
the water stands and where the joints drained."""
from __future__ import annotations

import numpy as np


def draw_pressure(ax, tri, joints: dict, segments_of, title: str) -> None:
    """The mesh `tri` (grey) with the joints coloured by joints["pressure"] [Pa], drawn in MPa with
    a colour bar; segments_of(x, values, tags, u_at) cuts the traces (pictures.joint_segments),
    each piece carrying its point's pressure."""
    from matplotlib.collections import LineCollection, PolyCollection  # slow: only when drawing
    ax.add_collection(PolyCollection(tri, facecolors="0.9", edgecolors="0.8", linewidths=0.2))
    pieces = segments_of(joints["x"], joints["pressure"], joints["tag"], np.zeros_like)
    if pieces:
        values = np.concatenate([np.full(len(s), float(v)) for v, s in pieces.items()]) * 1e-6
        lines = LineCollection(np.concatenate(list(pieces.values())), array=values, cmap="plasma",
                               linewidths=2.0)
        lines.set_clim(0.0, max(float(values.max()), 1e-12))
        ax.add_collection(lines)
        ax.figure.colorbar(lines, ax=ax, label="water pressure in the joints p [MPa]")
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title)
