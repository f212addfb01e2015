"""A member's flank in the coordinates the later stages work in.

:class:`lsbg.gear.geometry.GearPair` gives a flank point by its cone
distance and its polar angle from the member's axis. The stages after it
address the same points in two other ways, and this module holds the
conversions they share:

* by plane-of-action coordinates (rho, psi): a point of the plane at polar
  angle psi lies at the same polar angle from a member's axis at every
  distance and every rotation (cones through the apex meet the plane in
  rays), so a point of the field of contact names one flank point per member
  (:func:`member_polar_angle`, :func:`drive_flank`, :func:`active_polar_range`);
  the FE compliance, the local contact and the TCAs use it;
* by spherical coordinates about the apex, the polar angle from the axis and
  the azimuth about the forward rotation axis (:func:`sphere_points`); the
  solids and the FE segment's sections are built on such spheres.

And the mesh cycle's clock: the pinion rotation at a fraction of a base pitch
(:func:`mesh_phase_pinion_angle`).

All lengths in metres, all angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["member_polar_angle", "drive_flank", "active_polar_range", "sphere_points",
           "mesh_phase_pinion_angle"]


# ------------------------------------------------ plane-of-action coordinates
def member_polar_angle(pair, member, cone_distance, profile_angle):
    """Polar angle from a member's axis of plane-of-action points [rad].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
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
    pair : lsbg.gear.geometry.GearPair
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


def active_polar_range(pair, member, side="drive"):
    """Polar angles of a member's flank that the field of contact reaches [rad].

    A point of the plane of action at polar angle psi lies at the same polar
    angle from a member's axis at every distance (cones through the apex
    meet the plane in rays), so the field's limits psi_lo, psi_hi map to a
    range of the member's polar angle, within its involute flank.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    side : {"drive", "coast"}

    Returns
    -------
    (float, float)
        Lowest and highest polar angle [rad].
    """
    plane = pair.planes[side]
    rays = plane.point(1.0, np.array(plane.field[:2]))
    polar = np.arccos(np.clip(rays @ pair.axis[member], -1.0, 1.0))
    lo, hi = pair.flank_polar_range(member)
    return max(lo, float(polar.min())), min(hi, float(polar.max()))


# ------------------------------------------------------- spherical coordinates
def _sphere_frame(pair, member):
    """(a, e1, e2): axis from the apex into the body and the azimuth frame.

    A point at polar angle theta from ``a`` and azimuth phi about the
    rotation axis u = +-a is R (cos theta a + sin theta (cos phi e1 + sin phi e2)),
    consistent with :meth:`lsbg.gear.geometry.GearPair.azimuth`.
    """
    u = pair.rotation_axis[member]
    ref = pair.pitch_dir - (pair.pitch_dir @ u) * u
    ref = ref / np.linalg.norm(ref)
    return pair.axis[member], ref, np.cross(u, ref)


def sphere_points(pair, member, radius, polar, azimuth):
    """Points of a member's spheres about the apex, in the mesh frame [m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    radius : array_like
        Distance from the apex R [m].
    polar, azimuth : array_like
        Polar angle from the axis ``pair.axis[member]`` and azimuth about the
        forward rotation axis, measured as
        :meth:`lsbg.gear.geometry.GearPair.azimuth` does [rad]; broadcast
        against ``radius``.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
    """
    a, e1, e2 = _sphere_frame(pair, member)
    radius, polar, azimuth = (np.asarray(v, dtype=float)[..., None]
                              for v in (radius, polar, azimuth))
    across = np.cos(azimuth) * e1 + np.sin(azimuth) * e2
    return radius * (np.cos(polar) * a + np.sin(polar) * across)


# -------------------------------------------------------------- the mesh cycle
def mesh_phase_pinion_angle(pair, phase):
    """Pinion rotation at a mesh phase (fraction of a base pitch) [rad].

    The contact lines turn by phi1 e1 in the plane of action (e1 the sine of
    the pinion's base cone angle), so one base pitch Psi_p is a pinion turn of
    Psi_p / e1 = 2 pi / z1.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    phase : array_like
        Fraction of a base pitch [-].

    Returns
    -------
    numpy.ndarray
    """
    design = pair.design
    # the same operations as lsbg.contact.MeshContact's pitch / e1, bit for bit
    return np.asarray(phase, dtype=float) * design.base_pitch_angle \
        / math.sin(design.base_cone_angle(1))
