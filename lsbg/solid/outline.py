"""Section outlines of the solid gears: the toothed surface cut by spheres about the apex.

Each gear is the solid between two spheres about the apex (the toe at the
inner cone distance R_i and the heel at the outer cone distance R_e), the
toothed surface and a coaxial bore cylinder. On every sphere |r| = R the
toothed surface cuts a closed *section outline*: root arc, one flank from root
to tip, top land, the other flank from tip to root, next tooth. The flanks are
the exact surfaces of :class:`lsbg.gear.geometry.GearPair`. This module owns
those outlines (:func:`section_outline`), the spheres they are taken on
(:func:`section_cone_distances`) and the sampling of the solids
(:class:`MeshResolution`); the closed meshes lofted through them are
:mod:`lsbg.solid.solids`', the STEP solids :mod:`lsbg.solid.step`'s, and the
FE segment's sections (:mod:`lsbg.tooth.outline`) start from them too.

Coordinates on a member's spheres are the polar angle theta from the axis
``pair.axis[m]`` and the azimuth phi about the forward rotation axis
``pair.rotation_axis[m]``, measured as :meth:`lsbg.gear.geometry.GearPair.azimuth`
does (:func:`lsbg.gear.flank.sphere_points`).

Flank below the involute. Where the base cone lies above the root cone (the
paper's 9-tooth pinion: base 12.47 deg, root 10.55 deg) the spherical involute
does not reach the root. There the flank is continued along the meridian
(same azimuth, polar angle down to the root angle): a radial flank without a
fillet. It carries no load, since the field of contact ends at the base cone;
a generated pinion would be undercut there instead (``GearPair.undercut``:
the gear's tip passes the pinion's base cone by 0.5 deg in the plane of
action), which these solids ignore.

All lengths in metres, angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lsbg.gear.flank import sphere_points
from lsbg.gear.geometry import MEMBER_NAMES

__all__ = [
    "MeshResolution", "DEFAULT_RESOLUTION", "wrap_angle", "side_order", "flank_azimuth",
    "SectionOutline", "section_outline", "section_cone_distances"
]


@dataclass(frozen=True)
class MeshResolution:
    """Sampling of the solid meshes.

    The defaults keep the mesh volume within 0.1 % of the exact solid (the
    tests measure it against
    :func:`lsbg.solid.mass.quadrature_mass_properties`; for the paper's pair
    it is 0.04-0.05 % short, the axial inertia 0.06-0.08 %) with 40-50k
    triangles per gear.

    Parameters
    ----------
    chord_tolerance : float
        Largest gap between the outline polygon and the exact outline (flanks,
        top lands, root arcs), as a fraction of the cone distance [-]. Sets
        how many points each piece gets (fewer on the gear's nearly straight
        flanks than on the pinion's, which start at a cusp on the base cone).
    extension : int
        Points on the radial continuation below the base cone (when present) [-].
    twist_step : float
        Largest change of the teeth's azimuth between two lofted sections
        [rad]. Flat quads between sections (split along their shorter
        diagonal) cut the twisted teeth short by a fraction of order
        twist_step**2 / 12.
    min_sections : int
        Fewest sections along the face width [-].
    end_face_step : float
        Edge length of the end-face triangles as an angle on the sphere [rad];
        flat triangles lie about R step**2 / 12 inside the sphere.
    bore_points_per_tooth : int
        Least number of points on the bore circle per tooth [-]. Counts on
        every circle are multiples of the tooth number, so that the mesh keeps
        the gear's z-fold symmetry and its centre of mass stays on the axis.
    """

    chord_tolerance: float = 1.5e-5
    extension: int = 3
    twist_step: float = 0.04
    min_sections: int = 6
    end_face_step: float = 0.03
    bore_points_per_tooth: int = 2


DEFAULT_RESOLUTION = MeshResolution()


# ------------------------------------------------------------------ helpers
def wrap_angle(angle):
    """Angles wrapped into (-pi, pi] [rad]."""
    return np.pi - np.mod(np.pi - np.asarray(angle, dtype=float), 2 * np.pi)


def side_order(pair, member):
    """Flank sides of a tooth in order of increasing azimuth.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}

    Returns
    -------
    tuple of str
        (low, high): the side met first when the azimuth about the rotation
        axis increases across the tooth, then the other. The pinion's drive
        flank leads (high), the gear's trails (low).
    """
    d = pair.design
    points = [pair.flank(member, side, d.mean_cone_distance, d.pitch_angle(member))[0]
              for side in ("drive", "coast")]
    width = wrap_angle(pair.azimuth(member, points[0]) - pair.azimuth(member, points[1]))
    return ("coast", "drive") if width > 0 else ("drive", "coast")


# Near the base cone the spherical involute is a cusp, theta - delta_b ~ chi^2,
# phi ~ chi^3 (chi: roll angle); spacing chord-sag errors evenly along it
# (segment length ~ curvature^(-1/3)) gives theta - start ~ t^(6/5).
_FLANK_EXPONENT = 1.2


def _flank_parameter(pair, member, n):
    """Polar angles of the involute samples, t**1.2-spaced from the start up [rad]."""
    start, tip = pair.flank_polar_range(member)
    t = np.linspace(0.0, 1.0, n)
    return start + (tip - start) * t**_FLANK_EXPONENT


def flank_azimuth(pair, member, side, cone_distance, polar):
    """Azimuth of the flank points at (R, theta) [rad], shape (R, theta)."""
    points, _ = pair.flank(member, side, np.asarray(cone_distance)[:, None], polar[None, :])
    return pair.azimuth(member, points)


def _arc_count(length, radius, tolerance):
    """Segments for an arc of ``length`` and ``radius`` (unit sphere) whose
    chords stay within ``tolerance``: chord sag = chord^2 / (8 radius) [-]."""
    return max(1, int(math.ceil(length / math.sqrt(8 * radius * tolerance))))


def _outline_counts(pair, member, resolution):
    """(flank points, top-land and root-arc interior points) at the mean point [-].

    A curve of length L that turns by Theta, cut into n equal chords, leaves
    a gap of about L Theta / (8 n^2); circles (top land, root arc) as in
    :func:`_arc_count`. All measured on the unit sphere at the mean cone distance.
    """
    d = pair.design
    tol = resolution.chord_tolerance
    rm = d.mean_cone_distance
    polar = _flank_parameter(pair, member, 201)
    p, _ = pair.flank(member, "drive", rm, polar)
    seg = np.diff(p, axis=0) / rm
    length = np.linalg.norm(seg, axis=1)
    tangent = seg / length[:, None]
    turn = np.sum(np.arccos(np.clip(np.sum(tangent[1:] * tangent[:-1], axis=1), -1.0, 1.0)))
    n_flank = max(4, int(math.ceil(math.sqrt(length.sum() * turn / (8 * tol))))) + 1
    z = d.teeth[member - 1]
    root, tip = d.root_angle(member), d.tip_angle(member)
    start = pair.flank_polar_range(member)[0]
    low, high = side_order(pair, member)
    phi = {side: flank_azimuth(pair, member, side, [rm], np.array([start, tip]))[0]
           for side in (low, high)}
    top_width = wrap_angle(phi[high][1] - phi[low][1])
    root_width = 2 * np.pi / z - wrap_angle(phi[high][0] - phi[low][0])
    n_top = _arc_count(top_width * math.sin(tip), math.sin(tip), tol) - 1
    n_root = _arc_count(root_width * math.sin(root), math.sin(root), tol) - 1
    return n_flank, max(n_top, 1), max(n_root, 1)


# ---------------------------------------------------------------- outlines
@dataclass(frozen=True)
class SectionOutline:
    """Closed tooth outlines of one gear on spheres about the apex.

    Attributes
    ----------
    cone_distance : numpy.ndarray, shape (n,)
        Sphere radii R [m].
    polar_angle, azimuth : numpy.ndarray, shape (n, m)
        Polar angle from the axis and azimuth about the rotation axis of the
        outline's vertices [rad]; azimuth increases along each row, over
        exactly one turn.
    points : numpy.ndarray, shape (n, m, 3)
        Vertices in the mesh frame [m].
    per_tooth : int
        Vertices per tooth; tooth j occupies columns j*per_tooth ... [-].
    """

    cone_distance: np.ndarray
    polar_angle: np.ndarray
    azimuth: np.ndarray
    points: np.ndarray
    per_tooth: int


def section_outline(pair, member, cone_distance, resolution=DEFAULT_RESOLUTION):
    """Outline of the whole gear on spheres of radius ``cone_distance``.

    For each tooth, in increasing azimuth: the low-side flank root -> tip, the
    top land (polar angle = tip angle), the high-side flank tip -> root, the
    root arc (polar angle = root angle) to the next tooth. Every sphere has
    the same vertex count and the same parametrisation, so that consecutive
    outlines can be stitched into quads.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    cone_distance : array_like
        Sphere radii R [m], scalar or 1-D.
    resolution : MeshResolution

    Returns
    -------
    SectionOutline

    Raises
    ------
    ValueError
        If the flanks of neighbouring teeth meet below the root arc.
    """
    d = pair.design
    radius = np.atleast_1d(np.asarray(cone_distance, dtype=float))
    z = d.teeth[member - 1]
    root, tip = d.root_angle(member), d.tip_angle(member)
    start = pair.flank_polar_range(member)[0]
    n_flank, n_top, n_root = _outline_counts(pair, member, resolution)
    involute = _flank_parameter(pair, member, n_flank)
    # Radial continuation below the base cone: same azimuth as the involute start.
    extension = (np.linspace(root, start, resolution.extension + 1)[:-1]
                 if start > root + 1e-12 else np.empty(0))
    polar_side = np.concatenate([extension, involute])
    low, high = side_order(pair, member)
    phi_low = flank_azimuth(pair, member, low, radius, involute)
    phi_high = flank_azimuth(pair, member, high, radius, involute)
    # Unwrap each flank and place the high side just after the low side's tip.
    phi_low = phi_low[:, :1] + wrap_angle(phi_low - phi_low[:, :1])
    phi_high = phi_low[:, -1:] + wrap_angle(phi_high - phi_low[:, -1:])
    n_ext = extension.size
    phi_low = np.concatenate([np.repeat(phi_low[:, :1], n_ext, axis=1), phi_low], axis=1)
    phi_high = np.concatenate([np.repeat(phi_high[:, :1], n_ext, axis=1), phi_high], axis=1)

    def interior(a, b, n):
        s = np.arange(1, n + 1) / (n + 1)
        return a[:, None] + (b - a)[:, None] * s

    next_low = phi_low[:, 0] + 2 * np.pi / z
    top = interior(phi_low[:, -1], phi_high[:, -1], n_top)
    root_arc = interior(phi_high[:, 0], next_low, n_root)
    phi_tooth = np.concatenate([phi_low, top, phi_high[:, ::-1], root_arc, next_low[:, None]],
                               axis=1)
    # The meshing relies on azimuth never decreasing along the outline (no
    # pointed tooth, no flanks of neighbouring teeth meeting, no undercut loop).
    step = np.diff(phi_tooth, axis=1)
    if np.any(step < 0) or np.any(phi_high[:, -1] <= phi_low[:, -1]) \
            or np.any(next_low <= phi_high[:, 0]):
        raise ValueError(f"the {MEMBER_NAMES[member]} section outline is not single-valued "
                         f"in azimuth (smallest step {np.min(step):.3g} rad)")
    phi_tooth = phi_tooth[:, :-1]
    polar_tooth = np.concatenate([
        polar_side, np.full(n_top, tip), polar_side[::-1], np.full(n_root, root)])
    n = polar_tooth.size
    phi = (phi_tooth[:, None, :] + 2 * np.pi / z * np.arange(z)[:, None]).reshape(radius.size, -1)
    polar = np.broadcast_to(np.tile(polar_tooth, z), phi.shape).copy()
    points = sphere_points(pair, member, radius[:, None], polar, phi)
    return SectionOutline(radius, polar, phi, points, n)


def section_cone_distances(pair, member, resolution=DEFAULT_RESOLUTION):
    """Sphere radii of the lofted sections, from toe to heel [m].

    Geometrically spaced (the LSBG twists by equal angles between them) and
    as many as keep the twist per step below ``resolution.twist_step``.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    resolution : MeshResolution

    Returns
    -------
    numpy.ndarray, shape (n,)
    """
    d = pair.design
    r_in, r_out = d.inner_cone_distance, d.outer_cone_distance
    probe = np.geomspace(r_in, r_out, 65)
    polar = np.array([d.pitch_angle(member)])
    phi = np.unwrap(flank_azimuth(pair, member, "drive", probe, polar)[:, 0])
    steps = np.abs(np.diff(phi))
    n = max(resolution.min_sections, int(math.ceil(np.sum(steps) / resolution.twist_step)) + 1)
    return np.geomspace(r_in, r_out, n)
