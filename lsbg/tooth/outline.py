"""The FE segment's section outlines: its teeth, its cut, its root fillets.

The segment (:mod:`lsbg.tooth.segment`) is lofted through these outlines: on
each sphere of the loft, the exact outline of lsbg's gear blank
(:func:`lsbg.solid.outline.section_outline`) from the middle of the root of the gap
before its first tooth to that after its last, in smooth pieces.

lsbg's gear blank has a sharp corner where each flank (or its radial
continuation below the base cone) meets the root cone; the stress of an
elastic solid is singular there. The segment (:mod:`lsbg.tooth.segment`)
rounds each corner with the tool edge radius rho_a0 on every section of its
loft, so the lofted surface through the rounded sections is the fillet: a
circle of radius rho in the plane normal to the corner line, tangent to the
root and to the flank, seen obliquely on the section's sphere.

(OpenCASCADE's rolling-ball fillet of the lofted corner edges, the first way,
failed on the 9-tooth pinion at spiral angles of 20-32.5 deg and left the
37-tooth gear's trimmed solid empty at 42.5-45 deg; rounding the sections
never asks OCC to fillet.)

Lengths in metres.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from lsbg.gear.flank import sphere_points

__all__ = ["segment_sections", "tooth_zero_column", "fillet_corners", "distance_to_polyline",
           "round_corners", "ARC_POINTS"]

#: Sections of the segment's loft across the face width (and beyond it) [-].
SEGMENT_SECTIONS = 7
#: Points on each fillet arc of a section, ends included [-]: the spline
#: through them stays within 1e-4 rho of the circle for a quarter turn.
ARC_POINTS = 7
#: Fine samples of each neighbouring curve over the span the fillet can reach [-].
_SAMPLES = 400


def fillet_corners(pair, member, samples=41, margin=0.0):
    """Corner lines of tooth 0's root fillets: where each flank meets the root cone [m].

    The flank (or its radial continuation below the base cone) meets the root
    cone along a line at the flank's start azimuth; the fillet of radius rho
    rounds that corner and lies within about one rho of it.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    samples : int
        Points along each line [-].
    margin : float
        Extension beyond the toe and the heel [m].

    Returns
    -------
    numpy.ndarray, shape (2, samples, 3)
        Drive side, then coast side.
    """
    d = pair.design
    start = pair.flank_polar_range(member)[0]
    rho = np.linspace(d.inner_cone_distance - margin, d.outer_cone_distance + margin, samples)
    lines = []
    for side in ("drive", "coast"):
        foot, _ = pair.flank(member, side, rho, np.full(samples, start))
        lines.append(sphere_points(pair, member, rho, d.root_angle(member),
                                   pair.azimuth(member, foot)))
    return np.stack(lines)


def distance_to_polyline(points, line):
    """Distance of points to a polyline [m].

    Parameters
    ----------
    points : numpy.ndarray, shape (n, 3)
    line : numpy.ndarray, shape (s, 3)

    Returns
    -------
    numpy.ndarray, shape (n,)
    """
    seg = np.diff(line, axis=0)
    rel = points[:, None, :] - line[None, :-1, :]
    t = np.clip(np.sum(rel * seg[None], axis=2) / np.sum(seg * seg, axis=1)[None], 0, 1)
    return np.min(np.linalg.norm(rel - t[..., None] * seg[None], axis=2), axis=1)


def _chord_spline(points):
    """Interpolating cubic spline through ``points`` by chord length, as OCC's
    interpolation makes the loft's curves; returns (spline, lengths)."""
    length = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    return CubicSpline(length, points, axis=0), length


def _to_sphere(points, direction, radius):
    """Move points along ``direction`` onto the sphere |r| = radius (the nearer crossing)."""
    b = points @ direction
    c = np.sum(points * points, axis=-1) - radius ** 2
    root = np.sqrt(np.maximum(b * b - c, 0.0))
    s = np.where(np.abs(-b + root) < np.abs(-b - root), -b + root, -b - root)
    return points + s[..., None] * direction


def _round_corner(first, second, spine, sphere_radius, radius):
    """One corner's fillet on one section.

    Parameters
    ----------
    first, second : numpy.ndarray, shape (n, 3)
        The two curves' points leaving the corner (both start at it) [m].
    spine : numpy.ndarray, shape (3,)
        Unit tangent of the corner line there [-].
    sphere_radius, radius : float
        The section's cone distance and the fillet radius rho, as in
        :func:`round_corners` [m].

    Returns
    -------
    arc : numpy.ndarray, shape (ARC_POINTS, 3)
        From the tangent point on ``first`` to that on ``second`` [m].
    lengths : tuple of float
        The tangent points' chord-length parameters on the two curves [m].
    """
    corner = first[0]
    # the plane normal to the corner line, through the corner (b1 along the
    # first curve's start seen in it)
    b1 = first[1] - corner
    b1 -= (b1 @ spine) * spine
    b1 /= np.linalg.norm(b1)
    b2 = np.cross(spine, b1)
    plane = np.stack([b1, b2])
    curves = []
    for points in (first, second):
        spline, length = _chord_spline(points)
        s = np.linspace(0.0, min(length[-1], 6.0 * radius), _SAMPLES)
        curves.append((s, spline(s), (spline(s) - corner) @ plane.T))
    # start from the two tangent lines at the corner, then move each tangent
    # line to the curve's point nearest the circle's centre until it settles
    tangents = [c[2][1] - c[2][0] for c in curves]
    feet = [c[2][0] for c in curves]
    centre = None
    for _ in range(50):
        units = [t / np.linalg.norm(t) for t in tangents]
        normals = [np.array([-u[1], u[0]]) for u in units]
        # each normal towards the other curve: the wedge between them is the gap
        normals = [n if n @ (units[1 - i]) > 0 else -n for i, n in enumerate(normals)]
        # centre: on both lines offset by rho into the wedge
        matrix = np.stack(normals)
        rhs = np.array([normals[i] @ feet[i] + radius for i in (0, 1)])
        new = np.linalg.solve(matrix, rhs)
        if centre is not None and np.linalg.norm(new - centre) < 1e-6 * radius:
            centre = new
            break
        centre = new
        feet, tangents, at = [], [], []
        for s, _, xy in curves:
            j = int(np.argmin(np.linalg.norm(xy - centre, axis=1)))
            j = min(max(j, 1), s.size - 2)
            feet.append(xy[j])
            tangents.append(xy[j + 1] - xy[j - 1])
            at.append(s[j])
    else:
        raise RuntimeError("the fillet's centre did not settle")
    if max(at) >= 0.99 * min(curves[0][0][-1], curves[1][0][-1]):
        raise ValueError(f"the fillet of rho = {radius * 1e3:.3g} mm needs more than the "
                         f"{min(curves[0][0][-1], curves[1][0][-1]) * 1e3:.3g} mm of outline "
                         f"beside a corner on the sphere of R = {sphere_radius * 1e3:.4g} mm")
    # the tangent points: the splines' samples nearest the centre (400 over 6 rho),
    # put back on the sphere (the spline sags off it between the outline's points
    # by ~1e-8 m)
    ends = [(s0, xyz[int(np.searchsorted(s, s0))]) for s0, (s, xyz, _) in zip(at, curves)]
    ends = [(s0, p * sphere_radius / np.linalg.norm(p)) for s0, p in ends]
    a0 = [math.atan2(*(((p - corner) @ plane.T - centre)[::-1])) for _, p in ends]
    turn = (a0[1] - a0[0] + math.pi) % (2 * math.pi) - math.pi
    angle = a0[0] + turn * np.linspace(0.0, 1.0, ARC_POINTS)[1:-1]
    inner = corner + (centre[0] + radius * np.cos(angle))[:, None] * b1 \
        + (centre[1] + radius * np.sin(angle))[:, None] * b2
    arc = np.concatenate([[ends[0][1]], _to_sphere(inner, spine, sphere_radius), [ends[1][1]]])
    return arc, (ends[0][0], ends[1][0])


def round_corners(runs, corners, spines, sphere_radius, radius):
    """Round the corners of one section's open outline.

    Parameters
    ----------
    runs : list of numpy.ndarray, shape (n_i, 3)
        The outline's smooth pieces in order, each sharing its last point
        with the next one's first [m].
    corners : list of int
        The pieces after which a corner comes (piece i ends where i + 1
        starts) [-].
    spines : numpy.ndarray, shape (len(corners), 3)
        Unit tangents of the corner lines at this section [-].
    sphere_radius : float
        The section's cone distance [m].
    radius : float
        Fillet radius rho [m].

    Returns
    -------
    list of numpy.ndarray
        The pieces with a fillet arc inserted after each corner's first
        piece; points of the neighbours within the fillet's reach dropped.

    Raises
    ------
    ValueError
        If a fillet reaches past a neighbouring piece (the root gap is too
        narrow for the radius).
    """
    pieces = [np.asarray(r, dtype=float) for r in runs]
    cut_start, cut_end, arcs = {}, {}, {}
    for corner, spine in zip(corners, spines):
        before, after = pieces[corner], pieces[corner + 1]
        arc, (s_before, s_after) = _round_corner(before[::-1], after, spine, sphere_radius,
                                                 radius)
        arcs[corner], cut_end[corner], cut_start[corner + 1] = arc, s_before, s_after
    out = []
    for i, piece in enumerate(pieces):
        length = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(piece, axis=0),
                                                                  axis=1))])
        start, end = cut_start.get(i, 0.0), cut_end.get(i, 0.0)
        if start + end >= 0.95 * length[-1]:
            raise ValueError(f"the fillet of rho = {radius * 1e3:.3g} mm reaches past a "
                             f"{length[-1] * 1e3:.3g} mm piece of the outline on the sphere "
                             f"of R = {sphere_radius * 1e3:.4g} mm (a root gap too narrow)")
        # interior points clear of the fillets by a third of their spacing
        spacing = np.diff(length)
        clear = (length[1:-1] > start + 0.3 * spacing[0] * (i in cut_start)) \
            & (length[-1] - length[1:-1] > end + 0.3 * spacing[-1] * (i in cut_end))
        first = arcs[i - 1][-1] if i in cut_start else piece[0]
        last = arcs[i][0] if i in cut_end else piece[-1]
        out.append(np.concatenate([[first], piece[1:-1][clear], [last]]))
        if i in arcs:
            out.append(arcs[i])
    return out


def tooth_zero_column(pair, member, outline, section):
    """Outline tooth that holds tooth 0's flanks on one section [-].

    :meth:`lsbg.gear.geometry.GearPair.flank` gives the flanks of tooth 0; the
    outline counts its teeth from its own start. The tooth whose azimuth span
    (low-flank root to the next tooth's) contains tooth 0's drive flank at the
    middle of its profile is tooth 0.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    outline : lsbg.solid.outline.SectionOutline
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

    The outline is cut near the middle of the root arcs before the first and
    after the last tooth (at a column; :func:`_build_segment` moves the ends
    to the exact middles); each run is one smooth piece (root arc, flank, top
    land), sharing end columns with its neighbours.

    Returns
    -------
    runs : list of list of int
        Outline columns, in order, of each piece.
    corners : list of int
        Positions (in the open outline) of the flank-root corners.
    gaps : list of tuple of int
        The two outer gaps' root corner columns (high flank's, next low flank's).
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
    gaps = [(((j - 1) * n + root_start) % total, (j * n) % total)
            for j in (first_tooth, first_tooth + teeth)]
    return runs, corners, gaps


def segment_sections(pair, member, teeth, fillet_radius, sections=SEGMENT_SECTIONS):
    """The segment's open outline on each section of its loft, root fillets rounded.

    The outline runs from the exact middle of the root of the gap before the
    segment's first tooth to that after its last, in increasing azimuth
    about the rotation axis, as smooth pieces (root arcs, flanks, top lands,
    fillet arcs) that share their end points. The root corners of tooth 0's
    two gaps are rounded (:func:`lsbg.tooth.fillet.round_corners`): each
    rounded corner costs about 0.13 s in the blank's boolean, and rounding
    all 14 of a 7-tooth segment moved the mesh stiffness by 0.2 % and the
    root stresses by 0-2 % (the paper's pair, 35 deg), the stresses'
    mesh-to-mesh scatter.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    teeth : int
        Teeth in the segment, odd [-].
    fillet_radius : float
        rho [m].
    sections : int
        Sections of the loft [-].

    Returns
    -------
    radii : numpy.ndarray, shape (sections,)
        The sections' cone distances [m].
    outlines : list of list of numpy.ndarray
        Per section, the pieces' points, shapes (n_i, 3) [m].

    Raises
    ------
    ValueError
        If a gap's root is too narrow for its two fillets.
    """
    from lsbg.solid.step import loft_sections

    outline, n_top, n_root = loft_sections(pair, member, sections)
    radii = outline.cone_distance
    tooth = tooth_zero_column(pair, member, outline, sections // 2)
    runs, corners, gaps = _segment_runs(outline, tooth, teeth, n_top, n_root)
    # the pieces that end at a root corner (two a tooth, tooth 0 the middle one)
    ends = np.cumsum([len(run) - 1 for run in runs])
    corner_runs = [r for r, end in enumerate(ends) if end in corners]
    if len(corner_runs) != 2 * teeth:
        raise RuntimeError(f"found {len(corner_runs)} of the segment's {2 * teeth} root corners")
    rounded = [corner_runs[i] for i in range(teeth - 2, teeth + 2)]
    corner_points = np.stack([[outline.points[k][runs[r][-1]] for r in rounded]
                              for k in range(radii.size)])
    spines = np.gradient(corner_points, radii, axis=0, edge_order=2)
    spines /= np.linalg.norm(spines, axis=2, keepdims=True)
    root = pair.design.root_angle(member)
    outlines = []
    for k in range(radii.size):
        points = outline.points[k]
        # the open outline's ends at the exact middles of the outer gaps' roots
        phi = outline.azimuth[k]
        middles = [phi[a] + 0.5 * ((phi[b] - phi[a]) % (2 * math.pi)) for a, b in gaps]
        start, end = sphere_points(pair, member, radii[k], root, np.array(middles))
        pieces = [points[run] for run in runs]
        pieces[0] = np.concatenate([[start], pieces[0][1:]])
        pieces[-1] = np.concatenate([pieces[-1][:-1], [end]])
        try:
            outlines.append(round_corners(pieces, rounded, spines[k], radii[k], fillet_radius))
        except ValueError as error:
            raise ValueError(f"the {('pinion', 'gear')[member - 1]}'s root fillets do not fit: "
                             f"{error}") from None
    return radii, outlines
