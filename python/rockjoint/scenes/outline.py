# SPDX-License-Identifier: MIT
"""The outline of every block of a deformed 2D mesh (scene pictures): the edges a drawing must show
to read the blocks, their boundaries, openings and both faces of every joint."""
from __future__ import annotations

import numpy as np


def block_outline(tri: np.ndarray, u: np.ndarray, scale: float) -> np.ndarray:
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
