"""Closed triangle meshes: topology checks, mass properties, binary STL.

The solids of :mod:`lsbg.solid.solids` need a handful of operations on a triangle
mesh: its normals and triangles, whether it is watertight and consistently
wound, its mass properties by the divergence theorem and a binary STL file.
They live here on plain numpy arrays (a general mesh library's import would
cost each geometry job more than these few functions).

Mass properties: the solid is the signed sum of the tetrahedra from the
origin to each triangle (a, b, c). For one tetrahedron with a vertex at the
origin, V = a . (b x c) / 6, its first moment is V (a + b + c) / 4 and its
second moments are
``int x_i x_j dV = V / 20 (sum_k p_ki p_kj + s_i s_j)`` with s = a + b + c
(the standard formula for a simplex, e.g. Tonon 2004, J. Math. Stat. 1(1)).
Lengths in metres, density in kg/m^3.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

__all__ = ["TriangleMesh", "MeshMassProperties", "mesh_mass_properties", "write_stl",
           "read_stl"]

#: One facet of a binary STL file.
STL_FACET = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)),
                      ("attribute", "<u2")])


@dataclass(frozen=True)
class MeshMassProperties:
    """Mass properties of a closed triangle mesh.

    Attributes
    ----------
    volume : float
        [m^3]
    mass : float
        [kg]
    center_mass : numpy.ndarray, shape (3,)
        [m]
    inertia : numpy.ndarray, shape (3, 3)
        Inertia tensor about the centre of mass, the mesh's axes [kg m^2].
    """

    volume: float
    mass: float
    center_mass: np.ndarray
    inertia: np.ndarray


def mesh_mass_properties(triangles, density=1.0):
    """Volume, mass, centre of mass and inertia of a closed, outward-wound mesh.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (n, 3, 3)
        Vertices of each triangle, counter-clockwise seen from outside [m].
    density : float
        [kg/m^3]

    Returns
    -------
    MeshMassProperties
    """
    tri = np.asarray(triangles, dtype=float)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    volumes = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    s = a + b + c
    volume = volumes.sum()
    first = (volumes[:, None] * s).sum(axis=0) / 4.0
    # second moments int x_i x_j dV, summed over the tetrahedra
    outer = (np.einsum("n,ni,nj->ij", volumes, a, a) + np.einsum("n,ni,nj->ij", volumes, b, b)
             + np.einsum("n,ni,nj->ij", volumes, c, c) + np.einsum("n,ni,nj->ij", volumes, s, s))
    second = outer / 20.0
    mass = density * volume
    centre = first / volume
    about_origin = density * (np.trace(second) * np.eye(3) - second)
    inertia = about_origin - mass * ((centre @ centre) * np.eye(3) - np.outer(centre, centre))
    return MeshMassProperties(float(volume), float(mass), centre, inertia)


@dataclass(frozen=True, eq=False)
class TriangleMesh:
    """A triangle mesh: vertices and faces (indices into them).

    Parameters
    ----------
    vertices : numpy.ndarray, shape (n, 3)
        [m]
    faces : numpy.ndarray, shape (m, 3)
        Vertex indices, counter-clockwise seen from outside [-].
    metadata : dict
        Free-form description (member, name, sections for a gear).
    """

    vertices: np.ndarray
    faces: np.ndarray
    metadata: dict = field(default_factory=dict)

    @property
    def triangles(self):
        """Vertices of each face, shape (m, 3, 3) [m]."""
        return self.vertices[self.faces]

    @property
    def triangles_center(self):
        """Centroid of each face [m]."""
        return self.triangles.mean(axis=1)

    @property
    def face_normals(self):
        """Unit normal of each face (right-hand rule on its winding) [-]."""
        tri = self.triangles
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        return n / np.linalg.norm(n, axis=1, keepdims=True)

    @property
    def volume(self):
        """Enclosed volume [m^3] (positive for outward winding)."""
        return mesh_mass_properties(self.triangles).volume

    def _directed_edges(self):
        f = self.faces
        return np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])

    @property
    def edges_unique(self):
        """Each undirected edge once, shape (e, 2) [-]."""
        return np.unique(np.sort(self._directed_edges(), axis=1), axis=0)

    @property
    def is_watertight(self):
        """Every undirected edge is shared by exactly two faces."""
        _, counts = np.unique(np.sort(self._directed_edges(), axis=1), axis=0, return_counts=True)
        return bool(np.all(counts == 2))

    @property
    def is_winding_consistent(self):
        """Neighbouring faces run through their shared edge in opposite directions
        (no directed edge occurs twice)."""
        _, counts = np.unique(self._directed_edges(), axis=0, return_counts=True)
        return bool(np.all(counts == 1))

    @property
    def euler_number(self):
        """V - E + F of the vertices used by faces [-] (2 per sphere, 0 per torus)."""
        used = np.unique(self.faces).size
        return int(used - len(self.edges_unique) + len(self.faces))

    @property
    def body_count(self):
        """Connected pieces, faces joined through shared vertices [-]."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        edges = self.edges_unique
        n = len(self.vertices)
        graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
        _, labels = connected_components(graph, directed=False)
        return int(np.unique(labels[np.unique(self.faces)]).size)

    def export(self, path):
        """Write a binary STL file [m] (:func:`write_stl`)."""
        return write_stl(path, self)


def write_stl(path, mesh, header="lsbg"):
    """Write ``mesh`` as a binary STL file (single precision, metres).

    Parameters
    ----------
    path : str or os.PathLike
    mesh : TriangleMesh
    header : str
        Start of the 80-byte header (must not begin with ``solid``).

    Returns
    -------
    str
        The path written.
    """
    facets = np.zeros(len(mesh.faces), dtype=STL_FACET)
    facets["normal"] = mesh.face_normals
    facets["vertices"] = mesh.triangles
    with open(path, "wb") as handle:
        handle.write(header.encode("ascii")[:80].ljust(80, b"\0"))
        handle.write(np.uint32(len(facets)).tobytes())
        handle.write(facets.tobytes())
    return os.fspath(path)


def read_stl(path):
    """Read a binary STL file written by :func:`write_stl`.

    Vertices are merged where they coincide exactly (STL stores each facet's
    corners separately).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    TriangleMesh
    """
    with open(path, "rb") as handle:
        data = handle.read()
    if len(data) < 84:
        raise ValueError(f"{path}: not a binary STL file ({len(data)} bytes)")
    count = int(np.frombuffer(data, "<u4", 1, 80)[0])
    if len(data) != 84 + count * STL_FACET.itemsize:
        raise ValueError(f"{path}: {len(data)} bytes do not hold the {count} facets its header "
                         f"announces")
    facets = np.frombuffer(data, STL_FACET, count, 84)
    corners = facets["vertices"].reshape(-1, 3).astype(float)
    vertices, index = np.unique(corners, axis=0, return_inverse=True)
    return TriangleMesh(vertices, index.reshape(-1, 3))
