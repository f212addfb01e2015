"""The practice design: Gleason's depth shares and tooth thicknesses that balance root stress.

A bevel pair as a designer proportions it (docs/model.md, "The pair as a
designer would make it"):

* the depth: the Gleason system's long-and-short addenda, as ISO 23509's mean
  profile shift x_hm1 (:func:`lsbg.gear.practice.gleason_profile_shift`);
* the thickness: the pinion's tooth made thicker and the gear's thinner by the
  thickness modification x_smn1 that makes the two members' ISO 10300 root
  stresses equal (:func:`balanced_thickness_modification`), the Gleason
  system's own aim ("tooth thicknesses to give approximately equal stress in
  gear and pinion", AGMA 209.03) reached with the standard's own form and
  stress correction factors instead of its charts;
* undercut refused (``undercut: refuse``).
"""

from __future__ import annotations

import math

__all__ = ["root_stress_ratio", "balanced_thickness_modification", "practice_design"]


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
                    thickness_modification="balanced"):
    """The pair as practice makes it: shifted, thickness-balanced, not undercut.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        The published pair (its teeth, module, angles, face width, trace).
    section, tooth_section : dict
        The ``rating`` and ``tooth`` sections (the balance's form factors).
    profile_shift : "gleason" or float
        x_hm1 by the Gleason system (:func:`lsbg.gear.practice.gleason_profile_shift`)
        or given [-].
    thickness_modification : "balanced" or float
        x_smn1 that balances the root stresses, or given [-].

    Returns
    -------
    lsbg.gear.design.GearPairDesign
        With ``undercut="refuse"``.
    """
    from lsbg.gear.practice import gleason_profile_shift

    x_hm = gleason_profile_shift(design) if profile_shift == "gleason" else float(profile_shift)
    shifted = design.replace(profile_shift=x_hm, undercut="refuse")
    x_s = (balanced_thickness_modification(shifted, section, tooth_section)
           if thickness_modification == "balanced" else float(thickness_modification))
    return shifted.replace(thickness_modification=x_s)
