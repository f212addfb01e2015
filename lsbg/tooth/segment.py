"""A segment of a gear for finite elements: a few teeth, their rim, tetrahedra.

The tooth's compliance comes from a segment of each member, not from the
whole gear (:mod:`lsbg.tooth.compliance`): the tooth the contact loads (tooth
0 of :meth:`lsbg.gear.geometry.GearPair.flank`), its neighbours on both sides, and
the body under them down to the bore, as lsbg's gear blank defines it
(:mod:`lsbg.solid.outline`: the spherical shell R_i <= |r| <= R_e, bored).

The solid is lofted through the exact section outlines of
:func:`lsbg.solid.outline.section_outline` as the STEP solids are
(:mod:`lsbg.solid.step`), cut in each gap beyond the outer teeth along the middle of
the root (so the cut follows the spiral), the root corners of tooth 0's gaps
rounded in every section with the tool edge radius rho_a0 = ``fillet_radius``
x module (:mod:`lsbg.tooth.outline`): lsbg's blank has a sharp corner where
the flank meets the root cone, at which the stress of an elastic solid is
singular and no root stress converges.

gmsh meshes it with linear tetrahedra whose size is ``tooth_size`` on the
loaded tooth, smaller on its root fillets (the root stress is read there),
and grows with the distance from them (:func:`_size_field`) to ``body_size``;
the finite elements (:mod:`lsbg.tooth.elasticity`) put quadratic shape
functions on them. The bore and both cut faces are clamped.

Lengths in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lsbg.tooth.outline import (SEGMENT_SECTIONS, distance_to_polyline, fillet_corners,
                                segment_sections)

__all__ = ["SegmentMesh", "segment_mesh", "fillet_points"]

#: Growth of the element size with the distance from tooth 0 [m per m]: the
#: size doubles one tooth size away, which keeps the tetrahedra well shaped
#: (faster growth coarsens the rim under the tooth and stiffens it).
SIZE_GROWTH = 0.5
#: The fillets' size grows this many times faster [-] (their refinement is a
#: thin tube along the face width: most of the segment's elements).
FILLET_GROWTH = 1.5


@dataclass(frozen=True)
class SegmentMesh:
    """Tetrahedral mesh of a gear segment.

    Attributes
    ----------
    nodes : numpy.ndarray, shape (3, n)
        Node coordinates in the member's mesh frame [m].
    tetrahedra : numpy.ndarray, shape (4, m)
        Node indices of the linear tetrahedra [-].
    clamped : numpy.ndarray
        Indices of the nodes on the bore and the two cut faces [-].
    member : int
        1 pinion, 2 gear.
    teeth : int
        Teeth in the segment [-].
    tooth_size, body_size : float
        Element sizes on the loaded tooth and far from it [m].
    """

    nodes: np.ndarray
    tetrahedra: np.ndarray
    clamped: np.ndarray
    member: int
    teeth: int
    tooth_size: float
    body_size: float


def _build_segment(pair, member, teeth, fillet_radius, sections):
    """The segment's solid in the current gmsh model [volume tag].

    The loft runs through :func:`segment_sections`, closed down into the bore
    and round the axis there, and one boolean with the blank trims it.
    (Lofting the whole gear and splitting the segment off with surfaces
    through the gaps cost two to three times as long in OCC's booleans, for
    the same solid.)
    """
    import gmsh

    from lsbg.gear.vectors import rotate

    occ = gmsh.model.occ
    d = pair.design
    r_in, r_out = d.inner_cone_distance, d.outer_cone_distance
    radii, outlines = segment_sections(pair, member, teeth, fillet_radius, sections)
    axis, forward = pair.axis[member], pair.rotation_axis[member]
    root = d.root_angle(member)
    bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    # the outline, so the segment, runs in increasing azimuth about the rotation axis
    polar = np.linspace(root, 0.5 * math.asin(bore / radii[-1]), 5)
    wires = []
    for k, pieces in enumerate(outlines):
        curves, first, last = [], None, None
        for piece in pieces:  # consecutive pieces share their end points
            tags = [last or occ.addPoint(*piece[0])] + [occ.addPoint(*q) for q in piece[1:]]
            curves.append(occ.addSpline(tags))
            first, last = first or tags[0], tags[-1]
        start, end = pieces[0][0], pieces[-1][-1]
        turn = float(pair.azimuth(member, end) - pair.azimuth(member, start)) % (2 * math.pi)
        # the sides: from the middle of the outer gaps' roots down into the bore,
        # in the axial half-planes through them (so they follow the spiral from
        # section to section); an arc about the axis inside the bore closes the section
        sides = []
        for point in (end, start):
            radial = point - (point @ axis) * axis
            radial /= np.linalg.norm(radial)
            sides.append(radii[k] * (np.cos(polar)[:, None] * axis
                                     + np.sin(polar)[:, None] * radial))
        down = [last] + [occ.addPoint(*q) for q in sides[0][1:]]
        up = [occ.addPoint(*q) for q in sides[1][:0:-1]] + [first]
        curves.append(occ.addSpline(down))
        centre = occ.addPoint(*(radii[k] * math.cos(polar[-1]) * axis))
        previous = down[-1]
        for j in (1, 2):
            point = occ.addPoint(*rotate(sides[0][-1], forward, -turn * j / 3))
            curves.append(occ.addCircleArc(previous, centre, point))
            previous = point
        curves.append(occ.addCircleArc(previous, centre, up[0]))
        curves.append(occ.addSpline(up))
        wires.append(occ.addWire(curves))
    body = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    # the blank: the spherical shell R_i <= |r| <= R_e, bored (from simple
    # solids first: one boolean with the lofted body, the costly kind)
    outer, inner = occ.addSphere(0, 0, 0, r_out), occ.addSphere(0, 0, 0, r_in)
    cylinder = occ.addCylinder(0, 0, 0, *(axis * 2 * r_out), bore)
    blank, _ = occ.cut([(3, outer)], [(3, inner), (3, cylinder)])
    pieces, _ = occ.intersect(body, blank)
    occ.synchronize()
    # keep the piece that holds tooth 0
    lo, hi = pair.flank_polar_range(member)
    flank, normal = pair.flank(member, "drive", d.mean_cone_distance, 0.5 * (lo + hi))
    volumes = [t for dim, t in pieces if dim == 3]
    keep = [t for t in volumes
            if gmsh.model.isInside(3, t, list(flank - 2e-4 * normal)) or
            gmsh.model.isInside(3, t, list(flank + 2e-4 * normal))]
    if len(keep) != 1:
        raise RuntimeError(f"the segment came out as {len(keep)} volumes holding tooth 0")
    occ.remove([(dim, t) for dim, t in occ.getEntities() if dim == 3 and t != keep[0]],
               recursive=True)
    occ.remove([(2, t) for _, t in occ.getEntities(2)
                if t not in [abs(f) for _, f in gmsh.model.getBoundary([(3, keep[0])],
                                                                       oriented=False)]])
    occ.synchronize()
    return keep[0]


def _clamped_surfaces(pair, member, volume):
    """Surfaces of the bore and of the two cut faces [surface tags].

    The bore is the cylinder |r x a| = bore / 2; the cut faces are the
    surfaces that reach the bore and are not spheres or the cylinder itself
    (the tooth surfaces end at the root, far above the bore).
    """
    import gmsh

    d = pair.design
    axis = pair.axis[member]
    bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    clamped = []
    for _, surface in gmsh.model.getBoundary([(3, volume)], oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(2, surface)
        u, v = np.meshgrid(np.linspace(lo[0], hi[0], 7), np.linspace(lo[1], hi[1], 7))
        points = np.reshape(gmsh.model.getValue(2, surface, np.column_stack(
            [u.ravel(), v.ravel()]).ravel()), (-1, 3))
        off_axis = np.linalg.norm(np.cross(points, axis), axis=1)
        radius = np.linalg.norm(points, axis=1)
        if np.allclose(off_axis, bore, rtol=1e-6, atol=1e-9):
            clamped.append(surface)
        elif np.ptp(radius) > 1e-6 * radius.max() and off_axis.min() < bore * (1 + 1e-6):
            clamped.append(surface)
    return clamped


def _fillet_surfaces(pair, member, volume, fillet_radius):
    """Surfaces of the segment that round tooth 0's root corners [surface tags].

    A fillet surface lies wholly within about one fillet radius of its
    corner line; the flanks, the root and the end faces reach far beyond it.

    Returns
    -------
    list of list of int
        The drive side's surfaces, then the coast side's.
    """
    import gmsh

    corners = fillet_corners(pair, member, margin=0.2 * pair.design.face_width)
    found = [[], []]
    for _, surface in gmsh.model.getBoundary([(3, volume)], oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(2, surface)
        u, v = np.meshgrid(np.linspace(lo[0], hi[0], 5), np.linspace(lo[1], hi[1], 5))
        points = np.reshape(gmsh.model.getValue(2, surface, np.column_stack(
            [u.ravel(), v.ravel()]).ravel()), (-1, 3))
        for side, line in enumerate(corners):
            if np.all(distance_to_polyline(points, line) < 1.5 * fillet_radius):
                found[side].append(abs(surface))
    return found


def _tooth_centre(pair, member):
    """Frame about the axis centred on tooth 0, and its centre's azimuth by cone distance.

    Returns
    -------
    across, other : numpy.ndarray, shape (3,)
        Unit vectors normal to the axis: towards tooth 0's middle at the mean
        cone distance, and a quarter turn on about the rotation axis.
    coefficients : numpy.ndarray, shape (4,)
        Cubic in the cone distance [m] of the azimuth of tooth 0's middle
        from ``across`` [rad] (a spiral tooth turns across the face width by
        more than a gear's pitch).
    """
    d = pair.design
    axis = pair.rotation_axis[member]
    polar = d.pitch_angle(member)
    rho = np.linspace(d.inner_cone_distance, d.outer_cone_distance, 9)
    middle = 0.5 * sum(pair.flank(member, side, rho, np.full(rho.size, polar))[0]
                       for side in ("drive", "coast"))
    centre = middle[rho.size // 2] - (middle[rho.size // 2] @ axis) * axis
    across = centre / np.linalg.norm(centre)
    other = np.cross(axis, across)
    azimuth = np.unwrap(np.arctan2(middle @ other, middle @ across))
    return across, other, np.polyfit(rho, azimuth, 3)[::-1]


def _size_field(pair, member, volume, sizes, fillet_radius, growth):
    """Background size field of the segment's mesh [field tag].

    The smallest of

    * ``tooth`` on tooth 0 and the half gaps beside it, growing by ``growth``
      times the distance from there (sideways round the axis into the
      neighbouring teeth, and down below the root cone into the rim) up to
      ``body``: the neighbours are read only at their middle surface, which
      the rim carries, and the rim and the bore carry smooth, small strains;
    * ``fillet`` on tooth 0's root fillets, growing at the same rate to
      ``tooth``: the root stress is read there, and the stress of a quadratic
      field converges only with elements of a fraction of the fillet's radius.
    """
    import gmsh

    d = pair.design
    field = gmsh.model.mesh.field
    a = pair.axis[member]
    across, other, c = _tooth_centre(pair, member)
    pitch = 2 * math.pi / d.teeth[member - 1]
    r = "sqrt(x*x+y*y+z*z)"

    def dot(v):
        return f"(({v[0]:.17g})*x+({v[1]:.17g})*y+({v[2]:.17g})*z)"

    polar = f"acos({dot(a)}/{r})"
    below = f"max(0, ({d.root_angle(member):.17g} - {polar}) * {r})"
    centre = f"({c[0]:.17g}+{r}*({c[1]:.17g}+{r}*({c[2]:.17g}+{r}*({c[3]:.17g}))))"
    # azimuth from tooth 0's middle (gmsh's expressions have no atan2; the
    # segment lies within a quarter turn of tooth 0, where the component along
    # ``across`` is positive), and the arc beyond the middle of its gaps
    azimuth = f"atan({dot(other)} / max({dot(across)}, 1e-9 * {r}))"
    side = f"max(0, abs({azimuth} - {centre}) - {0.5 * pitch:.17g}) * {r} * sin({polar})"
    away = f"sqrt(({side})^2 + ({below})^2)"
    cone = field.add("MathEval")
    field.setString(cone, "F", f"min({sizes['body']:.17g}, {sizes['tooth']:.17g} + "
                               f"{growth:.17g} * {away})")
    fields = [cone]
    surfaces = _fillet_surfaces(pair, member, volume, fillet_radius)
    for side, key in enumerate(("fillet", "coast_fillet")):
        if sizes[key] >= sizes["tooth"]:
            continue
        if len(surfaces[side]) != 1:
            raise RuntimeError(f"found {len(surfaces[side])} root fillet surfaces on tooth 0's "
                               f"{('drive', 'coast')[side]} side, not 1")
        distance = field.add("Distance")
        field.setNumbers(distance, "SurfacesList", surfaces[side])
        # samples closer than the fillet's elements (its length runs across the face)
        field.setNumber(distance, "Sampling", int(min(400, 4 * d.face_width / sizes[key])))
        threshold = field.add("Threshold")
        field.setNumber(threshold, "InField", distance)
        field.setNumber(threshold, "SizeMin", sizes[key])
        field.setNumber(threshold, "SizeMax", sizes["tooth"])
        field.setNumber(threshold, "DistMin", 0.5 * sizes[key])
        field.setNumber(threshold, "DistMax", 0.5 * sizes[key]
                        + (sizes["tooth"] - sizes[key]) / (FILLET_GROWTH * growth))
        # beyond DistMax the threshold imposes nothing (else its SizeMax would cap the body)
        field.setNumber(threshold, "StopAtDistMax", 1)
        fields.append(threshold)
    smallest = field.add("Min")
    field.setNumbers(smallest, "FieldsList", fields)
    return smallest


def segment_mesh(pair, member, tooth_size, body_size=None, teeth=3, fillet_radius=0.25,
                 sections=SEGMENT_SECTIONS, fillet_size=None, coast_fillet_size=None,
                 growth=None):
    """Mesh a segment of a member with tetrahedra.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    tooth_size : float
        Element size on the loaded tooth (tooth 0) [m].
    body_size : float, optional
        Largest element size, in the rim far from tooth 0 [m]; default
        3 x ``tooth_size``.
    teeth : int
        Teeth in the segment, odd, at least 3 [-].
    fillet_radius : float
        Root fillet radius as a multiple of the mean normal module, the tool
        edge radius rho_a0 / m_mn [-] (0.2-0.3 in practice).
    sections : int
        Sections of the loft [-].
    fillet_size : float, optional
        Element size on tooth 0's drive-side root fillet [m], where the drive
        flank's loads pull; default ``tooth_size`` (no refinement).
    coast_fillet_size : float, optional
        Element size on tooth 0's coast-side root fillet [m], in compression
        under those loads; default ``fillet_size``.
    growth : float, optional
        Growth of the element size with the distance from tooth 0 and its
        fillets [-]; default ``SIZE_GROWTH``.

    Returns
    -------
    SegmentMesh

    Raises
    ------
    ValueError
        For an even or too small number of teeth, or sizes that are not
        positive.
    """
    from lsbg.solid.step import _gmsh

    if isinstance(teeth, bool) or int(teeth) != teeth or teeth < 3 or teeth % 2 == 0:
        raise ValueError(f"teeth = {teeth!r}: the segment needs an odd number >= 3 of teeth")
    body_size = 3.0 * tooth_size if body_size is None else body_size
    fillet_size = tooth_size if fillet_size is None else fillet_size
    coast_fillet_size = fillet_size if coast_fillet_size is None else coast_fillet_size
    growth = SIZE_GROWTH if growth is None else growth
    for name, value in (("tooth_size", tooth_size), ("body_size", body_size),
                        ("fillet_radius", fillet_radius), ("fillet_size", fillet_size),
                        ("coast_fillet_size", coast_fillet_size), ("growth", growth)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r}: must be a positive number")
    sizes = {"tooth": tooth_size, "body": max(body_size, tooth_size),
             "fillet": min(fillet_size, tooth_size),
             "coast_fillet": min(coast_fillet_size, tooth_size)}
    gmsh, started = _gmsh()
    try:
        gmsh.model.add(f"lsbg_segment_{member}")
        radius = fillet_radius * pair.design.mean_module * math.cos(pair.design.spiral_angle)
        volume = _build_segment(pair, member, int(teeth), radius, sections)
        clamped = _clamped_surfaces(pair, member, volume)
        gmsh.model.mesh.field.setAsBackgroundMesh(
            _size_field(pair, member, volume, sizes, radius, growth))
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)  # HXT: fast, deterministic
        # optimise only tetrahedra of quality below 0.15, not 0.3: the optimiser is most
        # of a 7-tooth segment's meshing time; the worst elements come out the same
        gmsh.option.setNumber("Mesh.OptimizeThreshold", 0.15)
        gmsh.option.setNumber("General.NumThreads", 1)
        # the curves' element sizes by integrating the size field to 1e-5, not
        # 1e-9: the same meshes, a second less per member
        gmsh.option.setNumber("Mesh.LcIntegrationPrecision", 1e-5)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
        index[tags.astype(np.int64)] = np.arange(tags.size)
        nodes = coords.reshape(-1, 3).T.copy()
        types, _, element_nodes = gmsh.model.mesh.getElements(3, volume)
        tets = [n for t, n in zip(types, element_nodes) if t == 4]
        tetrahedra = index[np.concatenate(tets).astype(np.int64)].reshape(-1, 4).T.copy()
        fixed = []
        for surface in clamped:
            surface_nodes, _, _ = gmsh.model.mesh.getNodes(2, surface, includeBoundary=True)
            fixed.append(index[surface_nodes.astype(np.int64)])
        gmsh.model.remove()
    finally:
        if started:
            gmsh.finalize()
    used = np.unique(tetrahedra)
    if used.size != nodes.shape[1]:  # nodes of removed construction geometry
        renumber = np.full(nodes.shape[1], -1)
        renumber[used] = np.arange(used.size)
        nodes, tetrahedra = nodes[:, used], renumber[tetrahedra]
        fixed = [renumber[f][renumber[f] >= 0] for f in fixed]
    return SegmentMesh(nodes=nodes, tetrahedra=tetrahedra,
                       clamped=np.unique(np.concatenate(fixed)) if fixed else np.empty(0, int),
                       member=int(member), teeth=int(teeth), tooth_size=float(tooth_size),
                       body_size=float(body_size))


def fillet_points(pair, member, segment_mesh, fillet_radius):
    """Points on the root fillets of tooth 0, both sides, and the tetrahedra around them.

    The fillet rounds the corner where the flank (or its radial continuation)
    meets the root cone; its surface lies within one fillet radius of that
    corner line. Its boundary vertices are the points, and on the drive side
    (the loaded flank's, in tension) also the middles of the boundary edges
    between them that run across the fillet: the quadratic field's other
    nodes, which halve the spacing of the points round the fillet's arc,
    where the stress peaks between a few rows of vertices. Points within 2 %
    of the face width of the toe and heel are left out (the end faces' edges).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    segment_mesh : SegmentMesh
    fillet_radius : float
        [m].

    Returns
    -------
    points : numpy.ndarray, shape (q, 3)
    cells : numpy.ndarray, shape (c,)
        Every tetrahedron that holds a point as a vertex or on an edge: the
        stress of the quadratic field jumps between them, and their mean is
        the point's stress (less dependent on which element one picks).
    owner : numpy.ndarray, shape (c,)
        The point of each of ``cells`` [-].
    side : numpy.ndarray, shape (q,)
        0 drive, 1 coast.
    cone_distance : numpy.ndarray, shape (q,)
    """
    d = pair.design
    nodes, tets = segment_mesh.nodes, segment_mesh.tetrahedra
    # boundary faces: those of one tetrahedron
    faces = np.sort(np.concatenate([tets[[0, 1, 2]], tets[[0, 1, 3]], tets[[0, 2, 3]],
                                    tets[[1, 2, 3]]], axis=1), axis=0)
    unique, counts = np.unique(faces, axis=1, return_counts=True)
    faces = unique[:, counts == 1]
    boundary = np.unique(faces)
    x = nodes[:, boundary].T
    radius = np.linalg.norm(x, axis=1)
    margin = 0.02 * d.face_width
    keep = (radius > d.inner_cone_distance + margin) & (radius < d.outer_cone_distance - margin)
    side = np.full(nodes.shape[1], -1)
    corners = fillet_corners(pair, member)
    for s, corner in enumerate(corners):
        near = keep & (distance_to_polyline(x, corner) < 1.05 * fillet_radius)
        side[boundary[near & (side[boundary] < 0)]] = s
    vertices = np.flatnonzero(side >= 0)
    # drive-side boundary edges across the fillet (more than 45 deg from its
    # corner line): both ends on the drive fillet
    edges = np.sort(np.concatenate([faces[[0, 1]], faces[[0, 2]], faces[[1, 2]]], axis=1), axis=0)
    edges = np.unique(edges[:, (side[edges[0]] == 0) & (side[edges[1]] == 0)], axis=1)
    along = np.diff(corners[0], axis=0)
    along /= np.linalg.norm(along, axis=1, keepdims=True)
    middle = 0.5 * (nodes[:, edges[0]] + nodes[:, edges[1]]).T
    nearest = np.argmin(np.linalg.norm(middle[:, None] - corners[0][None, :-1], axis=2), axis=1)
    direction = (nodes[:, edges[1]] - nodes[:, edges[0]]).T
    cosine = np.abs(np.sum(direction * along[nearest], axis=1)) / np.linalg.norm(direction, axis=1)
    edges = edges[:, cosine < math.cos(math.radians(45))]
    middles = 0.5 * (nodes[:, edges[0]] + nodes[:, edges[1]]).T
    points = np.concatenate([nodes[:, vertices].T, middles])
    # the tetrahedra round each vertex, then round each edge (holding both its ends)
    point = np.full(nodes.shape[1], -1)
    point[vertices] = np.arange(vertices.size)
    owner = point[tets]  # (4, m)
    corner, cells = np.nonzero(owner >= 0)
    owner = [owner[corner, cells]]
    cells = [cells]
    n = nodes.shape[1]
    key = {int(a) * n + int(b): i for i, (a, b) in enumerate(edges.T)}
    for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):
        a, b = np.minimum(tets[i], tets[j]), np.maximum(tets[i], tets[j])
        hit = np.flatnonzero((side[a] == 0) & (side[b] == 0))
        found = np.array([key.get(int(k), -1) for k in a[hit] * n + b[hit]], dtype=np.int64)
        cells.append(hit[found >= 0])
        owner.append(vertices.size + found[found >= 0])
    return (points, np.concatenate(cells), np.concatenate(owner),
            np.concatenate([side[vertices], np.zeros(edges.shape[1], int)]),
            np.linalg.norm(points, axis=1))
