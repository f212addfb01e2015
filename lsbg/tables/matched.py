"""The matched designs' answer (results/optimise/matched_pairs.nc) as a table and in words."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

__all__ = ["ALPHA", "matched_table", "state_table", "matched_text", "calmer_of"]

_QUANTITY_WORDS = {"gear_speed": "gear angular velocity",
                   "tangential_force_outer": "tangential force (torque / outer radius)"}


#: The largest Wilcoxon p of a resolved answer [-].
ALPHA = 0.05


def calmer_of(low, high, p):
    """The calmer trace by the mean log std(SBG)/std(LSBG) over the pairs: "LSBG" where its
    bootstrap interval lies above 0 and Wilcoxon's p is below :data:`ALPHA`, "SBG" where
    below 0 and p below, "not resolved" otherwise, "—" without an interval."""
    if not (math.isfinite(low) and math.isfinite(high)):
        return "—"
    if not p < ALPHA:
        return "not resolved"
    return "LSBG" if low > 0 else "SBG" if high < 0 else "not resolved"


def matched_table(ds):
    """Per boundary, quantity and estimate: the pairs, the std ratio and its statistics.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`lsbg.matched.dataset.matched_pairs_dataset`.

    Returns
    -------
    pandas.DataFrame
        ``boundary``, ``quantity``, ``estimate``, ``pairs``, ``ratio`` (exp of the mean
        log std(SBG)/std(LSBG) over the pairs [-]; > 1: the LSBG calmer), ``low``,
        ``high`` (the bootstrap interval, as ratios), ``positive`` (the share of pairs
        with the LSBG calmer), ``wilcoxon_p``, ``calmer`` (:func:`calmer_of`).
    """
    rows = []
    for e, estimate in enumerate(ds["estimate"].values):
        for b, boundary in enumerate(ds["boundary"].values):
            for q, quantity in enumerate(ds["quantity"].values):
                def value(name):
                    return float(ds[f"ratio_{name}"].values[e, b, q])

                rows.append({"boundary": str(boundary),
                             "quantity": _QUANTITY_WORDS.get(str(quantity), str(quantity)),
                             "estimate": str(estimate), "pairs": int(value("pairs")),
                             "ratio": math.exp(value("mean")), "low": math.exp(value("low")),
                             "high": math.exp(value("high")), "positive": value("positive"),
                             "wilcoxon_p": value("wilcoxon_p"),
                             "calmer": calmer_of(value("low"), value("high"),
                                                     value("wilcoxon_p"))})
    return pd.DataFrame(rows)


def state_table(ds):
    """The contact state's and life's figures over the pairs: per figure (the pattern's
    movement, the FE figures) the pairs, exp of the mean log SBG/LSBG (> 1: the LSBG's
    lower), its bootstrap interval, Wilcoxon's p and the lower trace (:func:`calmer_of`)."""
    rows = []
    for name in ds.data_vars:
        if not name.endswith("_ratio_mean"):
            continue
        figure = name[:-len("_ratio_mean")]

        def value(statistic):
            return float(ds[f"{figure}_ratio_{statistic}"])

        rows.append({"figure": figure, "pairs": int(value("pairs")),
                     "ratio": math.exp(value("mean")), "low": math.exp(value("low")),
                     "high": math.exp(value("high")), "wilcoxon_p": value("wilcoxon_p"),
                     "lower": calmer_of(value("low"), value("high"), value("wilcoxon_p"))})
    return pd.DataFrame(rows)


def matched_text(ds):
    """The matched designs' answer in words, with its limits (the pairs found, the
    proxy's error, the full runs' share)."""
    a = ds.attrs
    candidates = a["candidates"].split()
    found = int(a["pairs_found"])
    head = (f"**Matched designs:** {found} pairs of the {candidates[0]} LSBG and "
            f"{candidates[1]} SBG designs on the converged fronts, matched on "
            f"{a['match_objectives'].replace(' ', ' and ')} within a caliper of "
            f"{float(a['caliper']):g} in the common box ({int(a['dropped_by_caliper'])} of "
            f"{int(a['assigned'])} assigned pairs dropped; {int(a['pairs_sought'])} sought).")
    if not found:
        return head + " No stability or life comparison over matched designs here."
    table = matched_table(ds)
    proxy = table[(table["estimate"] == "proxy")]
    said = "; ".join(f"{r.boundary}, {r.quantity}: std ratio SBG/LSBG {r.ratio:.3g} "
                     f"[{r.low:.3g}, {r.high:.3g}], Wilcoxon p {r.wilcoxon_p:.2g} ({r.calmer})"
                     for r in proxy.itertuples())
    full = int(a["full_run_pairs"])
    checked = (f"; against them the proxy's largest relative error in a std: "
               f"{a['proxy_error_max']}, and in the log std ratio: "
               f"{a['proxy_log_ratio_error_max']}" if full else "")
    state = state_table(ds)
    life = "; ".join(f"{r.figure} {r.ratio:.3g} (p {r.wilcoxon_p:.2g})"
                     for r in state.itertuples())
    return (head + f" By the proxy over every pair: {said}. The full runs cover {full} of "
            f"the pairs{checked}" + (" (indicative)." if int(a["indicative"]) else ".")
            + (f" Contact state and life, SBG over LSBG (geometric mean over the pairs): "
               f"{life}; the ISO 10300 rating takes no ease-off (the design point's)."
               if len(state) else ""))
