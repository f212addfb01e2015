"""Unloaded tooth contact analysis (TCA) from the real flank surfaces.

:func:`tooth_contact_analysis` turns the pinion through one mesh cycle and, at
each position, finds where the modified pinion flank and the displaced gear
flank first touch (:func:`lsbg.tca.surface.contact_search`). From it:

* the unloaded **transmission error** TE = phi1 z1/z2 - phi2 [gear rotation,
  positive when the gear lags], the first thing a TCA predesigns (a
  parabola of a few arc-seconds per mesh cycle, Litvin & Fuentes 2004);
* the **path of contact** on the gear flank (cone distance, height above the
  root cone);
* the instantaneous **contact ellipse** at the marking-compound thickness
  (6.35 µm, the usual 0.00025 in): the set of flank points whose separation
  from the mate is at most that, from the first and second moments of the
  grid points inside it (a filled ellipse of semi-axes a, b has variances
  a^2/4 and b^2/4 along them);
* the **bearing pattern**: on a grid of the gear flank, the least separation
  over the mesh cycle; the pattern is where it is at most the marking
  thickness, the picture a gear lab takes with marking compound;
* a flag wherever a contact ellipse reaches an **edge** of the gear flank:
  toe, heel, tip (the gear's top land) or root (the pinion's top land, at
  the gear's root end).

Units: SI inside; the dataset speaks µrad, mm, µm and degrees (``units``
attributes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lsbg.tca import surface
from lsbg.tca.pattern import (MARKING_COMPOUND, bearing_pattern, chart_ellipses,
                               contact_ellipses, profile_height, raster_centres)
from lsbg.memo import arrays_key, copied, fields_key, memoised
from lsbg.tca.misalignment import Misalignment, member_frames
from lsbg.tca.modification import FlankModification, flank_attributes, relieved_flank
from lsbg.gear.flank import active_polar_range
from lsbg.files import short_labels
from lsbg.gear.vectors import unit

#: Mesh positions over one mesh cycle.
POSITIONS = 200
#: Pinion flank grid: points across the face and along the profile.
FACE_POINTS, PROFILE_POINTS = 101, 181
#: Gear-flank raster of the bearing pattern: cone distance x polar angle.
RASTER_SHAPE = (50, 40)
#: Pinion teeth searched around tooth 0.
TEETH = np.arange(-3, 4)


@dataclass(frozen=True)
class SurfacePair:
    """The kernel data of a displaced pair with a modified pinion flank.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification
    misalignment : Misalignment
    face_points, profile_points : int
        Pinion flank grid [-].

    Attributes
    ----------
    constants : numpy.ndarray
        The pair's constants for :mod:`lsbg.tca.surface` (``G_*``).
    points, normals : numpy.ndarray, shape (face x profile, 3)
        The modified pinion flank of tooth 0 [m] and its outward normals [-].
    line_turn : numpy.ndarray
        Turn of the conjugate contact line through each point [rad].
    cone_distance, profile_psi : numpy.ndarray
        The grid's cone distances [m] and plane-of-action polar angles [rad].
    relief : numpy.ndarray, shape (face, profile)
        The modification at the grid points [m].
    """

    pair: object
    modification: FlankModification
    misalignment: Misalignment
    constants: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    line_turn: np.ndarray
    order: np.ndarray
    cone_distance: np.ndarray
    profile_psi: np.ndarray
    relief: np.ndarray

    @classmethod
    def build(cls, pair, modification=None, misalignment=None, face_points=None,
              profile_points=None, side="drive"):
        """Grid the pinion flank, apply the modification, set the displacements
        (default grid: :data:`FACE_POINTS` x :data:`PROFILE_POINTS`). The
        modification applies to the drive flank; the coast flank (``side``)
        is the conjugate one, displaced."""
        face_points = face_points or FACE_POINTS
        profile_points = profile_points or PROFILE_POINTS
        modification = (modification or FlankModification()).load()
        misalignment = misalignment or Misalignment()
        # the grid does not depend on the design, the constants not on the modification:
        # an ease-off search and a V-H map ask for them again and again
        rho, psi, big_rho, big_psi, polar_range, flat_turn, order = memoised(
            pair, "flank_grid", (side, face_points, profile_points),
            lambda: _flank_grid(pair, side, face_points, profile_points))
        points, normals, relief = relieved_flank(pair, modification, big_rho, big_psi, side,
                                                 polar_range)
        g = memoised(pair, "surface_constants",
                     (side, fields_key(misalignment)),
                     lambda: _surface_constants(pair, misalignment, side))
        return cls(pair, modification, misalignment, g.copy(),
                   np.ascontiguousarray(points.reshape(-1, 3)),
                   np.ascontiguousarray(normals.reshape(-1, 3)),
                   *copied((flat_turn, order, rho, psi)), relief)

    @property
    def grid_shape(self):
        return self.cone_distance.size, self.profile_psi.size


def _flank_grid(pair, side, face_points, profile_points):
    """The pinion flank's grid of :meth:`SurfacePair.build`: cone distances [m] and
    polar angles psi [rad], both on the grid, the flank's polar range [rad], the
    conjugate lines' turns through the points [rad] and their order."""
    design = pair.design
    plane = pair.planes[side]
    # pinion flank grid: cone distance x plane-of-action polar angle psi
    # (uniform in psi is uniform along the path of contact)
    rho = np.linspace(design.inner_cone_distance, design.outer_cone_distance, face_points)
    polar_range = pair.flank_polar_range(1)
    psi_ends = (plane.tangency_angle[1]
                + plane.roll_sign[1] * pair.roll_angle(1, np.array(polar_range)))
    psi = np.linspace(psi_ends[0], psi_ends[1], profile_points)
    big_rho, big_psi = np.meshgrid(rho, psi, indexing="ij")
    line_turn = big_psi - plane.curve.polar_angle(big_rho)
    flat_turn = np.ascontiguousarray(line_turn.ravel())
    return (rho, psi, big_rho, big_psi, polar_range, flat_turn,
            np.argsort(flat_turn, kind="stable"))


def _surface_constants(pair, misalignment, side):
    """The pair's constants for :mod:`lsbg.tca.surface` (``G_*``) on a side, displaced."""
    design = pair.design
    plane = pair.planes[side]
    curve = plane.curve
    pinion_shift, gear_turn, gear_shift = member_frames(pair, misalignment)
    u2 = pair.rotation_axis[2]
    ref2 = unit(pair.pitch_dir - (pair.pitch_dir @ u2) * u2)
    g = np.zeros(surface.N_GEOMETRY)
    g[surface.G_U1:surface.G_U1 + 3] = pair.rotation_axis[1]
    g[surface.G_T1:surface.G_T1 + 3] = pinion_shift
    g[surface.G_TURN:surface.G_TURN + 9] = gear_turn.ravel()
    g[surface.G_T2:surface.G_T2 + 3] = gear_shift
    g[surface.G_A2:surface.G_A2 + 3] = pair.axis[2]
    g[surface.G_U2:surface.G_U2 + 3] = u2
    g[surface.G_REF2:surface.G_REF2 + 3] = ref2
    g[surface.G_OTHER2:surface.G_OTHER2 + 3] = np.cross(u2, ref2)
    g[surface.G_P:surface.G_P + 3] = plane.pitch_dir
    g[surface.G_Q:surface.G_Q + 3] = plane.cross_dir
    g[surface.G_PSI_G2], g[surface.G_ROLL2] = plane.tangency_angle[2], plane.roll_sign[2]
    g[surface.G_DELTA_B2] = design.base_cone_angle(2)
    g[surface.G_COS_DELTA_B2] = math.cos(g[surface.G_DELTA_B2])
    g[surface.G_COS_PSI_G2] = math.cos(g[surface.G_PSI_G2])
    g[surface.G_SIN_PSI_G2] = math.sin(g[surface.G_PSI_G2])
    g[surface.G_S2] = pair.axis_normal_component(2, side)
    g[surface.G_OFFSET2] = pair.flank_offset[(2, side)]
    g[surface.G_OFFSET1] = pair.flank_offset[(1, side)]
    g[surface.G_SIDE] = 1.0 if side == "drive" else -1.0
    g[surface.G_KIND] = 0.0 if curve.kind == "logarithmic" else 1.0
    g[surface.G_TAN_BETA] = math.tan(curve.plane_spiral_angle)
    g[surface.G_RM] = curve.mean_distance
    if curve.kind != "logarithmic":
        g[surface.G_RHO0], g[surface.G_THETA0], g[surface.G_BRANCH] = curve._arc
        g[surface.G_RC] = curve.cutter_radius
        g[surface.G_POLAR_SCALE] = curve.polar_scale
    # the gear's active flank: beyond it the gear's tip sweeps the pinion's
    # undercut, which the generated pinion does not have
    g[surface.G_THETA_LO2], g[surface.G_THETA_HI2] = active_polar_range(pair, 2, side)
    g[surface.G_R_IN], g[surface.G_R_OUT] = design.inner_cone_distance, design.outer_cone_distance
    z1, z2 = design.teeth
    g[surface.G_GEAR_PITCH], g[surface.G_PINION_PITCH] = 2 * math.pi / z2, 2 * math.pi / z1
    g[surface.G_RATIO] = z1 / z2
    g[surface.G_S1] = pair.axis_normal_component(1, side)
    g[surface.G_ROOT2] = design.root_angle(2)
    return g


def mesh_cycle_pinion_angles(pair, positions=POSITIONS):
    """Pinion rotations over one mesh cycle, 2 pi / z1, endpoint excluded [rad]."""
    return np.arange(int(positions)) / int(positions) * 2 * math.pi / pair.design.teeth[0]


def search(surface_pair, pinion_angles, marking=MARKING_COMPOUND, raster_shape=RASTER_SHAPE):
    """Run the contact search; returns (out, raster, raster limits).

    Parameters
    ----------
    surface_pair : SurfacePair
    pinion_angles : array_like
        Pinion rotations [rad].
    marking : float
        Marking-compound thickness [m].
    raster_shape : (int, int)
        Gear-flank raster (cone distance x polar angle) [-].
    """
    pair = surface_pair.pair
    design = pair.design
    lo, hi = active_polar_range(pair, 2)
    limits = np.array([design.inner_cone_distance, design.outer_cone_distance, lo, hi])
    raster = np.full(raster_shape, np.inf)
    angles = np.ascontiguousarray(np.atleast_1d(np.asarray(pinion_angles, dtype=float)))
    out = np.zeros((angles.size, surface.N_OUT))
    # a grid step of tolerance at the edges: face step [m], profile step [rad]
    tolerance = np.array([(limits[1] - limits[0]) / (surface_pair.grid_shape[0] - 1),
                          (hi - lo) / (surface_pair.grid_shape[1] - 1)])
    window = 0.1 * design.base_pitch_angle
    surface.contact_search(angles, TEETH, surface_pair.points, surface_pair.normals,
                           surface_pair.line_turn, surface_pair.order,
                           surface_pair.grid_shape, surface_pair.constants, window,
                           float(marking), tolerance, raster, limits, out)
    return out, raster, limits


def designed_transmission_error(pair, modification, side="drive"):
    """Peak-to-peak unloaded TE of a crowned pair, closed form [rad of gear].

    The classical predesign (Litvin & Fuentes 2004, §9): near the mean point
    the contact lines are straight in the ease-off coordinates, v = a + k u
    with k = tan(beta_p) b / (R_m Delta psi); the least relief on the line at
    offset a is a^2 C_L C_P / (C_L + C_P k^2) (bias 0), and consecutive lines
    are 2 / eps_alpha apart in a, so the pairs change over at
    a = +-1/eps_alpha. Divided by the normal approach per unit gear rotation
    at the mean point, R_m cos(beta_p) sin(delta_b2).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification
        Lengthwise and profile crowning (bias and topography are not part of
        the closed form).

    Returns
    -------
    float
        TE peak to peak [rad]; 0 when either crowning is 0 (a contact line
        always crosses the line of zero relief when eps_alpha > 1).
    """
    design = pair.design
    plane = pair.planes[side]
    c_l, c_p = modification.lengthwise_crowning, modification.profile_crowning
    if c_l == 0.0 or c_p == 0.0:
        return 0.0
    width = plane.field[1] - plane.field[0]
    beta = float(plane.curve.ray_angle(design.mean_cone_distance))
    k = math.tan(abs(beta)) * design.face_width / (design.mean_cone_distance * width)
    effective = c_l * c_p / (c_l + c_p * k * k)
    profile_ratio = width / design.base_pitch_angle
    lever = design.mean_cone_distance * math.cos(beta) * math.sin(design.base_cone_angle(2))
    return effective / profile_ratio**2 / lever


def _shown(misalignment):
    return ", ".join(f"{k} = {v:g}" for k, v in misalignment.to_config().items() if v) or "none"


def backlash(surface_pair, pinion_angles, drive=None):
    """Free play of the gear between its drive and its coast flanks [rad].

    The coast flanks' first contact is searched like the drive flanks' (on
    the displaced, conjugate coast flanks); the play is the gear rotation
    between the two contacts at each pinion position. For the aligned pair
    it is the design's backlash as a gear rotation, j_t / r_m2; <= 0: the
    members interfere.

    Parameters
    ----------
    surface_pair : SurfacePair
        The drive side's (its modification and displacements are used).
    pinion_angles : array_like
        Pinion rotations [rad].
    drive : numpy.ndarray, optional
        The drive side's :func:`search` output at those angles.

    Returns
    -------
    numpy.ndarray
        Gear rotation from drive to coast contact [rad] (NaN where either
        side has no contact).

    Notes
    -----
    The coast contact depends on the displacements and the positions only
    (the coast flanks stay conjugate), and is kept per pair
    (:func:`lsbg.memo.memoised`).
    """
    pair = surface_pair.pair
    if drive is None:
        drive, _, _ = search(surface_pair, pinion_angles)
    # half the grid: the play only has to be told from zero (a few µrad against the
    # design's 1406), and the conjugate coast flanks touch along lines
    face, profile = surface_pair.grid_shape
    grid = (max(21, face // 2 + 1), max(41, profile // 2 + 1))
    misalignment = surface_pair.misalignment
    angles = np.ascontiguousarray(np.atleast_1d(np.asarray(pinion_angles, dtype=float)))

    def coast_contact():
        coast_pair = SurfacePair.build(pair, surface_pair.modification, misalignment, *grid,
                                       side="coast")
        return search(coast_pair, angles)[0][:, surface.O_PHI2].copy()

    # the coast flanks are conjugate whatever the modification: an ease-off search
    # meets each displacement's coast contact again at every design
    coast = memoised(pair, "coast_contact",
                     (grid, fields_key(misalignment), arrays_key(angles)),
                     coast_contact)
    # the coast search runs on -phi2: its maximum is the gear's coast contact
    return -coast - drive[:, surface.O_PHI2]


def tooth_contact_analysis(pair, modification=None, misalignment=None, positions=POSITIONS,
                           marking=MARKING_COMPOUND, grid=None):
    """Unloaded TCA of a (modified, displaced) pair over one mesh cycle.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification, optional
        Relief of the pinion flank (default: none, the conjugate flank).
    misalignment : Misalignment, optional
        Assembly displacements (default: the aligned pair).
    positions : int
        Pinion positions over one mesh cycle, 2 pi / z1 [-] (at least 8).
    marking : float
        Marking-compound thickness [m].
    grid : (int, int), optional
        Pinion flank grid, points across the face and along the profile
        (default :data:`FACE_POINTS` x :data:`PROFILE_POINTS`) [-].

    Returns
    -------
    xarray.Dataset
        On ``mesh_phase``: ``transmission_error`` [urad], ``pinion_angle``
        [deg], the path of contact on the gear flank
        (``contact_cone_distance``, ``contact_height`` [mm]), the contact
        ellipse of the pair in first contact (centre ``ellipse_cone_distance``,
        ``ellipse_height``; true size ``ellipse_semi_major``,
        ``ellipse_semi_minor`` [mm] and ``ellipse_angle`` [deg] from the cone
        generator; in the flank chart ``chart_semi_major``,
        ``chart_semi_minor`` [mm], ``chart_angle`` [deg]), ``backlash``
        [urad], ``contact_tooth``,
        ``edge_contact`` (mesh_phase, edge); on the gear-flank raster
        (``cone_distance``, ``polar_angle``): ``least_separation`` [um]
        and the 2-D coordinate ``profile_height`` [mm]. Attributes: peak to
        peak TE, the pattern's centre and extent, the share of positions
        with edge contact, the modification and displacements.

    Raises
    ------
    ValueError
        For fewer than 8 positions, a marking thickness <= 0, or a
        displacement at which the drive flanks lose contact or the coast
        flanks close the backlash (the members interfere).
    """
    import xarray as xr

    found = _search_mesh_cycle(pair, modification, misalignment, positions, marking, grid)
    out, raster, limits, angles = found["out"], found["raster"], found["limits"], found["angles"]
    te, play = found["transmission_error"], found["backlash"]
    centre, semi_major, semi_minor, major = contact_ellipses(out)
    generator = centre / np.maximum(np.linalg.norm(centre, axis=1), 1e-300)[:, None]
    angle = np.degrees(np.arccos(np.clip(np.abs(np.sum(major * generator, 1)), 0, 1)))
    chart_centre, chart_major, chart_minor, chart_angle = chart_ellipses(out)
    edges = found["edges"]
    rho, theta = raster_centres(raster.shape, limits)
    height = profile_height(pair, *np.meshgrid(rho, theta, indexing="ij"))
    contact_rho, contact_theta = out[:, surface.O_R2], out[:, surface.O_THETA2]
    attrs = found["attrs"]
    phase = ("mesh_phase",)
    return short_labels(xr.Dataset(
        {
            "transmission_error": (phase, te * 1e6, {
                "units": "urad", "long_name": "unloaded transmission error, gear rotation "
                                              "behind its kinematic position phi1 z1/z2 - phi2"}),
            "pinion_angle": (phase, np.degrees(angles), {"units": "degree",
                                                         "long_name": "pinion rotation"}),
            "contact_tooth": (phase, out[:, surface.O_TOOTH].astype(np.int16), {
                "long_name": "pinion tooth in first contact (0: the reference tooth)"}),
            "contact_cone_distance": (phase, contact_rho * 1e3, {
                "units": "mm", "long_name": "path of contact on the gear flank: distance "
                                            "from the apex"}),
            "contact_height": (phase, profile_height(pair, contact_rho, contact_theta) * 1e3, {
                "units": "mm", "long_name": "path of contact on the gear flank: height above "
                                            "the root cone"}),
            "ellipse_cone_distance": (phase, chart_centre[:, 0] * 1e3, {
                "units": "mm", "long_name": "centre of the contact ellipse: distance from "
                                            "the apex"}),
            "ellipse_height": (phase, chart_centre[:, 1] * 1e3, {
                "units": "mm", "long_name": "centre of the contact ellipse: height above "
                                            "the gear's root cone"}),
            "ellipse_semi_major": (phase, semi_major * 1e3, {
                "units": "mm", "long_name": "semi-major axis of the contact ellipse at the "
                                            "marking-compound thickness (true size)"}),
            "ellipse_semi_minor": (phase, semi_minor * 1e3, {
                "units": "mm", "long_name": "semi-minor axis of the contact ellipse (true size)"}),
            "ellipse_angle": (phase, angle, {
                "units": "degree", "long_name": "angle of the ellipse's major axis to the cone "
                                                "generator (0: lengthwise, 90: along the profile)"}),
            "chart_semi_major": (phase, chart_major * 1e3, {
                "units": "mm", "long_name": "semi-major axis of the contact ellipse in the "
                                            "flank chart (cone distance, height)"}),
            "chart_semi_minor": (phase, chart_minor * 1e3, {
                "units": "mm", "long_name": "semi-minor axis of the contact ellipse in the "
                                            "flank chart"}),
            "chart_angle": (phase, np.degrees(chart_angle), {
                "units": "degree", "long_name": "angle of the chart ellipse's major axis from "
                                                "the cone-distance axis towards the tip"}),
            "backlash": (phase, play * 1e6, {
                "units": "urad", "long_name": "free play of the gear between its drive and "
                                              "coast contacts (gear rotation)"}),
            "edge_contact": (("mesh_phase", "edge"), edges, {
                "long_name": "1 where the contact ellipse reaches that edge of the gear's "
                             "active flank"}),
            "least_separation": (("cone_distance", "polar_angle"),
                                 np.where(np.isfinite(raster), raster * 1e6, np.nan), {
                "units": "um", "long_name": "least separation from the pinion flank over the "
                                            "mesh cycle; the bearing pattern is where it is at "
                                            "most the marking-compound thickness"}),
        },
        coords={
            "mesh_phase": ("mesh_phase", np.arange(int(positions)) / int(positions), {
                "units": "1", "long_name": "mesh phase, fraction of a mesh cycle (2 pi / z1 "
                                           "of pinion rotation)"}),
            "edge": ("edge", list(surface.EDGES), {
                "long_name": "edge of the gear's active flank (root: where the pinion's "
                             "tip runs)"}),
            "cone_distance": ("cone_distance", rho * 1e3, {
                "units": "mm", "long_name": "gear flank: distance from the apex"}),
            "polar_angle": ("polar_angle", np.degrees(theta), {
                "units": "degree", "long_name": "gear flank: polar angle about the gear axis"}),
            "profile_height": (("cone_distance", "polar_angle"), height * 1e3, {
                "units": "mm", "long_name": "gear flank: height above the root cone"}),
        },
        attrs=attrs,
    ))


def tooth_contact_summary(pair, modification=None, misalignment=None, positions=POSITIONS,
                          marking=MARKING_COMPOUND, grid=None):
    """The attributes of :func:`tooth_contact_analysis` without its arrays.

    A V-H map needs only the transmission error's peak to peak, the pattern
    and the edge-contact share of each cell; this skips the contact
    ellipses and the dataset.

    Parameters
    ----------
    pair, modification, misalignment, positions, marking, grid
        As :func:`tooth_contact_analysis`.

    Returns
    -------
    dict
        The dataset's attributes, the same values.

    Raises
    ------
    ValueError
        As :func:`tooth_contact_analysis`.
    """
    return _search_mesh_cycle(pair, modification, misalignment, positions, marking,
                              grid)["attrs"]


def _search_mesh_cycle(pair, modification, misalignment, positions, marking, grid):
    """The contact search over one mesh cycle, its checks and the summary attributes."""
    import lsbg

    if isinstance(positions, bool) or int(positions) != positions or positions < 8:
        raise ValueError(f"positions = {positions!r}: must be a whole number >= 8")
    if not (math.isfinite(marking) and marking > 0):
        raise ValueError(f"marking = {marking!r}: must be a number > 0 [m]")
    surface_pair = SurfacePair.build(pair, modification, misalignment, *(grid or (None, None)))
    modification, misalignment = surface_pair.modification, surface_pair.misalignment
    design = pair.design
    z1, z2 = design.teeth
    angles = mesh_cycle_pinion_angles(pair, positions)
    out, raster, limits = search(surface_pair, angles, marking)
    lost = ~np.isfinite(out[:, surface.O_PHI2])
    if lost.any():
        raise ValueError(f"misalignment {_shown(misalignment)}: the flanks lose contact at "
                         f"{int(lost.sum())} of {positions} mesh positions")
    te = angles * z1 / z2 - out[:, surface.O_PHI2]
    play = backlash(surface_pair, angles, out)
    design_play = design.backlash / design.mean_pitch_radius(2)   # j_t / r_m2
    if play.min() <= 0.0:
        raise ValueError(f"misalignment {_shown(misalignment)}: the members interfere (the coast "
                         f"flanks close the backlash: {play.min() * 1e6:.4g} urad of free play "
                         f"left of {design_play * 1e6:.4g})")
    edges = out[:, surface.O_TOE:surface.O_ROOT + 1].astype(np.int8)
    pattern = bearing_pattern(raster, limits, pair, marking)
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"Tooth contact analysis of a {design.trace} spiral bevel gear pair "
                 f"({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg)",
        "source": f"lsbg {lsbg.__version__} (lsbg.tca.analysis.tooth_contact_analysis), "
                  f"exact flank surfaces",
        "lsbg_version": lsbg.__version__,
        "positions": int(positions),
        "grid_points": f"{surface_pair.grid_shape[0]} x {surface_pair.grid_shape[1]}",
        "marking_compound_um": marking * 1e6,
        "transmission_error_peak_to_peak_urad": float(np.ptp(te) * 1e6),
        "transmission_error_peak_to_peak_arcsec": float(np.ptp(te) * 180 / math.pi * 3600),
        "transmission_error_mean_urad": float(te.mean() * 1e6),
        "backlash_min_urad": float(play.min() * 1e6),
        "backlash_design_urad": design_play * 1e6,
        "designed_transmission_error_peak_to_peak_urad":
            designed_transmission_error(pair, modification) * 1e6,
        "pattern_centre_cone_distance_mm": pattern["centre_cone_distance"] * 1e3,
        "pattern_centre_height_mm": pattern["centre_height"] * 1e3,
        "pattern_toe_mm": pattern["toe"] * 1e3,
        "pattern_heel_mm": pattern["heel"] * 1e3,
        "pattern_length_mm": pattern["length"] * 1e3,
        "pattern_length_per_face_width": pattern["length"] / design.face_width,
        "pattern_height_mm": pattern["height"] * 1e3,
        **{f"edge_contact_share_{name}": float(edges[:, i].mean())
           for i, name in enumerate(surface.EDGES)},
        "edge_contact_share": float(edges.any(axis=1).mean()),
        "mean_cone_distance_mm": design.mean_cone_distance * 1e3,
        "face_width_mm": design.face_width * 1e3,
        **flank_attributes(modification, misalignment),
        **{f"design_{k}": v for k, v in design.to_config().items()},
    }
    attrs = {k: (float(v) if isinstance(v, (np.floating, np.integer)) else v)
             for k, v in attrs.items()}
    return {"out": out, "raster": raster, "limits": limits, "angles": angles,
            "transmission_error": te, "backlash": play, "edges": edges, "attrs": attrs}
