# SPDX-License-Identifier: MIT
"""Plane geometry of a jointed 2D section, computed here instead of by OCC booleans.

A 2D section is an outline (the rectangle, and the opening's hole) cut by straight joint traces.
tunnel_section used to hand the traces to OCC's ``fragment``, which found the crossings and made
one surface per block: 2.0 s of the continuum bench's 8.4 s discrete tunnel (11k blocks, 316
traces; bench/results/tunnel_profile.md). The crossings of straight segments are a closed form, so
they are computed here (``arrange``): every trace becomes a chain of nodes, the outline's pieces are
split where traces end on them (``split_outline``), and gmsh's built-in kernel meshes ONE surface
with the traces' pieces embedded as mesh lines; the blocks are found on the mesh afterwards
(builders._block_labels), as they already were.

Outline pieces (``OutlinePiece``) are straight segments or circular arcs of less than pi, arcs
counter-clockwise around their centre. Lengths in metres.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree


@dataclass(frozen=True)
class OutlinePiece:
    """A straight piece start -> end (centre None) or a circular arc counter-clockwise around centre."""

    start: tuple
    end: tuple
    centre: tuple | None = None

    @property
    def radius(self) -> float:
        """Radius of the arc [m] (centre to start)."""
        return math.dist(self.start, self.centre)

    def span(self) -> float:
        """Angle of the arc [rad], in (0, 2 pi)."""
        a0, a1 = (math.atan2(p[1] - self.centre[1], p[0] - self.centre[0]) for p in (self.start, self.end))
        return (a1 - a0) % (2.0 * math.pi)

    @property
    def length(self) -> float:
        """Length of the piece [m]: the chord of a segment, radius × angle of an arc."""
        return math.dist(self.start, self.end) if self.centre is None else self.radius * self.span()

    def position(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(distance of each point from the piece [m], its position along the piece in [0, length]
        [m], clamped to the ends)."""
        p = np.atleast_2d(np.asarray(points, float))
        s = np.asarray(self.start, float)
        if self.centre is None:
            d = np.subtract(self.end, s)
            t = np.clip((p - s) @ d / (d @ d), 0.0, 1.0)
            return np.linalg.norm(p - (s + t[:, None] * d), axis=1), t * math.sqrt(d @ d)
        c, r, span = np.asarray(self.centre, float), self.radius, self.span()
        f = p - c
        a0 = math.atan2(s[1] - c[1], s[0] - c[0])
        phi = (np.arctan2(f[:, 1], f[:, 0]) - a0) % (2.0 * math.pi)
        on_arc = phi <= span
        ends = np.minimum(np.linalg.norm(p - s, axis=1), np.linalg.norm(p - np.asarray(self.end), axis=1))
        dist = np.where(on_arc, np.abs(np.linalg.norm(f, axis=1) - r), ends)
        return dist, r * np.where(on_arc, phi, np.where(phi - span < 2.0 * math.pi - phi, span, 0.0))


def rectangle(width: float, height: float) -> list:
    """The pieces of [0, width] x [0, height], counter-clockwise from the origin: bottom, right, top, left."""
    corners = [(0.0, 0.0), (width, 0.0), (width, height), (0.0, height)]
    return [OutlinePiece(corners[k], corners[(k + 1) % 4]) for k in range(4)]


def outline_distance(points: np.ndarray, pieces) -> np.ndarray:
    """Distance [m] of each point to the nearest of the outline pieces."""
    return np.min([piece.position(points)[0] for piece in pieces], axis=0)


def merge_points(points: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """(unique points, index of each input point's unique point): points closer than tol are one."""
    pairs = cKDTree(points).query_pairs(tol, output_type="ndarray")
    n = len(points)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n)) if len(pairs) else \
        coo_matrix((n, n))
    count, label = connected_components(graph, directed=False)
    first = np.full(count, n)
    np.minimum.at(first, label, np.arange(n))
    return points[first], label


#: pairs of segments examined at once by arrange (memory: a few arrays of this many doubles)
_PAIRS_PER_BLOCK = 1 << 20


def _crossings(a, d, length, tol: float, lo: int, hi: int):
    """Segments lo..hi-1 against every later segment: (rows (i, j, t, u) where they cross or touch,
    at a + t d of segment i and of segment j at u; pairs (i, j) that are collinear)."""
    ai, di, li = a[lo:hi, None, :], d[lo:hi, None, :], length[lo:hi, None]
    # a_i + t d_i = a_j + u d_j: with r = a_j - a_i, t = (r x d_j) / (d_i x d_j), u = (r x d_i) / (d_i x d_j)
    cross = di[..., 0] * d[None, :, 1] - di[..., 1] * d[None, :, 0]
    r = a[None, :, :] - ai
    r_dj = r[..., 0] * d[None, :, 1] - r[..., 1] * d[None, :, 0]
    r_di = r[..., 0] * di[..., 1] - r[..., 1] * di[..., 0]
    parallel = np.abs(cross) <= 1e-12 * li * length[None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        t, u = r_dj / cross, r_di / cross
    later = np.arange(len(a))[None, :] > np.arange(lo, hi)[:, None]
    # parameter tolerance of each segment: tol along it
    eps_i, eps_j = tol / li, (tol / length)[None, :]
    hit = later & ~parallel & (t >= -eps_i) & (t <= 1 + eps_i) & (u >= -eps_j) & (u <= 1 + eps_j)
    # collinear: parallel and the other's start within tol of this one's line (arrange then checks
    # whether their parameter intervals share more than a point)
    collinear = later & parallel & (np.abs(r_di) <= tol * li)
    bi, j = np.nonzero(hit)
    ci, cj = np.nonzero(collinear)
    return (np.column_stack([bi + lo, j, t[bi, j], u[bi, j]]), np.column_stack([ci + lo, cj]))


def arrange(segments: np.ndarray, names, tol: float, extra_points: np.ndarray = np.empty((0, 2))):
    """Where the straight segments ((n, 2, 2) [m]) cross or touch.

    Returns (nodes (m, 2), chains, extra): chains[k] are the node indices along segment k from its
    start to its end (its ends, and every point where another segment crosses it or ends on it);
    extra: the node of each of extra_points (e.g. the outline's corners), merged with the segments'
    nodes when closer than tol [m]. Collinear overlapping segments raise ValueError naming
    names[k] of both.
    """
    seg = np.asarray(segments, float).reshape(-1, 2, 2)
    n = len(seg)
    a, d = seg[:, 0], seg[:, 1] - seg[:, 0]
    length = np.linalg.norm(d, axis=1)
    hits, collinear = [], []
    rows = max(1, _PAIRS_PER_BLOCK // max(n, 1))   # segment i against every j > i, a block of i at once
    for lo in range(0, n, rows):
        hit_block, collinear_block = _crossings(a, d, length, tol, lo, min(n, lo + rows))
        hits.append(hit_block)
        collinear.append(collinear_block)
    for i, j in np.concatenate(collinear) if collinear else ():
        ends = ((seg[j] - a[i]) @ d[i]) / (length[i] ** 2)
        if min(ends.max(), 1.0) - max(ends.min(), 0.0) > tol / length[i]:
            raise ValueError(f"joints {names[i]!r} and {names[j]!r} overlap")
    hit = np.concatenate(hits) if hits else np.empty((0, 4))
    i, j, t, u = hit[:, 0].astype(np.int64), hit[:, 1].astype(np.int64), hit[:, 2], hit[:, 3]
    params = [[0.0, 1.0] for _ in range(n)]
    for k, pk in ((i, t), (j, u)):
        for s, p in zip(k, pk):
            params[s].append(min(max(float(p), 0.0), 1.0))
    raw = [a[k] + np.unique(params[k])[:, None] * d[k] for k in range(n)]
    raw.append(np.asarray(extra_points, float).reshape(-1, 2))
    nodes, label = merge_points(np.concatenate(raw), tol)
    chains, start = [], 0
    for k in range(n):
        c = label[start:start + len(raw[k])]
        start += len(raw[k])
        chains.append(c[np.concatenate([[True], c[1:] != c[:-1]])])   # crossings closer than tol: one node
    return nodes, chains, label[start:]


def split_outline(pieces, nodes: np.ndarray, candidates: np.ndarray, tol: float):
    """For each piece, the candidate nodes (indices into nodes) that lie on it within tol [m],
    strictly between its ends, in order along it: where the piece is split."""
    out = []
    pts = nodes[candidates]
    for k, piece in enumerate(pieces):
        dist, along = piece.position(pts)
        inside = (dist <= tol) & (along > tol) & (along < piece.length - tol)
        order = np.argsort(along[inside], kind="stable")
        out.append(candidates[inside][order])
    return out


def node_count(elements) -> np.ndarray:
    """gmsh's node count of a curve whose integral of ds / h is `elements`: N = max(2, int(a + 1.99))
    (gmsh's meshGEdgeProcessing, with Mesh.MinimumLineNodes = 2)."""
    return np.maximum(2, (np.asarray(elements, float) + 1.99).astype(np.int64))


def line_node_counts(lengths: np.ndarray, starts: np.ndarray, ends: np.ndarray, size_at, samples: int = 16):
    """gmsh's node count (node_count) of straight lines meshed with the size field size_at(points)
    [m], the integral of ds / h by the midpoint rule on `samples` intervals (the lines here are a
    few elements long)."""
    s = (np.arange(samples) + 0.5) / samples
    pts = starts[:, None, :] + s[None, :, None] * (ends - starts)[:, None, :]
    h = size_at(pts.reshape(-1, 2)).reshape(len(lengths), samples)
    return node_count(np.mean(1.0 / h, axis=1) * lengths)


def chain_lines(chains, owner: np.ndarray) -> tuple:
    """The mesh lines of arranged segments (arrange's chains, owner[k] the joint of segment k):
    (start node, end node, joint of every line, the nodes where a chain ends)."""
    if not chains:
        empty = np.empty(0, np.int64)
        return empty, empty, owner, empty
    starts = np.concatenate([c[:-1] for c in chains])
    ends = np.concatenate([c[1:] for c in chains])
    line_owner = np.concatenate([np.full(len(c) - 1, owner[k]) for k, c in enumerate(chains)])
    tips = np.unique(np.concatenate([[c[0], c[-1]] for c in chains]))
    return starts, ends, line_owner, tips


class GeoPoints:
    """gmsh built-in kernel points of the arranged nodes, each added on first use: points(k) is
    the tag of node k."""

    def __init__(self, geo, nodes: np.ndarray):
        self.geo, self.nodes = geo, nodes
        self.tags = np.zeros(len(nodes), dtype=np.int64)

    def __call__(self, k: int) -> int:
        if not self.tags[k]:
            self.tags[k] = self.geo.addPoint(*self.nodes[k], 0.0)
        return int(self.tags[k])
