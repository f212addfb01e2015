"""The tooth depth's taper along the face: where the face and root cones lie.

lsbg's teeth taper to the pitch apex by default (``depth_taper: apex``): the
face, pitch and root cones of both members meet at the common apex, the depth
grows in proportion to the cone distance and the outer addendum and dedendum
``h_a``, ``h_f`` (shifted by the profile shift) set the angles,
theta_a = atan(h_a,e / R_e), theta_f = atan(h_f,e / R_e). The other tapers
are ISO 23509:2016's, which sets the depth at the calculation (mean) point and
the face and root cones by their angles (Clause 7.3-7.4):

* ``given_dedendum_angles``: the dedendum angles theta_f1, theta_f2 of both
  members given (``dedendum_angles_deg``; ISO 23509's Table 3 input, its
  Annex F sample 1 gives theta_f1 = theta_a2 = 2.1342 deg and theta_f2 = 6.4934 deg);
* ``standard``: ISO 23509's standard depth (Annex C.5, Formulae (C.6)-(C.7)), each
  root cone through the pitch apex, theta_f,i = atan(h_fm,i / R_m);
* ``uniform``: uniform depth (Annex C.5), theta_f = 0, the depth the same
  across the face.

Under these three each member's face cone is parallel to the mate's root cone
(ISO 23509's Formulae (146)-(149) without hypoid offset: delta_a1 = Sigma -
delta_f2), so theta_a1 = theta_f2 and theta_a2 = theta_f1 and the clearance is
the same across the face. The depths at the mean point are those of the apex
taper (the design's ``h_a R_m / R_e +- x_hm1 m_mn``, ISO 23509's h_am, h_fm),
the outer and inner ones follow from the angles,
h_ae = h_am + (R_e - R_m) tan(theta_a), h_ai = h_am - (R_m - R_i) tan(theta_a)
(ISO 23509's Formulae (200)-(211) at c_be2 = 1/2). The face and root cones then
no longer pass through the pitch apex: their apexes lie off it along the
member's axis, and a cone's polar angle on a sphere about the pitch apex
changes with the sphere's radius (:func:`cone_polar_angle`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["TAPERS", "TAPER_DEFAULTS", "dedendum_angles", "addendum_angles", "mean_depth",
           "heel_depth", "toe_depth", "outer_tip_diameter", "cone_polar_angle", "tip_polar_angle",
           "root_polar_angle", "taper_problem", "angles_from_config", "angles_to_config"]

#: The depth tapers lsbg builds (``design.depth_taper``).
TAPERS = ("apex", "given_dedendum_angles", "standard", "uniform")

#: The taper's design keys and their defaults: beside :data:`lsbg.gear.design.CONFIG_KEYS`
#: (the keys every record holds), left out of
#: :meth:`lsbg.gear.design.GearPairDesign.to_config` under the apex taper (the published
#: pair's records stay as they were).
TAPER_DEFAULTS = {"depth_taper": "apex", "dedendum_angles_deg": None}


def dedendum_angles(design):
    """The dedendum angles (theta_f1, theta_f2) of a taper that is not ``apex`` [rad].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign

    Returns
    -------
    tuple of float
    """
    if design.depth_taper == "given_dedendum_angles":
        return tuple(float(a) for a in design.dedendum_angles)
    if design.depth_taper == "uniform":
        return 0.0, 0.0
    rm = design.mean_cone_distance
    return tuple(math.atan(mean_depth(design, member, "dedendum") / rm) for member in (1, 2))


def addendum_angles(design):
    """The addendum angles (theta_a1, theta_a2) = (theta_f2, theta_f1): ISO 23509's
    clearance rule, each face cone parallel to the mate's root cone [rad]."""
    theta_f1, theta_f2 = dedendum_angles(design)
    return theta_f2, theta_f1


def mean_depth(design, member, which):
    """The addendum or dedendum of a member at the mean point, h_am or h_fm [m].

    (h_a +- the outer shift) R_m / R_e and (h_f -+ it) R_m / R_e under every taper:
    ISO 23509's h_am = m_mn (k_hap +- x_hm1), h_fm = m_mn (k_hfp -+ x_hm1) with
    k_hap = h_a R_m / (R_e m_mn). Under the apex taper the outer value times
    R_m / R_e, the same float as ever.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    member : {1, 2}
    which : {"addendum", "dedendum"}
    """
    scale = design.mean_cone_distance / design.outer_cone_distance
    if which == "addendum":
        return (design.addendum + design.outer_shift(member)) * scale
    return (design.dedendum - design.outer_shift(member)) * scale


def _angle(design, member, which):
    return (design.member_addendum_angle(member) if which == "addendum"
            else design.member_dedendum_angle(member))


def heel_depth(design, member, which):
    """The addendum or dedendum at the outer cone distance under a taper other than
    ``apex``, h_m + (R_e - R_m) tan(theta) (ISO 23509's h_ae, h_fe) [m]."""
    run = design.outer_cone_distance - design.mean_cone_distance
    return mean_depth(design, member, which) + run * math.tan(_angle(design, member, which))


def toe_depth(design, member, which):
    """The addendum or dedendum at the inner cone distance, h_m - (R_m - R_i) tan(theta)
    (ISO 23509's h_ai, h_fi; under the apex taper the outer one times R_i / R_e) [m]."""
    if design.depth_taper == "apex":
        outer = design.outer_addendum(member) if which == "addendum" else design.outer_dedendum(member)
        return outer * design.inner_cone_distance / design.outer_cone_distance
    run = design.mean_cone_distance - design.inner_cone_distance
    return mean_depth(design, member, which) - run * math.tan(_angle(design, member, which))


def outer_tip_diameter(design, member, unit=1.0):
    """The outer tip diameter d_ae = d_e + 2 h_ae cos(delta) (ISO 23509's) [m, times unit].

    Under the apex taper 2 R_e sin(delta_a) / cos(theta_a), the same number.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    member : {1, 2}
    unit : float
        The scale of the result: 1 for metres, 1e3 for millimetres.
    """
    if design.depth_taper == "apex":
        return 2 * unit * design.outer_cone_distance * math.sin(
            design.tip_angle(member)) / math.cos(design.member_addendum_angle(member))
    return unit * (design.pitch_diameter(member)
                   + 2 * design.outer_addendum(member) * math.cos(design.pitch_angle(member)))


def cone_polar_angle(depth, angle, mean_cone_distance, cone_distance):
    """The angle, seen from the pitch apex, between the pitch cone and a face or root cone.

    In the member's axial section the cone's generator runs at ``angle`` to
    the pitch generator and ``depth`` from it at the mean cone distance R_m;
    its point at distance rho from the pitch apex lies at pitch-line coordinate
    u with u^2 + v(u)^2 = rho^2, v(u) = depth + (u - R_m) tan(angle), and at the
    angle atan(v / u) from the pitch generator. A cone through the apex
    (depth = R_m tan(angle)) gives ``angle`` at every rho.

    Parameters
    ----------
    depth : float
        The addendum (face cone) or dedendum (root cone) at the mean point [m].
    angle : float
        The addendum or dedendum angle [rad].
    mean_cone_distance : float
        R_m [m].
    cone_distance : array_like
        Distances rho from the pitch apex [m].

    Returns
    -------
    numpy.ndarray
        The angle [rad]: the face cone's polar angle is delta + this, the root
        cone's delta - this.
    """
    rho = np.asarray(cone_distance, dtype=float)
    t = math.tan(angle)
    c = depth - mean_cone_distance * t
    u = (-c * t + np.sqrt(rho**2 * (1 + t * t) - c * c)) / (1 + t * t)
    return np.arctan2(c + u * t, u)


def tip_polar_angle(design, member, cone_distance):
    """Polar angle from the member's axis of its face (tip) cone on spheres about the
    pitch apex [rad]: ``design.tip_angle(member)`` at every radius under the apex taper.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    member : {1, 2}
    cone_distance : array_like
        Sphere radii rho [m].
    """
    if design.depth_taper == "apex":
        return np.full(np.shape(cone_distance), design.tip_angle(member))
    return design.pitch_angle(member) + cone_polar_angle(
        mean_depth(design, member, "addendum"), design.member_addendum_angle(member),
        design.mean_cone_distance, cone_distance)


def root_polar_angle(design, member, cone_distance):
    """Polar angle of the root cone on spheres about the pitch apex [rad] (as
    :func:`tip_polar_angle`; ``design.root_angle(member)`` under the apex taper)."""
    if design.depth_taper == "apex":
        return np.full(np.shape(cone_distance), design.root_angle(member))
    return design.pitch_angle(member) - cone_polar_angle(
        mean_depth(design, member, "dedendum"), design.member_dedendum_angle(member),
        design.mean_cone_distance, cone_distance)


def angles_from_config(value, error):
    """``dedendum_angles_deg`` as the design's field: a tuple of radians, or None;
    ``error`` (:class:`lsbg.gear.design.DesignError`) raised where they are not numbers."""
    if value is None:
        return None
    try:
        return tuple(math.radians(float(v)) for v in value)
    except (TypeError, ValueError):
        raise error(f"dedendum_angles_deg = {value!r}: must be two angles in degrees "
                          f"[theta_f1, theta_f2]") from None


def angles_to_config(value, scale, inverse):
    """A taper key's value in the configuration's units (the angles in degrees)."""
    if scale is None or value is None:
        return value
    return [inverse(v, *scale) for v in value]


def _key_problem(design):
    if design.depth_taper not in TAPERS:
        return "depth_taper", design.depth_taper, f"must be one of {TAPERS}"
    given = design.depth_taper == "given_dedendum_angles"
    angles = design.dedendum_angles
    if given and (angles is None or isinstance(angles, (str, bytes)) or np.ndim(angles) != 1
                  or len(angles) != 2
                  or not all(np.isfinite(a) and abs(a) < math.radians(20) for a in angles)):
        return ("dedendum_angles", angles, "must be the two members' dedendum angles "
                "(theta_f1, theta_f2), each within (-20, 20) deg (in radians; "
                "design.dedendum_angles_deg in degrees)")
    if not given and angles is not None:
        return ("dedendum_angles", angles, f"are given, but depth_taper = "
                f"{design.depth_taper!r} sets the angles itself (given_dedendum_angles takes them)")
    return None


def taper_problem(design):
    """Why a taper's depths cannot be built, or None: the key at fault, its value, the why.

    A taper that leaves a member no dedendum or no addendum at the toe (the
    inner cone distance R_i) or at the heel is refused.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign

    Returns
    -------
    tuple or None
        ``(name, value, why)`` for :class:`lsbg.gear.design.DesignError`.
    """
    problem = _key_problem(design)
    if problem is not None or design.depth_taper == "apex":
        return problem
    key = ("dedendum_angles", design.dedendum_angles) \
        if design.depth_taper == "given_dedendum_angles" else ("depth_taper", design.depth_taper)
    for member, name in ((1, "pinion"), (2, "gear")):
        for which in ("dedendum", "addendum"):
            for where, value in (("toe", toe_depth(design, member, which)),
                                 ("heel", heel_depth(design, member, which))):
                if value <= 0:
                    angle = math.degrees(_angle(design, member, which))
                    return (*key, f"leaves the {name} no {which} at the {where} ({which} "
                                  f"{value:.6g} m; its {which} angle {angle:.4f} deg, mean "
                                  f"{which} {mean_depth(design, member, which):.6g} m)")
    return None
