"""The plane of action of a gear pair and the generating curve drawn in it.

A plane through the common apex, tangent to both base cones and containing
the pitch line, rolls on each base cone; a curve fixed in it sweeps both
members' flanks (:mod:`lsbg.gear.geometry`, DESIGN.md §2). This module owns
the two objects of that plane:

* :class:`GeneratingCurve`, the curve C as polar angle against distance
  from the apex: a plane logarithmic spiral (LSBG, a constant angle beta_p to
  every ray from the apex) or a circular arc (SBG, the face-mill cutter of
  radius r_c, at angle beta_p to the ray at the mean point only). A third
  tooth trace is a third ``kind`` here;
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

__all__ = ["GeneratingCurve", "PlaneOfAction"]


# ------------------------------------------------------------- generating curve
@dataclass(frozen=True)
class GeneratingCurve:
    """A curve in the plane of action, as polar angle against distance from the apex.

    Parameters
    ----------
    kind : {"logarithmic", "circular"}
    plane_spiral_angle : float
        Signed angle beta_p between the curve and the ray at the mean point
        [rad]; its sign sets the hand.
    mean_distance : float
        R_m, where the curve crosses the pitch line (psi = 0) [m].
    cutter_radius : float
        Arc radius for ``kind="circular"`` [m].
    """

    kind: str
    plane_spiral_angle: float
    mean_distance: float
    cutter_radius: float

    @cached_property
    def _arc(self):
        # Arc centre in the plane's (rho along pitch line, rho sin psi) coordinates.
        b, rm, rc = self.plane_spiral_angle, self.mean_distance, self.cutter_radius
        sign = math.copysign(1.0, b)
        cx = rm - sign * rc * math.sin(b)
        cy = sign * rc * math.cos(b)
        rho0, theta0 = math.hypot(cx, cy), math.atan2(cy, cx)
        return rho0, theta0, -math.copysign(1.0, theta0)

    def polar_angle(self, rho):
        """In-plane angle theta_c(rho) of the curve point at distance rho [rad]."""
        rho = np.asarray(rho, dtype=float)
        if self.kind == "logarithmic":
            return math.tan(self.plane_spiral_angle) * np.log(rho / self.mean_distance)
        rho0, theta0, branch = self._arc
        cos_arg = (rho**2 + rho0**2 - self.cutter_radius**2) / (2 * rho * rho0)
        return theta0 + branch * np.arccos(np.clip(cos_arg, -1.0, 1.0))

    def ray_angle(self, rho):
        """Signed angle beta_p(rho) between the curve and the ray [rad]."""
        rho = np.asarray(rho, dtype=float)
        if self.kind == "logarithmic":
            return np.full_like(rho, self.plane_spiral_angle)
        rm, rc, b = self.mean_distance, self.cutter_radius, self.plane_spiral_angle
        s = (rho**2 - rm**2 + 2 * rm * rc * math.sin(abs(b))) / (2 * rho * rc)
        return math.copysign(1.0, b) * np.arcsin(np.clip(s, -1.0, 1.0))

    def distance_at(self, theta):
        """Inverse of :meth:`polar_angle`: distance rho where theta_c = theta [m].

        Returns NaN where the curve never reaches that angle.
        """
        theta = np.asarray(theta, dtype=float)
        if self.kind == "logarithmic":
            return self.mean_distance * np.exp(theta / math.tan(self.plane_spiral_angle))
        rho0, theta0, _ = self._arc
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
