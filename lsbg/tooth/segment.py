"""A segment of a gear for finite elements: a few teeth, their rim, tetrahedra.

The tooth's compliance comes from a segment of each member, not from the
whole gear (:mod:`lsbg.tooth.compliance`): the tooth the contact loads (tooth
0 of :meth:`lsbg.geometry.GearPair.flank`), its neighbours on both sides, and
the body under them down to the bore, as lsbg's gear blank defines it
(:mod:`lsbg.solids`: the spherical shell R_i <= |r| <= R_e, bored).

The solid is lofted through the exact section outlines of
:func:`lsbg.solids.section_outline` as the STEP solids are
(:mod:`lsbg.step`), cut in each gap beyond the outer teeth along the middle of
the root (so the cut follows the spiral), and its root corners are rounded
with the tool edge radius rho_a0 = ``fillet_radius`` x module: lsbg's
blank has a sharp corner where the flank meets the root cone, at which the
stress of an elastic solid is singular and no root stress converges.

gmsh meshes it with linear tetrahedra whose size is ``tooth_size`` on the
loaded tooth and its fillets and grows to ``body_size`` away from them; the
finite elements (:mod:`lsbg.tooth.elasticity`) put quadratic shape functions
on them. The bore and both cut faces are clamped.

Lengths in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SegmentMesh", "segment_mesh", "tooth_zero_column"]

#: Sections of the loft across the face width (and beyond it) [-].
SEGMENT_SECTIONS = 7


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


def tooth_zero_column(pair, member, outline, section):
    """Outline tooth that holds tooth 0's flanks on one section [-].

    :meth:`lsbg.geometry.GearPair.flank` gives the flanks of tooth 0; the
    outline counts its teeth from its own start. The tooth whose azimuth span
    (low-flank root to the next tooth's) contains tooth 0's drive flank at the
    middle of its profile is tooth 0.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    outline : lsbg.solids.SectionOutline
    section : int
        Row of the outline to look on [-].

    Returns
    -------
    int
        Index j of the outline's tooth (columns j * per_tooth ...).
    """
    z = pair.design.teeth[member - 1]
    lo, hi = pair.flank_polar_range(member)
    point, _ = pair.flank(member, "drive", outline.cone_distance[section], 0.5 * (lo + hi))
    start = outline.azimuth[section, 0]
    offset = (float(pair.azimuth(member, point)) - start) % (2 * math.pi)
    return int(offset // (2 * math.pi / z)) % z


def _segment_runs(outline, tooth, teeth, n_top, n_root):
    """Column runs of the segment's open outline, and its root corners.

    The outline is cut in the middle of the root arcs before the first and
    after the last tooth; each run is one smooth piece (root arc, flank, top
    land), sharing end columns with its neighbours.

    Returns
    -------
    runs : list of list of int
        Outline columns, in order, of each piece.
    corners : list of int
        Positions (in the open outline) of the flank-root corners.
    """
    n = outline.per_tooth
    total = outline.points.shape[1]
    side = (n - n_top - n_root) // 2
    half = (teeth - 1) // 2
    first_tooth = tooth - half
    # middle of the root arc of the tooth before the first (its arc runs from
    # its high flank's root to the first tooth's low flank's root)
    root_start = 2 * side + n_top - 1
    middle = root_start + (n_root + 1) // 2
    start = (first_tooth - 1) * n + middle
    stop = (first_tooth + teeth - 1) * n + middle
    columns = np.arange(start, stop + 1)
    # piece boundaries of every tooth, relative to the tooth's first column
    boundaries = {0, side - 1, side + n_top, root_start}
    cuts = [i for i, c in enumerate(columns) if (c % n) in boundaries]
    corners = [i for i, c in enumerate(columns) if (c % n) in (0, root_start)]
    marks = sorted(set([0, *cuts, columns.size - 1]))
    runs = [[int(columns[i]) % total for i in range(a, b + 1)] for a, b in zip(marks[:-1], marks[1:])]
    return runs, corners


def _build_segment(pair, member, teeth, fillet_radius, sections):
    """The segment's solid in the current gmsh model [volume tag].

    The loft runs through the segment's teeth and closes each section with the
    root circle around the rest of the gear (a toothless ring lofts as
    reliably as the whole gear and costs a few teeth); after the root corners
    are rounded and the blank is cut, two surfaces through the middle of the
    outer gaps split the segment off.
    """
    import gmsh

    from lsbg.step import loft_sections
    from lsbg.vectors import rotate

    occ = gmsh.model.occ
    d = pair.design
    r_in, r_out = d.inner_cone_distance, d.outer_cone_distance
    outline, n_top, n_root = loft_sections(pair, member, sections)
    radii = outline.cone_distance
    tooth = tooth_zero_column(pair, member, outline, sections // 2)
    runs, corners = _segment_runs(outline, tooth, teeth, n_top, n_root)
    segment_columns = [c for run in runs for c in run[:-1]] + [runs[-1][-1]]
    corner_columns = [segment_columns[i] for i in corners]
    z = d.teeth[member - 1]
    if 4 * teeth > z:
        # a ring closing a wide segment lofts badly (OCC): loft the whole gear
        runs, _ = _segment_runs(outline, tooth, z, n_top, n_root)
    axis, forward = pair.axis[member], pair.rotation_axis[member]
    root, tip = d.root_angle(member), d.tip_angle(member)
    bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    columns = [c for run in runs for c in run[:-1]] + [runs[-1][-1]]
    wires, cut_lines = [], ([], [])
    for k in range(radii.size):
        points = outline.points[k]
        tags = {c: occ.addPoint(*points[c]) for c in columns}
        curves = [occ.addSpline([tags[c] for c in run]) for run in runs]
        if columns[0] != columns[-1]:
            # the root circle from the segment's end round to its start, in three arcs
            first, last = points[columns[0]], points[columns[-1]]
            sense = np.sign(forward @ axis)
            span = (sense * float(pair.azimuth(member, first) - pair.azimuth(member, last))) \
                % (2 * math.pi)
            centre = occ.addPoint(*(radii[k] * math.cos(root) * axis))
            previous = tags[columns[-1]]
            for j in (1, 2):
                point = occ.addPoint(*rotate(last, forward, sense * span * j / 3))
                curves.append(occ.addCircleArc(previous, centre, point))
                previous = point
            curves.append(occ.addCircleArc(previous, centre, tags[columns[0]]))
        wires.append(occ.addWire(curves))
        start, end = points[segment_columns[0]], points[segment_columns[-1]]
        # the cut curves: on the section's sphere, in the axial half-plane of
        # the segment's ends, from inside the bore to beyond the tip
        polar = np.linspace(0.5 * math.asin(bore / radii[-1]), tip + 0.1, 9)
        for lines, point in zip(cut_lines, (start, end)):
            radial = point - (point @ axis) * axis
            radial /= np.linalg.norm(radial)
            arc = radii[k] * (np.cos(polar)[:, None] * axis + np.sin(polar)[:, None] * radial)
            lines.append(occ.addWire([occ.addSpline([occ.addPoint(*q) for q in arc])]))
    body = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    cuts = [occ.addThruSections(lines, makeSolid=False, makeRuled=False) for lines in cut_lines]
    occ.synchronize()
    # round the root corners: the loft's edges that run through the corner points
    corner_points = [outline.points[k][corner_columns] for k in (0, -1)]
    edges = []
    for _, edge in gmsh.model.getEntities(1):
        ends = [gmsh.model.getValue(0, abs(p[1]), [])
                for p in gmsh.model.getBoundary([(1, edge)], oriented=False)]
        if len(ends) != 2:
            continue
        ends = np.array(ends)
        near = [np.min(np.linalg.norm(c[:, None] - ends[None], axis=2), axis=0) for c in corner_points]
        if np.any(near[0] < 1e-9) and np.any(near[1] < 1e-9):
            edges.append(edge)
    if len(edges) != len(corners):
        raise RuntimeError(f"found {len(edges)} of the segment's {len(corners)} root corners")
    body = occ.fillet([b[1] for b in body], edges, [fillet_radius], removeVolume=True)
    outer, inner = occ.addSphere(0, 0, 0, r_out), occ.addSphere(0, 0, 0, r_in)
    shell, _ = occ.cut([(3, outer)], [(3, inner)])
    body, _ = occ.intersect(body, shell)
    cylinder = occ.addCylinder(0, 0, 0, *(axis * 2 * r_out), bore)
    body, _ = occ.cut(body, [(3, cylinder)])
    pieces, _ = occ.fragment(body, [s for cut in cuts for s in cut])
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


def segment_mesh(pair, member, tooth_size, body_size=None, teeth=3, fillet_radius=0.25,
                 sections=SEGMENT_SECTIONS):
    """Mesh a segment of a member with tetrahedra.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    tooth_size : float
        Element size on the loaded tooth, its fillets and its neighbours [m].
    body_size : float, optional
        Element size far from the teeth, reached 3 tooth depths below the
        root [m]; default 3 x ``tooth_size``.
    teeth : int
        Teeth in the segment, odd, at least 3 [-].
    fillet_radius : float
        Root fillet radius as a multiple of the mean normal module, the tool
        edge radius rho_a0 / m_mn [-] (0.2-0.3 in practice).
    sections : int
        Sections of the loft [-].

    Returns
    -------
    SegmentMesh

    Raises
    ------
    ValueError
        For an even or too small number of teeth, or sizes that are not
        positive.
    """
    from lsbg.step import _gmsh

    if isinstance(teeth, bool) or int(teeth) != teeth or teeth < 3 or teeth % 2 == 0:
        raise ValueError(f"teeth = {teeth!r}: the segment needs an odd number >= 3 of teeth")
    body_size = 3.0 * tooth_size if body_size is None else body_size
    for name, value in (("tooth_size", tooth_size), ("body_size", body_size),
                        ("fillet_radius", fillet_radius)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r}: must be a positive number")
    gmsh, started = _gmsh()
    try:
        gmsh.model.add(f"lsbg_segment_{member}")
        radius = fillet_radius * pair.design.mean_module * math.cos(pair.design.spiral_angle)
        volume = _build_segment(pair, member, int(teeth), radius, sections)
        clamped = _clamped_surfaces(pair, member, volume)
        d = pair.design
        # size: fine within a tooth depth of the root cone, coarse below it
        field = gmsh.model.mesh.field
        depth = d.addendum + d.dedendum
        root_cone = field.add("MathEval")
        a = pair.axis[member]
        root = d.root_angle(member)
        # distance below the root cone, by the polar angle from the axis
        polar = f"acos((({a[0]:.17g})*x+({a[1]:.17g})*y+({a[2]:.17g})*z)/sqrt(x*x+y*y+z*z))"
        below = f"max(0, ({root:.17g} - {polar}) * sqrt(x*x+y*y+z*z))"
        growth = f"min(1, {below} / {3 * depth:.17g})"
        field.setString(root_cone, "F", f"{tooth_size:.17g} + ({body_size - tooth_size:.17g}) * {growth}")
        field.setAsBackgroundMesh(root_cone)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)  # HXT: fast, deterministic
        gmsh.option.setNumber("General.NumThreads", 1)
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
