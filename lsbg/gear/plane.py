"""The plane of action of a gear pair and the generating curve drawn in it.

A plane through the common apex, tangent to both base cones and containing
the pitch line, rolls on each base cone; a curve fixed in it sweeps both
members' flanks (:mod:`lsbg.gear.geometry`, DESIGN.md §2). This module owns
the two objects of that plane:

* :class:`GeneratingCurve`, the curve C as polar angle against distance
  from the apex: a plane logarithmic spiral (LSBG, a constant angle beta_p to
  every ray from the apex), a circular arc (the paper's SBG: the face-mill
  cutter of radius r_c drawn in the plane of action, at angle beta_p to the
  ray at the mean point only), or the curve that makes the face-milled SBG of
  ISO 23509 (its cutter circle in the pitch plane of the generating crown
  gear; see :class:`GeneratingCurve`);
* :class:`PlaneOfAction`, one side's plane: its frame, its curve, where it
  touches the base cones, the field of contact, and the contact lines (the
  curve turned by Psi about the plane normal) inside that field.

Inside a plane of action a point is given by polar coordinates (rho, psi):
distance from the apex [m] and angle from the pitch line about the plane
normal [rad]. :class:`lsbg.gear.geometry.GearPair` builds both sides' planes.

All lengths in metres, all angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["face_milled_spiral_angle", "GeneratingCurve", "PlaneOfAction"]


# ------------------------------------------------------------- generating curve
def face_milled_spiral_angle(cone_distance, mean_cone_distance, cutter_radius, mean_spiral_angle):
    """The pitch-cone spiral angle of a face-milled SBG by ISO 23509 [rad].

    The cutter circle of radius r_c0 lies in the pitch plane of the generating
    crown gear, through the mean point at beta_m; the triangle apex - point -
    cutter centre gives sin(beta(R)) = (R^2 - R_m^2 + 2 R_m r_c0 sin(beta_m)) /
    (2 R r_c0) (ISO 23509:2016, the spiral angles at the inner and outer cone
    distances of face milling; AGMA 929-A06 likewise).

    Parameters
    ----------
    cone_distance : array_like
        R, distance from the apex along the pitch cone [m] (or any one length unit
        for all three lengths).
    mean_cone_distance : float
        R_m [m].
    cutter_radius : float
        r_c0 [m].
    mean_spiral_angle : float
        beta_m [rad].

    Returns
    -------
    numpy.ndarray
        beta(R) [rad]; NaN where the circle does not reach R at an angle to the ray.
    """
    R = np.asarray(cone_distance, dtype=float)
    rm, rc = mean_cone_distance, cutter_radius
    with np.errstate(invalid="ignore"):
        return np.arcsin((R**2 - rm**2 + 2 * rm * rc * math.sin(mean_spiral_angle)) / (2 * R * rc))


@dataclass(frozen=True)
class GeneratingCurve:
    """A curve in the plane of action, as polar angle against distance from the apex.

    The flank's normal at a point of the pitch line lies in the plane of
    action, perpendicular to the curve there, so the pitch-cone spiral angle
    beta at cone distance R and the curve's angle beta_p(R) to the ray obey
    tan(beta) = tan(beta_p) / cos(gamma) at every R, gamma the plane's tilt
    from the pitch plane (the curve turned by Psi keeps its angles to the
    rays). ``kind`` says which curve:

    * ``"logarithmic"``: beta_p constant, theta_c = tan(beta_p) ln(rho / R_m);
    * ``"circular"``: a circle of radius r_c in the plane of action through
      (R_m, 0) at angle beta_p to the ray (the paper's SBG);
    * ``"face_milled"``: the curve whose pitch-cone trace is that of ISO
      23509's face-milled SBG, the cutter circle of radius r_c0 in the pitch
      plane of the generating crown gear, sin(beta(R)) = (R^2 - R_m^2 +
      2 R_m r_c0 sin(beta_m)) / (2 R r_c0). Its polar angle, from
      d theta_c / d rho = tan(beta_p) / rho = cos(gamma) tan(beta) / rho, is
      cos(gamma) times the polar angle of that pitch-plane circle (closed
      form, law of cosines); its inverse is the circle's at theta / cos(gamma).

    Parameters
    ----------
    kind : {"logarithmic", "circular", "face_milled"}
    plane_spiral_angle : float
        Signed angle beta_p between the curve and the ray at the mean point
        [rad]; its sign sets the hand.
    mean_distance : float
        R_m, where the curve crosses the pitch line (psi = 0) [m].
    cutter_radius : float
        Circle radius for ``kind="circular"`` and ``"face_milled"`` [m].
    tilt : float
        gamma, the plane of action's tilt from the pitch plane [rad]; used by
        ``kind="face_milled"`` only.
    """

    kind: str
    plane_spiral_angle: float
    mean_distance: float
    cutter_radius: float
    tilt: float = 0.0

    @cached_property
    def polar_scale(self) -> float:
        """theta_c over the circle's own polar angle: cos(gamma) for the face-milled
        curve, 1 for the circular arc [-]."""
        return math.cos(self.tilt) if self.kind == "face_milled" else 1.0

    @cached_property
    def circle_spiral_angle(self) -> float:
        """Signed angle of the circle to the ray at R_m [rad]: beta_p for the circular
        arc, the pitch-cone beta_m = atan(tan(beta_p) / cos(gamma)) for the face-milled
        curve (its circle lies in the pitch plane)."""
        if self.kind != "face_milled":
            return self.plane_spiral_angle
        return math.atan(math.tan(self.plane_spiral_angle) / self.polar_scale)

    @cached_property
    def _arc(self):
        # Circle centre in the (rho along pitch line, rho sin psi) coordinates of its
        # plane (the plane of action, or for face_milled the pitch plane).
        b, rm, rc = self.circle_spiral_angle, self.mean_distance, self.cutter_radius
        sign = math.copysign(1.0, b)
        cx = rm - sign * rc * math.sin(b)
        cy = sign * rc * math.cos(b)
        rho0, theta0 = math.hypot(cx, cy), math.atan2(cy, cx)
        return rho0, theta0, -math.copysign(1.0, theta0)

    def circle_sin_angle(self, rho):
        """sin of the circle's unsigned angle to the ray at distance rho [-].

        The triangle apex - point - circle centre:
        (rho^2 - R_m^2 + 2 R_m r_c sin|b|) / (2 rho r_c), b the circle's angle at R_m
        (:attr:`circle_spiral_angle`); beyond 1 the circle does not reach rho.

        Parameters
        ----------
        rho : array_like
            Distance from the apex [m].
        """
        rho = np.asarray(rho, dtype=float)
        rm, rc, b = self.mean_distance, self.cutter_radius, self.circle_spiral_angle
        return (rho**2 - rm**2 + 2 * rm * rc * math.sin(abs(b))) / (2 * rho * rc)

    def polar_angle(self, rho):
        """In-plane angle theta_c(rho) of the curve point at distance rho [rad].

        Parameters
        ----------
        rho : array_like
            Distance from the apex [m].
        """
        rho = np.asarray(rho, dtype=float)
        if self.kind == "logarithmic":
            return math.tan(self.plane_spiral_angle) * np.log(rho / self.mean_distance)
        rho0, theta0, branch = self._arc
        cos_arg = (rho**2 + rho0**2 - self.cutter_radius**2) / (2 * rho * rho0)
        theta = theta0 + branch * np.arccos(np.clip(cos_arg, -1.0, 1.0))
        return theta if self.kind == "circular" else self.polar_scale * theta

    def ray_angle(self, rho):
        """Signed angle beta_p(rho) between the curve and the ray [rad].

        Parameters
        ----------
        rho : array_like
            Distance from the apex [m].
        """
        rho = np.asarray(rho, dtype=float)
        if self.kind == "logarithmic":
            return np.full_like(rho, self.plane_spiral_angle)
        angle = np.arcsin(np.clip(self.circle_sin_angle(rho), -1.0, 1.0))
        if self.kind == "face_milled":
            angle = np.arctan(self.polar_scale * np.tan(angle))
        return math.copysign(1.0, self.plane_spiral_angle) * angle

    def distance_at(self, theta):
        """Inverse of :meth:`polar_angle`: distance rho where theta_c = theta [m].

        Parameters
        ----------
        theta : array_like
            Polar angle in the plane of action [rad].

        Returns
        -------
        numpy.ndarray
            rho [m]; NaN where the curve never reaches that angle.
        """
        theta = np.asarray(theta, dtype=float)
        if self.kind == "logarithmic":
            return self.mean_distance * np.exp(theta / math.tan(self.plane_spiral_angle))
        rho0, theta0, _ = self._arc
        if self.kind == "face_milled":
            theta = theta / self.polar_scale
        # rho^2 - 2 rho rho0 cos(theta - theta0) + rho0^2 - rc^2 = 0, root on
        # the arc's branch (the one through R_m, nearer to the apex side).
        cos_d = np.cos(theta - theta0)
        disc = self.cutter_radius**2 - rho0**2 * (1 - cos_d**2)
        with np.errstate(invalid="ignore"):
            rho = rho0 * cos_d + np.sqrt(disc)
        return np.where(disc >= 0, rho, np.nan)


# -------------------------------------------------------------- plane of action
@dataclass(frozen=True)
class PlaneOfAction:
    """One of the two planes of action (drive or coast side) of a gear pair.

    Attributes
    ----------
    side : str
        "drive" or "coast".
    normal, pitch_dir, cross_dir : numpy.ndarray, shape (3,)
        Unit normal N, pitch-line direction p and q = N x p; (p, q, N) is
        right-handed, so a turn Psi about N adds Psi to the polar angle psi.
    curve : GeneratingCurve
    tangency_angle : dict
        Polar angle psi_g,i of the line where the plane touches base cone i [rad].
    roll_sign : dict
        +-1: the side of that line (towards the pitch line) on which member i's
        involute flank lies.
    field : tuple
        (psi_lo, psi_hi, rho_inner, rho_outer): the field of contact [rad, m].
    contact_normal_sign : float
        +-1 so that ``contact_normal_sign * in_plane_normal`` points from the
        pinion flank into the gear flank.
    """

    side: str
    normal: np.ndarray
    pitch_dir: np.ndarray
    cross_dir: np.ndarray
    curve: GeneratingCurve
    tangency_angle: dict
    roll_sign: dict
    field: tuple
    contact_normal_sign: float

    def point(self, rho, psi):
        """3-D point of the plane at polar coordinates (rho [m], psi [rad])."""
        rho = np.asarray(rho, dtype=float)[..., None]
        psi = np.asarray(psi, dtype=float)[..., None]
        return rho * (np.cos(psi) * self.pitch_dir + np.sin(psi) * self.cross_dir)

    def in_plane_normal(self, rho, psi_line):
        """Unit normal of the rotated curve, in the plane (pinion -> gear).

        Parameters
        ----------
        rho : array_like
            Distance from the apex [m].
        psi_line : array_like
            Polar angle psi of the curve point at rho [rad].
        """
        beta = self.curve.ray_angle(rho)[..., None]
        psi = np.asarray(psi_line, dtype=float)[..., None]
        e_rho = np.cos(psi) * self.pitch_dir + np.sin(psi) * self.cross_dir
        e_psi = -np.sin(psi) * self.pitch_dir + np.cos(psi) * self.cross_dir
        return self.contact_normal_sign * (-np.sin(beta) * e_rho + np.cos(beta) * e_psi)

    def line_segment(self, phase):
        """Part of the contact line at turn ``phase`` inside the field of contact.

        The contact line is the generating curve turned by ``phase`` about N:
        psi(rho) = phase + theta_c(rho).

        Parameters
        ----------
        phase : array_like
            Turn Psi of the curve [rad].

        Returns
        -------
        rho_a, rho_b : numpy.ndarray
            Ends of the segment [m]; rho_a > rho_b (NaN-free) marks an empty one.
        """
        psi_lo, psi_hi, r_in, r_out = self.field
        phase = np.asarray(phase, dtype=float)
        r1 = self.curve.distance_at(psi_lo - phase)
        r2 = self.curve.distance_at(psi_hi - phase)
        r1 = np.where(np.isnan(r1), -np.inf if self.curve.plane_spiral_angle > 0 else np.inf, r1)
        r2 = np.where(np.isnan(r2), np.inf if self.curve.plane_spiral_angle > 0 else -np.inf, r2)
        lo = np.maximum(np.minimum(r1, r2), r_in)
        hi = np.minimum(np.maximum(r1, r2), r_out)
        return lo, hi
