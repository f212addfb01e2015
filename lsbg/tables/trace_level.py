"""The trace level's answer to the paper's three claims: front against front, matched designs.

The other levels answer the claims for two designs; the trace level answers them for
the tooth traces, from each trace's fronts compared as sets (``lsbg trace-fronts``, one
dataset per cell of the trace study) and from designs of both traces matched one to one
on the fronts (``lsbg matched-pairs``). The rule is docs/optimise.md's, "The trace
level's verdict": every statistic that decides a claim is a cell, and a side holds only
where every cell of the claim gives it.

* :func:`trace_claim_cells`: every cell of each claim with its statistic and side;
* :func:`trace_claims`: each claim's verdict word and number of cells, as
  :func:`lsbg.tables.first_screen.verdict_matrix` takes a level;
* :func:`with_trace_column`: the claims table with the column "the trace";
* :func:`trace_sentence` and :func:`trace_text`: the answer in words (Markdown).

Ratios are SBG over LSBG (> 1: the LSBG's lower or calmer), dimensionless.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

__all__ = ["CLAIMS", "CONTACT_OBJECTIVES", "CONTACT_FIGURES", "LIFE_FIGURES", "NOT_COUNTED",
           "trace_claim_cells", "trace_claims", "trace_answer", "with_trace_column",
           "trace_sentence", "trace_text"]

#: The claims, in the report's order.
CLAIMS = ("stability", "contact state", "service life")

#: The searches' objectives that are the contact state's: fronts searched on none of
#: them say nothing of it.
CONTACT_OBJECTIVES = ("transmission_error", "transmission_error_harmonic",
                      "envelope_transmission_error", "pattern_movement", "contact_pressure")

#: The matched designs' contact-state figures that decide: the FE loaded TE [µrad].
CONTACT_FIGURES = {"transmission_error": "FE loaded TE over the load range",
                   "rated_transmission_error": "FE loaded TE at the rated torque"}

#: The matched designs' life figures that decide: FE stresses [MPa].
LIFE_FIGURES = {"peak_contact_pressure": "FE peak contact pressure, edges included",
                "root_stress_pinion": "FE root stress, pinion",
                "root_stress_gear": "FE root stress, gear"}

#: Figures of the matched designs shown but not counted, and why.
NOT_COUNTED = {"pattern_movement": "a term the pairs are matched on",
               "contact_pressure": "near-matched: the pairs are matched on its uniform-bed twin"}

#: A cell's sides, in the order the words name them.
_SIDES = ("LSBG", "SBG", "tie", "not resolved", "no verdict")

_COLUMNS = ["claim", "cell", "source", "pairs", "statistic", "value", "low", "high", "p",
            "side"]


def _resolution(claim):
    """The claim's resolution at the other levels, relative [-] (why: a difference the
    model does not resolve is no ranking, however many pairs agree on it)."""
    from lsbg.tables.claims import CONTACT_STATE_RESOLUTION
    from lsbg.tables.rating import RESOLVED_STRESS_DIFFERENCE

    return CONTACT_STATE_RESOLUTION if claim == "contact state" else RESOLVED_STRESS_DIFFERENCE


def _matched_side(low, high, p, ratio, resolution=None):
    """A matched cell's side: :func:`lsbg.tables.matched.calmer_of` of its log interval
    and p, "not resolved" also where ``ratio`` (SBG/LSBG) lies within ``resolution``."""
    from lsbg.tables.claims import better_type
    from lsbg.tables.matched import calmer_of

    side = calmer_of(low, high, p)
    if side in ("LSBG", "SBG") and resolution is not None \
            and better_type(ratio, 1.0, resolution) == "tie":
        return "not resolved"
    return side


def _stability_cells(matched):
    """One row per boundary and quantity: the full runs' statistics where at least two
    pairs ran in full (Wilcoxon's p needs two), else the proxy's."""
    from lsbg.tables.matched import matched_table

    table = matched_table(matched)
    rows = []
    for (boundary, quantity), part in table.groupby(["boundary", "quantity"], sort=False):
        by = part.set_index("estimate")
        estimate = "full" if "full" in by.index and by.loc["full", "pairs"] >= 2 else "proxy"
        r = by.loc[estimate]
        if not r["pairs"]:
            continue
        rows.append({"claim": "stability",
                     "cell": f"{boundary.replace('_', ' ')}, {quantity}",
                     "source": "matched designs, " + ("full runs" if estimate == "full"
                                                      else "proxy"),
                     "pairs": int(r["pairs"]), "statistic": "std SBG/LSBG",
                     "value": r["ratio"], "low": r["low"], "high": r["high"],
                     "p": r["wilcoxon_p"], "side": r["calmer"]})
    return rows


def _figure_cells(matched, claim, figures):
    """One row per matched figure of ``figures`` that the dataset has, with pairs."""
    rows = []
    for name, words in figures.items():
        if f"{name}_ratio_mean" not in matched:
            continue
        pairs = int(matched[f"{name}_ratio_pairs"])
        if not pairs:
            continue
        mean, low, high, p = (float(matched[f"{name}_ratio_{s}"])
                              for s in ("mean", "low", "high", "wilcoxon_p"))
        ratio = math.exp(mean)
        rows.append({"claim": claim, "cell": words, "source": "matched designs, FE",
                     "pairs": pairs, "statistic": f"{name.replace('_', ' ')} SBG/LSBG",
                     "value": ratio, "low": math.exp(low), "high": math.exp(high), "p": p,
                     "side": _matched_side(low, high, p, ratio, _resolution(claim))})
    return rows


def _front_cells(trace_fronts):
    """One row per trace-study cell whose searches had a contact objective: its verdict."""
    from lsbg.tables.optimise import cell_name

    rows = []
    for ds in trace_fronts:
        if not set(ds.attrs.get("objectives", "").split()) & set(CONTACT_OBJECTIVES):
            continue
        code = float(ds["verdict"])
        side = ("no verdict" if not np.isfinite(code)
                else {1: "LSBG", -1: "SBG", 0: "tie"}[int(code)])
        rows.append({"claim": "contact state", "cell": f"fronts, {cell_name(ds)}",
                     "source": "fronts (A12 and the ε-indicator)", "pairs": np.nan,
                     "statistic": "A12 of the hypervolumes", "value": float(ds["a12"]),
                     "low": np.nan, "high": np.nan, "p": float(ds["mann_whitney_p"]),
                     "side": side})
    return rows


def trace_claim_cells(trace_fronts=(), matched=None):
    """Every cell of the trace level's claims, with its statistic and side.

    Parameters
    ----------
    trace_fronts : sequence of xarray.Dataset
        ``lsbg trace-fronts`` datasets, one per cell of the trace study (the paper's
        first; none: no front cell).
    matched : xarray.Dataset, optional
        ``lsbg matched-pairs`` (:func:`lsbg.matched.dataset.matched_pairs_dataset`);
        none, or no pair found: no matched cell.

    Returns
    -------
    pandas.DataFrame
        ``claim``, ``cell``, ``source``, ``pairs`` [-] (NaN for the fronts),
        ``statistic``, ``value`` (SBG/LSBG over the pairs, a geometric mean [-]; A12 for
        the fronts [-]), ``low``, ``high`` (its bootstrap interval [-]), ``p``
        (Wilcoxon's; Mann-Whitney's for the fronts, reported, not deciding) and ``side``:
        "LSBG" or "SBG" (the better), "not resolved", "tie" or "no verdict".
    """
    rows = _front_cells(trace_fronts)
    if matched is not None and int(matched.attrs.get("pairs_found", 0)):
        rows = (_stability_cells(matched) + rows
                + _figure_cells(matched, "contact state", CONTACT_FIGURES)
                + _figure_cells(matched, "service life", LIFE_FIGURES))
    table = pd.DataFrame(rows, columns=_COLUMNS)
    order = {c: k for k, c in enumerate(CLAIMS)}
    return table.sort_values("claim", key=lambda c: c.map(order), kind="stable") \
        .reset_index(drop=True)


def trace_claims(cells):
    """Each claim's verdict word and its number of cells, by docs/optimise.md's rule.

    Parameters
    ----------
    cells : pandas.DataFrame
        :func:`trace_claim_cells`.

    Returns
    -------
    claims : dict
        ``{claim: word}`` for every claim of :data:`CLAIMS`: "yes" (the LSBG better in
        every cell), "no, the opposite" (the SBG in every cell), "not shown" (any other
        mix: a cell not resolved, a tie or no verdict does not say "no") or "not tested"
        (no cell compared anything).
    counts : dict
        ``{claim: number of cells}`` (0 where not tested).
    """
    claims, counts = {}, {}
    for claim in CLAIMS:
        sides = cells.loc[cells["claim"] == claim, "side"]
        if not len(sides) or (sides == "no verdict").all():
            claims[claim], counts[claim] = "not tested", 0
            continue
        counts[claim] = len(sides)
        claims[claim] = ("yes" if (sides == "LSBG").all() else
                         "no, the opposite" if (sides == "SBG").all() else "not shown")
    return claims, counts


def trace_answer(word, n):
    """A claim's trace-level answer with its cells, e.g. "not shown (4 cells)" (text)."""
    if word == "not tested":
        return word
    return f"{word} ({n} cell{'' if n == 1 else 's'})"


def with_trace_column(table, claims, counts, column="the trace", at=None):
    """The finding's claims table with the trace level's answers in a column.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`lsbg.tables.finding.claims_table` (its column "the paper's claim").
    claims, counts : dict
        :func:`trace_claims`.
    column : str
        The column's heading.
    at : int, optional
        Where the column goes (default: before "baseline figures", else last).
    """
    from lsbg.tables.finding import CLAIMED

    names = {text: name for name, text in CLAIMED.items()}
    if at is None:
        at = (list(table.columns).index("baseline figures") if "baseline figures" in table
              else len(table.columns))
    out = table.copy()
    out.insert(at, column, [trace_answer(claims[names[c]], counts[names[c]])
                            if names.get(c) in claims else "—"
                            for c in out["the paper's claim"]])
    return out


def _pairs(matched):
    return int(matched.attrs.get("pairs_found", 0)) if matched is not None else 0


def trace_sentence(trace_fronts=(), matched=None):
    """What the trace column rests on, in one sentence (Markdown), for a first screen.

    Parameters
    ----------
    trace_fronts, matched
        As :func:`trace_claim_cells` takes them.
    """
    fronts = len(trace_fronts)
    decided = sum(bool(np.isfinite(float(ds["verdict"]))) for ds in trace_fronts)
    where = (f"{fronts} cell{'' if fronts == 1 else 's'} of the trace study"
             + ("" if decided == fronts else ", none with a verdict" if not decided
                else f", {decided} with a verdict"))
    pairs = _pairs(matched)
    sought = int(matched.attrs.get("pairs_sought", 0)) if matched is not None else 0
    said = (f"{pairs} matched pair{'' if pairs == 1 else 's'}"
            + (f" of {sought} sought" if sought else ""))
    # the least two-sided exact Wilcoxon p of n pairs, all of one sign: 2 / 2^n
    least = 2.0 ** (1 - pairs) if pairs else math.nan
    indicative = any(int(ds.attrs.get("indicative", 0)) for ds in trace_fronts) or (
        matched is not None and int(matched.attrs.get("indicative", 0)))
    if not pairs:
        limit = ": no stability or life comparison over matched designs"
    elif least >= 0.05:
        limit = f", too few for Wilcoxon's p to reach 0.05 (its least {least:.2g}): indicative"
    else:
        limit = ": indicative (fewer than 5 seeds, or pairs than sought)" if indicative else ""
    return (f"**The trace** column sets each trace's fronts against the other's "
            f"({where}) and {said}{limit}"
            f" (docs/optimise.md, \"The trace level's verdict\").")


def trace_text(cells, claims, counts):
    """The trace level's answer claim by claim, each with its cells' sides (Markdown).

    Parameters
    ----------
    cells : pandas.DataFrame
        :func:`trace_claim_cells`.
    claims, counts : dict
        :func:`trace_claims`.
    """
    parts = []
    for claim in CLAIMS:
        part = cells[cells["claim"] == claim]
        if claims[claim] == "not tested":
            parts.append(f"{claim} **not tested** (no front comparison gave a verdict and no "
                         f"pair was found)" if claim == "contact state" else
                         f"{claim} **not tested** (no matched pair)")
            continue
        sides = part["side"].value_counts()
        spread = ", ".join(f"{'the ' + s if s in ('LSBG', 'SBG') else s} in {sides[s]}"
                           for s in _SIDES if sides.get(s))
        parts.append(f"{claim} **{claims[claim]}** ({counts[claim]} "
                     f"cell{'' if counts[claim] == 1 else 's'}: {spread})")
    return ("**The trace** (front against front, matched designs; a side only where every "
            "cell gives it, docs/optimise.md): " + "; ".join(parts) + ".")
