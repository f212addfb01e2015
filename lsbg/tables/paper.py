"""Tables of the paper's reproduction (paper.html): its Tables 1 and 3 and its verdict, checked.

* :func:`design_table`: the pair's design data (Table 1) per gear type;
* :func:`theory_table` and :func:`paper_comparison_table`: simulated means
  against Eq. 12–13 (Table 3) and the paper's published figures (:data:`PAPER`);
* :func:`compare_types`, :func:`fluctuation_table` and
  :func:`fluctuation_conclusion`: the paper's "LSBG fluctuates less", with a
  number and an interval on it (:func:`lsbg.stats.compare_fluctuation`);
* :func:`control_charts`: the Xbar-R charts of 0.8–1.0 s (§4.3);
* :func:`at_spiral_angle` and :func:`cases_at_spiral_angle`: a report's files
  of its own design point among those of every angle.

Units are the run datasets' (deg/s, N).

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4, Tables 1–3.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg import stats
from lsbg.aggregate.runs import (QUANTITIES, QUANTITY_LABELS, TYPE_ORDER, gear_type,
                                 records_by_type, run_theory, runs_by_type, steady)

__all__ = [
    "PAPER", "design_words", "design_origin", "design_table", "design_rows", "theory_table", "paper_comparison_table", "compare_types",
    "fluctuation_table", "fluctuation_conclusion", "control_charts", "at_spiral_angle",
    "cases_at_spiral_angle"
]


#: The paper's published results (§4.1 and Table 3), per gear type and
#: quantity: mean, std, A², p, Table 3's theory, difference and error rate.
PAPER = {
    ("SBG", "gear_speed"): dict(mean=1872.69, std=21.55, ad_statistic=0.293, ad_pvalue=0.601,
                                theory=1873.703, difference=1.013, error_rate_percent=0.054),
    ("LSBG", "gear_speed"): dict(mean=1873.77, std=12.67, ad_statistic=0.264, ad_pvalue=0.697,
                                 theory=1873.703, difference=0.067,
                                 error_rate_percent=0.0036),
    ("SBG", "tangential_force"): dict(mean=24799.9, std=550.4, ad_statistic=0.514,
                                      ad_pvalue=0.192, theory=23603.48, difference=1196.42,
                                      error_rate_percent=4.82),
    ("LSBG", "tangential_force"): dict(mean=24747.5, std=280.0, ad_statistic=0.581,
                                       ad_pvalue=0.130, theory=23603.48, difference=1144.02,
                                       error_rate_percent=4.85),
}


# (key of design.json, description, unit, origin)
_DESIGN_ROWS = [
    ("pinion_teeth", "number of teeth z1 (pinion)", "-", "Table 1"),
    ("gear_teeth", "number of teeth z2 (gear)", "-", "Table 1"),
    ("module_mm", "outer transverse module m", "mm", "Table 1"),
    ("shaft_angle_deg", "shaft angle Σ", "deg", "Table 1"),
    ("pinion_hand", "hand of spiral of the pinion", "-", "Table 1"),
    ("pitch_diameter_pinion_mm", "outer pitch diameter d1", "mm", "Table 1"),
    ("pitch_diameter_gear_mm", "outer pitch diameter d2", "mm", "Table 1"),
    ("normal_pressure_angle_deg", "normal pressure angle αn", "deg", "Table 1"),
    ("spiral_angle_deg", "mean spiral angle βm", "deg", "Table 1"),
    ("addendum_mm", "addendum ha", "mm", "Table 1"),
    ("dedendum_mm", "dedendum hf", "mm", "Table 1"),
    ("trace", "tooth trace", "-", "type"),
    ("face_width_mm", "face width b", "mm", "assumed"),
    ("cutter_radius_mm", "cutter radius rc (SBG only)", "mm", "assumed"),
    ("backlash_mm", "backlash", "mm", "assumed"),
    ("base_cone_rule", "base cone rule", "-", "assumed"),
    ("pitch_angle_pinion_deg", "pitch angle δ1", "deg", "derived"),
    ("pitch_angle_gear_deg", "pitch angle δ2", "deg", "derived"),
    ("outer_cone_distance_mm", "outer cone distance Re", "mm", "derived"),
    ("mean_cone_distance_mm", "mean cone distance Rm", "mm", "derived"),
    ("inner_cone_distance_mm", "inner cone distance Ri", "mm", "derived"),
    ("base_cone_angle_pinion_deg", "base cone angle δb1", "deg", "derived"),
    ("base_cone_angle_gear_deg", "base cone angle δb2", "deg", "derived"),
    ("plane_spiral_angle_mean_deg", "spiral angle in the plane of action βp", "deg", "derived"),
    ("normal_pressure_angle_mean_deg", "normal pressure angle at the mean point", "deg",
     "measured"),
    ("contact_ratio", "total contact ratio", "-", "measured"),
    ("contact_ratio_profile", "profile contact ratio", "-", "measured"),
    ("contact_ratio_face", "face contact ratio", "-", "measured"),
    ("undercut_pinion_deg", "undercut of the pinion (roll angle)", "deg", "measured"),
    ("undercut_gear_deg", "undercut of the gear (roll angle)", "deg", "measured"),
    ("top_land_mean_pinion_mm", "top land at Rm, pinion", "mm", "measured"),
    ("top_land_mean_gear_mm", "top land at Rm, gear", "mm", "measured"),
    ("mass_pinion_kg", "mass of the pinion", "kg", "measured"),
    ("mass_gear_kg", "mass of the gear", "kg", "measured"),
    ("axial_inertia_pinion_kg_m2", "axial moment of inertia, pinion", "kg m²", "measured"),
    ("axial_inertia_gear_kg_m2", "axial moment of inertia, gear", "kg m²", "measured"),
]


#: The paper's Table 1 keys (the configuration's design keys, the paper's values).
TABLE1_KEYS = ("pinion_teeth", "gear_teeth", "module_mm", "shaft_angle_deg", "pinion_hand",
               "normal_pressure_angle_deg", "spiral_angle_deg", "addendum_mm", "dedendum_mm")
#: What the paper leaves open and lsbg assumes.
ASSUMED_KEYS = ("face_width_mm", "cutter_radius_mm", "backlash_mm", "base_cone_rule")


def _differs(mine, theirs):
    """Whether a design value differs from the paper's (numbers to 1e-9: mm from SI and back)."""
    if isinstance(mine, (int, float)) and isinstance(theirs, (int, float)):
        return not math.isclose(mine, theirs, rel_tol=1e-9)
    return mine != theirs


def _paper_record():
    """The paper's pair as ``design.json`` keys: Table 1, lsbg's assumptions, derived values."""
    from lsbg.gear.design import GearPairDesign

    paper = GearPairDesign()
    return {**paper.to_config(), **paper.derived()}


def design_words(record, spiral_angle=True):
    """A design in words, saying where it departs from the paper's Table 1.

    Parameters
    ----------
    record : dict
        ``design.json`` of a geometry directory (:func:`lsbg.solid.directory.read_record`),
        or a dataset's ``design_*`` attributes without the prefix.
    spiral_angle : bool
        Name the spiral angle, and count it among the changes where it is not the
        paper's (not for a sweep over it).

    Returns
    -------
    (str, bool)
        ``("the paper's Table 1 (9:37 teeth, module 4.5 mm, spiral angle 35°; face
        width 25 mm)", True)``, or ``("a pair modified from the paper's Table 1
        (module 5 mm; ...)", False)`` naming every key that differs from the paper's
        (and from lsbg's assumptions for what the paper leaves open).
    """
    paper = _paper_record()

    def value(key):
        text = f"{record[key]:g}" if isinstance(record[key], float) else str(record[key])
        unit = {"_mm": " mm", "_deg": "°"}.get(next((u for u in ("_mm", "_deg")
                                                      if key.endswith(u)), ""), "")
        return f"{key.removesuffix('_mm').removesuffix('_deg').replace('_', ' ')} {text}{unit}"

    changed = [key for key in (*TABLE1_KEYS, *ASSUMED_KEYS)
               if key in record and (spiral_angle or key != "spiral_angle_deg")
               and _differs(record[key], paper[key])]
    angle = f", spiral angle {record['spiral_angle_deg']:g}°" if spiral_angle else ""
    basics = (f"{record['pinion_teeth']}:{record['gear_teeth']} teeth, module "
              f"{record['module_mm']:g} mm{angle}; face width {record['face_width_mm']:g} mm")
    if not changed:
        return f"the paper's Table 1 ({basics})", True
    return (f"a pair modified from the paper's Table 1 ({basics}; changed: "
            f"{', '.join(value(k) for k in changed)})", False)


def design_origin(key, origin, values, paper=None):
    """Where a design row's value comes from, by comparing it with the paper's pair.

    Parameters
    ----------
    key : str
        The ``design.json`` key.
    origin : str
        The row's kind: "Table 1" (the paper gives it), "assumed" (the paper
        leaves it open), or any other (returned as it is).
    values : iterable
        The row's values of the compared types (NaN where a type has none).
    paper : dict, optional
        The paper's pair as ``design.json`` keys (default: lsbg's ``GearPairDesign()``).

    Returns
    -------
    str
        "paper Table 1" or "assumed" where every value is the paper's (lsbg's
        assumption's), else "changed (paper: 35)" or "changed (assumed: 25)".
    """
    if origin not in ("Table 1", "assumed"):
        return origin
    paper = _paper_record() if paper is None else paper
    theirs = paper.get(key)
    shown = [v for v in values if not (isinstance(v, float) and math.isnan(v))]
    if theirs is None or not any(_differs(v, theirs) for v in shown):
        return "paper Table 1" if origin == "Table 1" else "assumed"
    text = f"{theirs:g}" if isinstance(theirs, float) else str(theirs)
    return f"changed ({'paper' if origin == 'Table 1' else 'assumed'}: {text})"


def design_table(geometry_dirs) -> pd.DataFrame:
    """Table 1 and the derived and measured quantities of the compared designs.

    Parameters
    ----------
    geometry_dirs : dict or sequence
        ``{gear type: geometry directory}``, or directories (the gear type is
        read from ``design.json``).

    Returns
    -------
    pandas.DataFrame
        Columns ``quantity``, ``unit``, ``origin`` (:func:`design_origin`:
        'paper Table 1', 'assumed' for what the paper leaves open, 'changed
        (...)' where a value differs from either; 'derived' from the design
        formulas, 'measured' on the exact flanks and solids) and one column per
        gear type (SBG first), values as in ``design.json`` (the cutter radius
        only for circular traces, NaN otherwise).
    """
    return design_rows(records_by_type(geometry_dirs))


def design_rows(records, paper=None) -> pd.DataFrame:
    """:func:`design_table` of ``{gear type: design.json record}`` (``paper`` as
    :func:`design_origin` takes it)."""
    paper = _paper_record() if paper is None else paper
    rows = []
    for key, description, unit, origin in _DESIGN_ROWS:
        row = {"quantity": description, "unit": unit}
        for label, record in records.items():
            unused = key == "cutter_radius_mm" and record.get("trace") != "circular"
            row[label] = np.nan if unused else record.get(key, np.nan)
        row["origin"] = design_origin(key, origin, [row[t] for t in records], paper)
        rows.append(row)
    return pd.DataFrame(rows)[["quantity", "unit", "origin", *records]]


def theory_table(runs, start=0.2, quantities=QUANTITIES) -> pd.DataFrame:
    """Simulated means against Eq. 12–13, the paper's Table 3 (ours and its).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs (gear type from the attributes).
    start : float, default 0.2
        End of the transient [s].
    quantities : sequence of str
        Quantities of :data:`QUANTITIES`.

    Returns
    -------
    pandas.DataFrame
        Per gear type and quantity: ``simulated``, ``theory``, ``difference``
        (simulated − theory), ``error_rate_percent`` (100 |difference| /
        theory) [unit of the quantity, %], and the paper's ``paper_simulated``
        and ``paper_error_rate_percent`` where it has them.
    """
    rows = []
    for label, ds in runs_by_type(runs).items():
        for quantity in quantities:
            comparison = stats.compare_to_theory(steady(ds, quantity, start).mean(),
                                                 run_theory(ds, quantity))
            paper = PAPER.get((label, quantity), {})
            rows.append({"gear_type": label, "quantity": quantity,
                         "unit": ds[quantity].attrs.get("units", ""),
                         "simulated": comparison.simulated, "theory": comparison.theory,
                         "difference": comparison.difference,
                         "error_rate_percent": comparison.error_rate_percent,
                         "paper_simulated": paper.get("mean", np.nan),
                         "paper_error_rate_percent": paper.get("error_rate_percent", np.nan)})
    return pd.DataFrame(rows)


def paper_comparison_table(runs, start=0.2) -> pd.DataFrame:
    """The paper's §4.1 statistics beside ours (mean, std, A², p).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs.
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    pandas.DataFrame
        Per gear type, quantity (gear_speed, tangential_force) and statistic:
        ``paper``, ``this_work`` and ``ratio`` (this work / paper).
    """
    rows = []
    for label, ds in runs_by_type(runs).items():
        for quantity in ("gear_speed", "tangential_force"):
            x = steady(ds, quantity, start)
            ad = stats.anderson_darling(x)
            ours = {"mean": float(x.mean()), "std": float(x.std(ddof=1)),
                    "ad_statistic": ad.statistic, "ad_pvalue": ad.pvalue}
            paper = PAPER.get((label, quantity), {})
            for statistic, value in ours.items():
                published = paper.get(statistic, np.nan)
                rows.append({"gear_type": label, "quantity": quantity, "statistic": statistic,
                             "unit": (ds[quantity].attrs.get("units", "")
                                      if statistic in ("mean", "std") else "-"),
                             "paper": published, "this_work": value,
                             "ratio": value / published if published else np.nan})
    return pd.DataFrame(rows)


def compare_types(runs, quantity, start=0.2, **options) -> stats.FluctuationComparison:
    """Which gear type fluctuates less in ``quantity``: SBG against LSBG.

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        One SBG and one LSBG run.
    quantity : str
        Run variable.
    start : float, default 0.2
        End of the transient [s].
    **options
        Passed to :func:`lsbg.stats.compare_fluctuation` (``confidence``,
        ``n_boot``, ``block_length``, ``seed``, ``method``).

    Returns
    -------
    lsbg.stats.FluctuationComparison
        Ratio std(SBG)/std(LSBG) with its block-bootstrap interval.
    """
    by_type = runs_by_type(runs)
    missing = [t for t in TYPE_ORDER if t not in by_type]
    if missing:
        raise ValueError(f"compare_types needs an SBG and an LSBG run; missing {missing}")
    sbg, lsbg_run = by_type["SBG"], by_type["LSBG"]
    return stats.compare_fluctuation(steady(sbg, quantity, start),
                                     steady(lsbg_run, quantity, start), names=("SBG", "LSBG"),
                                     units=sbg[quantity].attrs.get("units", ""), **options)


def fluctuation_table(comparisons) -> pd.DataFrame:
    """:func:`compare_types` results as a table, with the paper's ratio.

    Parameters
    ----------
    comparisons : dict
        ``{quantity: lsbg.stats.FluctuationComparison}`` (SBG as a, LSBG as b).

    Returns
    -------
    pandas.DataFrame
        Per quantity: both standard deviations, ratio std(SBG)/std(LSBG), its
        interval, the Brown–Forsythe p, the effective sample sizes and the
        paper's ratio.
    """
    rows = []
    for quantity, c in comparisons.items():
        paper = [PAPER.get((name, quantity), {}).get("std", np.nan) for name in c.names]
        rows.append({"quantity": quantity, f"std_{c.names[0]}": c.std[0],
                     f"std_{c.names[1]}": c.std[1], "ratio": c.ratio, "ci_low": c.ci.low,
                     "ci_high": c.ci.high, "confidence": c.ci.confidence,
                     "brown_forsythe_p": c.brown_forsythe_pvalue,
                     f"ess_{c.names[0]}": c.effective_sample_size[0],
                     f"ess_{c.names[1]}": c.effective_sample_size[1],
                     "paper_ratio": paper[0] / paper[1]})
    return pd.DataFrame(rows)


def fluctuation_conclusion(comparisons, where="") -> str:
    """One paragraph: which type fluctuates less, by what factor, how sure.

    Parameters
    ----------
    comparisons : dict
        ``{quantity: lsbg.stats.FluctuationComparison}`` with names
        ('SBG', 'LSBG'), as from :func:`compare_types`.
    where : str, optional
        The design point and model the comparison was made at (e.g. "at the
        paper's design point, spiral angle 35°, under the point model"): the
        verdict is stated for it alone.

    Returns
    -------
    str
        Markdown built only from the numbers, set against the paper's claim
        that the LSBG fluctuates less.
    """
    sentences, calmer = [], set()
    for quantity, c in comparisons.items():
        label = QUANTITY_LABELS.get(quantity, quantity)
        if c.ratio >= 1.0:
            calm, factor, lo, hi = c.names[1], c.ratio, c.ci.low, c.ci.high
        else:
            calm, factor, lo, hi = c.names[0], 1.0 / c.ratio, 1.0 / c.ci.high, 1.0 / c.ci.low
        other = c.names[0] if calm == c.names[1] else c.names[1]
        sure = ("the interval excludes 1" if c.ci.excludes_one
                else "the interval includes 1, so the difference is not significant")
        if c.ci.excludes_one:
            calmer.add(calm)
        sentences.append(
            f"In the **{label}**, the {calm} fluctuates less than the {other} by a factor "
            f"{factor:.3g} (standard deviation ratio; {100 * c.ci.confidence:g} % "
            f"block-bootstrap interval {stats.OVER_WINDOWS} {lo:.3g}–{hi:.3g}: {sure}).")
        paper = [PAPER.get((name, quantity), {}).get("std") for name in c.names]
        if all(paper):
            sentences[-1] += (f" The paper's ratio std(SBG)/std(LSBG) is "
                              f"{paper[0] / paper[1]:.3g}; ours is {c.ratio:.3g}.")
    where = f" {where.strip()}" if where.strip() else ""
    if calmer == {"LSBG"}:
        verdict = ("The data support the paper's conclusion that the LSBG runs more "
                   f"smoothly than the SBG{where}, for every quantity where the difference is "
                   "significant.")
    elif calmer == {"SBG"}:
        verdict = (f"The data contradict the paper's conclusion{where}: the conventional "
                   "SBG fluctuates less than the LSBG in every quantity where the difference "
                   "is significant.")
    elif not calmer:
        verdict = (f"No difference is significant{where}: the data neither support nor contradict "
                   "the paper's conclusion that the LSBG runs more smoothly.")
    else:
        verdict = (f"The quantities disagree on which type fluctuates less{where}, so the data do "
                   "not support a general claim either way.")
    return " ".join(sentences) + " " + verdict


def control_charts(runs, quantity, window=(0.8, 1.0), subgroup_size=4) -> dict:
    """Xbar-R charts of one quantity for each gear type (Fig. 17–18).

    Returns
    -------
    dict
        ``{gear type: lsbg.stats.XbarRChart}`` in the paper's order.
    """
    return {label: stats.xbar_r_chart(stats.subgroups_from_window(
        ds[quantity].values, ds["time"].values, window[0], window[1], subgroup_size))
        for label, ds in runs_by_type(runs).items()}


def _at_angle(paths, spiral_angle):
    """The datasets of ``paths`` whose ``design_spiral_angle_deg`` is ``spiral_angle``."""
    import xarray as xr

    from lsbg.files import as_path_list

    for path in as_path_list(paths):
        with xr.open_dataset(path) as ds:
            if float(ds.attrs["design_spiral_angle_deg"]) == spiral_angle:
                yield ds.load()


def at_spiral_angle(paths, spiral_angle) -> dict:
    """The files of one design point among those of every spiral angle, by gear type.

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        NetCDF files of lsbg with the ``design_*`` attributes (unloaded
        TCAs, V-H maps, FE loaded TCAs, ratings).
    spiral_angle : float
        The design point's spiral angle [deg] (as its runs' attribute).

    Returns
    -------
    dict
        ``{gear type: dataset}`` (loaded) in the paper's order; a type with
        no file at that angle is left out.
    """
    found = {gear_type(ds): ds for ds in _at_angle(paths, spiral_angle)}
    return {t: found[t] for t in TYPE_ORDER if t in found}


def cases_at_spiral_angle(paths, spiral_angle) -> list:
    """The sensitivity cases' files of one design point (:func:`at_spiral_angle`), a list
    in the order of ``paths``."""
    return list(_at_angle(paths, spiral_angle))
