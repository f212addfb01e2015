"""Exact tooth flanks of spiral bevel gears swept by a plane rolling on a base cone.

One mechanism builds both gear types (paper §2.2, DESIGN.md §2). A plane
through the common apex, the *plane of action*, is tangent to both base cones,
sin(delta_b,i) = c sin(delta_i), and contains the pitch line. Rolling without
slip on base cone i it turns about its own normal N at Omega = omega_i sin(delta_b,i),
the same for both members when omega_1 / omega_2 = z2 / z1. A curve C fixed in
that plane therefore sweeps conjugate flanks on both members (line contact):

* LSBG: C is a plane logarithmic spiral, a constant angle beta_p to every ray
  from the apex. The flank is invariant under a spiral similarity about the
  gear axis, so its trace on every coaxial cone is a conical logarithmic spiral
  (the paper's Eq. 1) with one spiral angle.
* SBG: C is a circular arc (the face-mill cutter of radius r_c) whose angle to
  the ray equals beta_p at the mean point only.

The curve and the plane are :mod:`lsbg.gear.plane`'s
(:class:`~lsbg.gear.plane.GeneratingCurve`,
:class:`~lsbg.gear.plane.PlaneOfAction`); this module builds the pair on them
(:class:`GearPair`): the planes of both sides, the flanks they sweep, the
field of contact and the measurements of the teeth.

Frames. The apex is the origin, the pitch line is the x axis and the axial
plane (both axes) is the xy plane. The pinion axis ``a1`` and the gear axis
``a2`` point from the apex into the gear bodies. Each member turns forward
about ``u_i = +-a_i``; the pinion turns clockwise seen from its back, and the
forward sense of the gear is the one the pinion drives. Inside a plane of
action a point is given by polar coordinates (rho, psi): distance from the
apex [m] and angle from the pitch line about the plane normal [rad].

The drive flanks (loaded when the pinion drives forward) are swept in the plane
of action tilted by +gamma about the pitch line, the coast flanks in its mirror
image through the axial plane.

All lengths in metres, all angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.gear.depth import tip_polar_angle
from lsbg.gear.design import DesignError, GearPairDesign
from lsbg.gear.plane import GeneratingCurve, PlaneOfAction
from lsbg.gear.vectors import cross, rotate, unit

SIDES = ("drive", "coast")
MEMBERS = (1, 2)
MEMBER_NAMES = {1: "pinion", 2: "gear"}


# -------------------------------------------------------------------- gear pair
class GearPair:
    """Exact flank geometry of a spiral bevel gear pair.

    Parameters
    ----------
    design : GearPairDesign

    Raises
    ------
    DesignError
        If the teeth come out pointed, or the pair interferes so badly that
        it cannot keep one tooth pair in contact.
    """

    def __init__(self, design: GearPairDesign):
        self.design = design
        d = design
        d1, d2 = d.pitch_angle(1), d.pitch_angle(2)
        self.pitch_dir = np.array([1.0, 0.0, 0.0])
        # Axes in the axial (xy) plane on either side of the pitch line.
        self.axis = {1: np.array([math.cos(d1), math.sin(d1), 0.0]),
                     2: np.array([math.cos(d2), -math.sin(d2), 0.0])}
        self.mean_point = d.mean_cone_distance * self.pitch_dir
        gamma = d.plane_of_action_tilt
        # Pinion turns clockwise seen from its back end (looking at the apex).
        u1 = -self.axis[1]
        planes, u2 = {}, None
        for side, tilt in (("drive", gamma), ("coast", -gamma)):
            normal = np.array([0.0, math.cos(tilt), math.sin(tilt)])
            in_plane = np.cross(normal, self.pitch_dir)
            beta = self._hand_signed_beta(normal, in_plane)
            curve = GeneratingCurve(d.trace, beta, d.mean_cone_distance, d.cutter_radius,
                                    gamma)
            m0 = -math.sin(beta) * self.pitch_dir + math.cos(beta) * in_plane
            if side == "drive":
                # Pinion drives: its flank moves along the contact normal.
                sign = math.copysign(1.0, np.cross(u1, self.mean_point) @ m0)
                n = sign * m0
                u2 = math.copysign(1.0, np.cross(self.axis[2], self.mean_point) @ n) * self.axis[2]
            else:
                # Coast: the gear's coast flank pushes the pinion's backwards.
                sign = -math.copysign(1.0, np.cross(u1, self.mean_point) @ m0)
            tangency, roll = {}, {}
            for member in MEMBERS:
                a = self.axis[member]
                g = unit(a - (a @ normal) * normal)
                psi_g = math.atan2(g @ in_plane, g @ self.pitch_dir)
                tangency[member], roll[member] = psi_g, -math.copysign(1.0, psi_g)
            planes[side] = PlaneOfAction(side, normal, self.pitch_dir, in_plane, curve,
                                         tangency, roll, (0.0, 0.0, 0.0, 0.0), sign)
        self.rotation_axis = {1: u1, 2: u2}
        # Field of contact per side, clipped at the base cones (undercut).
        self.undercut = {}
        for side, plane in planes.items():
            lo_hi, undercut = self._field_limits(plane)
            planes[side] = PlaneOfAction(
                plane.side, plane.normal, plane.pitch_dir, plane.cross_dir, plane.curve,
                plane.tangency_angle, plane.roll_sign,
                (*lo_hi, d.inner_cone_distance, d.outer_cone_distance),
                plane.contact_normal_sign)
            self.undercut[side] = undercut
        self.planes = planes
        # Tooth placement: the coast flank of tooth 0 is the raw coast flank
        # turned by the angular tooth thickness on the mean pitch circle,
        # backwards on the pinion (its material trails its drive flank),
        # forwards on the gear.
        self.flank_offset = {
            (1, "drive"): 0.0, (2, "drive"): 0.0,
            (1, "coast"): -d.mean_tooth_thickness(1) / d.mean_pitch_radius(1),
            (2, "coast"): d.mean_tooth_thickness(2) / d.mean_pitch_radius(2),
        }
        self._check_tooth_form()

    # ----------------------------------------------------------- construction
    def _hand_signed_beta(self, normal, in_plane):
        """beta_p with the sign giving the pinion its hand of spiral."""
        d = self.design
        beta = d.plane_spiral_angle
        m0 = -math.sin(beta) * self.pitch_dir + math.cos(beta) * in_plane
        # Pitch-cone trace direction at the mean point (pitch tangent plane is
        # the xz plane, normal y), oriented outwards along the pitch line.
        trace = np.cross(m0, [0.0, 1.0, 0.0])
        trace *= math.copysign(1.0, trace @ self.pitch_dir)
        # Left hand: seen from the apex side, the outer half of the tooth
        # curves counter-clockwise, i.e. the azimuth about a1 decreases outwards.
        azimuth_rate = np.cross(self.axis[1], self.pitch_dir) @ trace
        want = -1.0 if d.pinion_hand == "left" else 1.0
        return beta if math.copysign(1.0, azimuth_rate) == want else -beta

    def _field_limits(self, plane):
        d = self.design
        limit, tip, undercut = {}, {}, {}
        for member in MEMBERS:
            psi_g, sgn = plane.tangency_angle[member], plane.roll_sign[member]
            delta_b = d.base_cone_angle(member)
            tip[member] = psi_g + sgn * self.roll_angle(member, d.tip_angle(member))
            # The involute exists from the base cone (or the root cone if that
            # lies above it) outwards.
            start = max(delta_b, d.root_angle(member))
            limit[member] = psi_g + sgn * self.roll_angle(member, start)
        # Member 2's tip bounds the field on member 1's side and vice versa.
        field = []
        for member, mate in ((1, 2), (2, 1)):
            own, mate_tip = limit[member], tip[mate]
            sgn = plane.roll_sign[member]
            # Positions further from the pitch line than ``own`` lie below
            # member's active flank: the generating cut undercuts there.
            overshoot = (own - mate_tip) * sgn
            undercut[MEMBER_NAMES[member]] = max(0.0, overshoot)
            field.append(own if overshoot > 0 else mate_tip)
        lo, hi = sorted(field)
        return (lo, hi), undercut

    def roll_angle(self, member, polar_angle):
        """In-plane angle chi between the base-cone tangency line and a flank point.

        A point of the plane of action at angle chi from the line where it
        touches base cone i lies at polar angle theta from axis i with
        cos(theta) = cos(delta_b,i) cos(chi).

        Parameters
        ----------
        member : {1, 2}
        polar_angle : array_like
            Angle theta between the flank point and the member's axis [rad],
            at least the base cone angle.

        Returns
        -------
        numpy.ndarray
            chi [rad]; NaN below the base cone, where no flank point exists.
        """
        delta_b = self.design.base_cone_angle(member)
        theta = np.asarray(polar_angle, dtype=float)
        # atan2 form: arccos(cos(theta)/cos(delta_b)) loses half the digits
        # near the base cone, where sin(chi)^2 = sin(theta-delta_b) sin(theta+delta_b) / cos(delta_b)^2.
        product = np.sin(theta - delta_b) * np.sin(theta + delta_b)
        # A few ulps below the base cone is rounding; further below is an error.
        product = np.where(product > -1e-15, np.maximum(product, 0.0), np.nan)
        return np.arctan2(np.sqrt(product), np.cos(theta))

    # ---------------------------------------------------------------- flanks
    def axis_normal_component(self, member, side):
        """u_i . N: signed sin(delta_b,i); Psi = (phi_i + offset) * (u_i . N) [-]."""
        return float(self.rotation_axis[member] @ self.planes[side].normal)

    def contact_phase(self, member, side, rotation):
        """Turn Psi of the contact line of tooth 0 at a member rotation.

        Parameters
        ----------
        member : {1, 2}
        side : {"drive", "coast"}
        rotation : array_like
            Forward rotation phi_i of the member [rad].

        Returns
        -------
        numpy.ndarray
            Psi [rad]: the contact line of tooth 0 is the generating curve
            turned by Psi about the plane normal (tooth j adds
            2 pi j / z_i to ``rotation``).
        """
        s = self.axis_normal_component(member, side)
        return (np.asarray(rotation, dtype=float) + self.flank_offset[(member, side)]) * s

    def flank(self, member, side, cone_distance, polar_angle):
        """Points and outward unit normals of a flank of tooth 0, body frame.

        The body frame is the mesh frame at rotation 0. Parameters are the
        distance from the apex and the polar angle from the member's axis;
        the flank is the sphere's spherical involute at each cone distance.

        Parameters
        ----------
        member : {1, 2}
            1 = pinion, 2 = gear.
        side : {"drive", "coast"}
        cone_distance : array_like
            Distance R from the apex [m].
        polar_angle : array_like
            Angle theta between the point and the axis [rad], from the base
            cone angle up (broadcast against ``cone_distance``).

        Returns
        -------
        points, normals : numpy.ndarray, shape (..., 3)
            Flank points [m] and unit normals pointing out of the tooth [-].
        """
        plane = self.planes[side]
        rho, theta = np.broadcast_arrays(np.asarray(cone_distance, float),
                                         np.asarray(polar_angle, float))
        psi = plane.tangency_angle[member] + plane.roll_sign[member] * self.roll_angle(member, theta)
        phase = psi - plane.curve.polar_angle(rho)
        s = self.axis_normal_component(member, side)
        turn = -phase / s + self.flank_offset[(member, side)]
        u = self.rotation_axis[member]
        points = rotate(plane.point(rho, psi), u, turn)
        normals = rotate(plane.in_plane_normal(rho, psi), u, turn)
        # Contact normal points pinion -> gear: out of the pinion tooth on the
        # drive side. The coast plane's sign already points from the gear's
        # coast flank into the pinion's, i.e. out of the gear tooth.
        outward = 1.0 if (member == 1) == (side == "drive") else -1.0
        return points, outward * normals

    def flank_polar_range(self, member):
        """(start, tip) polar angles of the involute flank of a member [rad]."""
        d = self.design
        return max(d.base_cone_angle(member), d.root_angle(member)), d.tip_angle(member)

    def azimuth(self, member, points):
        """Angle of points about the member's forward rotation axis [rad].

        Measured from the axial half-plane that contains the pitch line.
        """
        u = self.rotation_axis[member]
        ref = unit(self.pitch_dir - (self.pitch_dir @ u) * u)
        other = cross(u, ref)
        pts = np.asarray(points, float)
        return np.arctan2(pts @ other, pts @ ref)

    def angular_thickness(self, member, cone_distance, polar_angle):
        """Angular tooth thickness about the axis at a cone distance and polar angle [rad]."""
        pd, _ = self.flank(member, "drive", cone_distance, polar_angle)
        pc, _ = self.flank(member, "coast", cone_distance, polar_angle)
        diff = self.azimuth(member, pd) - self.azimuth(member, pc)
        diff = (diff + math.pi) % (2 * math.pi) - math.pi
        return diff if member == 1 else -diff

    def top_land(self, member, cone_distance):
        """Top land width (arc on the tip cone) at cone distances [m].

        The arc on the sphere of each cone distance at the face cone's polar
        angle there (:func:`lsbg.gear.depth.tip_polar_angle`: the tip angle under
        the apex taper).
        """
        d = self.design
        if d.depth_taper == "apex":
            tip = d.tip_angle(member)
            return (self.angular_thickness(member, cone_distance, tip)
                    * np.asarray(cone_distance) * math.sin(tip))
        tip = tip_polar_angle(d, member, cone_distance)
        return self.angular_thickness(member, cone_distance, tip) * np.asarray(cone_distance) * np.sin(tip)

    #: The narrowest top land lsbg builds, in mean normal modules (ISO 23509 and AGMA
    #: 929-A06 take about 0.2-0.3 m_mn as the least a case-hardened tip stands: a
    #: narrower one through-hardens and chips).
    MIN_TOP_LAND = 0.2

    def _check_tooth_form(self):
        d = self.design
        distances = np.linspace(d.inner_cone_distance, d.outer_cone_distance, 5)
        least = self.MIN_TOP_LAND * d.mean_normal_module
        for member in MEMBERS:
            land = self.top_land(member, distances)
            # (the least land at the toe, where it is least; the paper's pair has
            # 0.66 m_mn on the pinion)
            if np.min(land) < least:
                name = MEMBER_NAMES[member]
                at = distances[np.argmin(land)]
                culprit = ("base_cone_rule", d.base_cone_rule) if d.base_cone_rule == "paper" \
                    else ("dedendum_angles", d.dedendum_angles) if d.dedendum_angles \
                    else ("depth_taper", d.depth_taper) if d.depth_taper != "apex" \
                    else (("profile_shift", d.profile_shift) if d.profile_shift
                          or d.thickness_modification else ("addendum", d.addendum))
                shape = "come out pointed" if np.min(land) <= 0 else "get too narrow a top land"
                raise DesignError(
                    f"{culprit[0]} = {culprit[1]!r}: the {name} teeth {shape} "
                    f"(top land {1e3 * np.min(land):.3f} mm at cone distance {1e3 * at:.2f} mm, "
                    f"the least is {self.MIN_TOP_LAND:g} m_mn = {1e3 * least:.3f} mm; "
                    f"normal pressure angle at the mean point "
                    f"{math.degrees(d.mean_normal_pressure_angle):.2f} deg)")
        if d.depth_taper != "apex":
            # the field of contact, the solids, the FE segment and the TCAs bound the teeth by
            # cones through the pitch apex
            raise DesignError(
                f"depth_taper = {d.depth_taper!r}: lsbg's flanks, solids, FE tooth and TCAs "
                f"take the tip and root cones through the pitch apex (depth_taper: apex); "
                f"this taper is in the design's depths and angles (lsbg.gear.depth) and "
                f"the ISO 10300 rating (lsbg.rating) only")
        ratio = self.contact_ratio()
        if ratio["total"] < 1.0:
            raise DesignError(
                f"addendum = {d.addendum!r}: interference limits the path of contact to a "
                f"total contact ratio of {ratio['total']:.3f} < 1 (undercut "
                f"{ {k: round(math.degrees(v), 3) for k, v in self.undercut['drive'].items()} } deg)")
        undercut = {k: v for k, v in self.undercut["drive"].items() if v > 0}
        if undercut and d.undercut == "refuse":
            member, roll = max(undercut.items(), key=lambda item: item[1])
            raise DesignError(
                f"profile_shift = {d.profile_shift!r}: the {member} is undercut: its root cone "
                f"cuts {math.degrees(roll):.3f} deg of roll off the path of contact (a larger "
                f"pinion profile shift moves its root out; undercut: accept builds it)")

    # ---------------------------------------------------------- measurements
    def contact_ratio(self, side="drive"):
        """Profile, face and total contact ratios from the field of contact.

        The contact lines repeat every Psi_p in the plane; a line meets the
        field for a range of turns equal to the field's angular width
        (profile part) plus the turn of the curve across the face (face part).

        Returns
        -------
        dict
            ``profile``, ``face`` and ``total`` contact ratios [-].
        """
        plane = self.planes[side]
        psi_lo, psi_hi, r_in, r_out = plane.field
        pitch = self.design.base_pitch_angle
        face_turn = abs(float(plane.curve.polar_angle(r_out) - plane.curve.polar_angle(r_in)))
        profile = (psi_hi - psi_lo) / pitch
        face = face_turn / pitch
        return {"profile": profile, "face": face, "total": profile + face}

    def spiral_angle(self, member, cone_angle, cone_distance, side="drive"):
        """Spiral angle of the tooth trace on a coaxial cone through the apex.

        The trace of the flank on the cone of half-angle ``cone_angle`` is the
        flank at that polar angle; the spiral angle is the angle between its
        tangent and the cone generator.

        Parameters
        ----------
        member : {1, 2}
        cone_angle : float
            Half-angle of the coaxial cone, e.g. the pitch angle [rad].
        cone_distance : array_like
            Distances from the apex at which to measure [m].
        side : {"drive", "coast"}

        Returns
        -------
        numpy.ndarray
            Spiral angle [rad], in [0, pi/2]; the hand is given by the sign of
            :meth:`trace_azimuth_rate`.
        """
        rho = np.asarray(cone_distance, dtype=float)
        h = 1e-6 * self.design.outer_cone_distance
        p_plus, _ = self.flank(member, side, rho + h, cone_angle)
        p_minus, _ = self.flank(member, side, rho - h, cone_angle)
        p0, _ = self.flank(member, side, rho, cone_angle)
        tangent = unit(p_plus - p_minus)
        return np.arccos(np.clip(np.sum(tangent * unit(p0), axis=-1), -1.0, 1.0))

    def trace_azimuth_rate(self, member, cone_angle, cone_distance, side="drive"):
        """d(azimuth about a_i)/dR along the trace on a coaxial cone [rad/m].

        Negative for a left-hand member (DESIGN: seen from the apex, the outer
        half of the tooth curves counter-clockwise).
        """
        rho = np.asarray(cone_distance, dtype=float)
        h = 1e-6 * self.design.outer_cone_distance
        p_plus, _ = self.flank(member, side, rho + h, cone_angle)
        p_minus, _ = self.flank(member, side, rho - h, cone_angle)
        a = self.axis[member]
        ref = unit(self.pitch_dir - (self.pitch_dir @ a) * a)
        other = np.cross(a, ref)
        az = lambda p: np.arctan2(p @ other, p @ ref)  # noqa: E731
        diff = (az(p_plus) - az(p_minus) + math.pi) % (2 * math.pi) - math.pi
        return diff / (2 * h)

    def normal_pressure_angle(self, member, cone_distance, polar_angle, side="drive"):
        """Normal pressure angle at flank points [rad].

        The angle between the flank normal and the tangent plane of the
        coaxial cone through the point (on the pitch cone: the normal
        pressure angle alpha_n).

        Parameters
        ----------
        member : {1, 2}
        cone_distance : array_like
            Distance from the apex [m].
        polar_angle : array_like
            Polar angle of the point from the axis [rad].
        side : {"drive", "coast"}

        Returns
        -------
        numpy.ndarray
            Pressure angle [rad].
        """
        points, normals = self.flank(member, side, cone_distance, polar_angle)
        a = self.axis[member]
        radial = unit(points)
        # Normal of the cone's tangent plane: in the meridian plane, normal to the generator.
        meridian = unit(a - np.sum(a * radial, axis=-1)[..., None] * radial)
        return np.arcsin(np.clip(np.abs(np.sum(normals * meridian, axis=-1)), 0.0, 1.0))

    def contact_line(self, side, phase, n=50):
        """Points of the contact line at turn ``phase`` inside the field of contact.

        Parameters
        ----------
        side : {"drive", "coast"}
        phase : float
            Turn Psi of the generating curve [rad].
        n : int
            Number of points.

        Returns
        -------
        rho : numpy.ndarray, shape (n,)
            Distances from the apex [m] (empty when the line misses the field).
        points : numpy.ndarray, shape (n, 3)
            Contact points in the mesh frame [m].
        normals : numpy.ndarray, shape (n, 3)
            Contact normals, pinion -> gear [-].
        """
        plane = self.planes[side]
        lo, hi = plane.line_segment(phase)
        if not hi > lo:
            empty = np.empty((0, 3))
            return np.empty(0), empty, empty
        rho = np.linspace(lo, hi, n)
        psi = phase + plane.curve.polar_angle(rho)
        return rho, plane.point(rho, psi), plane.in_plane_normal(rho, psi)
