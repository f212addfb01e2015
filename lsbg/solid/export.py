"""Write the geometry of one design point: design.json, flanks, meshes, URDF, picture.

:func:`write_geometry` is the ``lsbg geometry`` stage of the workflow
(DESIGN.md §1). It builds everything in a temporary directory beside the
output directory and renames it into place at the end, so that a failure
leaves nothing half-written; the next write of the same directory removes
the temporaries of a writer that was killed. The files:

``design.json``
    Every input parameter (:meth:`GearPairDesign.to_config`, paper units),
    every derived quantity (:meth:`GearPairDesign.derived`) and measurements
    on the exact flanks and solids. Keys carry their unit as a suffix
    (``_mm``, ``_deg``, ``_kg``, ``_kg_m2``); values are plain numbers,
    strings or lists. :func:`lsbg.solid.directory.read_design` reads the design back
    exactly.
``flanks.nc``
    Points and outward normals of tooth 0's flanks, both members and sides,
    on a (cone distance, polar angle) grid (CF-1.11).
``pinion.stl``, ``gear.stl``
    Watertight solid meshes in metres, mesh frame at rotation 0 (binary
    STL: the URDF's visual meshes too; no OBJ copy, which would cost time and
    3 MB per design point).
``pair.urdf``
    The assembled pair for PyBullet (:func:`lsbg.solid.urdf.write_urdf`).
``pair.png``
    A picture of the assembled pair (:func:`lsbg.solid.render.render_pair`).
``manifest.json``
    Written last: size and SHA-256 of every other file and the design point
    they belong to (:func:`lsbg.solid.directory.write_manifest`); every reader checks it.
"""

from __future__ import annotations

import json
import logging
import math
import os
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import lsbg
from lsbg.solid import mass, render, solids, urdf
from lsbg.gear.design import GearPairDesign
from lsbg.solid.directory import (FILE_NAMES, MANIFEST, OPTIONAL_FILE_NAMES, read_design,
                                  write_manifest)
from lsbg.solid.outline import DEFAULT_RESOLUTION
from lsbg.files import remove_stale_temporaries, temporary_beside
from lsbg.gear.geometry import MEMBER_NAMES, MEMBERS, SIDES, GearPair

__all__ = ["GeometryFiles", "write_geometry", "read_design", "design_record",
           "flank_dataset", "FILE_NAMES", "STAGES"]  # read_design, FILE_NAMES: lsbg.files

log = logging.getLogger(__name__)

#: Timed stages of :func:`write_geometry`, in order.
STAGES = ("surfaces", "meshes", "mass_properties", "urdf", "picture")

#: Samples along the face width for ``spiral_angle_along_face_deg`` [-].
FACE_SAMPLES = 21


@dataclass(frozen=True)
class GeometryFiles:
    """Paths written by :func:`write_geometry` and the time each stage took.

    Attributes
    ----------
    directory : pathlib.Path
    paths : dict
        Key of :data:`FILE_NAMES` or ``manifest`` -> path.
    timings : dict
        Stage of :data:`STAGES` -> wall time [s], plus ``total``.
    """

    directory: Path
    paths: dict
    timings: dict = field(default_factory=dict)

    def __getitem__(self, key):
        return self.paths[key]


# ------------------------------------------------------------------ design
def _plain(value):
    """numpy scalars and arrays as plain Python numbers and lists."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def design_record(pair: GearPair, props=None, quadrature=None, meshes=None) -> dict:
    """The content of ``design.json``.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    props : dict, optional
        ``{member: lsbg.solid.mass.MassProperties}`` from the meshes.
    quadrature : dict, optional
        ``{member: lsbg.solid.mass.QuadratureMassProperties}``, the mesh-free check.
    meshes : dict, optional
        ``{member: lsbg.solid.polyhedra.TriangleMesh}``, for the triangle counts.

    Returns
    -------
    dict
        Inputs (:meth:`GearPairDesign.to_config`), :meth:`GearPairDesign.derived`, then:
        ``contact_ratio``, ``contact_ratio_profile``, ``contact_ratio_face``;
        ``undercut_{pinion,gear}_deg`` (drive side); ``top_land_{inner,mean,outer}_{member}_mm``;
        ``normal_pressure_angle_mean_deg`` measured on the pinion's drive
        flank at the mean point (``normal_pressure_angle_mean_design_deg`` is
        the design formula; each member and side also as
        ``normal_pressure_angle_mean_{member}_{side}_deg``);
        ``spiral_angle_along_face_deg`` on the gear's pitch cone at
        ``cone_distance_along_face_mm``; with ``props``: ``mass_{member}_kg``,
        ``volume_{member}_mm3``, ``centre_of_mass_{member}_mm``,
        ``axial_inertia_{member}_kg_m2``, ``principal_inertia_{member}_kg_m2``,
        ``inertia_tensor_{member}_kg_m2`` (about the centre of mass, mesh
        axes); with ``meshes``: ``mesh_triangles_{member}``; with ``quadrature``:
        ``mass_quadrature_{member}_kg``, ``axial_inertia_quadrature_{member}_kg_m2``;
        and ``lsbg_version``.
    """
    d = pair.design
    record = dict(d.to_config())
    derived = d.derived()
    derived["normal_pressure_angle_mean_design_deg"] = derived.pop("normal_pressure_angle_mean_deg")
    record.update(derived)
    ratio = pair.contact_ratio()
    record.update(contact_ratio=ratio["total"], contact_ratio_profile=ratio["profile"],
                  contact_ratio_face=ratio["face"])
    ends = {"inner": d.inner_cone_distance, "mean": d.mean_cone_distance,
            "outer": d.outer_cone_distance}
    for member in MEMBERS:
        name = MEMBER_NAMES[member]
        record[f"undercut_{name}_deg"] = math.degrees(pair.undercut["drive"][name])
        for end, radius in ends.items():
            record[f"top_land_{end}_{name}_mm"] = 1e3 * float(pair.top_land(member, radius))
    alpha = {(member, side): math.degrees(float(pair.normal_pressure_angle(
        member, d.mean_cone_distance, d.pitch_angle(member), side)))
        for member in MEMBERS for side in SIDES}
    record["normal_pressure_angle_mean_deg"] = alpha[(1, "drive")]
    for (member, side), value in alpha.items():
        record[f"normal_pressure_angle_mean_{MEMBER_NAMES[member]}_{side}_deg"] = value
    face = np.linspace(d.inner_cone_distance, d.outer_cone_distance, FACE_SAMPLES)
    record["cone_distance_along_face_mm"] = (1e3 * face).tolist()
    record["spiral_angle_along_face_deg"] = np.degrees(
        pair.spiral_angle(2, d.pitch_angle(2), face)).tolist()
    for member, p in (props or {}).items():
        name = MEMBER_NAMES[member]
        record[f"mass_{name}_kg"] = p.mass
        record[f"volume_{name}_mm3"] = 1e9 * p.volume
        record[f"centre_of_mass_{name}_mm"] = (1e3 * p.centre_of_mass).tolist()
        record[f"axial_inertia_{name}_kg_m2"] = p.axial_inertia
        record[f"principal_inertia_{name}_kg_m2"] = p.principal_moments.tolist()
        record[f"inertia_tensor_{name}_kg_m2"] = p.inertia.tolist()
    for member, mesh in (meshes or {}).items():
        record[f"mesh_triangles_{MEMBER_NAMES[member]}"] = len(mesh.faces)
    for member, q in (quadrature or {}).items():
        name = MEMBER_NAMES[member]
        record[f"mass_quadrature_{name}_kg"] = q.mass
        record[f"axial_inertia_quadrature_{name}_kg_m2"] = q.axial_inertia
    record["lsbg_version"] = lsbg.__version__
    return {key: _plain(value) for key, value in record.items()}


# ------------------------------------------------------------------ flanks
def flank_dataset(pair: GearPair, n_cone=21, n_profile=31):
    """Tooth-0 flanks of both members and sides as an xarray Dataset (CF-1.11).

    Only the involute flank, from :meth:`GearPair.flank_polar_range` up: the
    pinion's radial continuation below its base cone is left out.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    n_cone, n_profile : int
        Grid size along the face width and the profile [-].

    Returns
    -------
    xarray.Dataset
        ``point`` [mm] and ``normal`` [1] on dims (member, side, cone_distance,
        profile, xyz); coordinates ``cone_distance`` [mm], ``profile`` [1]
        (0 at the flank start, 1 at the tip) and ``polar_angle`` (member,
        profile) [deg] from the member's axis; ``axis`` and ``rotation_axis``.
    """
    import xarray as xr

    d = pair.design
    cone = np.linspace(d.inner_cone_distance, d.outer_cone_distance, n_cone)
    profile = np.linspace(0.0, 1.0, n_profile)
    polar = np.empty((2, n_profile))
    points = np.empty((2, 2, n_cone, n_profile, 3))
    normals = np.empty_like(points)
    for i, member in enumerate(MEMBERS):
        start, tip = pair.flank_polar_range(member)
        polar[i] = start + (tip - start) * profile
        for j, side in enumerate(SIDES):
            points[i, j], normals[i, j] = pair.flank(member, side, cone[:, None], polar[i][None, :])
    dims = ("member", "side", "cone_distance", "profile", "xyz")
    ds = xr.Dataset(
        {
            "point": (dims, 1e3 * points, {
                "units": "mm",
                "long_name": "flank point of tooth 0 in the mesh frame at rotation 0"}),
            "normal": (dims, normals, {
                "units": "1", "long_name": "outward unit normal of the flank"}),
            "axis": (("member", "xyz"), np.array([pair.axis[m] for m in MEMBERS]), {
                "units": "1", "long_name": "unit axis from the apex into the gear body"}),
            "rotation_axis": (("member", "xyz"),
                              np.array([pair.rotation_axis[m] for m in MEMBERS]),
                              {"units": "1", "long_name": "forward rotation axis"}),
        },
        coords={
            "member": ("member", [MEMBER_NAMES[m] for m in MEMBERS],
                       {"units": "1", "long_name": "gear member"}),
            "side": ("side", list(SIDES),
                     {"units": "1",
                      "long_name": "flank side (drive: loaded when the pinion drives)"}),
            "cone_distance": ("cone_distance", 1e3 * cone, {
                "units": "mm", "long_name": "distance from the apex (sphere radius)"}),
            "profile": ("profile", profile, {
                "units": "1",
                "long_name": "profile parameter, 0 at the flank start, 1 at the tip"}),
            "polar_angle": (("member", "profile"), np.degrees(polar), {
                "units": "degree", "long_name": "polar angle from the member's axis"}),
            "xyz": ("xyz", ["x", "y", "z"], {
                "units": "1", "long_name": "mesh frame axis (apex at the origin, x along the pitch line, "
                             "gear axes in the xy plane)"}),
        },
        attrs={
            "title": f"Tooth flanks of a {d.trace} spiral bevel gear pair",
            "source": f"lsbg {lsbg.__version__} (lsbg.gear.geometry.GearPair.flank)",
            # no time stamp: a rerun writes the same bytes, so the directory and
            # its manifest are bit-identical too
            "history": "created by lsbg.solid.export.flank_dataset",
            "Conventions": "CF-1.11",
            **{f"design_{key}": value for key, value in d.to_config().items()},
        },
    )
    return ds


# --------------------------------------------------------------- the stage
def write_geometry(design: GearPairDesign, out_dir, resolution=DEFAULT_RESOLUTION,
                   step=False, relief=None):
    """Write the geometry of one design point into ``out_dir``.

    The design is checked (:class:`lsbg.gear.geometry.GearPair` raises
    :class:`lsbg.gear.design.DesignError`) before anything is written. Files go to
    a temporary directory beside ``out_dir``, which replaces ``out_dir`` only
    when all of them and the manifest are written. Temporaries of ``out_dir``
    left by a killed writer are removed first.

    Parameters
    ----------
    design : GearPairDesign
    out_dir : str or os.PathLike
        Output directory; replaced if it exists.
    resolution : lsbg.solid.outline.MeshResolution
    step : bool
        Also write the exact solids as STEP (``pinion.step``, ``gear.step``;
        :mod:`lsbg.solid.step`, a few seconds per design point).
    relief : callable, optional
        The pinion's flank modification for its STEP solid,
        ``relief(cone_distance [m], polar_angle [rad])`` [m]
        (:func:`lsbg.solid.step.relieved_outline`); the other files keep the
        conjugate flanks.

    Returns
    -------
    GeometryFiles
        Paths of :data:`FILE_NAMES` and ``manifest`` and the time per stage of
        :data:`STAGES` [s].
    """
    timings = {}
    clock = time.perf_counter()
    start = clock

    def lap(stage):
        nonlocal clock
        now = time.perf_counter()
        timings[stage] = now - clock
        clock = now
        log.info("geometry %s: %.2f s", stage, timings[stage])

    pair = GearPair(design)            # raises DesignError before any file exists
    out_dir = Path(out_dir).absolute()
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(out_dir)
    work = temporary_beside(out_dir, "tmp", directory=True)
    paths = {key: work / name for key, name in FILE_NAMES.items()}
    try:
        flank_dataset(pair).to_netcdf(paths["flanks"])
        lap("surfaces")
        meshes = solids.gear_meshes(pair, resolution)
        for member in MEMBERS:
            name = MEMBER_NAMES[member]
            meshes[member].export(paths[f"{name}_stl"])
        lap("meshes")
        props = {m: mass.mass_properties(meshes[m], pair, m) for m in MEMBERS}
        quadrature = {m: mass.quadrature_mass_properties(pair, m) for m in MEMBERS}
        with open(paths["design"], "w", encoding="utf-8") as handle:
            json.dump(design_record(pair, props, quadrature, meshes), handle, indent=1)
            handle.write("\n")
        lap("mass_properties")
        urdf.write_urdf(paths["urdf"], pair, props,
                        {m: paths[f"{MEMBER_NAMES[m]}_stl"] for m in MEMBERS})
        lap("urdf")
        render.render_pair(paths["picture"], pair, meshes)
        lap("picture")
        if step:
            from lsbg.solid import step as step_files

            for member in MEMBERS:
                name = OPTIONAL_FILE_NAMES[f"{MEMBER_NAMES[member]}_step"]
                step_files.write_step(pair, member, work / name, relief=relief)
            lap("step")
        write_manifest(work)           # last: it vouches for the files above
        _replace_dir(work, out_dir)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    timings["total"] = time.perf_counter() - start
    log.info("geometry total: %.2f s -> %s", timings["total"], out_dir)
    names = {**FILE_NAMES, **(OPTIONAL_FILE_NAMES if step else {}), "manifest": MANIFEST}
    return GeometryFiles(out_dir, {key: out_dir / name for key, name in names.items()}, timings)


def _replace_dir(new, target):
    """Rename ``new`` to ``target``, replacing an existing ``target``."""
    if not target.exists():
        os.rename(new, target)
        return
    old = temporary_beside(target, "old", directory=True)
    os.rename(target, old / target.name)
    os.rename(new, target)
    shutil.rmtree(old, ignore_errors=True)
