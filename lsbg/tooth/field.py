"""The field of contact of generated flanks: where a small pinion's involute starts.

lsbg's flanks are involutes down to the base cone. Where a mate's tip
overshoots a small pinion's base cone (lsbg's ``undercut`` flag), the line
model's field of contact ends on that base cone's tangency line, where the
involute's radius of curvature is zero and Hertz's pressure has no bound. A
pinion generated with these proportions is undercut there: the tool's edge
(its tip radius) cuts a trochoid that removes the involute's start.
:func:`undercut_roll` finds the roll at which the generated involute starts
on the virtual spur gear of the normal section (the tool a rack with the
module's addendum and an edge radius), :func:`generated_flank_start` the
polar angle in the plane of action where it lies, and :func:`active_field`
the field both members' generated flanks bound, per band of the face width.
The loaded TCA with the FE compliance keeps its contact points inside it
(:func:`lsbg.tooth.ltca.fe_loaded_tca`).

SI inside.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["undercut_roll", "generated_flank_start", "active_field"]

#: Positions of the tool's edge per generating trochoid in :func:`undercut_roll` [-].
TROCHOID_POINTS = 4001


def undercut_roll(pitch_radius, pressure_angle, addendum, edge_radius, teeth):
    """Where a rack leaves a spur gear's involute when it undercuts it.

    The rack (straight flanks at ``pressure_angle``, tip line ``addendum``
    below its pitch line, edges rounded with ``edge_radius``) rolls on the
    pitch circle; past the base circle's tangency point T1 its rounded edge
    sweeps a trochoid (the offset of the edge centre's path) that cuts into
    the involute its flank has generated. The involute is left from the
    point where the trochoid last crosses it.

    Parameters
    ----------
    pitch_radius : array_like
        r [m], > 0.
    pressure_angle : float
        alpha [rad].
    addendum : array_like
        Rack addendum h (the gear's dedendum) [m].
    edge_radius : float
        Edge radius of the rack [m], >= 0.
    teeth : float
        Number of teeth [-] (bounds the search to the tooth's own side).

    Returns
    -------
    numpy.ndarray
        Roll distance from T1 along the line of action to the start of the
        involute [m]: sqrt(r_L^2 - r_b^2); 0 where the rack does not undercut
        (its straight flank ends above T1).
    """
    r, h = np.broadcast_arrays(np.atleast_1d(np.asarray(pitch_radius, float)),
                               np.atleast_1d(np.asarray(addendum, float)))
    alpha, rho = float(pressure_angle), float(edge_radius)
    base = r * math.cos(alpha)
    # rack frame: pitch point P = (0, r), tool on the +x side of its flank
    # x = (r - y) tan(alpha); the edge's centre lies rho inside flank and tip line
    yc = r - (h - rho)
    xc = (h - rho) * math.tan(alpha) + rho / math.cos(alpha)
    # the gear turns phi (counter-clockwise) while the rack moves r phi: in the
    # gear's frame the centre is rot(-phi) (xc - r phi, yc); it is below the
    # pitch circle for phi up to the end of the window below
    end = (xc + np.sqrt(np.maximum(r**2 - yc**2, 0.0))) / r
    phi = np.linspace(0.0, 1.0, TROCHOID_POINTS)[None, :] * end[:, None]
    big_x, big_y = xc[:, None] - r[:, None] * phi, yc[:, None]
    cos, sin = np.cos(phi), np.sin(phi)
    cx, cy = cos * big_x + sin * big_y, -sin * big_x + cos * big_y
    dx = -sin * big_x - r[:, None] * cos + cos * big_y
    dy = -cos * big_x + r[:, None] * sin - sin * big_y
    theta = np.arctan2(cx, cy)  # polar angle from the pitch point's ray
    # the edge's envelope: the centre's path offset by rho towards the tooth
    # (decreasing theta), where the tool cuts
    nx, ny = dy, -dx
    norm = np.hypot(nx, ny)
    flip = np.where(nx * np.cos(theta) - ny * np.sin(theta) > 0, -1.0, 1.0)
    ex, ey = cx + rho * flip * nx / norm, cy + rho * flip * ny / norm
    radius, angle = np.hypot(ex, ey), np.arctan2(ex, ey)

    def involute(a):
        return np.tan(a) - a

    # the generated involute: theta = inv(alpha) - inv(alpha_R) below the pitch circle
    on = (radius > base[:, None]) & (radius < r[:, None])
    pressure = np.arccos(np.clip(base[:, None] / np.where(on, radius, r[:, None]), -1.0, 1.0))
    flank = involute(alpha) - involute(pressure)
    gap = angle - flank
    inside = on & (gap < 0) & (gap > -0.5 * math.pi / teeth)
    # the last crossing: the largest radius inside, interpolated to the next
    # sample outside (the roll distance, ~sqrt(r_L - r_b), needs r_L finely)
    j = np.argmax(np.where(inside, radius, -np.inf), axis=1)[:, None]
    k = np.minimum(j + 1, TROCHOID_POINTS - 1)
    r0, r1 = (np.take_along_axis(radius, i, axis=1)[:, 0] for i in (j, k))
    g0, g1 = (np.take_along_axis(gap, i, axis=1)[:, 0] for i in (j, k))
    step = np.where((g1 >= 0) & (r1 > r0) & (g1 > g0), g0 / np.where(g1 > g0, g0 - g1, -1.0), 0.0)
    limit = np.where(inside.any(axis=1), r0 + step * (r1 - r0), base)
    return np.sqrt(np.maximum(limit**2 - base**2, 0.0))


def generated_flank_start(pair, member, edge_radius, cone_distance):
    """Polar angle in the drive plane of action where a member's generated flank starts [rad].

    lsbg's flanks are involutes from the base cone (or the root cone above
    it) up; a flank generated by a rack whose tip is the member's dedendum
    (the crown gear, its edges rounded with ``edge_radius`` as the FE
    segment's root fillets, :mod:`lsbg.tooth.segment`) starts higher: where
    the rack's straight flank ends, or, where the rack undercuts (a small
    pinion), where the undercut trochoid of its edge leaves the involute.
    Below that point there is no involute to carry a line contact.

    Each cone distance is taken as Tredgold's virtual spur gear in the sphere
    (pitch radius R tan(delta), pressure angle the plane of action's tilt
    gamma, rack addendum R theta_f, z / cos(delta) teeth), as the bevel gear
    standards check undercut; the roll distance from the base cone's
    tangency line maps to the polar angle as an arc of radius R. Where the
    rack does not undercut, the end of its straight flank lies at the depth
    h - r_e (1 - sin(gamma)) below the pitch line, where the plane of action
    is at R sin(psi) sin(gamma).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    edge_radius : float
        Edge radius of the generating rack [m], >= 0.
    cone_distance : array_like
        R [m].

    Returns
    -------
    numpy.ndarray
        psi of the flank's start on the member's side of the pitch line.
    """
    d = pair.design
    plane = pair.planes["drive"]
    gamma = d.plane_of_action_tilt
    delta = d.pitch_angle(member)
    radius = np.atleast_1d(np.asarray(cone_distance, float))
    addendum = radius * d.member_dedendum_angle(member)  # the rack cuts the member's root
    straight = addendum - edge_radius * (1 - math.sin(gamma))
    tangency, toward_pitch = plane.tangency_angle[member], plane.roll_sign[member]
    side = math.copysign(1.0, tangency)
    undercut = straight / math.sin(gamma) >= radius * math.tan(delta) * math.sin(gamma)
    roll = (undercut_roll(radius * math.tan(delta), gamma, addendum, edge_radius,
                          d.teeth[member - 1] / math.cos(delta))
            if np.any(undercut) else np.zeros(radius.shape))
    flank_end = side * np.arcsin(np.clip(straight / (radius * math.sin(gamma)), -1.0, 1.0))
    return np.where(undercut, tangency + toward_pitch * roll / radius, flank_end)


def active_field(pair, edge_radius, cone_distance):
    """The field of contact across the profile, bounded by both generated flanks' starts.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    edge_radius : float
        Edge radius of the generating rack [m].
    cone_distance : array_like
        R [m].

    Returns
    -------
    psi_lo, psi_hi : numpy.ndarray
        Bounds at each cone distance [rad], inside lsbg's field (the mating
        tips still bound it where they come first).

    Raises
    ------
    ValueError
        If no field is left.
    """
    psi_lo, psi_hi = pair.planes["drive"].field[:2]
    radius = np.atleast_1d(np.asarray(cone_distance, float))
    lo, hi = np.full(radius.shape, psi_lo), np.full(radius.shape, psi_hi)
    for member in (1, 2):
        start = generated_flank_start(pair, member, edge_radius, radius)
        if pair.planes["drive"].tangency_angle[member] > 0:
            hi = np.minimum(hi, start)
        else:
            lo = np.maximum(lo, start)
    if np.any(hi <= lo):
        raise ValueError("the generated flanks leave no field of contact (edge_radius "
                         f"{edge_radius!r} m)")
    return lo, hi
