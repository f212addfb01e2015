"""The tooth's compliance by finite elements: influence coefficients over the flank.

For each member a segment (:mod:`lsbg.tooth.segment`) is loaded, one unit
normal force at a time, at the points of a grid on the drive flank of its
middle tooth (tooth 0) -- each spread over the flank by the tent of its grid
point, the shape with which the LTCA's bilinear interpolation spreads a
contact load -- and the answers are read

* on every tooth of the segment (-1, 0, +1) at the same grid points: the
  displacement along the load direction of the point of the tooth's middle
  surface under the flank point (the tooth's bending, shear and rim
  deflection, and what the load does to the neighbours). The compression of
  the tooth between its flank and its middle is the local contact term of
  :mod:`lsbg.tooth.local` (Hertz's half-width against the half thickness),
  so the two do not count it twice;
* at points of the root fillets of tooth 0, both sides: the stress tensor
  (the mean of the tetrahedra around each point), from which
  :mod:`lsbg.tooth.ltca` takes the largest tensile principal stress of the
  superposed loads.

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
from lsbg.gear.flank import drive_flank, member_polar_angle

__all__ = ["ToothMaterial", "FEMeshSettings", "FlankGrid", "flank_grid", "mesh_sizes",
           "member_compliance", "tooth_compliance", "compliance_hash"]

#: Tooth offsets of the segment's teeth from the loaded one [-].
TOOTH_OFFSETS = (-1, 0, 1)
#: Element size on tooth 0's drive-side root fillet, as a fraction of the fillet
#: radius per mean normal module of ``tooth_size`` [-]: 0.45 rho at the default
#: 0.5, halving with the tooth size. The root stress peaks there; with 0.6 rho
#: the gear's maximum still moved by 5-8 % from one mesh to the next.
FILLET_REFINEMENT = 0.9
#: The coast-side fillet's element size over the drive side's [-]: compressed
#: under drive-side loads, its stress is not read, but its resolution sets 2 %
#: of the tooth's bending compliance.
COAST_FILLET = 1.5
#: Sub-cells per grid cell and axis of the quadrature of the spread unit loads [-].
LOAD_SUBDIVISION = 4
#: Largest ``tooth_size`` [m_mn]: three elements across the normal tooth
#: thickness at the mean point, about pi/2 m_mn (a pair's own thickness is
#: checked by :func:`mesh_sizes`).
MAX_TOOTH_SIZE = math.pi / 6
#: Fewest elements across a member's own normal tooth thickness at the mean point
#: (:func:`mesh_sizes`; 2.9: the paper's teeth are a little thinner than the
#: nominal pi/2 m_mn of MAX_TOOTH_SIZE, and keep the size they were converged at) [-].
MIN_ACROSS = 2.9


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
        Element size on the loaded tooth, as a fraction of the mean normal
        module [-]; the element size in metres is ``tooth_size * m_mn``. At
        most pi/6 (three elements across the tooth). The drive-side root
        fillet gets ``FILLET_REFINEMENT * tooth_size * fillet_radius * m_mn``
        (0.45 of the fillet radius at the default), and every size grows
        from there with the distance (:mod:`lsbg.tooth.segment`), so refining
        ``tooth_size`` refines the whole mesh. Default 0.5: a further
        refinement to 0.375 moves the mesh stiffness by 0.5-0.6 % and the
        largest root stresses by 0.4-4.5 % (the paper's pair, 35 deg, both
        traces, 7-tooth segments; the stresses scatter by about 3 % from mesh
        to mesh).
    body_size : float
        Largest element size, far in the rim, as a multiple of the tooth size
        [-].
    fillet_radius : float
        Root fillet radius, a multiple of the mean normal module [-].
    face_points, profile_points : int
        Load points across the face width and across the field of contact
        [-].
    segment_teeth : int
        Teeth of the segment, odd, >= 3 [-]. Its cut faces are clamped, which
        stiffens the rim under the loaded tooth: in the spur-like limit
        (tests/tooth/test_limits.py) the tooth compliance at the pitch point
        is 0.78 of the potential-energy reference with 3 teeth, 0.85 with 5
        and 0.90 with 7 (9 teeth add about 2 % more); 7 costs about 5 % more
        degrees of freedom than 3, the rim's elements being large.
    """

    tooth_size: float = 0.5
    body_size: float = 6.0
    fillet_radius: float = 0.25
    face_points: int = 9
    profile_points: int = 7
    segment_teeth: int = 7

    def __post_init__(self):
        if not (math.isfinite(self.tooth_size) and 0.1 <= self.tooth_size <= MAX_TOOTH_SIZE):
            raise ValueError(f"tooth_size = {self.tooth_size!r}: must lie in [0.1, "
                             f"{MAX_TOOTH_SIZE:.3f}] mean normal modules (coarser leaves fewer "
                             f"than three elements across the tooth, whose normal thickness at "
                             f"the mean point is about pi/2 m_mn; finer costs time and memory, "
                             f"see lsbg.tooth.resources.fe_resource_estimate)")
        if not (math.isfinite(self.body_size) and 1.0 <= self.body_size <= 10.0):
            raise ValueError(f"body_size = {self.body_size!r}: must lie in [1, 10] tooth sizes")
        if not (math.isfinite(self.fillet_radius) and 0.05 <= self.fillet_radius <= 0.4):
            raise ValueError(f"fillet_radius = {self.fillet_radius!r}: must lie in [0.05, 0.4] "
                             f"mean normal modules")
        teeth = self.segment_teeth
        if isinstance(teeth, bool) or int(teeth) != teeth or teeth < 3 or teeth % 2 == 0:
            raise ValueError(f"segment_teeth = {teeth!r}: must be an odd whole number >= 3")
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


def flank_grid(pair, member, settings):
    """The flank grid of one member (tooth 0, drive side).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    settings : FEMeshSettings
        Its ``face_points`` x ``profile_points`` grid (:func:`grid_axes`).

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


def _hat_weights(axis, fine):
    """Tent functions of a grid axis at fine points, shape (n, len(fine)) [-].

    The weights of linear interpolation on the axis (one-sided at its ends):
    the shape of the bilinear interpolation the LTCA spreads a load with.
    """
    return np.stack([np.interp(fine, axis, np.eye(axis.size)[i]) for i in range(axis.size)])


def _load_patches(pair, member, grid, depth):
    """Points, directions and weights of the flank grid's unit loads [m, -, N per N].

    Load (i, j) of the grid is not a point force but a unit normal force
    spread over the flank with the bilinear tent of grid point (i, j) as its
    pressure: the LTCA spreads each contact load bilinearly over the grid
    points anyway, and a point force would put a singular stress field into
    the root fillet next to the lowest row of the grid (the gear's lies
    about a millimetre above its fillet), which no mesh converges. The
    tents' surface integral is a midpoint rule on ``LOAD_SUBDIVISION``
    sub-cells per grid cell.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    grid : FlankGrid
    depth : float
        How far below the flank the forces act, inside the faceted mesh [m].

    Returns
    -------
    points : numpy.ndarray, shape (s, 3)
    directions : numpy.ndarray, shape (s, 3)
        Into the tooth.
    weights : numpy.ndarray, shape (s, f * p)
        Force of each point in each load (face-major), each column summing to 1.
    """
    rho, psi = grid.cone_distance, grid.profile_angle
    n = LOAD_SUBDIVISION

    def midpoints(axis):
        edges = np.interp(np.arange((axis.size - 1) * n + 1) / n, np.arange(axis.size), axis)
        return 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)

    fine_rho, d_rho = midpoints(rho)
    fine_psi, d_psi = midpoints(psi)
    radius, angle = np.meshgrid(fine_rho, fine_psi, indexing="ij")
    h = 1e-6
    flank, outward, _ = drive_flank(pair, member, radius,
                                    member_polar_angle(pair, member, radius, angle))
    # surface area per unit rho and psi, by differences
    x_rho = drive_flank(pair, member, radius + h * rho.mean(),
                        member_polar_angle(pair, member, radius + h * rho.mean(), angle))[0]
    x_psi = drive_flank(pair, member, radius, member_polar_angle(
        pair, member, radius, angle + h))[0]
    area = np.linalg.norm(np.cross(x_rho - flank, x_psi - flank), axis=-1) \
        / (h * rho.mean() * h) * d_rho[:, None] * d_psi[None, :]
    tents = np.einsum("ia,jb,ab->abij", _hat_weights(rho, fine_rho),
                      _hat_weights(psi, fine_psi), area)
    weights = tents.reshape(fine_rho.size * fine_psi.size, rho.size * psi.size)
    weights /= weights.sum(axis=0, keepdims=True)
    inward = -outward.reshape(-1, 3)
    return flank.reshape(-1, 3) + depth * inward, inward, weights


def mesh_sizes(pair, member, settings):
    """Element sizes of a member's segment mesh [m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    settings : FEMeshSettings
        Its ``tooth_size`` and ``fillet_radius`` [mean normal modules] and
        ``body_size`` [tooth sizes].

    Returns
    -------
    dict
        ``tooth`` (tooth 0), ``fillet`` (its drive-side root fillet),
        ``coast_fillet`` and ``body`` (the largest, far in the rim) [m], and
        ``across``, the elements across the member's normal tooth thickness at
        the mean point [-].

    Notes
    -----
    A member whose teeth would get fewer than :data:`MIN_ACROSS` elements
    across at ``tooth_size`` (a tooth thinned by the design's thickness
    modification) is meshed at its thickness over :data:`MIN_ACROSS` instead.
    """
    d = pair.design
    normal_module = d.mean_module * math.cos(d.spiral_angle)
    tooth = settings.tooth_size * normal_module
    fillet = FILLET_REFINEMENT * settings.tooth_size * settings.fillet_radius * normal_module
    thickness = d.mean_tooth_thickness(member) * math.cos(d.spiral_angle)
    if thickness / tooth < MIN_ACROSS:
        # a member thinned by its design (the gear of a shifted pair, ISO 23509's
        # x_smn) keeps three elements across its own teeth; the other keeps its size
        tooth = thickness / MIN_ACROSS
        fillet = FILLET_REFINEMENT * tooth * settings.fillet_radius
    across = thickness / tooth
    return {"tooth": tooth, "fillet": fillet, "coast_fillet": COAST_FILLET * fillet,
            "body": settings.body_size * tooth, "across": across}


def member_compliance(pair, member, material, settings):
    """Influence coefficients and fillet stresses of one member by finite elements.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    material : ToothMaterial
    settings : FEMeshSettings

    Returns
    -------
    dict
        ``compliance`` (offset, face_load... ) as an array of shape
        (3, f, p, f, p): displacement [m/N] of the middle point under grid
        point (i, j) of tooth ``offset`` along the load direction there, for
        a unit normal force on tooth 0's flank spread by the tent of grid
        point (k, l) (:func:`_load_patches`); ``fillet_stress`` (q, 3, 3, f, p)
        [Pa/N] at the fillet points,
        ``fillet_side``, ``fillet_cone_distance``, ``fillet_points``;
        ``grid`` (:class:`FlankGrid`); and the mesh figures ``nodes``,
        ``elements``, ``dofs``, ``seconds``.
    """
    import time

    from lsbg.tooth.elasticity import ElasticSegment
    from lsbg.tooth.segment import fillet_points, segment_mesh
    from lsbg.gear.vectors import rotate

    started = time.perf_counter()
    d = pair.design
    normal_module = d.mean_module * math.cos(d.spiral_angle)
    sizes = mesh_sizes(pair, member, settings)
    size = sizes["tooth"]
    mesh = segment_mesh(pair, member, size, sizes["body"], teeth=settings.segment_teeth,
                        fillet_radius=settings.fillet_radius,
                        fillet_size=sizes["fillet"], coast_fillet_size=sizes["coast_fillet"])
    solid = ElasticSegment(mesh, material.young_modulus, material.poisson_ratio)
    grid = flank_grid(pair, member, settings)
    f, p = grid.half_thickness.shape
    inward = -grid.outward.reshape(-1, 3)
    # just under the surface, inside the faceted mesh (the probes at the middle
    # surface, half a tooth thickness away, do not see the difference)
    points, directions, weights = _load_patches(pair, member, grid, 0.2 * size)
    displacement = solid.solve(solid.point_forces(points, directions, weights))
    axis = pair.rotation_axis[member]
    pitch = 2 * math.pi / d.teeth[member - 1]
    compliance = np.zeros((len(TOOTH_OFFSETS), f, p, f, p))
    for o, offset in enumerate(TOOTH_OFFSETS):
        where = rotate(grid.middle.reshape(-1, 3), axis, offset * pitch)
        along = rotate(inward, axis, offset * pitch)
        compliance[o] = solid.displacement_along(displacement, where, along).reshape(f, p, f, p)
    fillet_radius = settings.fillet_radius * normal_module
    fillet, cells, owner, side, radius = fillet_points(pair, member, mesh, fillet_radius)
    stress = solid.mean_stress(displacement, fillet, cells, owner)  # (q, n, 3, 3)
    stress = np.transpose(stress, (0, 2, 3, 1)).reshape(len(fillet), 3, 3, f, p)
    return {"compliance": compliance, "fillet_stress": stress, "fillet_side": side,
            "fillet_cone_distance": radius, "fillet_points": fillet, "grid": grid,
            "nodes": mesh.nodes.shape[1], "elements": mesh.tetrahedra.shape[1],
            "dofs": solid.dofs, "seconds": time.perf_counter() - started}


def compliance_hash(design, material, settings):
    """Hash of a compliance's inputs: the design, the material, the mesh settings, lsbg's
    tooth sources and the flank helpers its grid is built with [hex]."""
    from pathlib import Path

    digest = hashlib.sha256()
    digest.update(json.dumps({"design": design.to_config(), "material": asdict(material),
                              "settings": asdict(settings)}, sort_keys=True).encode())
    here = Path(__file__).parent
    for path in (here / "segment.py", here / "elasticity.py", here / "cholesky.py",
                 here / "compliance.py", here.parent / "gear" / "flank.py"):
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def tooth_compliance(pair, material=None, settings=None):
    """Finite-element compliance of both members of a pair.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
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
