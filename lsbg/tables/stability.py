"""The stability answer by frequency band, and over the claim's cells.

The fluctuation ratio std(SBG)/std(LSBG) of a pair's line-model runs mixes the
band of the first mesh harmonics, which the static transmission error excites,
with the band the boundary's mesh mode amplifies. :func:`band_table` splits both
types' full-rate variance by mesh-harmonic band (:mod:`lsbg.stats.bands`) for
each pair the report compares (published, practice, best against best), states
the calmer type per band and names the band that decides the total: the band
carrying the largest share of the difference of the two variances,
var(SBG) − var(LSBG), on the side of the total's sign. :func:`band_text` says it
in words.

A block-bootstrap interval (:mod:`lsbg.stats.bootstrap`) runs over windows of one
deterministic, periodic run. Whether one trace is calmer is a question over the
claim's cells (model forms, crownings, displacements, samplings):
:func:`cells_range` gives the least and largest ratio over the cells of a
claim's stability table, the interval over cells.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import QUANTITY_LABELS, run_band_split
from lsbg.experiments.sensitivity import case_label
from lsbg.stats.bands import BAND_LABELS, HARMONIC_BANDS, deciding_band

__all__ = ["BAND_RESOLUTION", "EMPTY_BAND", "band_table", "band_text", "band_finding",
           "cells_range", "cells_text", "DRIVELINE_CELL", "BOUNDARY_NAMES", "driveline_pair",
           "boundary_answers", "boundary_sentence"]

#: Band ratios within this of 1 are a tie: the ratio of one run's windows varies
#: by about ±1 %, so a smaller difference is not resolved by a run [-].
BAND_RESOLUTION = 0.02

_MODE = "mode"


#: A band holding less than this share of both types' variance ranks nothing [-].
EMPTY_BAND = 1e-3


def _calmer(ratio, shares=(1.0, 1.0)):
    if not np.isfinite(ratio) or max(shares) < EMPTY_BAND:
        return "—"
    if abs(ratio - 1.0) <= BAND_RESOLUTION:
        return "tie"
    return "LSBG" if ratio > 1.0 else "SBG"


def band_table(pairs, start=0.2, quantities=("gear_speed", "tangential_force")):
    """std(SBG)/std(LSBG) per mesh-harmonic band, for each pair and quantity.

    Parameters
    ----------
    pairs : dict
        ``{pair name: {'SBG': run, 'LSBG': run}}`` (line-model runs with a full-rate
        record); pairs without both types are skipped.
    start : float
        Start of the steady state [s].
    quantities : sequence of str
        Keys of :data:`lsbg.aggregate.runs.FULL_RATE_OF`.

    Returns
    -------
    pandas.DataFrame
        Per pair, quantity and band (the four of
        :data:`lsbg.stats.bands.HARMONIC_BANDS`, ``total``, and ``mode``: within one
        mesh frequency of each type's own mesh mode): ``pair``, ``quantity``,
        ``band``, ``std_SBG``, ``std_LSBG`` [unit of the quantity: the square root
        of the band's part of the variance], ``ratio``, ``share_SBG``,
        ``share_LSBG`` (of each type's total variance), ``difference_share`` (the
        band's var(SBG) − var(LSBG) over the total's; the harmonic bands' add up to
        1), ``calmer`` (ties within :data:`BAND_RESOLUTION`; "—" for a band holding
        less than :data:`EMPTY_BAND` of both variances) and ``decides`` (the band of
        :func:`lsbg.stats.bands.deciding_band`).
    """
    rows = []
    for pair, runs in pairs.items():
        if not {"SBG", "LSBG"} <= set(runs):
            continue
        for quantity in quantities:
            split = {t: run_band_split(runs[t], quantity, start) for t in ("SBG", "LSBG")}
            deciding, _ = deciding_band(split["SBG"], split["LSBG"])
            difference = split["SBG"].total - split["LSBG"].total
            for band in (*HARMONIC_BANDS, "total", _MODE):
                var = {t: (s.total if band == "total" else
                           sum(s.mode_variance.values()) if band == _MODE and s.mode_variance
                           else math.nan if band == _MODE else s.variance[band])
                       for t, s in split.items()}
                ratio = (math.sqrt(var["SBG"] / var["LSBG"]) if var["LSBG"] > 0 else math.nan)
                shares = {t: var[t] / split[t].total for t in split}
                rows.append({
                    "pair": pair, "quantity": quantity, "band": band,
                    "std_SBG": math.sqrt(var["SBG"]), "std_LSBG": math.sqrt(var["LSBG"]),
                    "ratio": ratio, "share_SBG": shares["SBG"], "share_LSBG": shares["LSBG"],
                    "difference_share": ((var["SBG"] - var["LSBG"]) / difference
                                         if band in HARMONIC_BANDS and difference else math.nan),
                    "calmer": _calmer(ratio, tuple(shares.values())),
                    "decides": band == deciding})
    return pd.DataFrame(rows, columns=["pair", "quantity", "band", "std_SBG", "std_LSBG", "ratio",
                                       "share_SBG", "share_LSBG", "difference_share", "calmer",
                                       "decides"])


def _band_words(band):
    if band in ("total", _MODE):
        return {"total": "in total", _MODE: "around the mesh mode"}[band]
    return f"at {BAND_LABELS[band]}" if band != "below 1" else BAND_LABELS[band]


def band_text(table):
    """One sentence per pair and quantity: the ratio and calmer type by band, the deciding band.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`band_table`.

    Returns
    -------
    list of str
        Markdown sentences, in the table's order; empty for an empty table.
    """
    sentences = []
    for (pair, quantity), part in table.groupby(["pair", "quantity"], sort=False):
        part = part.set_index("band")
        label = QUANTITY_LABELS.get(quantity, quantity)

        def said(band):
            row = part.loc[band]
            who = "a tie" if row.calmer == "tie" else f"the {row.calmer} calmer"
            return f"{row.ratio:.3g} {_band_words(band)} ({who})"

        bands = [b for b in HARMONIC_BANDS if b != "below 1"]
        decides = part.index[part["decides"].astype(bool)][0]
        share = part.loc[decides, "difference_share"]
        total = part.loc["total"]
        mode = part.loc[_MODE]
        mode_text = (f"; {100 * mode.share_SBG:.0f} % (SBG) and {100 * mode.share_LSBG:.0f} % "
                     f"(LSBG) of the variance lie within one mesh frequency of the mesh mode"
                     if np.isfinite(mode.share_SBG) and np.isfinite(mode.share_LSBG) else "")
        if total.calmer == "tie" or not np.isfinite(share):
            decides_text = (f"the total is a tie: the bands' differences cancel, the largest "
                            f"at {BAND_LABELS[decides]}")
        else:
            decides_text = (f"the band of **{BAND_LABELS[decides]}** decides the total: it "
                            f"carries {100 * share:.0f} % of the difference of the variances")
        sentences.append(
            f"*{pair}, {label}:* std(SBG)/std(LSBG) {said('total')}; "
            + ", ".join(said(b) for b in bands) + f"; {decides_text}{mode_text}."
            if np.isfinite(total.ratio) else f"*{pair}, {label}:* no fluctuation to compare.")
    return sentences


def band_finding(table, quantity="gear_speed"):
    """One sentence for a report's finding: each pair's ratio by band and its deciding band.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`band_table`.
    quantity : str
        The quantity to state.

    Returns
    -------
    str
        Markdown; "" where the table lacks the quantity.
    """
    parts = []
    for pair, part in table[table["quantity"] == quantity].groupby("pair", sort=False):
        part = part.set_index("band")
        total = part.loc["total"]
        if not np.isfinite(total.ratio):
            continue
        decides = part.index[part["decides"].astype(bool)][0]
        verdict = ("a tie in total" if total.calmer == "tie" else
                   f"decided at {BAND_LABELS[decides]} ({total.calmer} calmer)")
        parts.append(f"the {pair}: {total.ratio:.3g} in total, "
                     + ", ".join(f"{part.loc[b, 'ratio']:.3g} at {b.replace('-', '–')}"
                                 for b in ("1-3", "4-7", "8 and up")) + f", {verdict}")
    if not parts:
        return ""
    label = QUANTITY_LABELS.get(quantity, quantity)
    return (f"By mesh-harmonic band (Section 15), std(SBG)/std(LSBG) of the {label} is, for "
            + "; for ".join(parts) + ".")


def cells_range(cells):
    """The interval over a claim's cells: the least and largest ratio, per quantity.

    Parameters
    ----------
    cells : pandas.DataFrame
        A stability table in the claims' long form
        (:func:`lsbg.tables.claims.stability_cells`: ``cell``, ``quantity``,
        ``ratio``, ``better``).

    Returns
    -------
    pandas.DataFrame
        Per quantity: ``cells`` (their number), ``ratio_least``, ``ratio_most``
        (std(SBG)/std(LSBG) over the cells) and ``calmer``: the LSBG where every
        cell's ratio exceeds 1, the SBG where every one is below, else ``neither``.
    """
    rows = []
    for quantity, part in cells.groupby("quantity", sort=False):
        least, most = float(part["ratio"].min()), float(part["ratio"].max())
        rows.append({"quantity": quantity, "cells": int(part["cell"].nunique()),
                     "ratio_least": least, "ratio_most": most,
                     "calmer": "LSBG" if least > 1 else "SBG" if most < 1 else "neither"})
    return pd.DataFrame(rows, columns=["quantity", "cells", "ratio_least", "ratio_most", "calmer"])


def cells_text(tables):
    """Sentences of the interval over cells, one per pair and quantity.

    Parameters
    ----------
    tables : dict
        ``{pair name: stability table in the claims' long form}``.

    Returns
    -------
    str
        Markdown; "" without tables.
    """
    parts = []
    for pair, cells in tables.items():
        for r in cells_range(cells).itertuples():
            where = ("every cell's ratio above 1" if r.calmer == "LSBG" else
                     "every cell's ratio below 1" if r.calmer == "SBG" else
                     "the cells on both sides of 1" if r.ratio_least < 1 < r.ratio_most
                     else "a cell at 1")
            parts.append(f"{pair}, {r.quantity}: {r.ratio_least:.3g}–{r.ratio_most:.3g} over "
                         f"its {r.cells} cell{'s' if r.cells != 1 else ''} ({where})")
    return "; ".join(parts) + "." if parts else ""


# ------------------------------------------------------------ per boundary
#: The stability cell whose runs put the mesh inside the torsional driveline (the
#: sensitivity case ``boundary: [driveline]``); every other cell prescribes the pinion.
DRIVELINE_CELL = case_label("boundary_driveline")

#: The boundaries in words, in the order the answers state them.
BOUNDARY_NAMES = ("prescribed pinion speed", "torsional driveline")


def driveline_pair(runs, case="boundary_driveline"):
    """``{gear type: run}`` of a pair's driveline case among its sensitivity runs.

    Parameters
    ----------
    runs : iterable of xarray.Dataset
        Sensitivity runs, read from their files ``{trace}_beta{spiral}_{case}.nc``
        (:func:`lsbg.tables.finding.sensitivity_cells` reads them so).
    case : str
        The case's name.
    """
    from pathlib import Path

    from lsbg.aggregate.runs import gear_type

    return {gear_type(ds): ds for ds in runs
            if Path(ds.encoding.get("source", "")).stem.endswith(f"_{case}")
            and ds.attrs.get("solver_boundary") == "driveline"}


def boundary_answers(cells, bands=None, quantity="gear_speed"):
    """The stability claim's answer per pair and boundary, with the band that decides it.

    Parameters
    ----------
    cells : dict
        ``{pair name: stability table in the claims' long form}``
        (:func:`lsbg.tables.claims.stability_cells`); the cell :data:`DRIVELINE_CELL`
        runs under the torsional driveline, the others under the prescribed pinion.
    bands : pandas.DataFrame, optional
        :func:`band_table` with the pair's baseline runs under ``pair`` and its driveline
        runs under ``"<pair>, torsional driveline"``.
    quantity : str
        The quantity whose deciding band is named.

    Returns
    -------
    pandas.DataFrame
        ``pair``, ``boundary`` (of :data:`BOUNDARY_NAMES`), ``cells`` (their number),
        ``verdict`` (:func:`lsbg.tables.claims.claim_word`) and ``deciding_band`` (words;
        "" where the band table has no such pair).
    """
    from lsbg.tables.claims import claim_verdict, claim_word

    rows = []
    for pair, table in cells.items():
        under = table["cell"] == DRIVELINE_CELL
        for boundary, part in zip(BOUNDARY_NAMES, (table[~under], table[under])):
            if part.empty:
                continue
            name = pair if boundary == BOUNDARY_NAMES[0] else f"{pair}, {boundary}"
            band = ""
            if bands is not None and len(bands):
                row = bands[(bands["pair"] == name) & (bands["quantity"] == quantity)
                            & bands["decides"].astype(bool)]
                band = BAND_LABELS.get(row["band"].iloc[0], "") if len(row) else ""
            rows.append({"pair": pair, "boundary": boundary,
                         "cells": int(part["cell"].nunique()),
                         "verdict": claim_word(claim_verdict(part, "fluctuates less")),
                         "deciding_band": band})
    return pd.DataFrame(rows, columns=["pair", "boundary", "cells", "verdict", "deciding_band"])


def boundary_sentence(answers, quantity="gear_speed"):
    """The stability answer per boundary in one sentence (Markdown), for a first screen.

    Parameters
    ----------
    answers : pandas.DataFrame
        :func:`boundary_answers`.
    quantity : str
        The quantity whose deciding band :func:`boundary_answers` named.
    """
    if answers.empty:
        return ""
    label = QUANTITY_LABELS.get(quantity, quantity)
    parts = []
    for pair, part in answers.groupby("pair", sort=False):
        said = []
        for row in part.itertuples():
            cells = "1 cell" if row.cells == 1 else f"{row.cells} cells"
            band = f", the {label} decided at {row.deciding_band}" if row.deciding_band else ""
            said.append(f"under the {row.boundary} **{row.verdict}** ({cells}{band})")
        parts.append(f"{pair}: " + "; ".join(said))
    return "**Stability by boundary** — " + ". ".join(parts) + "."

