"""A sparse Cholesky factorisation by nodes, for the FE segments' stiffness.

The segment's stiffness (:mod:`lsbg.tooth.elasticity`) is symmetric positive
definite with 3 x 3 blocks per node; scipy has only SuperLU, a general L U.
:class:`NodalCholesky` orders the node graph with SuperLU's minimum degree,
groups the columns into relaxed supernodes and factors the dense fronts with
LAPACK/BLAS, one OpenBLAS thread (:func:`single_threaded_blas`) so that a
study's parallel jobs do not wait on each other's threads. The work by entry
around them (the factor's structure, the fronts' assembly, the extend-add) is
compiled with numba.
"""

from __future__ import annotations

import contextlib

import numpy as np
import scipy.sparse as sp
from numba import njit

__all__ = ["NodalCholesky", "single_threaded_blas"]


@contextlib.contextmanager
def single_threaded_blas():
    """numpy's and scipy's OpenBLAS on one thread inside the block.

    On a machine whose other cores are busy (a study runs a job per core)
    OpenBLAS's threads wait for each other at every call, which makes the
    factorisation of :class:`NodalCholesky` several times slower than on one
    thread. Its thread count is set through the
    libraries' own ``*_set_num_threads`` (the ones loaded in this process,
    found in ``/proc/self/maps``) and restored on leaving; where they cannot be
    found the block runs unchanged.
    """
    import ctypes

    names = (("scipy_openblas_get_num_threads64_", "scipy_openblas_set_num_threads64_"),
             ("scipy_openblas_get_num_threads", "scipy_openblas_set_num_threads"),
             ("openblas_get_num_threads", "openblas_set_num_threads"))
    found = []
    try:
        with open("/proc/self/maps", encoding="utf-8") as maps:
            paths = sorted({line.split()[-1] for line in maps
                            if "openblas" in line.lower() and ".so" in line})
        for path in paths:
            library = ctypes.CDLL(path)
            for get, put in names:
                if hasattr(library, get) and hasattr(library, put):
                    found.append((int(getattr(library, get)()), getattr(library, put)))
                    break
    except OSError:
        found = []
    for _, put in found:
        put(1)
    try:
        yield
    finally:
        for threads, put in found:
            put(threads)


class NodalCholesky:
    """Sparse Cholesky factor L L^T of a stiffness matrix, by nodes (multifrontal).

    SuperLU (scipy's only sparse direct solver) factors the segment's
    stiffness as L U with its own kernels at about 8 GFlop/s; the matrix is
    symmetric positive definite, so a Cholesky factor does half the work,
    and LAPACK/BLAS (scipy's OpenBLAS) run the dense fronts at 20-30 GFlop/s.
    On the paper's segments (35-50 k DOFs) the factor and its solves are faster
    than SuperLU's (symmetric mode, diagonal pivots), to the same residual
    (1e-13).

    The ordering is SuperLU's minimum degree on A^T + A of the *node* graph
    (three DOFs a node: a third the size, and 3 x 3 blocks in the factor),
    and the structure of the factor the node graph's, found symbolically
    from its elimination tree. Columns with nested structure form supernodes; each is a
    dense front: the matrix's columns and its children's update matrices,
    added in (extend-add), then ``dpotrf``, ``dtrsm`` and ``dsyrk``, in
    place on the front's three blocks.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (N, N), or None
        Symmetric positive definite on ``free`` [N/m]; None with ``elements``.
    free : numpy.ndarray, shape (n,)
        The DOFs kept (the others are clamped), increasing [-].
    node : numpy.ndarray, shape (n,)
        The node of each kept DOF [-].
    elements : tuple, optional
        ``(element_dofs, element_matrices)``, shapes (30, m) and (m, 30, 30):
        the matrix by elements (:func:`element_stiffness`), assembled here
        straight into the factor's order instead of ``matrix``.

    Raises
    ------
    numpy.linalg.LinAlgError
        If the matrix is not positive definite (an unclamped segment).
    """

    def __init__(self, matrix, free, node, elements=None):
        from scipy.linalg import blas, lapack
        from scipy.sparse.linalg import spilu

        nodes, node = np.unique(node, return_inverse=True)
        count = np.bincount(node)
        n = free.size
        if elements is not None:
            # the kept DOFs of each element's 30, -1 where clamped
            element_dofs, element_matrices = elements
            kept = np.full(int(element_dofs.max()) + 1, -1, dtype=np.int64)
            kept[free] = np.arange(n)
            local = kept[element_dofs]  # (30, m)
            ends = local[::3]  # one DOF of each of the 10 nodes
            ends = np.where(ends >= 0, node[np.maximum(ends, 0)], -1)
            first_end = np.broadcast_to(ends[:, None], (10, 10, ends.shape[1]))
            other_end = np.broadcast_to(ends[None], (10, 10, ends.shape[1]))
            both = (first_end >= 0) & (other_end >= 0)
            graph = sp.csc_matrix((-np.ones(both.sum()), (first_end[both], other_end[both])),
                                  shape=(nodes.size, nodes.size))
        else:
            belong = sp.csr_matrix((np.ones(n), (np.arange(n), node)), shape=(n, nodes.size))
            graph = (belong.T @ abs(matrix[free][:, free]) @ belong).tocsc()
        # the node graph as an M-matrix: -1 off the diagonal, diagonally dominant
        graph.data[:] = -1.0
        graph = (graph + sp.diags(1.0 - np.asarray(graph.sum(axis=1)).ravel())).tocsc()
        # SuperLU's ordering (minimum degree, then its elimination tree's postorder) from
        # an incomplete factor that keeps the diagonal alone: SuperLU's own complete
        # factor of the graph gave the same order and, at eight times the cost, the
        # structure _factor_structure finds from it (tests/tooth/test_cholesky.py)
        ordering = spilu(graph, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                         drop_tol=np.inf, fill_factor=1.0,
                         options={"SymmetricMode": True}).perm_c
        inverse = np.empty_like(ordering)
        inverse[ordering] = np.arange(ordering.size)
        ordered = graph[inverse][:, inverse].tocsc()
        blocks, renumber = _supernodes(_factor_structure(
            ordered.indptr.astype(np.int64), ordered.indices.astype(np.int64)))
        rank = renumber[ordering]  # new position of each node
        # DOFs in the new node order: the k-th node's at first[k] ... first[k + 1] - 1;
        # order[i]: the kept DOF (its index in ``free``) at new position i
        width = count[np.argsort(rank)]
        first = np.concatenate([[0], np.cumsum(width)])
        by_node = np.argsort(node, kind="stable")
        within = np.empty(n, dtype=np.int64)
        within[by_node] = np.arange(n) - np.repeat(np.cumsum(count) - count, count)
        self.order = np.empty(n, dtype=np.int64)
        new = first[rank[node]] + within
        self.order[new] = np.arange(n)
        if elements is not None:
            # assembled straight into the new order, lower triangle only (all the
            # factorisation reads): half the entries, no permutation of a matrix
            at = np.where(local >= 0, new[np.maximum(local, 0)], -1).astype(np.int32)
            values, row, col = _lower_entries(element_matrices, at)
            permuted = sp.csc_matrix((values, (row, col)), shape=(n, n))
        else:
            kept = free[self.order]
            permuted = matrix[kept][:, kept].tocsc()
        permuted.sum_duplicates()
        permuted.sort_indices()
        owner = np.repeat(np.arange(len(blocks)), [b - a for a, b, _ in blocks])
        # the DOFs of every front, all fronts end to end: front k's rows[ptr[k]:ptr[k + 1]],
        # node f's first[f] ... first[f] + width[f] - 1 in turn
        nodes_of = np.concatenate([front for _, _, front in blocks])
        dofs = width[nodes_of]
        rows = np.repeat(first[nodes_of] - np.cumsum(dofs) + dofs, dofs) + np.arange(dofs.sum())
        ptr = np.concatenate([[0], np.cumsum(dofs)])[
            np.concatenate([[0], np.cumsum([front.size for _, _, front in blocks])])]
        position = np.empty(n, dtype=np.int64)
        updates, self.fronts = {}, []
        kp, ki, kd = permuted.indptr, permuted.indices, permuted.data
        for k, (a, b, front) in enumerate(blocks):  # front: nodes a ... b - 1, those below
            idx = rows[ptr[k]:ptr[k + 1]]
            m, c0, c1 = idx.size, first[a], first[b]
            ns = c1 - c0
            a11, a21, a22 = _assemble_front(kp, ki, kd, idx, c0, c1, position)
            for update, where in updates.pop(k, ()):
                _extend_add(a11, a21, a22, update, where, position)
            # the blocks are Fortran-ordered arrays of their own: LAPACK works in
            # place on the same values and leading dimensions f2py's copies had
            l11, info = lapack.dpotrf(a11, lower=1, clean=0, overwrite_a=1)
            if info != 0:
                raise np.linalg.LinAlgError(f"the stiffness matrix is not positive definite "
                                            f"(supernode {k}, pivot {info})")
            l21 = a21  # empty if nothing is below
            if m > ns:
                l21 = blas.dtrsm(1.0, l11, a21, side=1, lower=1, trans_a=1, overwrite_b=1)
                update = blas.dsyrk(-1.0, l21, beta=1.0, c=a22, lower=1, overwrite_c=1)
                updates.setdefault(owner[front[b - a]], []).append((update, idx[ns:]))
            self.fronts.append((c0, c1, idx[ns:], l11, l21))

    def solve(self, rhs):
        """Solutions of the factored system for right-hand sides on the kept DOFs.

        Parameters
        ----------
        rhs : numpy.ndarray, shape (n, k)

        Returns
        -------
        numpy.ndarray, shape (n, k)
        """
        from scipy.linalg import blas

        rhs = np.asarray(rhs, float)
        if rhs.ndim == 1:
            return self.solve(rhs[:, None])[:, 0]
        y = np.array(rhs[self.order], order="C")
        for c0, c1, below, l11, l21 in self.fronts:
            y[c0:c1] = blas.dtrsm(1.0, l11, y[c0:c1], lower=1)
            if below.size:
                y[below] -= l21 @ y[c0:c1]
        for c0, c1, below, l11, l21 in reversed(self.fronts):
            z = y[c0:c1] - l21.T @ y[below] if below.size else y[c0:c1]
            y[c0:c1] = blas.dtrsm(1.0, l11, z, lower=1, trans_a=1)
        x = np.empty_like(y)
        x[self.order] = y
        return x


@njit(cache=True)
def _factor_structure(indptr, indices):
    """The structure of the Cholesky factor L of a symmetric structure, symbolically.

    The elimination tree first (Liu's algorithm, with path compression); then
    each column's rows are its own below the diagonal and its children's
    below themselves, merged in order of the columns: the structure
    elimination fills without cancellation.

    Parameters
    ----------
    indptr, indices : numpy.ndarray
        The matrix's structure, both triangles, CSC (int64) [-].

    Returns
    -------
    ptr, rows : numpy.ndarray
        L's structure, CSC: each column's rows increasing, its diagonal first [-].
    """
    n = indptr.size - 1
    parent = np.full(n, -1, dtype=np.int64)
    ancestor = np.full(n, -1, dtype=np.int64)
    for j in range(n):
        for p in range(indptr[j], indptr[j + 1]):
            i = indices[p]
            while i != -1 and i < j:
                after = ancestor[i]
                ancestor[i] = j
                if after == -1:
                    parent[i] = j
                i = after
    # each column's children, as linked lists in increasing order
    child = np.full(n, -1, dtype=np.int64)
    sibling = np.full(n, -1, dtype=np.int64)
    for j in range(n - 1, -1, -1):
        if parent[j] >= 0:
            sibling[j] = child[parent[j]]
            child[parent[j]] = j
    mark = np.full(n, -1, dtype=np.int64)
    ptr = np.zeros(n + 1, dtype=np.int64)
    rows = np.empty(2 * indices.size + n, dtype=np.int64)
    at = 0
    for j in range(n):
        if rows.size < at + n - j:  # room for a full column
            grown = np.empty(2 * rows.size + n - j, dtype=np.int64)
            grown[:at] = rows[:at]
            rows = grown
        rows[at] = j
        mark[j] = j
        at = _rows_below(indices, indptr[j], indptr[j + 1], j, mark, rows, at + 1)
        c = child[j]
        while c != -1:  # a child's rows after its diagonal
            at = _rows_below(rows, ptr[c] + 1, ptr[c + 1], j, mark, rows, at)
            c = sibling[c]
        rows[ptr[j] + 1:at].sort()
        ptr[j + 1] = at
    return ptr, rows[:at].copy()


@njit(cache=True)
def _rows_below(source, start, stop, j, mark, rows, at):
    """Append to column j's rows those of ``source[start:stop]`` below j not yet there.

    Parameters
    ----------
    source : numpy.ndarray
        Row numbers [-].
    start, stop : int
        The part of ``source`` read [-].
    j : int
        The column [-].
    mark : numpy.ndarray
        ``mark[i] == j`` where row i is already in column j; updated [-].
    rows : numpy.ndarray
        Written from ``at`` on [-].
    at : int
        The next free place in ``rows`` [-].

    Returns
    -------
    int
        The next free place after those appended [-].
    """
    for p in range(start, stop):
        i = source[p]
        if i > j and mark[i] != j:
            mark[i] = j
            rows[at] = i
            at += 1
    return at


def _supernodes(pattern, small=4, most=32, zeros=0.3):
    """Relaxed supernodes of a node-level Cholesky structure, and their column order.

    Columns whose structure nests (j + 1's is j's without j) form fundamental
    supernodes; on these meshes four in five are single nodes, and the
    Python work of a front outweighs its arithmetic. A supernode is merged
    into its parent when both together have at most ``small`` nodes, or at
    most ``most`` and the explicit zeros added are at most ``zeros`` of the
    merged front (relaxed amalgamation). The merged columns are made
    contiguous by a new postorder of the supernodal tree: any postorder of the
    elimination tree fills the same.

    Parameters
    ----------
    pattern : tuple of numpy.ndarray
        ``(ptr, rows)``: the structure of the factor L, CSC, each column's rows
        increasing (:func:`_factor_structure`) [-].
    small, most : int
        Nodes [-].
    zeros : float
        [-].

    Returns
    -------
    blocks : list of tuple
        ``(a, b, rows)`` per supernode in the new order: its columns a ... b - 1
        and its rows (those columns, then the ones below), new numbering.
    renumber : numpy.ndarray
        New position of each old column [-].
    """
    ptr, rows = pattern
    n = ptr.size - 1
    size = np.diff(ptr)
    below = np.where(size > 1, rows[np.minimum(ptr[:-1] + 1, ptr[1:] - 1)], -1)
    joins = (below[:-1] == np.arange(1, n)) & (size[1:] == size[:-1] - 1)
    start = np.concatenate([[0], 1 + np.flatnonzero(~joins), [n]])
    count = start.size - 1
    owner = np.repeat(np.arange(count), np.diff(start))
    columns = [np.arange(start[k], start[k + 1]) for k in range(count)]
    structure = [rows[ptr[start[k]]:ptr[start[k] + 1]] for k in range(count)]
    parent = [int(owner[r[c.size]]) if r.size > c.size else -1
              for c, r in zip(columns, structure)]
    children = [[] for _ in range(count)]
    for k, p in enumerate(parent):
        if p >= 0:
            children[p].append(k)

    def storage(nodes, height):
        return nodes * height - nodes * (nodes - 1) / 2

    kept = np.ones(count, dtype=bool)
    for k in range(count):  # children come before their parent
        mine = children[k]
        children[k] = []
        for c in sorted(mine, key=lambda c: columns[c].size):
            together = columns[c].size + columns[k].size
            merged = _union(structure[c], structure[k])
            extra = storage(together, merged.size) - storage(columns[c].size, structure[c].size) \
                - storage(columns[k].size, structure[k].size)
            if together <= small or (together <= most
                                     and extra <= zeros * storage(together, merged.size)):
                columns[k] = np.concatenate([columns[c], columns[k]])
                structure[k] = merged
                kept[c] = False
                children[k].extend(children[c])
            else:
                children[k].append(c)
    # a postorder of the merged tree: each supernode after its children
    order, blocks = [], []
    stack = [(k, False) for k in range(count - 1, -1, -1) if kept[k] and parent[k] < 0]
    while stack:
        k, done = stack.pop()
        if done:
            blocks.append(k)
            order.append(np.sort(columns[k]))
        else:
            stack.append((k, True))
            stack.extend((c, False) for c in reversed(children[k]))
    renumber = np.empty(n, dtype=np.int64)
    renumber[np.concatenate(order)] = np.arange(n)
    out, at = [], 0
    for k in blocks:
        width = columns[k].size
        out.append((at, at + width, np.sort(renumber[structure[k]])))
        at += width
    return out, renumber


@njit(cache=True)
def _lower_entries(element_matrices, at):
    """The elements' entries in the lower triangle, as COO triplets.

    In the order of numpy's boolean indexing of the ``(30, 30, m)`` arrays
    (local row, local column, element), so that scipy sums the duplicates
    in the same order; counted, then filled, without building the
    ``(30, 30, m)`` masks.

    Parameters
    ----------
    element_matrices : numpy.ndarray, shape (m, 30, 30)
        [N/m].
    at : numpy.ndarray, shape (30, m)
        The position of each element's DOFs in the factor's order, -1 where
        clamped [-].

    Returns
    -------
    values : numpy.ndarray
        [N/m].
    row, col : numpy.ndarray
        Positions, ``row >= col >= 0`` [-].
    """
    size, m = at.shape
    count = 0
    for i in range(size):
        for j in range(size):
            for e in range(m):
                count += 0 <= at[j, e] <= at[i, e]
    values = np.empty(count)
    row, col = np.empty(count, dtype=at.dtype), np.empty(count, dtype=at.dtype)
    k = 0
    for i in range(size):
        for j in range(size):
            for e in range(m):
                if 0 <= at[j, e] <= at[i, e]:
                    values[k], row[k], col[k] = element_matrices[e, i, j], at[i, e], at[j, e]
                    k += 1
    return values, row, col


@njit(cache=True)
def _union(a, b):
    """The union of two increasing arrays (``numpy.union1d``, without its sort).

    Parameters
    ----------
    a, b : numpy.ndarray
        Increasing [-].

    Returns
    -------
    numpy.ndarray
        Increasing, of ``a``'s type [-].
    """
    out = np.empty(a.size + b.size, dtype=a.dtype)
    i = j = k = 0
    while i < a.size or j < b.size:
        if j == b.size or (i < a.size and a[i] < b[j]):
            out[k] = a[i]
            i += 1
        elif i == a.size or b[j] < a[i]:
            out[k] = b[j]
            j += 1
        else:  # in both
            out[k] = a[i]
            i += 1
            j += 1
        k += 1
    return out[:k].copy()


@njit(cache=True)
def _assemble_front(indptr, indices, data, rows, c0, c1, position):
    """A supernode's dense front, its columns of the matrix put in; the rest zero.

    The front is three Fortran-ordered blocks: ``[[a11, .], [a21, a22]]``, the
    supernode's columns (``ns = c1 - c0``) first.

    Parameters
    ----------
    indptr, indices, data : numpy.ndarray
        The permuted matrix, CSC with sorted indices and no duplicates (its
        entries at or below the supernode's first column are all read) [N/m].
    rows : numpy.ndarray, shape (m,)
        The front's DOFs, increasing: the supernode's columns c0 ... c1 - 1
        first, then the rows below [-].
    c0, c1 : int
        The supernode's columns [-].
    position : numpy.ndarray, shape (n,)
        Filled here: the row of each of ``rows`` in the front (read by
        :func:`_extend_add` for the children's updates) [-].

    Returns
    -------
    a11 : numpy.ndarray, shape (ns, ns)
    a21 : numpy.ndarray, shape (m - ns, ns)
    a22 : numpy.ndarray, shape (m - ns, m - ns)
        [N/m].
    """
    ns, m = c1 - c0, rows.size
    for i in range(m):
        position[rows[i]] = i
    # transposed C arrays: Fortran order, a column contiguous
    a11, a21, a22 = np.zeros((ns, ns)).T, np.zeros((ns, m - ns)).T, np.zeros((m - ns, m - ns)).T
    for j in range(ns):
        for p in range(indptr[c0 + j], indptr[c0 + j + 1]):
            if indices[p] >= c0:
                i = position[indices[p]]
                if i < ns:
                    a11[i, j] = data[p]
                else:
                    a21[i - ns, j] = data[p]
    return a11, a21, a22


@njit(cache=True)
def _extend_add(a11, a21, a22, update, where, position):
    """Add a child's update matrix (lower triangle) into its parent's front, in place.

    Each entry of the lower triangle is added once, ``front + update`` as numpy's
    ``+=`` would; the upper triangles are never read (``dpotrf``, ``dtrsm`` and
    ``dsyrk`` take the lower one), so they are left out.

    Parameters
    ----------
    a11, a21, a22 : numpy.ndarray
        The parent's front (:func:`_assemble_front`) [N/m].
    update : numpy.ndarray, shape (p, p)
        The child's update matrix [N/m].
    where : numpy.ndarray, shape (p,)
        The update's DOFs, increasing, all among the front's [-].
    position : numpy.ndarray, shape (n,)
        The row of each of the front's DOFs in it (:func:`_assemble_front`) [-].
    """
    ns, size = a11.shape[0], where.size
    row = np.empty(size, dtype=np.int64)  # the update's rows in the front
    for i in range(size):
        row[i] = position[where[i]]
    split = np.searchsorted(row, ns)  # rows before it in the supernode's columns
    for j in range(split):
        for i in range(j, split):
            a11[row[i], row[j]] += update[i, j]
        for i in range(split, size):
            a21[row[i] - ns, row[j]] += update[i, j]
    for j in range(split, size):
        for i in range(j, size):
            a22[row[i] - ns, row[j] - ns] += update[i, j]
