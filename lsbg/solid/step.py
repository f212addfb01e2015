"""Exact solids as STEP files, through OpenCASCADE (gmsh's OCC kernel).

CAD tools read STEP. Each member becomes one closed solid whose toothed
surface is lofted through the exact section outlines of
:func:`lsbg.solid.outline.section_outline` (on spheres about the apex): per tooth an
interpolating spline through the flank points of each side, the top land and
the root arc, so that the surface passes through the exact flank points of
every section and interpolates smoothly between them
(``occ.addThruSections``). Lofted a little beyond the toe and the heel, the
body is cut to the spherical shell R_i <= |r| <= R_e and bored, as
:mod:`lsbg.solid.outline` defines the gear blank.

Checked (``tests/solid/test_step.py``) by reading the file back with OCC: one closed
solid, its volume against :func:`lsbg.solid.mass.quadrature_mass_properties`, and the
exact flanks' distance from its surface at a few hundred points (measured for
the paper's pair: 0.2 µm on the pinion, 0.05 µm on the gear).

The STEP header's time stamp is fixed (:data:`STEP_TIME_STAMP`), so the same
design gives the same file, byte for byte. Lengths in metres inside; STEP
files are written in millimetres, CAD's usual unit (gmsh's
``Geometry.OCCTargetUnit``).
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
from pathlib import Path

import numpy as np

from lsbg.gear.geometry import MEMBER_NAMES
from lsbg.solid.outline import DEFAULT_RESOLUTION, _outline_counts, section_outline, side_order

__all__ = ["STEP_SECTIONS", "STEP_TIME_STAMP", "write_step", "read_step", "flank_deviation"]

#: Sections of the loft across the face width (and 1 mm beyond it) [-].
STEP_SECTIONS = 9
#: How far the loft reaches beyond the toe and the heel before the cut [m].
LOFT_MARGIN = 1e-3
#: The time stamp every STEP header carries: fixed, for byte-identical reruns.
STEP_TIME_STAMP = "2000-01-01T00:00:00"


@contextlib.contextmanager
def _quiet():
    """Silence OCC's STEP translator, which prints to the process's stdout itself."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def _gmsh():
    """gmsh, initialised quietly (its OCC kernel), and whether this call did it."""
    import gmsh

    started = not gmsh.isInitialized()
    if started:
        gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    return gmsh, started


def _tooth_edges(outline, n_top, n_root):
    """Index runs of one section's outline: per tooth the low flank, top land, high
    flank and root arc, each sharing its end points with its neighbours."""
    n, teeth = outline.per_tooth, outline.points.shape[1] // outline.per_tooth
    side = (n - n_top - n_root) // 2
    total = n * teeth
    runs = []
    for j in range(teeth):
        b = j * n
        for start, stop in ((b, b + side), (b + side - 1, b + side + n_top + 1),
                            (b + side + n_top, b + 2 * side + n_top),
                            (b + 2 * side + n_top - 1, b + n + 1)):
            runs.append([i % total for i in range(start, stop)])
    return runs


def relieved_outline(pair, outline, relief):
    """The pinion's section outline with its drive flanks relieved [m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    outline : lsbg.solid.outline.SectionOutline
        The pinion's (member 1).
    relief : callable
        ``relief(cone_distance, polar_angle)``: material removed normal to the
        drive flank [m] at flank points (R [m], theta [rad]), e.g. a
        :class:`lsbg.tca.modification.FlankModification` through its
        coordinates. Below the involute (the radial continuation) the relief
        at its start is kept.

    Returns
    -------
    numpy.ndarray, shape of ``outline.points``
    """
    from lsbg.gear.vectors import rotate

    n = outline.per_tooth
    n_top = np.sum(np.isclose(outline.polar_angle[0, :n], pair.design.tip_angle(1)))
    n_root = np.sum(np.isclose(outline.polar_angle[0, :n], pair.design.root_angle(1)))
    side = (n - n_top - n_root) // 2
    low, _ = side_order(pair, 1)
    first = 0 if low == "drive" else side + n_top
    columns = np.concatenate([np.arange(first, first + side) + j * n
                              for j in range(outline.points.shape[1] // n)])
    start = pair.flank_polar_range(1)[0]
    radius = np.broadcast_to(outline.cone_distance[:, None], outline.polar_angle.shape)[:, columns]
    polar = np.maximum(outline.polar_angle[:, columns], start)
    # the flank of tooth 0 there, turned onto the outline's tooth about the axis
    flank, normal = pair.flank(1, "drive", radius, polar)
    turn = pair.azimuth(1, outline.points[:, columns]) - pair.azimuth(1, flank)
    normal = rotate(normal, pair.rotation_axis[1], turn)
    points = outline.points.copy()
    points[:, columns] -= np.asarray(relief(radius, polar))[..., None] * normal
    return points


def loft_sections(pair, member, sections):
    """Section outlines of a loft across the face width and ``LOFT_MARGIN`` beyond it.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    sections : int
        Spheres, evenly spaced in cone distance [-].

    Returns
    -------
    outline : lsbg.solid.outline.SectionOutline
    n_top, n_root : int
        Interior points of each top land and root arc [-].
    """
    d = pair.design
    radii = np.linspace(d.inner_cone_distance - LOFT_MARGIN, d.outer_cone_distance + LOFT_MARGIN,
                        int(sections))
    _, n_top, n_root = _outline_counts(pair, member, DEFAULT_RESOLUTION)
    return section_outline(pair, member, radii), n_top, n_root


def build_solid(pair, member, sections=STEP_SECTIONS, relief=None):
    """Build one member's solid in the current gmsh model [volume tag].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    sections : int
        Sections of the loft [-].
    relief : callable, optional
        The pinion's flank modification (:func:`relieved_outline`); ignored
        for the gear.

    Returns
    -------
    int
        The OCC volume tag of the solid (gmsh must be initialised).
    """
    import gmsh

    occ = gmsh.model.occ
    d = pair.design
    r_in, r_out = d.inner_cone_distance, d.outer_cone_distance
    outline, n_top, n_root = loft_sections(pair, member, sections)
    radii = outline.cone_distance
    runs = _tooth_edges(outline, n_top, n_root)
    points = (relieved_outline(pair, outline, relief) if relief is not None and member == 1
              else outline.points)
    wires = []
    for k in range(radii.size):
        tags = [occ.addPoint(*p) for p in points[k]]
        wires.append(occ.addWire([occ.addSpline([tags[i] for i in run]) for run in runs]))
    body = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    # The sections' points and curves stay in the model (removing them costs OCC
    # seconds for the gear's ~10 000 points): write_step writes the solid alone.
    # The blank, the bored spherical shell R_i <= |r| <= R_e, from the simple
    # solids first: one boolean with the lofted body, the costly kind.
    outer, inner = occ.addSphere(0, 0, 0, r_out), occ.addSphere(0, 0, 0, r_in)
    bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
    cylinder = occ.addCylinder(0, 0, 0, *(pair.axis[member] * 2 * r_out), bore)
    blank, _ = occ.cut([(3, outer)], [(3, inner), (3, cylinder)])
    solid, _ = occ.intersect(body, blank)
    occ.synchronize()
    if len(solid) != 1 or solid[0][0] != 3:
        raise RuntimeError(f"the {MEMBER_NAMES[member]} solid came out as {solid}, not one volume")
    return solid[0][1]


def write_step(pair, member, path, relief=None):
    """Write one member as a STEP file (millimetres) [path].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    path : str or os.PathLike
    relief : callable, optional
        The pinion's flank modification (:func:`relieved_outline`).

    Returns
    -------
    pathlib.Path
    """
    gmsh, started = _gmsh()
    path = Path(path)
    try:
        gmsh.model.add(f"lsbg_{MEMBER_NAMES[member]}")
        solid = build_solid(pair, member, relief=relief)
        # the solid alone: not the loft's section points and curves (build_solid)
        gmsh.model.setVisibility(gmsh.model.getEntities(), 0)
        gmsh.model.setVisibility([(3, solid)], 1, recursive=True)
        # the model is in metres; OCC's writer converts to the file's millimetres
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        part = path.with_name(path.name + ".part.step")
        only_visible = gmsh.option.getNumber("Geometry.OCCExportOnlyVisible")
        gmsh.option.setNumber("Geometry.OCCExportOnlyVisible", 1)
        try:
            with _quiet():
                gmsh.write(str(part))
        finally:  # a gmsh session shared with the caller gets its option back
            gmsh.option.setNumber("Geometry.OCCExportOnlyVisible", only_visible)
        gmsh.model.remove()
    finally:
        if started:
            gmsh.finalize()
    text = part.read_text(encoding="utf-8")
    # FILE_NAME('name','time stamp',...): the only part that changes between runs
    text = re.sub(r"(FILE_NAME\('[^']*',')[^']*(')", rf"\g<1>{STEP_TIME_STAMP}\g<2>", text,
                  count=1)
    # ... and the product's name, which counts the process's writes
    text = re.sub(r"Open CASCADE STEP translator [0-9.]+ \d+", f"lsbg {MEMBER_NAMES[member]}",
                  text)
    path.write_text(text, encoding="utf-8")
    part.unlink()
    return path


def read_step(path):
    """Read a STEP file back with OCC: its volumes and their total volume.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    dict
        ``volumes`` (count), ``volume`` [m^3], ``open_edges`` (edges of the
        boundary used by one face only: 0 for a closed solid) and
        ``faces`` (surface tags), read in metres.
    """
    with _imported(path) as (gmsh, shapes):
        volumes = [t for dim, t in shapes if dim == 3]
        faces = gmsh.model.getBoundary([(3, t) for t in volumes], oriented=False)
        uses = {}
        for _, face in faces:
            for _, edge in gmsh.model.getBoundary([(2, face)], oriented=False):
                uses[abs(edge)] = uses.get(abs(edge), 0) + 1
        return {"volumes": len(volumes),
                "volume": float(sum(gmsh.model.occ.getMass(3, t) for t in volumes)),
                "open_edges": sum(1 for n in uses.values() if n < 2),
                "faces": [t for _, t in faces]}


@contextlib.contextmanager
def _imported(path):
    """(gmsh, shapes) of a STEP file read into a model of its own, in metres."""
    gmsh, started = _gmsh()
    try:
        gmsh.model.add("lsbg_import")
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        with _quiet():
            shapes = gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        yield gmsh, shapes
    finally:
        gmsh.model.remove()
        if started:
            gmsh.finalize()


def flank_deviation(pair, member, path, points=200, seed=0, relief=None):
    """Distance of exact flank points from a STEP solid's surface [m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    path : str or os.PathLike
        The member's STEP file (:func:`write_step`).
    points : int
        Random points per flank side, inside the face and the flank [-].
    seed : int
    relief : callable, optional
        The pinion's drive-flank modification the file was written with
        (:func:`relieved_outline`): the points are taken on the relieved flank.

    Returns
    -------
    numpy.ndarray, shape (2 * points,)
        Least distance of each point from the solid's faces [m].
    """
    rng = np.random.default_rng(seed)
    d = pair.design
    margin = 0.02 * d.face_width
    rho = rng.uniform(d.inner_cone_distance + margin, d.outer_cone_distance - margin, points)
    low, _ = pair.flank_polar_range(member)
    polar = rng.uniform(low + 0.02 * (d.tip_angle(member) - low),
                        d.tip_angle(member) - 0.02 * (d.tip_angle(member) - low), points)
    sides = []
    for side in ("drive", "coast"):
        flank, normal = pair.flank(member, side, rho, polar)
        if relief is not None and member == 1 and side == "drive":
            flank = flank - np.asarray(relief(rho, polar))[:, None] * normal
        sides.append(flank)
    exact = np.concatenate(sides)
    with _imported(path) as (gmsh, shapes):
        faces = gmsh.model.getBoundary([s for s in shapes if s[0] == 3], oriented=False)
        least = np.full(len(exact), np.inf)
        for _, face in faces:
            closest, _ = gmsh.model.getClosestPoint(2, face, exact.ravel())
            least = np.minimum(least, np.linalg.norm(np.reshape(closest, (-1, 3)) - exact, axis=1))
        return least
