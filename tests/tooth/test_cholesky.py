"""The numba kernels of :class:`lsbg.tooth.cholesky.NodalCholesky` against the numpy they
replace (bit for bit), the factor's structure against a dense factor's and SuperLU's, and
the factor assembled from elements against a dense solve."""

import numpy as np
import pytest

from lsbg.tooth.cholesky import (
    NodalCholesky,
    _extend_add,
    _factor_structure,
    _lower_entries,
    _union,
)


def test_extend_add_adds_the_lower_triangle_as_numpy_does():
    rng = np.random.default_rng(5)
    n, ns = 60, 9  # the front: 9 columns of the supernode, 31 rows below
    rows = np.sort(rng.choice(n, 40, replace=False))
    where = np.sort(rng.choice(rows[2:], 25, replace=False))  # some in each block
    position = np.full(n, -1)
    position[rows] = np.arange(rows.size)
    front = rng.standard_normal((rows.size, rows.size))
    update = np.asfortranarray(rng.standard_normal((where.size, where.size)))
    blocks = [np.asfortranarray(b) for b in (front[:ns, :ns], front[ns:, :ns], front[ns:, ns:])]
    _extend_add(*blocks, update, where, position)
    expected = front.copy()
    at = position[where]
    expected[np.ix_(at, at)] += update
    lower = np.tril(np.ones_like(front, dtype=bool))
    got = np.block([[blocks[0], front[:ns, ns:]], [blocks[1], blocks[2]]])
    assert np.array_equal(got[lower], expected[lower])
    # the upper triangles are left as they were
    assert np.array_equal(got[~lower], front[~lower])


def test_lower_entries_are_numpys_boolean_indexing():
    rng = np.random.default_rng(6)
    m = 17
    element_matrices = rng.standard_normal((m, 30, 30))
    at = rng.integers(-1, 50, (30, m)).astype(np.int32)  # -1: clamped
    row = np.broadcast_to(at[:, None, :], (30, 30, m))
    col = np.broadcast_to(at[None, :, :], (30, 30, m))
    lower = (col >= 0) & (row >= col)
    expected = (np.transpose(element_matrices, (1, 2, 0))[lower], row[lower], col[lower])
    for got, want in zip(_lower_entries(element_matrices, at), expected):
        assert got.dtype == want.dtype and np.array_equal(got, want)


@pytest.mark.parametrize("sizes", [(0, 5), (5, 0), (7, 12), (30, 30)])
def test_union_is_numpys(sizes):
    rng = np.random.default_rng(sum(sizes))
    a, b = (np.sort(rng.choice(40, size, replace=False)).astype(np.int32) for size in sizes)
    got = _union(a, b)
    assert got.dtype == np.int32 and np.array_equal(got, np.union1d(a, b))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_factor_structure_is_the_filled_structure_of_a_dense_factor(seed):
    # a random symmetric structure (a path, so that the graph is connected, and
    # random edges), as an M-matrix: no entry of its factor cancels by chance
    import scipy.sparse as sp

    rng = np.random.default_rng(seed)
    n = 60
    i = np.concatenate([np.arange(1, n), rng.integers(0, n, 90)])
    j = np.concatenate([np.arange(n - 1), rng.integers(0, n, 90)])
    i, j = rng.permutation(n)[i], rng.permutation(n)[j]  # (two orders: not a path)
    graph = sp.csc_matrix((-np.ones(i.size), (i, j)), shape=(n, n))
    graph = (graph + graph.T).tocsc()
    graph.data[:] = -1.0
    graph = (graph + sp.diags(1.0 - np.asarray(graph.sum(axis=1)).ravel())).tocsc()
    graph.sort_indices()
    ptr, rows = _factor_structure(graph.indptr.astype(np.int64), graph.indices.astype(np.int64))
    factor = np.linalg.cholesky(graph.toarray())
    for column in range(n):
        expected = np.flatnonzero(np.abs(factor[:, column]) > 1e-14 * factor[column, column])
        assert np.array_equal(rows[ptr[column]:ptr[column + 1]], expected)
    # SuperLU's complete factor of the same M-matrix in the same order, the way the
    # structure was found before
    from scipy.sparse.linalg import splu

    lower = splu(graph, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                 options={"SymmetricMode": True}).L.tocsc()
    lower.sort_indices()
    assert np.array_equal(ptr, lower.indptr) and np.array_equal(rows, lower.indices)


def test_the_factor_by_elements_solves_as_a_dense_solve():
    # 10-node "elements" on 150 nodes (the first 15 hold each node once, 65 more at
    # random), SPD element matrices; the first two nodes clamped
    rng = np.random.default_rng(7)
    nodes, m = 150, 80
    element_nodes = np.concatenate([rng.permutation(nodes).reshape(15, 10)]
                                   + [rng.choice(nodes, (1, 10), replace=False)
                                      for _ in range(m - 15)]).T
    element_dofs = (3 * element_nodes[:, None, :] + np.arange(3)[None, :, None]).reshape(30, m)
    g = rng.standard_normal((m, 30, 30))
    element_matrices = g @ np.transpose(g, (0, 2, 1)) + 0.1 * np.eye(30)
    full = np.zeros((3 * nodes, 3 * nodes))
    for e in range(m):
        full[np.ix_(element_dofs[:, e], element_dofs[:, e])] += element_matrices[e]
    free = np.arange(6, 3 * nodes)
    factor = NodalCholesky(None, free, free // 3, elements=(element_dofs, element_matrices))
    rhs = rng.standard_normal((free.size, 3))
    expected = np.linalg.solve(full[np.ix_(free, free)], rhs)
    assert np.allclose(factor.solve(rhs), expected, rtol=0, atol=1e-12 * np.abs(expected).max())
