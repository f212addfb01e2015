"""Closed triangle meshes: mass properties against closed forms, topology, STL."""

import numpy as np
import pytest

from lsbg.solid.polyhedra import TriangleMesh, mesh_mass_properties, read_stl


def box(lx, ly, lz, origin=(0.0, 0.0, 0.0)):
    """A box [0, lx] x [0, ly] x [0, lz] shifted by origin, outward winding."""
    v = np.array([[x, y, z] for x in (0, lx) for y in (0, ly) for z in (0, lz)], float)
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                      [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return TriangleMesh(v + np.asarray(origin), faces)


def test_box_mass_properties_match_the_closed_form():
    lx, ly, lz, rho = 0.3, 0.2, 0.1, 7850.0
    mesh = box(lx, ly, lz, origin=(1.0, -2.0, 0.5))
    p = mesh_mass_properties(mesh.triangles, rho)
    m = rho * lx * ly * lz
    assert p.volume == pytest.approx(lx * ly * lz, rel=1e-12)
    assert p.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(p.center_mass, [1.15, -1.9, 0.55], rtol=1e-12)
    expected = m / 12 * np.diag([ly**2 + lz**2, lx**2 + lz**2, lx**2 + ly**2])
    np.testing.assert_allclose(p.inertia, expected, atol=1e-12 * m)


def test_sphere_inertia_converges_to_two_fifths_m_r_squared():
    # icosphere-like mesh from a fine latitude-longitude grid
    r, n = 0.05, 120
    theta = np.linspace(0, np.pi, n + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, 2 * n, endpoint=False)
    t, f = np.meshgrid(theta, phi, indexing="ij")
    ring = r * np.stack([np.sin(t) * np.cos(f), np.sin(t) * np.sin(f), np.cos(t)], -1).reshape(-1, 3)
    v = np.vstack([[0, 0, r], ring, [0, 0, -r]])
    m = 2 * n
    faces = [[0, 1 + j, 1 + (j + 1) % m] for j in range(m)]
    for i in range(n - 2):
        for j in range(m):
            a, b = 1 + i * m + j, 1 + i * m + (j + 1) % m
            faces += [[a, a + m, b], [b, a + m, b + m]]
    last = len(v) - 1
    base = 1 + (n - 2) * m
    faces += [[base + j, last, base + (j + 1) % m] for j in range(m)]
    mesh = TriangleMesh(v, np.array(faces))
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.euler_number == 2 and mesh.body_count == 1
    p = mesh_mass_properties(mesh.triangles)
    assert p.volume == pytest.approx(4 / 3 * np.pi * r**3, rel=1e-3)
    np.testing.assert_allclose(np.diag(p.inertia), 0.4 * p.mass * r**2, rtol=1e-3)


def test_topology_flags_catch_a_hole_and_a_flipped_face():
    mesh = box(1, 1, 1)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.euler_number == 2
    holed = TriangleMesh(mesh.vertices, mesh.faces[:-1])
    assert not holed.is_watertight
    flipped = mesh.faces.copy()
    flipped[0] = flipped[0, ::-1]
    assert TriangleMesh(mesh.vertices, flipped).is_watertight
    assert not TriangleMesh(mesh.vertices, flipped).is_winding_consistent
    two = TriangleMesh(np.vstack([mesh.vertices, mesh.vertices + 5]),
                       np.vstack([mesh.faces, mesh.faces + 8]))
    assert two.body_count == 2


def test_stl_round_trip(tmp_path):
    mesh = box(0.3, 0.2, 0.1)
    path = mesh.export(tmp_path / "box.stl")
    back = read_stl(path)
    assert len(back.faces) == 12 and len(back.vertices) == 8
    assert back.is_watertight and back.is_winding_consistent
    assert back.volume == pytest.approx(0.006, rel=1e-6)
    with open(path, "rb") as handle:
        assert not handle.read(5) == b"solid"   # binary, not ASCII STL
    (tmp_path / "short.stl").write_bytes(b"\0" * 90)
    with pytest.raises(ValueError, match="short.stl"):
        read_stl(tmp_path / "short.stl")
