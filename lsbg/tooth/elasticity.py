"""Linear elasticity of a gear segment with quadratic tetrahedra (scikit-fem).

One stiffness matrix per segment, its element matrices computed at once
(:func:`element_stiffness`) and factored once (:class:`NodalCholesky`, a
multifrontal Cholesky by nodes); every unit load of the flank grid is one more
right-hand side of the same factor. Loads are forces at points (the
consistent nodal forces of the quadratic shape functions there, weighted into
load cases); the answers read at points are the interpolated displacements
and, for the root stress, the stress tensor of the quadratic field at points
on the fillet (the mean of the tetrahedra around each).

SI units: m, N, Pa.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from lsbg.tooth.cholesky import NodalCholesky, single_threaded_blas

__all__ = ["ElasticSegment", "NodalCholesky", "single_threaded_blas", "element_stiffness",
           "mean_and_deviator", "largest_principal", "largest_principal_over_points",
           "check_material"]


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

def mean_and_deviator(xx, yy, zz, xy, xz, yz):
    """Mean normal stress and the deviator's squared norm of stress tensors.

    The deviator's principal stresses s_k sum to 0 and their squares to J, so
    every principal stress lies within m -+ sqrt(2 J/3), and the tensor's
    Frobenius norm is sqrt(3 m^2 + J).

    Parameters
    ----------
    xx, yy, zz, xy, xz, yz : numpy.ndarray
        The tensors' six components, broadcast [Pa].

    Returns
    -------
    mean : numpy.ndarray
        m = (xx + yy + zz) / 3 [Pa].
    j2 : numpy.ndarray
        J = |S - m I|^2 from the components (no difference of large squares) [Pa^2].
    """
    mean = (xx + yy + zz) / 3
    j2 = (xx - mean) ** 2 + (yy - mean) ** 2 + (zz - mean) ** 2 + 2 * (xy ** 2 + xz ** 2 + yz ** 2)
    return mean, j2


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


def largest_principal_over_points(stress):
    """The largest of the largest principal stresses of each row's points [Pa].

    ``largest_principal(stress).max(axis=1)`` to the last bit, with the
    eigenvalues of only the points that can hold the maximum. With m the
    mean normal stress and J = |S - m I|^2 (the deviator's squared norm), the
    deviatoric principal stresses s_k (sum 0, sum of squares J) have
    sqrt(J/6) <= max s_k <= sqrt(2 J/3); a diagonal entry, a Rayleigh
    quotient, is a lower bound too. A point whose upper bound m + sqrt(2 J/3)
    lies below its row's largest lower bound (less 1e-12 of the row's largest
    tensor norm, for rounding) cannot hold the row's maximum and is left out: in a
    loaded tooth's fillets 80-90 % of them.

    Parameters
    ----------
    stress : numpy.ndarray, shape (rows, points, 3, 3)
        Symmetric stress tensors [Pa].

    Returns
    -------
    numpy.ndarray, shape (rows,)
    """
    stress = np.asarray(stress, float)
    # entry by entry, each (rows, points) in the caller's memory order
    xx, yy, zz = (stress[..., i, i] for i in range(3))
    mean, j2 = mean_and_deviator(xx, yy, zz, stress[..., 0, 1], stress[..., 0, 2],
                                 stress[..., 1, 2])
    largest = np.maximum(np.maximum(xx, yy), zz)
    lower = np.maximum(largest, mean + np.sqrt(j2 / 6)).max(axis=1)
    size = np.sqrt(3 * mean**2 + j2).max(axis=1)  # Frobenius norm: >= every entry
    row, point = np.nonzero(mean + np.sqrt(2 * j2 / 3) >= (lower - 1e-12 * size)[:, None])
    out = np.full(stress.shape[0], -np.inf)
    np.maximum.at(out, row, largest_principal(stress[row, point]))
    return out


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
