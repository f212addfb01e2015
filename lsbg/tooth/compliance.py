"""The tooth's compliance by finite elements: influence coefficients over the flank.

For each member a segment (:mod:`lsbg.tooth.segment`) is loaded, one unit
normal force at a time, at the points of a grid on the drive flank of its
middle tooth (tooth 0), and the answers are read

* on every tooth of the segment (-1, 0, +1) at the same grid points: the
  displacement along the load direction of the point of the tooth's middle
  surface under the flank point (the tooth's bending, shear and rim
  deflection, and what the load does to the neighbours). The compression of
  the tooth between its flank and its middle is the local contact term of
  :mod:`lsbg.tooth.local` (Hertz's half-width against the half thickness),
  so the two do not count it twice;
* at points of the root fillets of tooth 0, both sides: the stress tensor,
  from which :mod:`lsbg.tooth.ltca` takes the largest tensile principal
  stress of the superposed loads.

The grid is the field of contact of the plane of action: cone distances
across the face width times polar angles psi across the field; a point of the
plane at polar angle psi meets a member's flank at the same polar angle from
its axis at every rotation, so the grid is one set of flank points per member,
whichever tooth pair is in contact there. The LTCA interpolates the
coefficients bilinearly to its contact points.

The result is a :class:`xarray.Dataset` written once per design point as
NetCDF with the hash of its inputs (:func:`compliance_for_design`), and reused
by every analysis of that design point.

SI inside; the dataset's variables carry their units.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict, dataclass

import numpy as np

import lsbg

__all__ = ["ToothMaterial", "FEMeshSettings", "FlankGrid", "drive_flank", "flank_grid",
           "member_compliance", "tooth_compliance", "compliance_hash"]

#: Tooth offsets of the segment's teeth from the loaded one [-].
TOOTH_OFFSETS = (-1, 0, 1)


@dataclass(frozen=True)
class ToothMaterial:
    """Elastic constants of both members.

    Parameters
    ----------
    young_modulus : float
        E [Pa] (steel 2.06e11).
    poisson_ratio : float
        nu [-] (steel 0.3).
    """

    young_modulus: float = 2.06e11
    poisson_ratio: float = 0.3

    def __post_init__(self):
        from lsbg.tooth.elasticity import check_material

        check_material(self.young_modulus, self.poisson_ratio)


@dataclass(frozen=True)
class FEMeshSettings:
    """Finite-element mesh and flank grid of the compliance.

    Parameters
    ----------
    tooth_size : float
        Element size on the teeth, as a fraction of the mean normal module
        [-]; the element size in metres is ``tooth_size * m_mn``.
    body_size : float
        Element size deep in the rim, as a multiple of the tooth size [-].
    fillet_radius : float
        Root fillet radius, a multiple of the mean normal module [-].
    face_points, profile_points : int
        Load points across the face width and across the field of contact
        [-].
    """

    tooth_size: float = 0.6
    body_size: float = 3.0
    fillet_radius: float = 0.25
    face_points: int = 9
    profile_points: int = 7

    def __post_init__(self):
        if not (math.isfinite(self.tooth_size) and 0.1 <= self.tooth_size <= 1.0):
            raise ValueError(f"tooth_size = {self.tooth_size!r}: must lie in [0.1, 1.0] mean "
                             f"normal modules (coarser leaves fewer than about three elements "
                             f"across the tooth; finer, see lsbg.tooth.compliance.resources)")
        if not (math.isfinite(self.body_size) and 1.0 <= self.body_size <= 10.0):
            raise ValueError(f"body_size = {self.body_size!r}: must lie in [1, 10] tooth sizes")
        if not (math.isfinite(self.fillet_radius) and 0.05 <= self.fillet_radius <= 0.4):
            raise ValueError(f"fillet_radius = {self.fillet_radius!r}: must lie in [0.05, 0.4] "
                             f"mean normal modules")
        for name in ("face_points", "profile_points"):
            value = getattr(self, name)
            if isinstance(value, bool) or int(value) != value or not 3 <= value <= 25:
                raise ValueError(f"{name} = {value!r}: must be a whole number in [3, 25]")


@dataclass(frozen=True)
class FlankGrid:
    """Load and probe points of one member's flank grid.

    Attributes
    ----------
    cone_distance : numpy.ndarray, shape (f,)
        Grid distances from the apex [m].
    profile_angle : numpy.ndarray, shape (p,)
        Grid polar angles psi in the plane of action [rad].
    flank, outward : numpy.ndarray, shape (f, p, 3)
        Points of tooth 0's drive flank and their normals out of the tooth.
    middle : numpy.ndarray, shape (f, p, 3)
        Points of the tooth's middle surface under the flank points [m].
    half_thickness : numpy.ndarray, shape (f, p)
        Distance from the flank point to the middle point [m].
    """

    cone_distance: np.ndarray
    profile_angle: np.ndarray
    flank: np.ndarray
    outward: np.ndarray
    middle: np.ndarray
    half_thickness: np.ndarray


def grid_axes(pair, settings):
    """Cone distances and plane-of-action polar angles of the flank grid [m, rad].

    Both run a little inside the field (2 % of its extent) so that the load
    points lie inside the meshed solid; the LTCA extrapolates linearly to the
    field's edges.
    """
    psi_lo, psi_hi, r_in, r_out = pair.planes["drive"].field
    inset = 0.02
    rho = np.linspace(r_in + inset * (r_out - r_in), r_out - inset * (r_out - r_in),
                      int(settings.face_points))
    psi = np.linspace(psi_lo + inset * (psi_hi - psi_lo), psi_hi - inset * (psi_hi - psi_lo),
                      int(settings.profile_points))
    return rho, psi


def member_polar_angle(pair, member, cone_distance, profile_angle):
    """Polar angle from a member's axis of plane-of-action points [rad].

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    cone_distance, profile_angle : array_like
        (rho [m], psi [rad]) in the drive side's plane of action.

    Returns
    -------
    numpy.ndarray
    """
    plane = pair.planes["drive"]
    point = plane.point(np.asarray(cone_distance, float), np.asarray(profile_angle, float))
    unit = point / np.linalg.norm(point, axis=-1, keepdims=True)
    return np.arccos(np.clip(unit @ pair.axis[member], -1.0, 1.0))


def drive_flank(pair, member, cone_distance, polar_angle):
    """Tooth 0's drive flank, its normal out of the tooth, and its coast flank [m, -, m].

    The tooth lies between its drive and coast flanks at the same cone
    distance and polar angle, which fixes the normal's sense.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    cone_distance, polar_angle : array_like
        [m], [rad] from the member's axis.

    Returns
    -------
    flank, outward, coast : numpy.ndarray, shape (..., 3)
    """
    flank, normal = pair.flank(member, "drive", cone_distance, polar_angle)
    coast, _ = pair.flank(member, "coast", cone_distance, polar_angle)
    outward = -np.sign(np.sum(normal * (coast - flank), axis=-1))[..., None] * normal
    return flank, outward, coast


def flank_grid(pair, member, settings):
    """The flank grid of one member (tooth 0, drive side).

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    settings : FEMeshSettings

    Returns
    -------
    FlankGrid
    """
    rho, psi = grid_axes(pair, settings)
    radius, angle = np.meshgrid(rho, psi, indexing="ij")
    polar = member_polar_angle(pair, member, radius, angle)
    flank, outward, coast = drive_flank(pair, member, radius, polar)
    return FlankGrid(rho, psi, flank, outward, 0.5 * (flank + coast),
                     0.5 * np.linalg.norm(coast - flank, axis=-1))


def _fillet_points(pair, member, segment_mesh, fillet_radius):
    """Boundary vertices on the root fillets of tooth 0, both sides.

    The fillet rounds the corner where the flank (or its radial continuation)
    meets the root cone; its surface lies within one fillet radius of that
    corner line. Points within 2 % of the face width of the toe and heel are
    left out (the end faces' edges).

    Returns
    -------
    points : numpy.ndarray, shape (p, 3)
    cells : numpy.ndarray, shape (p,)
        A tetrahedron holding each point.
    side : numpy.ndarray, shape (p,)
        0 drive, 1 coast.
    cone_distance : numpy.ndarray, shape (p,)
    """
    from lsbg.solids import _sphere_points

    d = pair.design
    nodes, tets = segment_mesh.nodes, segment_mesh.tetrahedra
    # boundary vertices: those of faces used by one tetrahedron
    faces = np.sort(np.concatenate([tets[[0, 1, 2]], tets[[0, 1, 3]], tets[[0, 2, 3]],
                                    tets[[1, 2, 3]]], axis=1), axis=0)
    unique, counts = np.unique(faces, axis=1, return_counts=True)
    boundary = np.unique(unique[:, counts == 1])
    x = nodes[:, boundary].T
    radius = np.linalg.norm(x, axis=1)
    margin = 0.02 * d.face_width
    keep = (radius > d.inner_cone_distance + margin) & (radius < d.outer_cone_distance - margin)
    start = pair.flank_polar_range(member)[0]
    rows, sides = [], []
    for s, side in enumerate(("drive", "coast")):
        samples = np.linspace(d.inner_cone_distance, d.outer_cone_distance, 41)
        foot, _ = pair.flank(member, side, samples, np.full(samples.size, start))
        azimuth = pair.azimuth(member, foot)
        corner = _sphere_points(pair, member, samples, d.root_angle(member), azimuth)
        # distance of each vertex to the corner polyline
        seg = np.diff(corner, axis=0)
        rel = x[:, None, :] - corner[None, :-1, :]
        t = np.clip(np.sum(rel * seg[None], axis=2) / np.sum(seg * seg, axis=1)[None], 0, 1)
        distance = np.min(np.linalg.norm(rel - t[..., None] * seg[None], axis=2), axis=1)
        near = keep & (distance < 1.05 * fillet_radius)
        rows.append(np.flatnonzero(near))
        sides.append(np.full(np.count_nonzero(near), s))
    chosen = np.concatenate(rows)
    vertex = boundary[chosen]
    # one tetrahedron per vertex
    owner = np.full(nodes.shape[1], -1)
    for corner_index in range(4):
        owner[tets[corner_index]] = np.arange(tets.shape[1])
    return x[chosen], owner[vertex], np.concatenate(sides), radius[chosen]


def member_compliance(pair, member, material, settings):
    """Influence coefficients and fillet stresses of one member by finite elements.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    material : ToothMaterial
    settings : FEMeshSettings

    Returns
    -------
    dict
        ``compliance`` (offset, face_load... ) as an array of shape
        (3, f, p, f, p): displacement [m/N] of the middle point under grid
        point (i, j) of tooth ``offset`` along the load direction there, for
        a unit normal force at grid point (k, l) of tooth 0 pressing on the
        flank; ``fillet_stress`` (q, 3, 3, f, p) [Pa/N] at the fillet points,
        ``fillet_side``, ``fillet_cone_distance``, ``fillet_points``;
        ``grid`` (:class:`FlankGrid`); and the mesh figures ``nodes``,
        ``elements``, ``dofs``, ``seconds``.
    """
    import time

    from lsbg.tooth.elasticity import ElasticSegment
    from lsbg.tooth.segment import segment_mesh
    from lsbg.vectors import rotate

    started = time.perf_counter()
    d = pair.design
    normal_module = d.mean_module * math.cos(d.spiral_angle)
    size = settings.tooth_size * normal_module
    mesh = segment_mesh(pair, member, size, settings.body_size * size,
                        fillet_radius=settings.fillet_radius)
    solid = ElasticSegment(mesh, material.young_modulus, material.poisson_ratio)
    grid = flank_grid(pair, member, settings)
    f, p = grid.half_thickness.shape
    inward = -grid.outward.reshape(-1, 3)
    # just under the surface, inside the faceted mesh (the probes at the middle
    # surface, half a tooth thickness away, do not see the difference)
    points = grid.flank.reshape(-1, 3) + 0.2 * size * inward
    displacement = solid.solve(solid.point_forces(points, inward))
    axis = pair.rotation_axis[member]
    pitch = 2 * math.pi / d.teeth[member - 1]
    compliance = np.zeros((len(TOOTH_OFFSETS), f, p, f, p))
    for o, offset in enumerate(TOOTH_OFFSETS):
        where = rotate(grid.middle.reshape(-1, 3), axis, offset * pitch)
        along = rotate(inward, axis, offset * pitch)
        compliance[o] = solid.displacement_along(displacement, where, along).reshape(f, p, f, p)
    fillet_radius = settings.fillet_radius * normal_module
    fillet, cells, side, radius = _fillet_points(pair, member, mesh, fillet_radius)
    stress = solid.stress(displacement, fillet, cells)  # (q, n, 3, 3)
    stress = np.transpose(stress, (0, 2, 3, 1)).reshape(len(fillet), 3, 3, f, p)
    return {"compliance": compliance, "fillet_stress": stress, "fillet_side": side,
            "fillet_cone_distance": radius, "fillet_points": fillet, "grid": grid,
            "nodes": mesh.nodes.shape[1], "elements": mesh.tetrahedra.shape[1],
            "dofs": solid.dofs, "seconds": time.perf_counter() - started}


def compliance_hash(design, material, settings):
    """Hash of a compliance's inputs: the design, the material, the mesh settings, lsbg's
    tooth sources [hex]."""
    from pathlib import Path

    digest = hashlib.sha256()
    digest.update(json.dumps({"design": design.to_config(), "material": asdict(material),
                              "settings": asdict(settings)}, sort_keys=True).encode())
    here = Path(__file__).parent
    for name in ("segment.py", "elasticity.py", "compliance.py"):
        digest.update((here / name).read_bytes())
    return digest.hexdigest()[:16]


def tooth_compliance(pair, material=None, settings=None):
    """Finite-element compliance of both members of a pair.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    material : ToothMaterial, optional
    settings : FEMeshSettings, optional

    Returns
    -------
    xarray.Dataset
        ``compliance_pinion``, ``compliance_gear`` (tooth_offset, face, profile,
        load_face, load_profile) [um/N... stored in m/N]; ``half_thickness_*``
        (face, profile) [m]; ``fillet_stress_*`` (fillet_*, i, j, load_face,
        load_profile) [Pa/N] with their side and cone distance; coordinates
        ``cone_distance`` [m] and ``profile_angle`` [rad] of the grid.
        Attributes: the inputs' hash, the mesh figures, E, nu and the design.
    """
    import xarray as xr

    material = material or ToothMaterial()
    settings = settings or FEMeshSettings()
    design = pair.design
    variables, attrs = {}, {}
    for member, name in ((1, "pinion"), (2, "gear")):
        out = member_compliance(pair, member, material, settings)
        grid = out["grid"]
        variables[f"compliance_{name}"] = (
            ("tooth_offset", "face", "profile", "load_face", "load_profile"), out["compliance"],
            {"units": "m/N", "long_name": f"{name}: displacement of the tooth's middle surface "
                                          f"along the load direction per unit normal load"})
        variables[f"half_thickness_{name}"] = (("face", "profile"), grid.half_thickness,
                                               {"units": "m", "long_name": "flank to middle surface"})
        variables[f"fillet_stress_{name}"] = (
            (f"fillet_{name}", "i", "j", "load_face", "load_profile"), out["fillet_stress"],
            {"units": "Pa/N", "long_name": f"{name}: stress tensor at root fillet points "
                                           f"per unit normal load"})
        variables[f"fillet_side_{name}"] = (f"fillet_{name}", out["fillet_side"],
                                            {"long_name": "0 drive side, 1 coast side"})
        variables[f"fillet_cone_distance_{name}"] = (f"fillet_{name}", out["fillet_cone_distance"],
                                                     {"units": "m"})
        for key in ("nodes", "elements", "dofs"):
            attrs[f"fe_{key}_{name}"] = int(out[key])
        attrs[f"fe_seconds_{name}"] = float(out["seconds"])
        rho, psi = grid.cone_distance, grid.profile_angle
    attrs.update({
        "title": f"Finite-element tooth compliance of a {design.trace} spiral bevel gear pair",
        "source": f"lsbg {lsbg.__version__} (lsbg.tooth.compliance), scikit-fem P2 tetrahedra",
        "inputs_hash": compliance_hash(design, material, settings),
        **{f"material_{k}": float(v) for k, v in asdict(material).items()},
        **{f"fe_{k}": v for k, v in asdict(settings).items()},
        **{f"design_{k}": v for k, v in design.to_config().items()},
    })
    return xr.Dataset(variables, coords={
        "tooth_offset": ("tooth_offset", np.array(TOOTH_OFFSETS)),
        "cone_distance": ("face", rho, {"units": "m"}),
        "profile_angle": ("profile", psi, {"units": "rad"}),
    }, attrs=attrs)
