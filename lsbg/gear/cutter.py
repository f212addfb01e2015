"""The SBG's face-mill cutter as a design variable: nominal sizes, fit, lengthwise curvature.

A face-milled SBG's tooth trace is curved by its cutter; the LSBG's trace, a
conical logarithmic spiral, has a lengthwise curvature of its own. This module
compares the two at the mean point:

* :data:`NOMINAL_CUTTER_RADII`: the nominal face-mill cutter radii (the inch series of
  face-mill cutter diameters 3.5 to 12 in; ISO 23509 Annex F sample 1 uses the
  9-in cutter, r_c0 = 114.3 mm; lsbg's default SBG the 6-in one, 76.2 mm). ISO 23509:2016
  tabulates the standard cutter radii (its Table E.1, by cutting method and the wheel's
  mean cone distance R_m2) [1]_; that table is not public, and this series is not checked
  against it beyond the sample's 9-in cutter (tests/gear/test_iso23509.py);
* :func:`trace_curvature_radius`: the radius of curvature of a member's tooth trace on
  its pitch cone, measured on the flank and taken in the cone's development (the
  generating crown gear's pitch plane, where a face-mill cutter's circle lies);
* :func:`lsbg_curvature_radius`: the LSBG's, exactly R_m / sin beta_m. Developing the
  pitch cone (angle delta) onto a plane keeps cone distances and turns an azimuth
  phi about the axis into phi sin(delta), so a conical logarithmic spiral of spiral
  angle beta becomes a plane logarithmic spiral meeting every ray at beta; a plane
  curve meeting the rays at a constant angle beta has radius of curvature
  R / sin(beta) at distance R from the pole. In space the trace curves more (the cone's
  own normal curvature across the generator adds sin^2 beta / (R tan delta)); the
  cutter's curvature is the development's;
* :func:`matched_cutter_radius`: the cutter radius of an SBG of a given trace whose pitch-cone
  trace has the LSBG's curvature at the mean point (for a cutter circle in the crown
  gear's pitch plane, r_c = R_m / sin beta_m; lsbg's circular arc lies in the plane of
  action, so it is solved for on the flank);
* :func:`fitting_radii`: the nominal radii that fit a pair (the rule below).

Fit. A nominal radius fits a pair if (1) the cutter spans the face at the spiral angle:
the design with that radius passes :class:`~lsbg.gear.design.GearPairDesign`'s own check
of the trace (the arc does not turn radial between toe and heel) and its flanks build,
and (2) it lies in the usual range for the pair's size, ``usual_range`` times the outer
cone distance R_e (the study's default 0.5-1.5: lsbg's 76.2-mm cutter is 0.89 R_e of the
paper's pair, the ISO 23509 sample's 114.3-mm one 1.22 R_e of its pair). The criterion
practice uses is the ratio of the cutter radius to the wheel's mean cone distance R_m
(small- and large-cutter designs) [1]_; no public source found gives its bounds, so the
range is lsbg's own, wide enough for both cutters named (1.04 R_m and 1.41 R_m) and the
nominal series' neighbours, and configurable (``cutter_sweep.usual_range_outer_cone_distance``).

All lengths in metres, angles in radians.

References
----------
.. [1] FVA-Workbench documentation, "Cutter head radius" (rc0, attribute
   cutter_radius_iso23509_2016): the cutter radius sets the lengthwise curvature; the
   standard cutter radii are ISO 23509:2016's Table E.1, chosen by the cutting method and
   the mean cone distance R_m2; the ratio of cutter radius to mean cone distance is the
   criterion of small- and large-cutter designs.
   https://adoc.fva-service.de/help/8.1/en/attr/PMID_19482.htm (also 9.2, 10.0:
   PMID_19480).
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.gear.design import DesignError, GearPairDesign

__all__ = ["NOMINAL_CUTTER_DIAMETERS_IN", "NOMINAL_CUTTER_RADII", "USUAL_RANGE",
           "trace_curvature_radius", "lsbg_curvature_radius", "matched_cutter_radius",
           "cutter_fit_problem", "fitting_radii"]

#: Nominal face-mill cutter diameters [in].
NOMINAL_CUTTER_DIAMETERS_IN = (3.5, 5.0, 6.0, 7.5, 9.0, 10.5, 12.0)
#: Their radii [m]: 44.45, 63.5, 76.2, 95.25, 114.3, 133.35, 152.4 mm.
NOMINAL_CUTTER_RADII = tuple(round(d * 25.4e-3 / 2, 8) for d in NOMINAL_CUTTER_DIAMETERS_IN)
#: The usual cutter radii of a pair, as multiples of its outer cone distance [-].
USUAL_RANGE = (0.5, 1.5)


def trace_curvature_radius(pair, member=2, cone_distance=None, side="drive"):
    """Radius of curvature of a tooth trace on the pitch cone, in the cone's development.

    The trace is the flank on the member's pitch cone; developed onto a plane (cone
    distance kept, azimuth about the axis times sin of the pitch angle) it is a plane
    curve, whose curvature is taken by central differences.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    member : {1, 2}
    cone_distance : float, optional
        Where [m]; default the mean cone distance R_m.
    side : {"drive", "coast"}

    Returns
    -------
    float
        Radius of curvature [m], > 0 (inf for a straight developed trace).
    """
    d = pair.design
    rho = d.mean_cone_distance if cone_distance is None else float(cone_distance)
    delta = d.pitch_angle(member)
    h = 2e-3 * d.face_width
    rs = rho + h * np.arange(-2, 3)
    points, _ = pair.flank(member, side, rs, np.full(rs.shape, delta))
    a = pair.axis[member]
    ref = pair.pitch_dir - (pair.pitch_dir @ a) * a
    ref /= np.linalg.norm(ref)
    other = np.cross(a, ref)
    phi = np.unwrap(np.arctan2(points @ other, points @ ref))
    psi = (phi - phi[2]) * math.sin(delta)
    x, y = rs * np.cos(psi), rs * np.sin(psi)
    # fourth-order central differences at the middle point
    d1 = lambda f: (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)  # noqa: E731
    d2 = lambda f: (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h)  # noqa: E731
    cross = abs(d1(x) * d2(y) - d1(y) * d2(x))
    speed = math.hypot(d1(x), d1(y))
    return math.inf if cross == 0 else speed ** 3 / cross


def lsbg_curvature_radius(design):
    """The LSBG's lengthwise radius of curvature at the mean point, R_m / sin(beta_m) [m].

    Exact for lsbg's LSBG, whose pitch-cone trace is a conical logarithmic spiral of
    constant spiral angle beta_m (module docstring).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    """
    return design.mean_cone_distance / math.sin(design.spiral_angle)


def _sbg(design, trace, radius):
    return design.replace(trace=trace, cutter_radius=float(radius))


def matched_cutter_radius(design, trace="circular", member=2):
    """The cutter radius of the SBG whose trace curves as the LSBG's at the mean point [m].

    Solves :func:`trace_curvature_radius` (member's pitch cone, mean point) of the SBG of
    ``trace`` = :func:`lsbg_curvature_radius` for the cutter radius; for ``face_milled``
    (the cutter circle in the crown gear's pitch plane) that radius is R_m / sin(beta_m)
    itself, returned without the solve.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        The pair (its trace and cutter radius are replaced).
    trace : str
        The SBG's trace (a kind of :data:`lsbg.gear.design.TRACES` with a cutter).
    member : {1, 2}

    Returns
    -------
    float
        r_c [m].

    Raises
    ------
    lsbg.gear.design.DesignError
        Naming ``cutter_radius`` if no cutter radius in R_m sin(beta_m) .. 20 R_e gives it.
    """
    target = lsbg_curvature_radius(design)
    if trace == "face_milled":
        # the cutter circle lies in the pitch cone's development: its own radius is the
        # trace's curvature radius there (the solve below agrees to 1e-9, the tests show)
        _sbg(design, trace, target)  # DesignError if it cannot span the face
        return target

    from scipy.optimize import brentq

    from lsbg.gear.geometry import GearPair


    def excess(radius):
        try:
            pair = GearPair(_sbg(design, trace, radius))
        except DesignError:
            return -target  # a radius too small to span the face curves too tightly
        return trace_curvature_radius(pair, member) - target

    low = design.mean_cone_distance * math.sin(design.spiral_angle)
    high = 20 * design.outer_cone_distance
    if not excess(low) < 0 < excess(high):
        raise DesignError(f"cutter_radius: no {trace} cutter between {low:.6g} and "
                          f"{high:.6g} m curves the trace as the LSBG's ({target:.6g} m)")
    return float(brentq(excess, low, high, xtol=1e-9, rtol=1e-10))


def cutter_fit_problem(design, trace, radius, usual_range=USUAL_RANGE):
    """Why a cutter radius does not fit a pair, or None (the module's rule).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    trace : str
        The SBG's trace.
    radius : float
        Cutter radius [m].
    usual_range : (float, float)
        The usual radii as multiples of the outer cone distance [-]; None: no range.

    Returns
    -------
    str or None
        A reason without the key (the caller names it).
    """
    from lsbg.gear.geometry import GearPair

    try:
        GearPair(_sbg(design, trace, radius))
    except DesignError as error:
        why = str(error).split(": ", 1)[-1]
        return f"cannot span the face at the spiral angle: the cutter {why}"
    if usual_range is not None:
        low, high = (f * design.outer_cone_distance for f in usual_range)
        if not low <= radius <= high:
            return (f"is outside the usual cutter radii of the pair, {usual_range[0]:g}-"
                    f"{usual_range[1]:g} R_e = {low * 1e3:.4g}-{high * 1e3:.4g} mm")
    return None


def fitting_radii(design, trace, usual_range=USUAL_RANGE, radii=NOMINAL_CUTTER_RADII):
    """The nominal cutter radii that fit a pair (:func:`cutter_fit_problem`), ascending [m].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    trace : str
    usual_range : (float, float)
    radii : iterable of float
        Candidates [m].
    """
    return [r for r in sorted(radii) if cutter_fit_problem(design, trace, r, usual_range) is None]


def sbg_design(design: GearPairDesign, trace, radius) -> GearPairDesign:
    """The SBG of ``trace`` cut with ``radius`` [m] on ``design``'s pair."""
    return _sbg(design, trace, radius)
