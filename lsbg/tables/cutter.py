"""The cutter-radius sweep's tables: a row per point, and the difference's two shares.

Read from the points' files (``lsbg cutter-point``: a V-H map with the point's other
figures as attributes, :func:`lsbg.experiments.cutter.point_dataset`).
"""

from __future__ import annotations

import math

import pandas as pd

__all__ = ["FIGURES", "cutter_table", "decomposition"]

#: The compared figures: column -> (unit, words).
FIGURES = {
    "loaded_te_peak_to_peak": ("µrad", "loaded TE, peak to peak (uniform bed)"),
    "pattern_movement": ("mm", "bearing pattern's movement per 0.1 mm of displacement"),
    "max_contact_pressure": ("MPa", "FE largest contact pressure"),
    "root_stress_pinion": ("MPa", "FE root stress, pinion"),
    "root_stress_gear": ("MPa", "FE root stress, gear"),
}


def cutter_table(points):
    """A row per point of the sweep, the LSBG first, then the SBGs by cutter radius.

    Parameters
    ----------
    points : iterable of xarray.Dataset
        The points' files (``lsbg cutter-point``).

    Returns
    -------
    pandas.DataFrame
        ``type`` (LSBG or SBG), ``trace``, ``cutter_radius_mm`` (the LSBG's: its
        R_m / sin beta_m), ``roles`` (space-separated: ``lsbg``, ``design``, ``nominal``,
        ``matched``), ``trace_curvature_radius_mm`` (the gear's pitch-cone trace at the
        mean point, developed), ``spiral_angle_toe_deg``, ``spiral_angle_heel_deg`` and the
        :data:`FIGURES`.
    """
    from lsbg.gear.design import TRACE_LABELS
    from lsbg.tables.contact_state import pattern_movement

    rows = []
    for ds in points:
        a = ds.attrs
        rows.append({"type": TRACE_LABELS.get(a["cutter_trace"], "SBG"),
                     "trace": a["cutter_trace"], "cutter_radius_mm": float(a["cutter_radius_mm"]),
                     "roles": a["cutter_roles"],
                     "trace_curvature_radius_mm": a["cutter_trace_curvature_radius"],
                     "spiral_angle_toe_deg": a["cutter_spiral_angle_toe"],
                     "spiral_angle_heel_deg": a["cutter_spiral_angle_heel"],
                     "loaded_te_peak_to_peak": a["cutter_loaded_te_peak_to_peak"],
                     "pattern_movement": pattern_movement(ds)["total"],
                     **{k: a[f"cutter_{k}"] for k in ("max_contact_pressure",
                                                      "root_stress_pinion",
                                                      "root_stress_gear")}})
    table = pd.DataFrame(rows)
    order = (table["type"] != "LSBG").astype(int) * 1e9 + table["cutter_radius_mm"]
    return table.iloc[order.argsort(kind="stable")].reset_index(drop=True)


def _row(table, role):
    hits = table[table["roles"].str.split().apply(lambda roles: role in roles)]
    if hits.empty:
        raise ValueError(f"the cutter sweep has no point of role {role!r}")
    return hits.iloc[0]


def decomposition(table):
    """Each figure's difference LSBG - SBG(design's cutter), split in two shares.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`cutter_table`.

    Returns
    -------
    pandas.DataFrame
        Per figure of :data:`FIGURES`: ``figure``, ``unit``, ``SBG (design's cutter)``,
        ``SBG (curvature-matched)``, ``LSBG``, ``difference`` = LSBG - SBG (design's
        cutter), ``curvature's share`` = SBG (matched) - SBG (design's cutter),
        ``constant spiral angle's share`` = LSBG - SBG (matched) (the two shares add up
        to the difference) and ``curvature's fraction`` of the difference [-] (NaN where
        the difference is 0 or a value is missing).
    """
    default, matched, lsbg = (_row(table, r) for r in ("design", "matched", "lsbg"))
    rows = []
    for name, (unit, words) in FIGURES.items():
        a, b, c = float(default[name]), float(matched[name]), float(lsbg[name])
        rows.append({"figure": words, "unit": unit, "SBG (design's cutter)": a,
                     "SBG (curvature-matched)": b, "LSBG": c, "difference": c - a,
                     "curvature's share": b - a, "constant spiral angle's share": c - b,
                     "curvature's fraction": (b - a) / (c - a) if c != a else math.nan})
    return pd.DataFrame(rows)
