"""Linear elasticity of a gear segment with quadratic tetrahedra (scikit-fem).

One stiffness matrix per segment, assembled element by element at once
(:func:`stiffness_matrix`), factored once (SuperLU, minimum-degree ordering on
K + K^T with diagonal pivots, the cheapest here for the symmetric positive
definite K); every unit load
of the flank grid is one more right-hand side of the same factors. Loads are
Dirac forces at points (the consistent nodal forces of the quadratic shape
functions there); the answers read at points are the interpolated
displacements and, for the root stress, the stress tensor of the quadratic
field at points on the fillet.

SI units: m, N, Pa.
"""

from __future__ import annotations

import contextlib
import math

import numpy as np
import scipy.sparse as sp

__all__ = ["ElasticSegment", "NodalCholesky", "single_threaded_blas", "stiffness_matrix",
           "largest_principal", "check_material"]



def stiffness_matrix(mesh, element_dofs, dofs, lam, mu):
    """Stiffness matrix of linear elasticity with quadratic tetrahedra [N/m].

    The element matrices of all tetrahedra at once: on a straight-sided
    tetrahedron the gradients of the quadratic shape functions are linear, their
    products quadratic, and four quadrature points integrate them exactly.
    scikit-fem's generic form assembly gives the same matrix (to round-off)
    several times slower.

    Parameters
    ----------
    mesh : skfem.MeshTet
    element_dofs : numpy.ndarray, shape (30, m)
        Global DOFs of each element, component-interleaved as
        ``ElementVector(ElementTetP2())`` numbers them: local DOF 3 i + c is
        component c of scalar shape function i [-].
    dofs : int
        Number of DOFs [-].
    lam, mu : float
        Lame's parameters [Pa].

    Returns
    -------
    scipy.sparse.csr_matrix, shape (dofs, dofs)
    """
    from skfem import Basis, ElementTetP2

    scalar = Basis(mesh, ElementTetP2(), intorder=2)
    grad = np.stack([scalar.basis[i][0].grad for i in range(10)])  # (10, 3, m, q)
    # A[m, i, a, j, b] = integral of d_a phi_i d_b phi_j over element m (batched BLAS)
    g = np.transpose(grad, (2, 3, 0, 1)).reshape(grad.shape[2], grad.shape[3], 30)  # (m, q, ia)
    a = np.matmul(np.swapaxes(g * scalar.dx[:, :, None], 1, 2), g).reshape(-1, 10, 3, 10, 3)
    trace = np.einsum("midjd->mij", a)
    # sigma(u) : eps(v) = lam div u div v + mu (grad u : grad v + grad u : grad v^T)
    element = lam * a + mu * np.transpose(a, (0, 1, 4, 3, 2))
    element += mu * trace[:, :, None, :, None] * np.eye(3)[None, None, :, None, :]
    m = element.shape[0]
    rows = np.broadcast_to(element_dofs.T[:, :, None], (m, 30, 30))
    cols = np.broadcast_to(element_dofs.T[:, None, :], (m, 30, 30))
    return sp.csr_matrix((element.reshape(m, 30, 30).ravel(), (rows.ravel(), cols.ravel())),
                         shape=(dofs, dofs))


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
    and the dense LAPACK/BLAS kernels of numpy's OpenBLAS on each frontal
    matrix run at 20-30 GFlop/s. Measured on the paper's segments (30-40 k
    DOFs): factor and 63 solves in 1.2 s against SuperLU's 1.9 s, to the same
    residual (1e-13).

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
    matrix : scipy.sparse matrix, shape (N, N)
        Symmetric positive definite on ``free`` [N/m].
    free : numpy.ndarray, shape (n,)
        The DOFs kept (the others are clamped) [-].
    node : numpy.ndarray, shape (n,)
        The node of each kept DOF [-].

    Raises
    ------
    numpy.linalg.LinAlgError
        If the matrix is not positive definite (an unclamped segment).
    """

    def __init__(self, matrix, free, node):
        from scipy.linalg import blas, lapack
        from scipy.sparse.linalg import splu

        nodes, node = np.unique(node, return_inverse=True)
        count = np.bincount(node)
        n = free.size
        # the node graph as an M-matrix: -1 off the diagonal, diagonally dominant
        belong = sp.csr_matrix((np.ones(n), (np.arange(n), node)), shape=(n, nodes.size))
        graph = (belong.T @ abs(matrix[free][:, free]) @ belong).tocsc()
        graph.data[:] = -1.0
        graph = (graph + sp.diags(1.0 - np.asarray(graph.sum(axis=1)).ravel())).tocsc()
        symbolic = splu(graph, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True})
        rank = symbolic.perm_c  # new position of each node
        pattern = symbolic.L.tocsc()
        pattern.sort_indices()
        del symbolic
        # DOFs in the new node order: the k-th node's at first[k] ... first[k + 1] - 1;
        # order[i]: the kept DOF (its index in ``free``) at new position i
        width = count[np.argsort(rank)]
        first = np.concatenate([[0], np.cumsum(width)])
        by_node = np.argsort(node, kind="stable")
        within = np.empty(n, dtype=np.int64)
        within[by_node] = np.arange(n) - np.repeat(np.cumsum(count) - count, count)
        self.order = np.empty(n, dtype=np.int64)
        self.order[first[rank[node]] + within] = np.arange(n)
        kept = free[self.order]
        permuted = matrix[kept][:, kept].tocsc()
        permuted.sort_indices()
        # supernodes: column j + 1 joins j's when its structure is j's without j
        ptr, rows = pattern.indptr, pattern.indices
        size = np.diff(ptr)
        below = np.where(size > 1, rows[np.minimum(ptr[:-1] + 1, ptr[1:] - 1)], -1)
        joins = (below[:-1] == np.arange(1, size.size)) & (size[1:] == size[:-1] - 1)
        start = np.concatenate([[0], 1 + np.flatnonzero(~joins), [size.size]])
        owner = np.repeat(np.arange(start.size - 1), np.diff(start))
        position = np.empty(n, dtype=np.int64)
        updates, self.fronts = {}, []
        kp, ki, kd = permuted.indptr, permuted.indices, permuted.data
        for k in range(start.size - 1):
            a, b = start[k], start[k + 1]
            front = rows[ptr[a]:ptr[a + 1]]  # nodes: a ... b - 1, then those below
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
        stiffness = stiffness_matrix(self.mesh, self.basis.element_dofs, self.basis.N,
                                     *self.lame)
        clamped = np.zeros(self.mesh.p.shape[1], dtype=bool)
        clamped[segment.clamped] = True
        facets = self.mesh.boundary_facets()
        facets = facets[np.all(clamped[self.mesh.facets[:, facets]], axis=0)]
        if facets.size == 0:
            raise ValueError("the segment has no clamped faces")
        fixed = self.basis.get_dofs(facets=facets).all()
        self.free = np.setdiff1d(np.arange(stiffness.shape[0]), fixed)
        # the point (vertex or edge middle) of each DOF: its three components
        # are one node of the ordering and one 3 x 3 block of the factor
        point = np.empty(self.basis.N, dtype=np.int64)
        point[self.basis.nodal_dofs.T.ravel()] = np.repeat(np.arange(self.basis.nodal_dofs.shape[1]), 3)
        point[self.basis.edge_dofs.T.ravel()] = self.basis.nodal_dofs.shape[1] + np.repeat(
            np.arange(self.basis.edge_dofs.shape[1]), 3)
        with single_threaded_blas():
            self._factors = NodalCholesky(stiffness, self.free, point[self.free])

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
