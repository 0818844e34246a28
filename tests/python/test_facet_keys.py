# SPDX-License-Identifier: MIT
"""Facet keys (meshes.node_splitting): exact for any node count, comparable across arrays.

The old mixed-radix key n³ capped tetrahedron meshes at about 1.66 M nodes. The reference here
is Python's own tuple comparison of the rows, independent of the encoding.
"""
import numpy as np
import pytest

from rockjoint.meshes.node_splitting import common_facet_keys, facet_keys

# Past the old cap (n³ < 2^62, n ≈ 1.66 M) and past int64 itself (n³ ≥ 2^63 from n = 2^21).
N_LARGE = 3_000_000


def random_sorted_rows(rng, m, n, k=3):
    rows = np.sort(rng.integers(0, n, size=(m, k)), axis=1)
    # Near-collisions: rows that differ by one in a single column, at the largest ids.
    top = np.array([[n - 3, n - 2, n - 1], [n - 4, n - 2, n - 1], [n - 3, n - 2, n - 2],
                    [0, n - 2, n - 1], [0, 1, n - 1], [0, 1, 2]])[:, :k]
    return np.concatenate([rows, top, rows[:50], top])  # with repeats


def check_against_tuples(rows, keys):
    """Equal rows <-> equal keys, and keys order the rows as Python orders the tuples."""
    tuples = [tuple(r) for r in rows.tolist()]
    rank = {t: i for i, t in enumerate(sorted(set(tuples)))}
    expected = np.array([rank[t] for t in tuples])
    order = np.argsort(keys, kind="stable")
    assert np.array_equal(expected[order], np.sort(expected)), "keys do not order the rows lexicographically"
    same_key = keys[order][1:] == keys[order][:-1]
    same_row = expected[order][1:] == expected[order][:-1]
    assert np.array_equal(same_key, same_row), "equal keys must mean equal rows and vice versa"


@pytest.mark.parametrize("n", [1000, 1_700_000, N_LARGE, 2**40])
def test_keys_are_exact_for_tetrahedron_facets_beyond_the_old_cap(n):
    rng = np.random.default_rng(7)
    rows = random_sorted_rows(rng, 3000, n)
    keys = facet_keys(rows, n)
    assert keys.dtype == np.int64 and keys.shape == (rows.shape[0],)
    check_against_tuples(rows, keys)


def test_triangle_facets_of_a_large_2d_mesh():
    rng = np.random.default_rng(3)
    rows = random_sorted_rows(rng, 3000, N_LARGE, k=2)
    check_against_tuples(rows, facet_keys(rows, N_LARGE))


def test_keys_of_several_arrays_are_comparable():
    """Joint/boundary groups are looked up among the cell facets by key: common keys must match."""
    rng = np.random.default_rng(11)
    cells = random_sorted_rows(rng, 4000, N_LARGE)
    picked = cells[rng.choice(cells.shape[0], 300, replace=False)]
    foreign = np.array([[5, 6, 7], [N_LARGE - 5, N_LARGE - 4, N_LARGE - 3]])
    foreign = foreign[[tuple(r) not in set(map(tuple, cells.tolist())) for r in foreign.tolist()]]
    k_cells, k_picked, k_foreign = common_facet_keys([cells, picked, foreign], N_LARGE)
    assert np.all(np.isin(k_picked, k_cells))
    assert not np.any(np.isin(k_foreign, k_cells))
    check_against_tuples(np.concatenate([cells, picked, foreign]),
                         np.concatenate([k_cells, k_picked, k_foreign]))


def test_bad_node_ids_are_refused_with_the_range():
    with pytest.raises(ValueError, match=r"node ids in \[0, 10\], outside \[0, n_nodes=10\)"):
        facet_keys(np.array([[0, 1, 10]]), 10)
    with pytest.raises(ValueError, match=r"node ids in \[-1, 2\]"):
        facet_keys(np.array([[-1, 1, 2]]), 10)
    with pytest.raises(ValueError, match=r"array 1 must be \(m, 3\) node ids, got shape \(2, 2\)"):
        common_facet_keys([np.zeros((1, 3), int), np.zeros((2, 2), int)], 10)
