"""Linear elasticity of a gear segment with quadratic tetrahedra (scikit-fem).

One stiffness matrix per segment, assembled for all elements at once
(:func:`stiffness_matrix`) and factored once (:class:`NodalCholesky`, a
multifrontal Cholesky by nodes); every unit load of the flank grid is one more
right-hand side of the same factor. Loads are forces at points (the
consistent nodal forces of the quadratic shape functions there, weighted into
load cases); the answers read at points are the interpolated displacements
and, for the root stress, the stress tensor of the quadratic field at points
on the fillet (the mean of the tetrahedra around each).

SI units: m, N, Pa.
"""

from __future__ import annotations

import contextlib
import math

import numpy as np
import scipy.sparse as sp

__all__ = ["ElasticSegment", "NodalCholesky", "single_threaded_blas", "element_stiffness",
           "stiffness_matrix", "largest_principal", "check_material"]


def element_stiffness(mesh, lam, mu):
    """Stiffness matrices of linear elasticity of all quadratic tetrahedra [N/m].

    On a straight-sided tetrahedron the gradients of the quadratic shape
    functions are linear, their products quadratic, and four quadrature
    points integrate them exactly; all elements at once in batched BLAS.
    scikit-fem's generic form assembly gives the same matrices (to
    round-off) several times slower.

    Parameters
    ----------
    mesh : skfem.MeshTet
    lam, mu : float
        Lame's parameters [Pa].

    Returns
    -------
    numpy.ndarray, shape (m, 30, 30)
        Local DOF 3 i + c is component c of scalar shape function i, as
        ``ElementVector(ElementTetP2())`` numbers them.
    """
    from skfem import Basis, ElementTetP2

    scalar = Basis(mesh, ElementTetP2(), intorder=2)
    grad = np.stack([scalar.basis[i][0].grad for i in range(10)])  # (10, 3, m, q)
    # A[m, i, a, j, b] = integral of d_a phi_i d_b phi_j over element m
    g = np.transpose(grad, (2, 3, 0, 1)).reshape(grad.shape[2], grad.shape[3], 30)  # (m, q, ia)
    a = np.matmul(np.swapaxes(g * scalar.dx[:, :, None], 1, 2), g).reshape(-1, 10, 3, 10, 3)
    trace = np.einsum("midjd->mij", a)
    # sigma(u) : eps(v) = lam div u div v + mu (grad u : grad v + grad u : grad v^T)
    element = lam * a + mu * np.transpose(a, (0, 1, 4, 3, 2))
    element += mu * trace[:, :, None, :, None] * np.eye(3)[None, None, :, None, :]
    return element.reshape(-1, 30, 30)


def stiffness_matrix(mesh, element_dofs, dofs, lam, mu):
    """Stiffness matrix of linear elasticity with quadratic tetrahedra [N/m].

    Parameters
    ----------
    mesh : skfem.MeshTet
    element_dofs : numpy.ndarray, shape (30, m)
        Global DOFs of each element (see :func:`element_stiffness`) [-].
    dofs : int
        Number of DOFs [-].
    lam, mu : float
        Lame's parameters [Pa].

    Returns
    -------
    scipy.sparse.csr_matrix, shape (dofs, dofs)
    """
    element = element_stiffness(mesh, lam, mu)
    m = element.shape[0]
    rows = np.broadcast_to(element_dofs.T[:, :, None], (m, 30, 30))
    cols = np.broadcast_to(element_dofs.T[:, None, :], (m, 30, 30))
    return sp.csr_matrix((element.ravel(), (rows.ravel(), cols.ravel())), shape=(dofs, dofs))


@contextlib.contextmanager
def single_threaded_blas():
    """numpy's and scipy's OpenBLAS on one thread inside the block.

    On a machine whose other cores are busy (a study runs a job per core)
    OpenBLAS's threads wait for each other at every call: measured, the
    factorisation of :class:`NodalCholesky` took 48 s instead of 7 s with
    another process on the second core. Its thread count is set through the
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
    Measured on the paper's segments (35-50 k DOFs): the factor and 63 solves
    1.6-1.8 times faster than SuperLU's (symmetric mode, diagonal pivots), to
    the same residual (1e-13).

    The ordering is SuperLU's minimum degree on A^T + A of the *node* graph
    (three DOFs a node: a third the size, and 3 x 3 blocks in the factor),
    and the structure of the factor the node graph's own factor from
    SuperLU: an M-matrix with the same graph, whose elimination has no
    cancellation. Columns with nested structure form supernodes; each is a
    dense front: the matrix's columns and its children's update matrices,
    added in (extend-add, by contiguous runs of rows), then ``dpotrf``,
    ``dtrsm`` and ``dsyrk``.

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
        from scipy.sparse.linalg import splu

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
        symbolic = splu(graph, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True})
        pattern = symbolic.L.tocsc()
        pattern.sort_indices()
        blocks, renumber = _supernodes(pattern)
        rank = renumber[symbolic.perm_c]  # new position of each node
        del symbolic
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
            row = np.broadcast_to(at[:, None, :], (30, 30, at.shape[1]))
            col = np.broadcast_to(at[None, :, :], (30, 30, at.shape[1]))
            lower = (col >= 0) & (row >= col)
            values = np.transpose(element_matrices, (1, 2, 0))[lower]
            permuted = sp.csc_matrix((values, (row[lower], col[lower])), shape=(n, n))
        else:
            kept = free[self.order]
            permuted = matrix[kept][:, kept].tocsc()
        permuted.sum_duplicates()
        permuted.sort_indices()
        owner = np.repeat(np.arange(len(blocks)), [b - a for a, b, _ in blocks])
        position = np.empty(n, dtype=np.int64)
        updates, self.fronts = {}, []
        kp, ki, kd = permuted.indptr, permuted.indices, permuted.data
        for k, (a, b, front) in enumerate(blocks):  # front: nodes a ... b - 1, those below
            idx = np.repeat(first[front], width[front]) + np.arange(width[front].sum()) \
                - np.repeat(np.cumsum(width[front]) - width[front], width[front])
            m, c0, c1 = idx.size, first[a], first[b]
            ns = c1 - c0
            position[idx] = np.arange(m)
            dense = np.zeros((m, m), order="F")
            lo, hi = kp[c0], kp[c1]
            r = ki[lo:hi]
            lower = r >= c0
            column = np.repeat(np.arange(ns), np.diff(kp[c0:c1 + 1]))
            dense[position[r[lower]], column[lower]] = kd[lo:hi][lower]
            for update, where in updates.pop(k, ()):
                _extend_add(dense, update, position[where])
            l11, info = lapack.dpotrf(dense[:ns, :ns], lower=1, clean=0)
            if info != 0:
                raise np.linalg.LinAlgError(f"the stiffness matrix is not positive definite "
                                            f"(supernode {k}, pivot {info})")
            if m > ns:
                l21 = blas.dtrsm(1.0, l11, dense[ns:, :ns], side=1, lower=1, trans_a=1)
                update = blas.dsyrk(-1.0, l21, beta=1.0, c=dense[ns:, ns:], lower=1)
                updates.setdefault(owner[front[b - a]], []).append((update, idx[ns:]))
            else:
                l21 = np.zeros((0, ns))
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
    pattern : scipy.sparse.csc_matrix
        The structure of the factor L, sorted indices [-].
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
    ptr, rows = pattern.indptr, pattern.indices
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
            merged = np.union1d(structure[c], structure[k])
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


def _extend_add(dense, update, position):
    """Add a child's update matrix (lower triangle) into its parent's front, in place.

    ``position`` (increasing) are the update's rows in the front; by blocks of
    contiguous runs (slices, at memory speed) when that costs less than one
    fancy-indexed addition (about 1.5 us a slice against 10 us and 5 ns an
    entry, measured).
    """
    cut = np.flatnonzero(np.diff(position) != 1) + 1
    runs = cut.size + 1
    if runs * (runs + 1) / 2 * 1.5e-6 > 1e-5 + 5e-9 * position.size ** 2:
        dense[np.ix_(position, position)] += update
        return
    starts = np.concatenate([[0], cut])
    ends = np.concatenate([cut, [position.size]])
    for j in range(starts.size):
        sj, ej, fj = starts[j], ends[j], position[starts[j]]
        for i in range(j, starts.size):
            si, ei, fi = starts[i], ends[i], position[starts[i]]
            dense[fi:fi + ei - si, fj:fj + ej - sj] += update[si:ei, sj:ej]


class ElasticSegment:
    """The factored stiffness of a meshed segment, ready for unit loads.

    Parameters
    ----------
    segment : lsbg.tooth.segment.SegmentMesh
    young_modulus : float
        E [Pa].
    poisson_ratio : float
        nu [-].
    """

    def __init__(self, segment, young_modulus, poisson_ratio):
        from skfem import Basis, ElementTetP2, ElementVector, MeshTet
        from skfem.models.elasticity import lame_parameters

        self.segment = segment
        self.lame = lame_parameters(young_modulus, poisson_ratio)
        self.mesh = MeshTet(np.ascontiguousarray(segment.nodes),
                            np.ascontiguousarray(segment.tetrahedra))
        # the vector basis numbers the DOFs and maps points for the probes and
        # the stress; one quadrature point is all it needs (no form is assembled on it)
        self.basis = Basis(self.mesh, ElementVector(ElementTetP2()), intorder=1)
        elements = element_stiffness(self.mesh, *self.lame)
        clamped = np.zeros(self.mesh.p.shape[1], dtype=bool)
        clamped[segment.clamped] = True
        facets = self.mesh.boundary_facets()
        facets = facets[np.all(clamped[self.mesh.facets[:, facets]], axis=0)]
        if facets.size == 0:
            raise ValueError("the segment has no clamped faces")
        fixed = self.basis.get_dofs(facets=facets).all()
        self.free = np.setdiff1d(np.arange(self.basis.N), fixed)
        # the point (vertex or edge middle) of each DOF: its three components
        # are one node of the ordering and one 3 x 3 block of the factor
        point = np.empty(self.basis.N, dtype=np.int64)
        vertices, edges = self.basis.nodal_dofs, self.basis.edge_dofs  # (3, count) each
        point[vertices.T.ravel()] = np.repeat(np.arange(vertices.shape[1]), 3)
        point[edges.T.ravel()] = vertices.shape[1] + np.repeat(np.arange(edges.shape[1]), 3)
        with single_threaded_blas():
            self._factors = NodalCholesky(None, self.free, point[self.free],
                                          elements=(self.basis.element_dofs, elements))

    @property
    def dofs(self):
        """Degrees of freedom of the quadratic field [-]."""
        return self.basis.N

    def locate(self, points):
        """Tetrahedra holding points, and the points' reference coordinates in them.

        Among the 12 tetrahedra with the nearest centroids, the one the point
        lies deepest inside (largest smallest barycentric coordinate; a point
        just outside the faceted boundary goes to the nearest one). scikit-fem's
        element finder does the same job several times slower here.

        Parameters
        ----------
        points : numpy.ndarray, shape (n, 3)
            [m].

        Returns
        -------
        cells : numpy.ndarray, shape (n,)
        local : numpy.ndarray, shape (3, n)
            Reference coordinates [-].
        """
        from scipy.spatial import cKDTree

        if not hasattr(self, "_finder"):
            corners = self.mesh.p[:, self.mesh.t]  # (3, 4, m)
            edges = np.transpose(corners[:, 1:] - corners[:, :1], (2, 0, 1))  # (m, 3 xyz, 3)
            self._finder = (cKDTree(corners.mean(axis=1).T), corners[:, 0].T,
                            np.linalg.inv(edges))
        tree, origin, inverse = self._finder
        points = np.asarray(points, float).reshape(-1, 3)
        _, near = tree.query(points, k=min(12, origin.shape[0]))
        near = near.reshape(len(points), -1)
        local = np.einsum("pkij,pkj->pki", inverse[near], points[:, None, :] - origin[near])
        depth = np.minimum(local.min(axis=2), 1.0 - local.sum(axis=2))
        best = np.argmax(depth, axis=1)
        rows = np.arange(len(points))
        return near[rows, best], local[rows, best].T

    def _vector_probes(self, points):
        """Sparse (3 n, N) interpolation of the displacement at points, component-major."""
        cells, local = self.locate(points)
        n = cells.size
        mapping, elem = self.basis.mapping, self.basis.elem
        # values[k, c, i]: component c of vector shape function k at point i
        values = np.stack([np.asarray(elem.gbasis(mapping, local[:, :, None], k, tind=cells)[0])
                           [:, :, 0] for k in range(self.basis.Nbfun)])
        rows = np.broadcast_to(np.arange(3 * n).reshape(3, n), values.shape)
        cols = np.broadcast_to(self.basis.element_dofs[:, cells][:, None, :], values.shape)
        return sp.csr_matrix((values.ravel(), (rows.ravel(), cols.ravel())),
                             shape=(3 * n, self.basis.N))

    def point_forces(self, points, directions, weights=None):
        """Consistent nodal forces of forces at points [N per N].

        Parameters
        ----------
        points : numpy.ndarray, shape (n, 3)
            Points inside the segment [m].
        directions : numpy.ndarray, shape (n, 3)
            Unit force directions [-].
        weights : numpy.ndarray, shape (n, k), optional
            Force of each point in each of k load cases [N per N]; default
            one unit force per load case (the identity).

        Returns
        -------
        scipy.sparse.csc_matrix, shape (N, n) or (N, k)
        """
        probes = self._vector_probes(points)
        n = len(points)
        # (N, n): column i is the nodal force of a unit force at point i
        forces = sum(probes[c * n:(c + 1) * n].T.multiply(directions[:, c][None, :])
                     for c in range(3)).tocsr()
        if weights is not None:
            forces = forces @ np.asarray(weights, float)
        return sp.csc_matrix(forces)

    def solve(self, forces):
        """Displacements under load cases [m].

        Parameters
        ----------
        forces : scipy.sparse matrix or numpy.ndarray, shape (N, n)
            Nodal forces of n load cases [N].

        Returns
        -------
        numpy.ndarray, shape (N, n)
        """
        forces = forces.toarray() if hasattr(forces, "toarray") else np.asarray(forces)
        out = np.zeros((self.dofs, forces.shape[1]))
        with single_threaded_blas():
            out[self.free] = self._factors.solve(np.ascontiguousarray(forces[self.free]))
        return out

    def displacement_along(self, displacements, points, directions):
        """Displacement components at points along directions [m].

        Parameters
        ----------
        displacements : numpy.ndarray, shape (N, n)
        points, directions : numpy.ndarray, shape (p, 3)

        Returns
        -------
        numpy.ndarray, shape (p, n)
        """
        probes = self._vector_probes(points)
        p = len(points)
        return sum(directions[:, c][:, None] * (probes[c * p:(c + 1) * p] @ displacements)
                   for c in range(3))

    def stress(self, displacements, points, cells):
        """Stress tensors at points of given cells [Pa].

        Parameters
        ----------
        displacements : numpy.ndarray, shape (N, n)
        points : numpy.ndarray, shape (p, 3)
            Points in (or on the boundary of) their cells [m].
        cells : numpy.ndarray, shape (p,)
            Tetrahedron of each point [-].

        Returns
        -------
        numpy.ndarray, shape (p, n, 3, 3)
        """
        mapping = self.basis.mapping
        cells = np.asarray(cells, dtype=np.int64)
        local = mapping.invF(np.asarray(points, float).T[:, :, None], tind=cells)
        # (p, 9, k): d u_c / d x_d (c, d flattened) of vector shape function k
        grad = np.stack([np.asarray(self.basis.elem.gbasis(mapping, local, k, tind=cells)[0].grad)
                         [:, :, :, 0] for k in range(self.basis.Nbfun)], axis=-1)
        grad = np.moveaxis(grad.reshape(9, len(cells), -1), 0, 1)
        values = displacements[self.basis.element_dofs[:, cells].T]  # (p, k, n)
        gradient = np.moveaxis(np.matmul(grad, values).reshape(len(cells), 3, 3, -1), -1, 1)
        strain = 0.5 * (gradient + np.swapaxes(gradient, 2, 3))
        lam, mu = self.lame
        trace = np.trace(strain, axis1=2, axis2=3)
        return 2 * mu * strain + lam * trace[..., None, None] * np.eye(3)


    def mean_stress(self, displacements, points, cells, owner):
        """Stress tensors at points, the mean over the tetrahedra around each [Pa].

        The stress of the quadratic field is linear in each tetrahedron and
        jumps between them; at a vertex or an edge's middle the mean of the
        tetrahedra that hold it depends less on the mesh than any one of them.
        (A least-squares linear fit over the patch, as Zienkiewicz and Zhu's
        recovery, smooths the fillet's peak away: 20 % low on these meshes.)

        Parameters
        ----------
        displacements : numpy.ndarray, shape (N, n)
        points : numpy.ndarray, shape (p, 3)
            Points on (vertices or edges of) their tetrahedra [m].
        cells : numpy.ndarray, shape (c,)
            Tetrahedra around the points [-].
        owner : numpy.ndarray, shape (c,)
            The point of each of ``cells`` [-].

        Returns
        -------
        numpy.ndarray, shape (p, n, 3, 3)
        """
        owner = np.asarray(owner, np.int64)
        around = self.stress(displacements, np.asarray(points, float)[owner], cells)
        out = np.zeros((len(points),) + around.shape[1:])
        np.add.at(out, owner, around)
        return out / np.bincount(owner, minlength=len(points))[:, None, None, None]

def largest_principal(stress):
    """Largest principal stress of stress tensors [Pa].

    Parameters
    ----------
    stress : numpy.ndarray, shape (..., 3, 3)

    Returns
    -------
    numpy.ndarray, shape (...)
    """
    return np.linalg.eigvalsh(stress)[..., -1]


def check_material(young_modulus, poisson_ratio):
    """Reject a Young's modulus or Poisson ratio out of physical range.

    Raises
    ------
    ValueError
        Naming the key: E outside [1e9, 1e12] Pa (metals and ceramics lie
        within), nu outside (0, 0.5).
    """
    if not (math.isfinite(young_modulus) and 1e9 <= young_modulus <= 1e12):
        raise ValueError(f"young_modulus = {young_modulus!r} Pa: must lie in [1e9, 1e12] Pa "
                         f"(steel: 2.06e11)")
    if not (math.isfinite(poisson_ratio) and 0.0 < poisson_ratio < 0.5):
        raise ValueError(f"poisson_ratio = {poisson_ratio!r}: must lie in (0, 0.5) (steel: 0.3)")
