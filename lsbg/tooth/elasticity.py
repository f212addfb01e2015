"""Linear elasticity of a gear segment with quadratic tetrahedra (scikit-fem).

One stiffness matrix per segment, factored once (SuperLU, minimum-degree
ordering on K + K^T, the cheapest here for the symmetric K); every unit load
of the flank grid is one more right-hand side of the same factors. Loads are
Dirac forces at points (the consistent nodal forces of the quadratic shape
functions there); the answers read at points are the interpolated
displacements and, for the root stress, the stress tensor of the quadratic
field at points on the fillet.

SI units: m, N, Pa.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["ElasticSegment", "largest_principal", "check_material"]


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
        from scipy.sparse.linalg import splu
        from skfem import Basis, ElementTetP2, ElementVector, MeshTet, asm
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        self.segment = segment
        self.lame = lame_parameters(young_modulus, poisson_ratio)
        self.mesh = MeshTet(np.ascontiguousarray(segment.nodes),
                            np.ascontiguousarray(segment.tetrahedra))
        self.basis = Basis(self.mesh, ElementVector(ElementTetP2()))
        stiffness = asm(linear_elasticity(*self.lame), self.basis)
        clamped = np.zeros(self.mesh.p.shape[1], dtype=bool)
        clamped[segment.clamped] = True
        facets = self.mesh.boundary_facets()
        facets = facets[np.all(clamped[self.mesh.facets[:, facets]], axis=0)]
        if facets.size == 0:
            raise ValueError("the segment has no clamped faces")
        fixed = self.basis.get_dofs(facets=facets).all()
        self.free = np.setdiff1d(np.arange(stiffness.shape[0]), fixed)
        self._factors = splu(stiffness[self.free][:, self.free].tocsc(),
                             permc_spec="MMD_AT_PLUS_A")

    @property
    def dofs(self):
        """Degrees of freedom of the quadratic field [-]."""
        return self.basis.N

    def _vector_probes(self, points):
        """Sparse (3 n, N) interpolation of the displacement at points, component-major."""
        return self.basis.probes(np.ascontiguousarray(np.asarray(points, float).T)).tocsr()

    def point_forces(self, points, directions):
        """Consistent nodal forces of unit forces at points [N per N].

        Parameters
        ----------
        points : numpy.ndarray, shape (n, 3)
            Points inside the segment [m].
        directions : numpy.ndarray, shape (n, 3)
            Unit force directions [-].

        Returns
        -------
        scipy.sparse.csc_matrix, shape (N, n)
        """
        probes = self._vector_probes(points)
        n = len(points)
        forces = sum(probes[c * n:(c + 1) * n].T.multiply(directions[:, c][None, :])
                     for c in range(3))
        return forces.tocsc()

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
        dofs = self.basis.element_dofs[:, cells]  # (Nbfun, p)
        gradient = np.zeros((len(cells), displacements.shape[1], 3, 3))
        for k in range(self.basis.Nbfun):
            grad = np.asarray(self.basis.elem.gbasis(mapping, local, k, tind=cells)[0].grad)
            # grad[c, d, p, 0]: d u_c / d x_d of shape function k
            values = displacements[dofs[k]]  # (p, n)
            gradient += values[:, :, None, None] * np.transpose(grad[:, :, :, 0], (2, 0, 1))[:, None]
        strain = 0.5 * (gradient + np.swapaxes(gradient, 2, 3))
        lam, mu = self.lame
        trace = np.trace(strain, axis1=2, axis2=3)
        return 2 * mu * strain + lam * trace[..., None, None] * np.eye(3)


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
