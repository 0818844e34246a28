# SPDX-License-Identifier: MIT
"""meshes.planar_section: the crossings of straight joint traces, the outline pieces and the node
counts of the 2D section builder, against closed forms."""
import math

import numpy as np
import pytest

from rockjoint.meshes import planar_section as ps
from rockjoint.meshes.openings import CircularOpening, HorseshoeOpening


def grid(m, n, width=10.0, height=8.0):
    """m horizontal and n vertical segments across [0, width] x [0, height]."""
    ys, xs = (np.arange(1, m + 1) * height / (m + 1)), (np.arange(1, n + 1) * width / (n + 1))
    return ([[[0.0, y], [width, y]] for y in ys] + [[[x, 0.0], [x, height]] for x in xs]), xs, ys


def test_a_grid_of_traces_crosses_at_every_pair():
    """m horizontal x n vertical traces: m n crossings, 2 (m + n) ends, each trace's chain in order
    through the crossings at the closed-form positions."""
    segs, xs, ys = grid(4, 3)
    nodes, chains, extra = ps.arrange(np.array(segs), [f"j{k}" for k in range(7)], 1e-9)
    assert len(nodes) == 4 * 3 + 2 * (4 + 3) and extra.size == 0
    for k, y in enumerate(ys):
        assert np.allclose(nodes[chains[k]], np.column_stack([[0.0, *xs, 10.0], np.full(5, y)]), atol=1e-12)
    for k, x in enumerate(xs):
        assert np.allclose(nodes[chains[4 + k]], np.column_stack([np.full(6, x), [0.0, *ys, 8.0]]), atol=1e-12)


def test_oblique_crossing_t_junction_and_shared_points():
    """Two diagonals cross at the closed-form point; a trace ending on another (T-junction) shares
    its end node; the extra points (outline corners) merge with a trace end at the same place."""
    segs = np.array([[[0.0, 0.0], [4.0, 2.0]], [[0.0, 2.0], [4.0, 0.0]], [[1.0, 3.0], [1.0, 0.5]]])
    nodes, chains, extra = ps.arrange(segs, ["a", "b", "t"], 1e-9, np.array([[0.0, 0.0], [9.0, 9.0]]))
    # a: y = x / 2, b: y = 2 - x / 2, t: x = 1 from y = 3 down to a (the T), crossing b at y = 1.5
    assert np.allclose(nodes[chains[0]], [[0.0, 0.0], [1.0, 0.5], [2.0, 1.0], [4.0, 2.0]])
    assert np.allclose(nodes[chains[1]], [[0.0, 2.0], [1.0, 1.5], [2.0, 1.0], [4.0, 0.0]])
    assert chains[0][2] == chains[1][2] and chains[2][1] == chains[1][1] and chains[2][2] == chains[0][1]
    assert len(chains[2]) == 3 and len(nodes) == 8 + 1   # 8 distinct + the far extra point
    assert extra[0] == chains[0][0] and np.allclose(nodes[extra[1]], [9.0, 9.0])


def test_overlapping_collinear_traces_are_named():
    segs = np.array([[[0.0, 1.0], [5.0, 1.0]], [[4.0, 1.0], [8.0, 1.0]]])
    with pytest.raises(ValueError, match="'first' and 'second' overlap"):
        ps.arrange(segs, ["first", "second"], 1e-9)
    # collinear but end to end: one shared node, no overlap
    nodes, chains, _ = ps.arrange(np.array([[[0.0, 1.0], [5.0, 1.0]], [[5.0, 1.0], [8.0, 1.0]]]), ["a", "b"], 1e-9)
    assert chains[0][-1] == chains[1][0] and len(nodes) == 3


def test_outline_pieces_of_the_openings_close_and_measure_the_perimeter():
    for opening in (CircularOpening((5.0, 4.0), 2.0), HorseshoeOpening((5.0, 4.0), 2.0, 1.5, 0.0),
                    HorseshoeOpening((5.0, 4.0), 2.0, 1.5, 1.2)):
        pieces = opening.pieces()
        for a, b in zip(pieces, pieces[1:] + pieces[:1]):
            assert np.allclose(a.end, b.start, atol=1e-14)
        assert sum(p.length for p in pieces) == pytest.approx(opening.perimeter, rel=1e-13)
        assert all(p.span() < math.pi for p in pieces if p.centre is not None)


def test_distance_and_position_on_a_piece():
    arc = ps.OutlinePiece((2.0, 0.0), (0.0, 2.0), (0.0, 0.0))   # quarter circle r = 2, counter-clockwise
    d, along = arc.position(np.array([[3.0, 0.0], [math.sqrt(2), math.sqrt(2)], [0.0, -1.0], [-3.0, 0.0]]))
    assert np.allclose(d, [1.0, 0.0, math.hypot(2.0, 1.0), math.hypot(3.0, 2.0)])
    assert along[1] == pytest.approx(0.25 * math.pi * 2.0) and along[0] == 0.0
    line = ps.OutlinePiece((0.0, 0.0), (4.0, 0.0))
    d, along = line.position(np.array([[1.0, 2.0], [6.0, 0.0]]))
    assert np.allclose(d, [2.0, 2.0]) and np.allclose(along, [1.0, 4.0])
    # the rectangle's distance: to its nearest side
    assert ps.outline_distance(np.array([[1.0, 3.0]]), ps.rectangle(10.0, 8.0))[0] == pytest.approx(1.0)


def test_split_outline_orders_the_ends_along_each_piece():
    pieces = CircularOpening((0.0, 0.0), 1.0).pieces()
    ang = np.array([3.0, 0.3, 1.2, 5.0])   # rad, counter-clockwise from +x
    nodes = np.column_stack([np.cos(ang), np.sin(ang)])
    split = ps.split_outline(pieces, nodes, np.arange(4), 1e-9)
    assert [s.tolist() for s in split] == [[1, 2], [0], [], [3]]


@pytest.mark.parametrize("length, h", [(0.5, 1.0), (1.0, 1.0), (1.005, 1.0), (1.02, 1.0), (3.7, 1.0)])
def test_line_node_counts_follow_gmsh_rule(length, h):
    """A uniform size h: N = max(2, int(L / h + 1.99)) (gmsh's meshGEdgeProcessing)."""
    n = ps.line_node_counts(np.array([length]), np.zeros((1, 2)), np.array([[length, 0.0]]),
                            lambda p: np.full(len(p), h))
    assert n[0] == max(2, int(length / h + 1.99))


def test_line_node_counts_integrate_a_graded_size():
    """h = 1 + x along [0, 4]: the integral of dx / (1 + x) is ln 5, so N = int(ln 5 + 1.99) = 3
    (the midpoint rule on 16 intervals is within 0.2 % of ln 5)."""
    n = ps.line_node_counts(np.array([4.0]), np.zeros((1, 2)), np.array([[4.0, 0.0]]), lambda p: 1.0 + p[:, 0])
    assert n[0] == int(math.log(5.0) + 1.99) == 3


def test_crossings_are_the_same_in_blocks(monkeypatch):
    """arrange examines the pairs a block of segments at a time (memory O(block x n), not n²): a
    block of one segment gives the nodes and chains of one block of all."""
    rng = np.random.default_rng(3)
    segs = rng.uniform(0.0, 10.0, size=(40, 2, 2))
    whole = ps.arrange(segs, [f"j{k}" for k in range(40)], 1e-9)
    monkeypatch.setattr(ps, "_PAIRS_PER_BLOCK", 1)
    blocks = ps.arrange(segs, [f"j{k}" for k in range(40)], 1e-9)
    assert np.array_equal(whole[0], blocks[0])
    assert all(np.array_equal(a, b) for a, b in zip(whole[1], blocks[1]))
    # every pair of crossing segments shares exactly one node: the count of crossings is the closed
    # form of the segment-segment test done pair by pair here
    crossings = 0
    for i in range(40):
        for j in range(i + 1, 40):
            (p, q), (r, s) = segs[i], segs[j]
            m = np.column_stack([q - p, r - s])
            if abs(np.linalg.det(m)) > 1e-12:
                t, u = np.linalg.solve(m, r - p)
                crossings += (0 <= t <= 1) and (0 <= u <= 1)
    assert sum(len(c) - 2 for c in whole[1]) == 2 * crossings
