"""The practice design: the pair as a bevel-gear designer would make it.

The paper's pair (docs/model.md, "The pair as a designer would make it") is
made as practice makes it, each step by a stated rule:

* the depth: long-and-short addenda as ISO 23509's mean profile shift x_hm1, by
  ISO 23509's mean addendum factor c_ham (``practice.addendum_rule: iso23509``,
  the default) or by the Gleason system's addenda of AGMA 209.03 (``agma209``)
  (:func:`lsbg.gear.practice.practice_profile_shift`);
* the thickness: the pinion's tooth made thicker and the gear's thinner by
  the thickness modification x_smn1 that makes the two members' ISO 10300
  root stresses equal (:func:`balanced_thickness_modification`), the Gleason
  system's own aim ("tooth thicknesses to give approximately equal stress in
  gear and pinion", AGMA 209.03) reached with the standard's own form and
  stress correction factors instead of its charts;
* undercut refused (``undercut: refuse``);
* its SBG face-milled as ISO 23509 defines it (``practice.sbg_trace``,
  :func:`practice_traces`): the cutter circle in the generating crown gear's
  pitch plane, where the published pair keeps the paper's arc;
* the edges: a linear tip relief of both members whose amount is the mesh's
  deflection under the rated load, C_a = F_mt / (b_eff c_gamma_alpha), with
  ISO 6336-1's mesh stiffness of the virtual cylindrical gears (the figure its
  transverse load factor sets profile deviations against), run out over the
  roll from the tip to the highest point of single contact, L = (eps_alpha -
  1) / eps_alpha of the active profile (a "long" relief; Niemann and Winter,
  Maschinenelemente II, 21.4) (:func:`deflection_tip_relief`);
* its load: its rated pitting torque by ISO 10300 (:func:`rated_gear_torque`).

:func:`practice_overlay` writes all of it as a configuration overlay, the
study's configuration with these keys set over it.
"""

from __future__ import annotations

import math

__all__ = ["root_stress_ratio", "balanced_thickness_modification", "practice_design",
           "rated_gear_torque", "deflection_tip_relief", "practice_traces", "practice_overlay"]


def _rating(design, config, gear_torque):
    from lsbg.rating.config import rate_design

    speed = math.radians(float(config["simulation"]["pinion_speed_deg_s"]))
    rating, _, _ = rate_design(design, config["rating"], config["tooth"], gear_torque, speed)
    return rating


def root_stress_ratio(design, section, tooth_section):
    """sigma_F1 / sigma_F2 of a design by ISO 10300 (method B1) [-].

    The ratio depends on the two members' form, stress-correction and
    root-factor terms only, not on the load or the speed.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    section, tooth_section : dict
        The configuration's ``rating`` and ``tooth`` sections.
    """
    from lsbg.rating.config import rate_design

    result, _, _ = rate_design(design, section, tooth_section, 1000.0, 100.0)
    return result.root_stress[0] / result.root_stress[1]


def balanced_thickness_modification(design, section, tooth_section, bracket=(-0.4, 0.4)):
    """The thickness modification x_smn1 at which both members' root stresses are equal.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        With its profile shift; its own ``thickness_modification`` is replaced.
    section, tooth_section : dict
        The ``rating`` and ``tooth`` sections.
    bracket : (float, float)
        Where to look [mean normal modules].

    Returns
    -------
    float
        x_smn1 [-], to 1e-9.

    Raises
    ------
    ValueError
        If no thickness in ``bracket`` balances them.
    """
    from scipy.optimize import brentq

    def gap(x):
        return math.log(root_stress_ratio(design.replace(thickness_modification=x), section,
                                          tooth_section))

    low, high = bracket
    if gap(low) * gap(high) > 0:
        raise ValueError(f"no thickness modification in [{low}, {high}] balances the root "
                         f"stresses (sigma_F1/sigma_F2 {math.exp(gap(low)):.3g} to "
                         f"{math.exp(gap(high)):.3g})")
    return brentq(gap, low, high, xtol=1e-9)


def practice_design(design, section, tooth_section, profile_shift="gleason",
                    thickness_modification="balanced", addendum_rule="iso23509"):
    """The pair as practice makes it: shifted, thickness-balanced, not undercut.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        The published pair (its teeth, module, angles, face width, trace).
    section, tooth_section : dict
        The ``rating`` and ``tooth`` sections (the balance's form factors).
    profile_shift : "gleason" or float
        x_hm1 by ``addendum_rule`` (:func:`lsbg.gear.practice.practice_profile_shift`)
        or given [-].
    thickness_modification : "balanced" or float
        x_smn1 that balances the root stresses, or given [-].
    addendum_rule : {"iso23509", "agma209"}
        The rule of ``profile_shift="gleason"``: ISO 23509's mean addendum factor
        or AGMA 209.03's gear addendum.

    Returns
    -------
    lsbg.gear.design.GearPairDesign
        With ``undercut="refuse"``.
    """
    from lsbg.gear.practice import practice_profile_shift

    x_hm = (practice_profile_shift(design, addendum_rule) if profile_shift == "gleason"
            else float(profile_shift))
    shifted = design.replace(profile_shift=x_hm, undercut="refuse")
    x_s = (balanced_thickness_modification(shifted, section, tooth_section)
           if thickness_modification == "balanced" else float(thickness_modification))
    return shifted.replace(thickness_modification=x_s)


def rated_gear_torque(design, config):
    """The gear torque at which ISO 10300's pitting and root safety factors are 1 [N m].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    config : dict
        The study's configuration (its ``rating``, ``tooth`` and ``simulation``
        sections; K_v = 1, the static rating: the dynamic factor is lsbg's to
        measure at that load).

    Returns
    -------
    dict
        ``pitting`` and ``bending`` (the lesser of the two members) [N m].
    """
    rating = _rating(design, config, 1000.0)
    ratio = design.gear_teeth / design.pinion_teeth
    return {"pitting": rating.rated_pinion_torque_contact * ratio,
            "bending": rating.rated_pinion_torque_bending * ratio}


def deflection_tip_relief(design, config, gear_torque, profile_contact_ratio):
    """The tip relief that takes up the mesh's deflection at a torque: amount and length.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    config : dict
        The study's configuration (``rating``, ``tooth``, ``simulation``).
    gear_torque : float
        The design load [N m].
    profile_contact_ratio : float
        eps_alpha of the pair's own field of contact
        (:meth:`lsbg.gear.geometry.GearPair.contact_ratio`) [-], > 1.

    Returns
    -------
    amount : float
        C_a = F_mt / (b_eff c_gamma_alpha) [m], F_mt the tangential force at
        the mean point, b_eff the rating's effective face width and
        c_gamma_alpha = c' (0.75 eps_valpha + 0.25) the mesh stiffness of the
        virtual cylindrical gears (ISO 6336-1:2019, method B; their numbers of
        teeth, profile shifts and helix angle).
    length : float
        L = (eps_alpha - 1) / eps_alpha [-]: from the tip to the highest point
        of single contact, as a fraction of the active profile.
    """
    from lsbg.tooth.reference import (
        iso6336_mesh_stiffness,
        iso6336_single_pair_stiffness,
    )

    if not profile_contact_ratio > 1:
        raise ValueError(f"profile_contact_ratio = {profile_contact_ratio!r}: a long tip "
                         f"relief needs a profile contact ratio above 1")
    rating = _rating(design, config, gear_torque)
    f = rating.factors
    # the basic rack's dedendum factor h_fP / m (of the unshifted pair)
    single = iso6336_single_pair_stiffness(
        f["normal_teeth_pinion"], f["normal_teeth_gear"], design.profile_shift,
        -design.profile_shift, design.normal_pressure_angle, design.dedendum / design.module,
        f["helix_angle"])
    mesh = iso6336_mesh_stiffness(single, f["transverse_contact_ratio"])
    amount = f["F_mt1"] / (f["effective_face_width"] * mesh)
    return float(amount), (profile_contact_ratio - 1.0) / profile_contact_ratio


def practice_traces(config):
    """The practice design's two traces: the LSBG and ``practice.sbg_trace``'s SBG.

    Parameters
    ----------
    config : dict
        Its ``practice`` section with the schema's defaults.

    Returns
    -------
    tuple of str
        ``("logarithmic", "face_milled")`` by default (ISO 23509's SBG, its cutter
        circle in the generating crown gear's pitch plane), or with ``"circular"``
        (the paper's arc in the plane of action).
    """
    return ("logarithmic", config["practice"]["sbg_trace"])


def shift_rule(section):
    """What gave the practice design's x_hm1, in words (the report's and the overlay's).

    Parameters
    ----------
    section : dict
        The ``practice`` section, defaults filled in.
    """
    from lsbg.gear.practice import ADDENDUM_RULES

    if section["profile_shift"] != "gleason":
        return "given (practice.profile_shift)"
    return f"{ADDENDUM_RULES[section['addendum_rule']]}; practice.addendum_rule: " \
           f"{section['addendum_rule']}"


def practice_overlay(published, config):
    """The practice design as a configuration overlay, and the figures behind it.

    Parameters
    ----------
    published : lsbg.gear.design.GearPairDesign
        The published pair at the study's paper spiral angle (either trace:
        the rules see the mean point only, and the traces' profile contact
        ratios, which set the relief's length, agree within 1e-3).
    config : dict
        The study's configuration, defaults filled in (``lsbg.config``): its
        ``practice``, ``rating``, ``tooth``, ``simulation`` and
        ``flank_modification`` sections.

    Returns
    -------
    overlay : dict
        ``design`` (profile_shift, thickness_modification, undercut: refuse),
        ``flank_modification`` (the study's ease-off with both tip reliefs)
        and ``simulation.load_torque_N_m`` (the practice load), to merge over
        the study's configuration.
    figures : dict
        x_hm1 and the rule that gave it (``profile_shift_rule``), x_smn1, the rated
        torques of both designs [N m], C_a [um] and
        L, and the practice load [N m].
    """
    from lsbg.gear.geometry import GearPair

    section = config["practice"]
    design = practice_design(published, config["rating"], config["tooth"],
                             section["profile_shift"], section["thickness_modification"],
                             section["addendum_rule"])
    rated = rated_gear_torque(design, config)
    load = rated["pitting"] if section["load_torque_N_m"] == "rated" \
        else float(section["load_torque_N_m"])
    ratio = float(GearPair(design).contact_ratio()["profile"])
    amount, length = deflection_tip_relief(design, config, load, ratio)
    if section["tip_relief_um"] != "deflection":
        amount = float(section["tip_relief_um"]) * 1e-6
    if section["tip_relief_length"] != "long":
        length = float(section["tip_relief_length"])
    # rounded as a designer writes them down: 0.01 um, 1e-4 of the profile, 1 mN m
    amount_um, length = round(amount * 1e6, 2), round(length, 4)
    overlay = {
        "design": {"profile_shift": round(design.profile_shift, 6),
                   "thickness_modification": round(design.thickness_modification, 6),
                   "undercut": "refuse"},
        "flank_modification": {
            **{k: v for k, v in config["flank_modification"].items() if v is not None},
            "pinion_tip_relief_um": amount_um, "pinion_tip_relief_length": length,
            "gear_tip_relief_um": amount_um, "gear_tip_relief_length": length},
        "simulation": {"load_torque_N_m": round(load, 3)},
    }
    published_rated = rated_gear_torque(published, config)
    figures = {"profile_shift": design.profile_shift,
               "profile_shift_rule": shift_rule(section),
               "thickness_modification": design.thickness_modification,
               "rated_torque_pitting_N_m": rated["pitting"],
               "rated_torque_bending_N_m": rated["bending"],
               "published_rated_torque_pitting_N_m": published_rated["pitting"],
               "published_rated_torque_bending_N_m": published_rated["bending"],
               "tip_relief_um": amount_um, "tip_relief_length": length,
               "load_torque_N_m": load, "profile_contact_ratio": ratio}
    return overlay, figures
