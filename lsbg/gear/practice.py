"""A bevel pair as practice proportions it: the depth shared out between the members.

Two rules give the practice design's mean profile shift x_hm1
(``practice.addendum_rule``, :func:`practice_profile_shift`):

* ``iso23509`` (the default): ISO 23509:2016's mean addendum factor of the gear,
  its Gleason-type rule for spiral bevel gears (Annex C, C.3.2.3, Table C.2;
  also ANSI/AGMA 2005-D03's gear mean addendum factor)

      c_ham = 0.210 + 0.290 / u_a^2,  u_a = m_90 the equivalent 90-deg ratio,

  the gear's mean addendum c_ham h_mw of the mean working depth h_mw = k_d m_mn,
  hence (ISO 23509's Table 4, data type II to I) x_hm1 = k_d (0.5 - c_ham)
  (:func:`iso23509_profile_shift`). At ISO 23509's Annex F sample 1 (14/39,
  k_d = 2) c_ham = 0.24737 and x_hm1 = 0.505, the pair of ISO/TR 10300-30's
  sample 1;
* ``agma209``: the Gleason spiral bevel system of AGMA 209.03 (below).

The paper's pair has equal addenda (0.85 m of a 1.7 m working depth each), so
its 9-tooth pinion is undercut and its gear's teeth stronger than they need
be. Bevel practice gives a pinion with few teeth most of the working depth:
the Gleason spiral bevel system (AGMA 209.03, 1964; Gleason Works, "Method for
designing spiral bevel gears") sets the gear's outer addendum

    a_oG = m (0.46 + 0.39 / m_90^2)  of a working depth h_k = 1.7 m,

m_90 = sqrt(z2 cos(delta_1) / (z1 cos(delta_2))) the equivalent 90-deg ratio
(z2 / z1 at a shaft angle of 90 deg), and the pinion's a_oP = h_k - a_oG. In
ISO 23509's terms (type I data) this is a mean profile shift x_hm1 =
k_d / 2 - c_ham with the gear's mean addendum factor c_ham = a_oG / (h_k / k_d)
: the basic crown gear moved x_hm1 m_mn towards the pinion's tip, the gear's
addendum shorter by as much. :func:`gleason_profile_shift` scales the rule to a
design's own working depth (2 h_a, 1.7 m for the paper's Table 1) and returns
x_hm1 in mean normal modules.
"""

from __future__ import annotations

import math

__all__ = ["ADDENDUM_RULES", "equivalent_ratio", "gleason_gear_addendum",
           "gleason_profile_shift", "iso23509_mean_addendum_factor", "iso23509_profile_shift",
           "practice_profile_shift"]

#: The rules of the practice design's profile shift (``practice.addendum_rule``),
#: each with the words a report says it in.
ADDENDUM_RULES = {
    "iso23509": "ISO 23509's mean addendum factor c_ham = 0.210 + 0.290/u_a²",
    "agma209": "the Gleason system's addenda of AGMA 209.03",
}


def equivalent_ratio(design):
    """The equivalent 90-deg ratio m_90 = sqrt(z2 cos(delta_1) / (z1 cos(delta_2))) [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    """
    z1, z2 = design.teeth
    return math.sqrt(z2 * math.cos(design.pitch_angle(1)) / (z1 * math.cos(design.pitch_angle(2))))


def gleason_gear_addendum(design):
    """The gear's outer addendum by the Gleason system, on the design's working depth [m].

    ``(0.46 + 0.39 / m_90^2) / 1.7`` of the working depth ``2 h_a`` (the rule's
    share of its 1.7 m working depth; for the paper's pair 0.483 m).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    """
    share = (0.46 + 0.39 / equivalent_ratio(design) ** 2) / 1.7
    return share * 2 * design.addendum


def gleason_profile_shift(design):
    """The pinion's mean profile shift x_hm1 that gives the Gleason system's addenda [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        Its unshifted addendum ``h_a`` (half the working depth), module and
        spiral angle.

    Returns
    -------
    float
        x_hm1 in mean normal modules: the outer depth moved from the gear's
        addendum to the pinion's, ``h_a - a_oG``, over ``m_mn R_e / R_m`` (the
        teeth taper to the apex).
    """
    moved = design.addendum - gleason_gear_addendum(design)
    return moved / (design.mean_normal_module * design.outer_cone_distance
                    / design.mean_cone_distance)


def iso23509_mean_addendum_factor(design):
    """ISO 23509's mean addendum factor of the gear, c_ham = 0.210 + 0.290 / u_a^2 [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        Its teeth and pitch angles (u_a = :func:`equivalent_ratio`).
    """
    return 0.210 + 0.290 / equivalent_ratio(design) ** 2


def iso23509_profile_shift(design):
    """The pinion's mean profile shift x_hm1 = k_d (0.5 - c_ham) by ISO 23509 [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        Its unshifted addendum ``h_a`` sets the depth factor: the mean working
        depth h_mw = 2 h_a R_m / R_e (the apex taper's, kept by every taper) is
        k_d m_mn.

    Returns
    -------
    float
        x_hm1 in mean normal modules: the gear's mean addendum c_ham h_mw, the
        pinion's (1 - c_ham) h_mw.
    """
    working = 2 * design.addendum * design.mean_cone_distance / design.outer_cone_distance
    depth_factor = working / design.mean_normal_module
    return depth_factor * (0.5 - iso23509_mean_addendum_factor(design))


def practice_profile_shift(design, rule="iso23509"):
    """x_hm1 by one of :data:`ADDENDUM_RULES` [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    rule : {"iso23509", "agma209"}
    """
    if rule == "iso23509":
        return iso23509_profile_shift(design)
    if rule == "agma209":
        return gleason_profile_shift(design)
    raise ValueError(f"practice.addendum_rule = {rule!r}: must be one of {sorted(ADDENDUM_RULES)}")
