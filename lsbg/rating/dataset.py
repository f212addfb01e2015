"""A design point's rating as a dataset: ISO 10300 beside the FE loaded TCA's stresses.

One file per design point (``lsbg rate``): the standard's stresses, permissible
stresses, safety factors and rated torques of both members, every factor as an
attribute, and, where the design point's loaded TCA with the tooth's own
compliance is given, its largest contact pressure and root stresses over the
mesh cycle beside the standard's nominal values (the FE LTCA's load is the
nominal torque on aligned, crowned flanks: it has no K_A, K_v, K_Hbeta).
Stresses in MPa, torques in N m (the paper's units, at the edge).
"""

from __future__ import annotations

import re

import numpy as np

__all__ = ["rating_dataset", "MEMBERS"]

MEMBERS = ("pinion", "gear")


def _attribute_name(symbol):
    """An ISO symbol as an attribute name: 'Z_M-B' -> 'factor_Z_M_B'."""
    return "factor_" + re.sub(r"[^0-9A-Za-z_]", "_", symbol)


def rating_dataset(rating, design, material, conditions, dynamic_factor_source, fe_ltca=None,
                   envelope=None, cases=None):
    """The rating of one design point, with the FE stresses beside it.

    Parameters
    ----------
    rating : lsbg.rating.iso10300.BevelRating
    design : lsbg.gear.design.GearPairDesign
    material : lsbg.rating.iso10300.RatingMaterial
    conditions : lsbg.rating.iso10300.RatingConditions
    dynamic_factor_source : str
        Where K_v comes from (a run file, or the configuration).
    fe_ltca : xarray.Dataset, optional
        The design point's FE loaded TCA (``lsbg ltca --compliance fe``) at
        the same load.
    envelope : xarray.Dataset, optional
        The FE loaded TCA's stresses at the corners of the assembly's
        displacement envelope (:func:`lsbg.tooth.analysis.fe_envelope`).
    cases : dict, optional
        ``{sensitivity case: BevelRating}``: the same pair rated with the
        dynamic factor of each case's run (:mod:`lsbg.experiments.sensitivity`).

    Returns
    -------
    xarray.Dataset
        Variables over ``member`` (pinion, gear) and scalars, in MPa and N m.
    """
    import xarray as xr

    from lsbg.rating.config import rating_fields

    mpa = 1e-6
    ratio = design.gear_teeth / design.pinion_teeth
    factors = rating.factors
    nominal_root = np.array([factors["sigma_F0_pinion"], factors["sigma_F0_gear"]]) * mpa

    def member(values, units, name):
        return ("member", np.asarray(values, dtype=float), {"units": units, "long_name": name})

    def scalar(value, units, name):
        return ((), float(value), {"units": units, "long_name": name})

    variables = {
        "contact_stress": scalar(rating.contact_stress * mpa, "MPa",
                                 "contact stress sigma_H (ISO 10300-2, method B1)"),
        "nominal_contact_stress": scalar(rating.nominal_contact_stress * mpa, "MPa",
                                         "nominal contact stress sigma_H0, no load factors"),
        "permissible_contact_stress": member(np.array(rating.permissible_contact_stress) * mpa,
                                             "MPa", "permissible contact stress sigma_HP"),
        "contact_safety": member(rating.contact_safety, "1", "safety factor S_H"),
        "root_stress": member(np.array(rating.root_stress) * mpa, "MPa",
                              "tooth root stress sigma_F (ISO 10300-3, method B1)"),
        "nominal_root_stress": member(nominal_root, "MPa",
                                      "nominal root stress sigma_F0, no load factors"),
        "permissible_root_stress": member(np.array(rating.permissible_root_stress) * mpa, "MPa",
                                          "permissible root stress sigma_FP"),
        "bending_safety": member(rating.bending_safety, "1", "safety factor S_F"),
        "gear_torque": scalar(rating.pinion_torque * ratio, "N m", "the rated load T_2"),
        "rated_gear_torque_contact": scalar(rating.rated_pinion_torque_contact * ratio, "N m",
                                            "gear torque at which S_H = 1"),
        "rated_gear_torque_bending": scalar(rating.rated_pinion_torque_bending * ratio, "N m",
                                            "gear torque at which the smaller S_F = 1"),
    }
    attrs = {
        "title": "ISO 10300:2023 method B1 rating of a bevel gear pair",
        "standard": "ISO 10300-1/-2/-3:2023, method B1, no hypoid offset, drive flank; "
                    "Z_NT = Y_NT = 1 (long life)",
        "dynamic_factor_source": dynamic_factor_source,
        "design_trace": design.trace,
        **{f"design_{k}": v for k, v in design.to_config().items()},
        **rating_fields(material, conditions),
        **{_attribute_name(k): float(v) for k, v in factors.items()},
    }
    coords = {"member": ("member", list(MEMBERS))}
    if fe_ltca is not None:
        variables.update(_fe_stresses(fe_ltca, "fe", ""))
        attrs["fe_ltca_load_torque_N_m"] = float(fe_ltca.attrs.get("load_torque_N_m", np.nan))
    if envelope is not None:
        variables.update(_fe_stresses(envelope, "fe_displaced", ", displaced assembly"))
        variables["displacement"] = (("corner", "axis"), envelope["displacement"].values,
                                     dict(envelope["displacement"].attrs))
        coords.update(corner=("corner", [str(c) for c in envelope["corner"].values]),
                      axis=("axis", [str(a) for a in envelope["axis"].values]))
    if cases:
        names = list(cases)
        variables.update({
            "case_dynamic_factor": ("case", [cases[n].factors["K_v"] for n in names],
                                    {"units": "1", "long_name": "K_v of the case's run"}),
            "case_contact_stress": ("case", [cases[n].contact_stress * mpa for n in names],
                                    {"units": "MPa", "long_name": "contact stress sigma_H with "
                                     "the case's K_v"}),
            "case_root_stress": (("case", "member"),
                                 [np.array(cases[n].root_stress) * mpa for n in names],
                                 {"units": "MPa", "long_name": "root stress sigma_F with the "
                                  "case's K_v"}),
        })
        coords["case"] = ("case", names)
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def _fe_stresses(ltca, prefix, what):
    """An FE loaded TCA's largest stresses over the mesh cycle as variables [MPa].

    ``ltca`` holds ``max_contact_pressure`` and ``root_stress_<member>`` over
    ``mesh_phase`` (and, for the displacement envelope, ``corner``); the
    variables keep its other dimensions.
    """
    pressure = ltca["max_contact_pressure"]
    lead = tuple(d for d in pressure.dims if d != "mesh_phase")
    roots = np.stack([ltca[f"root_stress_{m}"].max("mesh_phase").values for m in MEMBERS],
                     axis=-1)
    source = f"{what} (FE loaded TCA)"
    return {
        f"{prefix}_max_contact_pressure": (lead, pressure.max("mesh_phase").values, {
            "units": "MPa", "long_name": f"largest Hertz pressure over the mesh cycle{source}"}),
        f"{prefix}_median_contact_pressure": (lead, pressure.median("mesh_phase").values, {
            "units": "MPa", "long_name": "median over the mesh cycle of each position's "
                                         f"largest Hertz pressure{source}"}),
        f"{prefix}_max_root_stress": ((*lead, "member"), roots, {
            "units": "MPa", "long_name": "largest tensile principal stress in the root fillet "
                                         f"over the mesh cycle{source}"}),
    }
