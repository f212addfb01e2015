"""A design's load curves: what the loaded TCA and the standard say against torque.

A gear's development report shows transmission error, contact pattern and
stresses over a range of torque, not at one load, and judges the design at
its rated load. :func:`load_curve` runs the FE loaded TCA over a range of
gear torques (fractions of the design's rated pitting torque, plus any other
load such as the paper's; :func:`lsbg.tooth.load_range.fe_load_range`, the
per-position setup shared by the torques) and puts ISO 10300's contact and
root stresses at the same torques beside it (method B1, K_v = 1: the loaded
TCA is quasi-static).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["load_torques", "iso_stresses", "load_curve"]


def load_torques(rated_torque, fractions, others=()):
    """The gear torques of a load curve, ascending [N m].

    Parameters
    ----------
    rated_torque : float
        The design's rated pitting torque on the gear [N m], > 0.
    fractions : sequence of float
        Of the rated torque [-], > 0.
    others : sequence of float
        Further gear torques [N m] (the paper's load), > 0.

    Returns
    -------
    numpy.ndarray
        Unique torques, rounded to 1 mN m.
    """
    if not (math.isfinite(rated_torque) and rated_torque > 0):
        raise ValueError(f"rated_torque = {rated_torque!r}: must be a number > 0 [N m]")
    values = [rated_torque * float(f) for f in fractions] + [float(t) for t in others]
    bad = [v for v in values if not (math.isfinite(v) and v > 0)]
    if bad or not values:
        raise ValueError(f"load curve torques {values!r}: need at least one, each > 0 [N m]")
    return np.unique(np.round(values, 3))


def iso_stresses(design, config, torques):
    """ISO 10300 (method B1, K_v = 1) stresses at each gear torque.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    config : dict
        The ``rating``, ``tooth`` and ``simulation`` sections.
    torques : array_like
        Gear torques [N m].

    Returns
    -------
    dict
        ``contact`` (sigma_H), ``nominal_contact`` (sigma_H0) [Pa], shape (n,);
        ``root`` (sigma_F of pinion and gear) [Pa], shape (n, 2); and the
        design's ``rated_pitting`` and ``rated_bending`` gear torques [N m].
    """
    from lsbg.rating.config import rate_design

    speed = math.radians(float(config["simulation"]["pinion_speed_deg_s"]))
    ratio = design.gear_teeth / design.pinion_teeth
    out = {"contact": [], "nominal_contact": [], "root": []}
    for torque in np.asarray(torques, float):
        rating, _, _ = rate_design(design, config["rating"], config["tooth"], float(torque),
                                   speed, dynamic_factor=1.0)
        out["contact"].append(rating.contact_stress)
        out["nominal_contact"].append(rating.nominal_contact_stress)
        out["root"].append(rating.root_stress)
    result = {k: np.array(v, float) for k, v in out.items()}
    result["rated_pitting"] = rating.rated_pinion_torque_contact * ratio
    result["rated_bending"] = rating.rated_pinion_torque_bending * ratio
    return result


def load_curve(contact, compliance, config, fractions, others=(), phases=100,
               design_set="paper"):
    """FE loaded TCA and ISO 10300 over a range of torques: one dataset on ``torque``.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        The line model of the design point (its bands and real flanks).
    compliance : xarray.Dataset
        The design point's FE compliance (:func:`lsbg.tooth.compliance.tooth_compliance`).
    config : dict
        The ``rating``, ``tooth`` and ``simulation`` sections.
    fractions : sequence of float
        Torques as fractions of the design's rated pitting torque [-].
    others : sequence of float
        Further gear torques [N m].
    phases : int
        Mesh positions per base pitch of the FE loaded TCA [-].
    design_set : str
        ``"paper"`` or ``"practice"``, recorded.

    Returns
    -------
    xarray.Dataset
        :func:`lsbg.tooth.load_range.fe_load_range`'s variables, with
        ``iso_contact_stress``, ``iso_nominal_contact_stress`` and
        ``iso_root_stress_pinion``/``_gear`` [MPa] on ``torque``, and the
        design's rated torques as attributes.
    """
    from lsbg.files import short_labels
    from lsbg.tooth.load_range import fe_load_range

    design = contact.pair.design
    rated = iso_stresses(design, config, [1000.0])
    torques = load_torques(rated["rated_pitting"], fractions, others)
    ds = fe_load_range(contact, compliance, torques, phases=phases)
    iso = iso_stresses(design, config, ds["torque"].values)
    ds["iso_contact_stress"] = ("torque", iso["contact"] * 1e-6, {
        "units": "MPa", "long_name": "ISO 10300 contact stress",
        "description": "sigma_H by ISO 10300-2 method B1, K_v = 1"})
    ds["iso_nominal_contact_stress"] = ("torque", iso["nominal_contact"] * 1e-6, {
        "units": "MPa", "long_name": "ISO 10300 nominal contact stress",
        "description": "sigma_H0 by ISO 10300-2 method B1: without the load factors"})
    for k, member in enumerate(("pinion", "gear")):
        ds[f"iso_root_stress_{member}"] = ("torque", iso["root"][:, k] * 1e-6, {
            "units": "MPa", "long_name": f"ISO 10300 root stress, {member}",
            "description": "sigma_F by ISO 10300-3 method B1, K_v = 1"})
    ds.attrs.update({
        "design_set": design_set,
        "rated_torque_pitting_N_m": float(rated["rated_pitting"]),
        "rated_torque_bending_N_m": float(rated["rated_bending"]),
        "load_fractions": [float(f) for f in fractions],
        "other_loads_N_m": [float(t) for t in others],
        **{f"design_{k}": v for k, v in design.to_config().items()},
    })
    return short_labels(ds)
