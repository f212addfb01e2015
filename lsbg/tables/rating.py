"""Tables of the service life: the ISO 10300 rating beside the tooth's own stresses.

Built from the rating datasets of a design point (:func:`lsbg.rating.dataset.
rating_dataset`, one per gear type). Units are the datasets' (MPa, N m).

* :func:`rating_table`: per gear type, the standard's stresses, safety factors
  and rated torques, and the FE loaded TCA's largest stresses beside the
  standard's nominal values, aligned and at the worst corner of the
  assembly's displacement envelope;
* :func:`life_table`: the life of the LSBG over the SBG's that each stress
  ratio implies on the Basquin lines of ISO 6336's life factors, with the
  exponent's range (:func:`lsbg.rating.life.life_ratio`);
* :func:`read_rating_sweep`: the rating of every design point of the sweep
  (``lsbg rate-sweep``) as a table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import TYPE_ORDER

__all__ = ["rating_table", "life_table", "life_statement", "read_rating_sweep", "LIFE_STRESSES",
           "RESOLVED_STRESS_DIFFERENCE"]


def _value(ds, name, member=None):
    """A scalar of the dataset; over the envelope's corners, the largest (NaN if absent)."""
    if name not in ds:
        return float("nan")
    data = ds[name]
    if member is not None:
        data = data.sel(member=member)
    return float(data.max())


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
            ("FE: largest root stress, gear", "MPa", ("fe_max_root_stress", "gear"), None),
            ("FE, displaced (worst corner): largest Hertz pressure", "MPa",
             "fe_displaced_max_contact_pressure", None),
            ("FE, displaced: median of the largest pressure", "MPa",
             "fe_displaced_median_contact_pressure", None),
            ("FE, displaced: largest root stress, pinion", "MPa",
             ("fe_displaced_max_root_stress", "pinion"), None),
            ("FE, displaced: largest root stress, gear", "MPa",
             ("fe_displaced_max_root_stress", "gear"), None)]
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
    ("pitting, displaced, FE median of the largest pressure", "contact",
     "fe_displaced_median_contact_pressure", None),
    ("pitting, displaced, FE largest pressure", "contact", "fe_displaced_max_contact_pressure",
     None),
    ("root, pinion, displaced, FE largest stress", "bending", "fe_displaced_max_root_stress",
     "pinion"),
    ("root, gear, displaced, FE largest stress", "bending", "fe_displaced_max_root_stress",
     "gear"),
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


#: Stress differences smaller than this are not resolved by the FE model: its
#: root stresses moved by 1-2.7 % when the mesh was refined from 0.5 to
#: 0.375 m_mn (docs/model.md, "The tooth itself") [-].
RESOLVED_STRESS_DIFFERENCE = 0.03


def life_statement(ratings, where="", brief=False):
    """One sentence on the paper's third claim, from :func:`life_table`.

    A type is said to live longer only where every FE stress that the table
    compares (contact and root, aligned and displaced) is lower for it by
    more than :data:`RESOLVED_STRESS_DIFFERENCE`, so that its life ratio
    exceeds 1 over the whole range of exponents; the standard's stresses,
    which differ only through K_v, are named but decide nothing.

    Parameters
    ----------
    ratings : dict
        ``{gear type: rating dataset}`` with both ``"SBG"`` and ``"LSBG"``.
    where : str
        Where it holds, opening the sentence ("at 35°").
    brief : bool
        Only the verdict and the stress ratios (for a report's first screen);
        else every comparison with its life ratio and range.

    Returns
    -------
    str
        Markdown.
    """
    table = life_table(ratings)
    fe = table[table["stress"].str.contains("FE")]
    if fe.empty:
        return ("Without the FE loaded TCA this study compares no stresses from the teeth; by "
                "ISO 10300 the two types are rated alike.")
    ratio = fe["stress ratio LSBG/SBG"]
    resolved = (ratio - 1.0).abs() > RESOLVED_STRESS_DIFFERENCE
    lsbg_longer, sbg_longer = int((resolved & (ratio < 1)).sum()), int((resolved & (ratio > 1)).sum())
    n, ties = len(fe), int((~resolved).sum())
    tie_text = (f" (the other{'s' if ties > 1 else ''} a tie within the scatter)" if ties else "")
    if lsbg_longer == n:
        verdict = "the **LSBG** lives longer in every comparison"
    elif sbg_longer == n:
        verdict = "the **SBG** lives longer in every comparison"
    elif not resolved.any():
        verdict = ("neither lives measurably longer: every stress differs by less than the FE "
                   f"model's {RESOLVED_STRESS_DIFFERENCE:.0%} scatter")
    elif lsbg_longer and sbg_longer:
        verdict = (f"**neither** type lives longer in every comparison (the LSBG in "
                   f"{lsbg_longer}, the SBG in {sbg_longer} of {n})")
    else:
        winner, count = ("LSBG", lsbg_longer) if lsbg_longer else ("SBG", sbg_longer)
        loser = "SBG" if winner == "LSBG" else "LSBG"
        verdict = (f"the {loser} lives longer in no comparison; the **{winner}** in {count} of "
                   f"{n}{tie_text}")
    lines = []
    for _, row in fe.iterrows():
        lines.append(f"{row['stress']}: stress ×{row['stress ratio LSBG/SBG']:.3g}, life "
                     f"×{row['life ratio LSBG/SBG']:.2g} ({row['least over the p range']:.2g}–"
                     f"{row['most over the p range']:.2g})")
    iso = table[table["stress"].str.contains("ISO")]
    iso_text = (f"By ISO 10300 the stresses differ only through K_v (×"
                f"{iso['stress ratio LSBG/SBG'].iloc[0]:.4g}). " if not iso.empty else "")
    opening = f"{where[0].upper()}{where[1:]}, {verdict}" if where else verdict[0].upper() + verdict[1:]
    if brief:
        ratio_of = dict(zip(fe["stress"], fe["stress ratio LSBG/SBG"]))

        def group(rows):
            return ", ".join(f"{short} ×{ratio_of[name]:.3g}" for short, name in rows
                             if name in ratio_of)

        text = f"{opening}. Largest FE stresses LSBG/SBG: " + group(
            (("contact", "pitting, FE largest pressure"),
             ("pinion root", "root, pinion, FE largest stress"),
             ("gear root", "root, gear, FE largest stress")))
        displaced = group((("contact", "pitting, displaced, FE largest pressure"),
                           ("pinion root", "root, pinion, displaced, FE largest stress"),
                           ("gear root", "root, gear, displaced, FE largest stress")))
        if displaced:
            text += f"; at the worst displaced corner {displaced}"
        return (text + f". By ISO 10300 equal but for K_v; differences within "
                f"{RESOLVED_STRESS_DIFFERENCE:.0%} are ties.")
    return (f"{opening} (LSBG over SBG; "
            + "; ".join(lines) + "). " + iso_text
            + "A life ratio follows the stress ratio to the power p = 6–16, so only stress "
            f"differences beyond the FE model's {RESOLVED_STRESS_DIFFERENCE:.0%} scatter count.")


def read_rating_sweep(path) -> pd.DataFrame:
    """The ISO 10300 rating of every design point of the sweep (``lsbg rate-sweep``).

    Parameters
    ----------
    path : str, os.PathLike or ""
        The file of :func:`lsbg.experiments.rating_sweep.rating_sweep_dataset`
        ("" or None: none).

    Returns
    -------
    pandas.DataFrame
        Per gear type (and ``trace``, which tells the SBGs apart) and spiral angle
        [deg], as :func:`lsbg.experiments.rating_sweep.rating_by_angle` gives it:
        ``K_v``, the stresses [MPa], the safety factors and the rated gear
        torque [N m]; empty without a file.

    Raises
    ------
    lsbg.files.InputError
        Naming a file that is missing or not a rating sweep.
    """
    from lsbg.experiments.rating_sweep import RATING_SWEEP_VARIABLES
    from lsbg.files import as_path_list, open_dataset

    paths = as_path_list(path)
    if not paths:
        return pd.DataFrame()
    columns = ("gear_type", "spiral_angle", *RATING_SWEEP_VARIABLES)
    ds = open_dataset(paths[0], "rating sweep", columns, (),
                      "a rating sweep of lsbg rate-sweep")
    columns = ("gear_type", *(["trace"] if "trace" in ds else []), *columns[1:])
    return pd.DataFrame({name: ds[name].values.tolist() if name in ("gear_type", "trace")
                         else ds[name].values for name in columns})
