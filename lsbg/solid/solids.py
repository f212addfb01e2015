"""Solid gears from the exact flanks: closed triangle meshes.

Each gear is the solid between two spheres about the apex (the toe at the
inner cone distance R_i and the heel at the outer cone distance R_e), the
toothed surface and a coaxial bore cylinder. Its mesh lofts the section
outlines of :mod:`lsbg.solid.outline` between spheres, closes the ends on the
toe and heel spheres from the tooth outline down to the bore circle, and adds
the bore (:func:`gear_mesh`); every vertex lies on the exact surfaces
(DESIGN.md §1: solids feed the mass properties, :mod:`lsbg.solid.mass`, and
the URDF, :mod:`lsbg.solid.urdf`; contact comes from the exact geometry, never
from these meshes).

Coordinates on a member's spheres are those of the outlines: the polar angle
theta from the axis and the azimuth phi about the forward rotation axis
(:func:`lsbg.gear.flank.sphere_points`).

All lengths in metres, angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.gear.flank import sphere_points
from lsbg.gear.geometry import MEMBERS, MEMBER_NAMES
from lsbg.solid.outline import DEFAULT_RESOLUTION, section_cone_distances, section_outline
from lsbg.solid.polyhedra import TriangleMesh

__all__ = ["gear_mesh", "gear_meshes"]


# ------------------------------------------------------------------ meshing
def _zip(index_a, phi_a, index_b, phi_b):
    """Triangles between two closed loops ordered by increasing azimuth.

    Loop a must lie nearer to the axis than loop b (smaller polar angle).
    The result is counter-clockwise in the (azimuth, polar angle) chart.

    Parameters
    ----------
    index_a, phi_a : numpy.ndarray, shape (na,)
        Vertex indices and azimuths [rad] of loop a, azimuth increasing over one turn.
    index_b, phi_b : numpy.ndarray, shape (nb,)
        The same for loop b.

    Returns
    -------
    numpy.ndarray, shape (na + nb, 3)
    """
    phi_a = phi_a[0] + np.mod(phi_a - phi_a[0], 2 * np.pi)
    # Start loop b at its first vertex at or after a's start.
    rel_b = np.mod(phi_b - phi_a[0], 2 * np.pi)
    first = int(np.argmin(rel_b))
    index_b, rel_b = np.roll(index_b, -first), np.roll(rel_b, -first)
    rel_a = phi_a - phi_a[0]
    na, nb = index_a.size, index_b.size
    # Close both loops: vertex n is vertex 0 one turn later.
    ia = np.append(index_a, index_a[0])
    ib = np.append(index_b, index_b[0])
    keys = np.concatenate([np.append(rel_a[1:], 2 * np.pi),
                           np.append(rel_b[1:], 2 * np.pi + rel_b[0])])
    is_a = np.concatenate([np.ones(na, bool), np.zeros(nb, bool)])
    order = np.argsort(keys, kind="stable")
    step_a = is_a[order]
    i_after = np.cumsum(step_a)
    j_after = np.cumsum(~step_a)
    i0, j0 = i_after - step_a, j_after - ~step_a
    faces = np.where(step_a[:, None],
                     np.stack([ia[i0], ia[np.minimum(i0 + 1, na)], ib[j0]], axis=1),
                     np.stack([ia[i0], ib[np.minimum(j0 + 1, nb)], ib[j0]], axis=1))
    return faces


def _line_starts(azimuth):
    """Indices where a run of equal azimuths (one meridian line) starts [-]."""
    return np.flatnonzero(np.diff(azimuth, prepend=np.nan) != 0)


def _chain_zip(vertex, polar, left_start, left_count, right_start, right_count):
    """Triangles between pairs of meridian chains (left at the smaller azimuth), pair by pair.

    Each chain runs up from the root in polar angle. Within a pair the steps
    up either chain are taken in order of the polar angle they reach (left
    first on ties), each step one triangle; the result is counter-clockwise
    in the (azimuth, polar angle) chart, like :func:`_zip`. All pairs are
    zipped at once: a call per pair (~1500 per gear) is much slower.

    Parameters
    ----------
    vertex, polar : numpy.ndarray, shape (n,)
        Vertex indices and polar angles [rad] of all chains end to end; the
        polar angle never decreases along a chain.
    left_start, left_count, right_start, right_count : numpy.ndarray of int, shape (k,)
        Position in ``vertex`` of each pair's left and right chain and their
        vertex counts (at least 1 each) [-].

    Returns
    -------
    numpy.ndarray, shape (sum(left_count + right_count - 2), 3)
        The faces of pair 0, then pair 1, ...
    """
    def steps(count):  # (pair, position of the step's upper vertex 1 ... count - 1)
        owner = np.repeat(np.arange(count.size), count - 1)
        first = np.cumsum(count - 1) - (count - 1)
        return owner, np.arange(owner.size) - first[owner] + 1

    pair_l, pos_l = steps(left_count)
    pair_r, pos_r = steps(right_count)
    pair, pos = np.concatenate([pair_l, pair_r]), np.concatenate([pos_l, pos_r])
    is_left = np.arange(pair.size) < pair_l.size
    key = polar[np.where(is_left, left_start[pair], right_start[pair]) + pos]
    # Stable: ties go to the left chain (listed first), then up the chain.
    order = np.lexsort((key, pair))
    pair, pos, is_left = pair[order], pos[order], is_left[order]
    per_pair = left_count + right_count - 2
    rank = np.arange(pair.size) - (np.cumsum(per_pair) - per_pair)[pair]
    # Steps already taken up the left (i) and right (j) chain before this one.
    i0 = np.where(is_left, pos - 1, rank - (pos - 1))
    j0 = np.where(is_left, rank - (pos - 1), pos - 1)
    lower_left, lower_right = left_start[pair] + i0, right_start[pair] + j0
    third = np.where(is_left, lower_left + 1, lower_right + 1)
    return np.stack([vertex[lower_left], vertex[lower_right], vertex[third]], axis=1)


def _tooth_region(index, polar, azimuth, root, step, new_points):
    """Triangulate an end face between the root circle and the tooth outline.

    The region {root <= theta <= theta_out(phi)} is cut along meridians
    through the outline vertices into columns; each meridian gets vertices
    at the root and every ``step`` up to the outline, and neighbouring
    meridians are zipped in polar angle. (A plain zip between the outline and
    a ring below it would fold over the radial flank continuation.)

    Parameters
    ----------
    index, polar, azimuth : numpy.ndarray, shape (m,)
        Outline vertex indices, polar angles and (increasing) azimuths [rad].
    root : float
        Root angle [rad].
    step : float
        Largest vertical edge [rad].
    new_points : callable
        ``new_points(theta, phi) -> indices`` adds vertices.

    Returns
    -------
    bottom : numpy.ndarray
        Vertex indices on the root circle, one per meridian, by azimuth.
    faces : numpy.ndarray, shape (k, 3)
    """
    starts = _line_starts(azimuth)
    ends = np.append(starts[1:], index.size)
    n_lines = starts.size
    line = np.repeat(np.arange(n_lines), ends - starts)
    # Levels below the lowest outline vertex of each meridian, unless it is on the root.
    lowest = np.minimum.reduceat(polar, starts)
    rise = lowest - root
    count = np.where(np.isclose(lowest, root, rtol=0, atol=1e-12), 0,
                     np.maximum(np.ceil(rise / step), 0)).astype(np.int64)
    owner = np.repeat(np.arange(n_lines), count)
    level = np.arange(owner.size) - (np.cumsum(count) - count)[owner]
    # Same operations, in the same order, as root + rise * arange(n) / n per meridian.
    new_theta = root + rise[owner] * level / count[owner]
    added = new_points(new_theta, azimuth[starts][owner])
    # Each meridian's chain: its new levels, then its outline vertices, sorted
    # by polar angle (stable, so new levels first on ties).
    theta = np.concatenate([new_theta, polar])
    chain_line = np.concatenate([owner, line])
    order = np.lexsort((theta, chain_line))
    chains, chain_polar, chain_line = (np.concatenate([added, index])[order], theta[order],
                                       chain_line[order])
    size = count + (ends - starts)
    first = np.cumsum(size) - size
    # Column g joins meridian g (up to the outline vertex that leaves it) to
    # meridian h = g + 1 (up to the one that enters it); chains are sorted, so
    # these are prefixes.
    below = (chain_polar <= polar[ends - 1][chain_line],
             chain_polar <= polar[starts][chain_line])
    left_count, right_count = (np.add.reduceat(b.astype(np.int64), first) for b in below)
    faces = _chain_zip(chains, chain_polar, first, left_count,
                       np.roll(first, -1), np.roll(right_count, -1))
    return chains[first], faces


def _quads(first, second, points=None, period=None):
    """Two triangles per quad between two closed rows of vertex indices.

    Parameters
    ----------
    first, second : numpy.ndarray, shape (n,)
        Vertex indices of the rows; quad i is first[i], first[i+1],
        second[i+1], second[i].
    points : numpy.ndarray, optional
        Vertex positions [m]. If given, each quad is split along its shorter
        diagonal, which follows a twisted surface (the spiral teeth) more
        closely; otherwise always along first[i] - second[i+1].
    period : int, optional
        Quads repeat with this period (one tooth): the choice made on the
        first period is copied, so that rounding cannot break the gear's
        symmetry.

    Returns
    -------
    numpy.ndarray, shape (2 n, 3)
    """
    a, b = first, second
    a1, b1 = np.roll(a, -1), np.roll(b, -1)
    split = np.ones(a.size, bool)
    if points is not None:
        n = a.size if period is None else period
        split = np.resize(np.linalg.norm(points[a[:n]] - points[b1[:n]], axis=1)
                          <= np.linalg.norm(points[a1[:n]] - points[b[:n]], axis=1), a.size)
    one = np.where(split[:, None], np.stack([a, a1, b1], axis=1), np.stack([a, a1, b], axis=1))
    two = np.where(split[:, None], np.stack([a, b1, b], axis=1), np.stack([a1, b1, b], axis=1))
    return np.concatenate([one, two])


def _orient(vertices, faces, outward):
    """Flip a patch whose area-weighted normals point against ``outward(centroids)``."""
    tri = vertices[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    if np.sum(normals * outward(tri.mean(axis=1))) < 0:
        return faces[:, ::-1]
    return faces


def gear_mesh(pair, member, resolution=DEFAULT_RESOLUTION):
    """Watertight triangle mesh of one gear (teeth, hub and bore).

    The section outlines (:func:`section_outline`, including the radial flank
    continuation below a base cone that lies above the root cone) are lofted
    between the toe and heel spheres; the end faces on those spheres run from
    the tooth outline down to the root circle along meridians, then through
    rings of constant polar angle to the bore circle; the bore is a polygonal
    cylinder of diameter ``pinion_bore`` / ``gear_bore`` coaxial with the axis.
    All vertices lie on the exact surfaces. The mesh is in the mesh frame at
    rotation 0 (tooth 0 as :meth:`lsbg.gear.geometry.GearPair.flank`).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    resolution : lsbg.solid.outline.MeshResolution

    Returns
    -------
    lsbg.solid.polyhedra.TriangleMesh
        Watertight, consistently wound, outward normals [m]. ``metadata``
        holds ``member``, ``name`` and ``sections``.
    """
    d = pair.design
    z = d.teeth[member - 1]
    a = pair.axis[member]
    bore_radius = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    root = d.root_angle(member)
    radii = section_cone_distances(pair, member, resolution)
    outline = section_outline(pair, member, radii, resolution)
    n_sec, m = outline.azimuth.shape

    vertices = [outline.points.reshape(-1, 3)]
    count = n_sec * m
    rows = np.arange(count).reshape(n_sec, m)
    flat = outline.points.reshape(-1, 3)
    faces = {"lateral": np.concatenate([_quads(rows[k], rows[k + 1], flat, outline.per_tooth)
                                        for k in range(n_sec - 1)])}

    def add(points):
        nonlocal count
        vertices.append(points)
        index = np.arange(count, count + len(points))
        count += len(points)
        return index

    # Bore circles: the same azimuths on both spheres, so the cylinder is quads.
    n_bore = z * max(resolution.bore_points_per_tooth,
                     int(math.ceil(2 * np.pi / resolution.end_face_step / z)))
    phi_bore = 2 * np.pi * (np.arange(n_bore) + 0.5) / n_bore
    bore_rows = {}
    end_faces = {}
    for end, k in (("inner", 0), ("outer", n_sec - 1)):
        radius = radii[k]
        theta_bore = math.asin(bore_radius / radius)
        bore_rows[end] = add(sphere_points(pair, member, radius, theta_bore, phi_bore))
        # Rings of constant polar angle between the bore and the root cone.
        n_rings = int(math.ceil((root - theta_bore) / resolution.end_face_step))
        loops = [(bore_rows[end], phi_bore)]
        for theta in np.linspace(theta_bore, root, n_rings + 1)[1:-1]:
            n_ring = z * max(1, int(math.ceil(2 * np.pi * math.sin(theta)
                                              / resolution.end_face_step / z)))
            phi = 2 * np.pi * (np.arange(n_ring) + 0.5) / n_ring
            loops.append((add(sphere_points(pair, member, radius, theta, phi)), phi))
        bottom, columns = _tooth_region(
            rows[k], outline.polar_angle[k], outline.azimuth[k], root,
            resolution.end_face_step,
            lambda theta, phi: add(sphere_points(pair, member, radius, theta, phi)))
        loops.append((bottom, outline.azimuth[k][_line_starts(outline.azimuth[k])]))
        end_faces[end] = np.concatenate([_zip(ia, pa, ib, pb)
                                         for (ia, pa), (ib, pb) in zip(loops[:-1], loops[1:])]
                                        + [columns])
    faces["bore"] = _quads(bore_rows["inner"], bore_rows["outer"])
    vertices = np.concatenate(vertices)

    def radial(c):  # away from the axis
        r = c - (c @ a)[:, None] * a
        return r / np.linalg.norm(r, axis=1, keepdims=True)

    def spherical(c):
        return c / np.linalg.norm(c, axis=1, keepdims=True)

    def polar(c):  # towards larger polar angle: out of the root and tip cones
        r = spherical(c)
        cos = r @ a
        return cos[:, None] * radial(c) - np.sqrt(1 - cos**2)[:, None] * a

    outward = {"lateral": polar, "bore": lambda c: -radial(c),
               "inner": lambda c: -spherical(c), "outer": spherical}
    faces.update(end_faces)
    all_faces = np.concatenate([_orient(vertices, f, outward[name]) for name, f in faces.items()])
    mesh = TriangleMesh(vertices, all_faces,
                        metadata={"member": member, "name": MEMBER_NAMES[member],
                                  "sections": n_sec})
    return mesh


def gear_meshes(pair, resolution=DEFAULT_RESOLUTION):
    """Meshes of both members, ``{1: pinion, 2: gear}`` (see :func:`gear_mesh`)."""
    return {member: gear_mesh(pair, member, resolution) for member in MEMBERS}
