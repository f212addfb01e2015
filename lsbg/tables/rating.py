"""Tables of the service life: the ISO 10300 rating beside the tooth's own stresses.

Built from the rating datasets of a design point (:func:`lsbg.rating.dataset.
rating_dataset`, one per gear type). Units are the datasets' (MPa, N m).

* :func:`rating_table`: per gear type, the standard's stresses, safety factors
  and rated torques, and the FE loaded TCA's largest stresses beside the
  standard's nominal values;
* :func:`life_table`: the life of the LSBG over the SBG's that each stress
  ratio implies on the Basquin lines of ISO 6336's life factors, with the
  exponent's range (:func:`lsbg.rating.life.life_ratio`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lsbg.runs import TYPE_ORDER

__all__ = ["rating_table", "life_table", "LIFE_STRESSES"]


def _value(ds, name, member=None):
    if name not in ds:
        return float("nan")
    data = ds[name]
    return float(data.sel(member=member) if member is not None else data)


def rating_table(ratings) -> pd.DataFrame:
    """The standard's rating and the FE stresses of each gear type.

    Parameters
    ----------
    ratings : dict
        ``{gear type: rating dataset}``.

    Returns
    -------
    pandas.DataFrame
        Columns ``figure``, ``unit`` and one per gear type (SBG, LSBG order).
    """
    rows = [("gear torque (the study's load)", "N m", "gear_torque", None),
            ("K_v (lsbg's dynamic factor)", "-", None, "factor_K_v"),
            ("contact stress σ_H (ISO 10300-2)", "MPa", "contact_stress", None),
            ("  safety S_H", "-", ("contact_safety", "pinion"), None),
            ("root stress σ_F, pinion (ISO 10300-3)", "MPa", ("root_stress", "pinion"), None),
            ("root stress σ_F, gear", "MPa", ("root_stress", "gear"), None),
            ("  safety S_F, pinion", "-", ("bending_safety", "pinion"), None),
            ("  safety S_F, gear", "-", ("bending_safety", "gear"), None),
            ("rated gear torque, pitting (S_H = 1)", "N m", "rated_gear_torque_contact", None),
            ("rated gear torque, root (S_F = 1)", "N m", "rated_gear_torque_bending", None),
            ("nominal σ_H0 (no load factors)", "MPa", "nominal_contact_stress", None),
            ("FE: largest Hertz pressure over the cycle", "MPa", "fe_max_contact_pressure", None),
            ("FE: its median over the positions", "MPa", "fe_median_contact_pressure", None),
            ("nominal σ_F0, pinion", "MPa", ("nominal_root_stress", "pinion"), None),
            ("FE: largest root stress, pinion", "MPa", ("fe_max_root_stress", "pinion"), None),
            ("nominal σ_F0, gear", "MPa", ("nominal_root_stress", "gear"), None),
            ("FE: largest root stress, gear", "MPa", ("fe_max_root_stress", "gear"), None)]
    types = [t for t in TYPE_ORDER if t in ratings]
    out = []
    for label, unit, variable, attr in rows:
        row = {"figure": label, "unit": unit}
        for t in types:
            ds = ratings[t]
            if attr is not None:
                row[t] = float(ds.attrs.get(attr, np.nan))
            elif isinstance(variable, tuple):
                row[t] = _value(ds, *variable)
            else:
                row[t] = _value(ds, variable)
        out.append(row)
    return pd.DataFrame(out)


#: Stress behind each life comparison: (label, kind, variable, member).
LIFE_STRESSES = (
    ("pitting, ISO σ_H", "contact", "contact_stress", None),
    ("pitting, FE median of the largest pressure", "contact", "fe_median_contact_pressure", None),
    ("pitting, FE largest pressure", "contact", "fe_max_contact_pressure", None),
    ("root, pinion, ISO σ_F", "bending", "root_stress", "pinion"),
    ("root, pinion, FE largest stress", "bending", "fe_max_root_stress", "pinion"),
    ("root, gear, ISO σ_F", "bending", "root_stress", "gear"),
    ("root, gear, FE largest stress", "bending", "fe_max_root_stress", "gear"),
)


def life_table(ratings) -> pd.DataFrame:
    """Life of the LSBG over the SBG's from each stress ratio.

    Parameters
    ----------
    ratings : dict
        ``{gear type: rating dataset}`` with both ``"SBG"`` and ``"LSBG"``.

    Returns
    -------
    pandas.DataFrame
        Per stress (:data:`LIFE_STRESSES`): the two stresses [MPa], their
        ratio LSBG / SBG, the Basquin exponent stated and the life ratio
        LSBG / SBG with its least and most over the exponents' range (> 1:
        the LSBG lives longer). Rows whose stress a dataset lacks are left out.
    """
    from lsbg.rating.life import life_ratio

    sbg, lsbg = ratings["SBG"], ratings["LSBG"]
    rows = []
    for label, kind, variable, member in LIFE_STRESSES:
        s, s_ref = _value(lsbg, variable, member), _value(sbg, variable, member)
        if not (np.isfinite(s) and np.isfinite(s_ref)):
            continue
        life = life_ratio(s, s_ref, kind)
        rows.append({"stress": label, "SBG [MPa]": s_ref, "LSBG [MPa]": s,
                     "stress ratio LSBG/SBG": s / s_ref, "exponent p": life["exponent"],
                     "life ratio LSBG/SBG": life["ratio"], "least over the p range": life["low"],
                     "most over the p range": life["high"]})
    return pd.DataFrame(rows)
