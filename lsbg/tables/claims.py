"""The paper's three claims, each as a table of model-form cells and a verdict.

The paper claims that the LSBG (1) meshes more stably, (2) has a better tooth
contact state and (3) lives longer. Each claim is answered at the paper's
design point from the study's files, in every cell of a model-form
sensitivity study (:mod:`lsbg.experiments.sensitivity`): the baseline and the cases that
reach the claim's analysis. A ranking is stated only where it holds in every
cell (:func:`claim_verdict`).

* :func:`stability_table`: per pair (conjugate, crowned at each crowning,
  displaced to each corner of the envelope), the fluctuation ratios of the
  line-model runs with the loaded transmission error of the V-H maps;
* :func:`contact_state_table`: per cell (the study's crowning, each crowning
  and line-stiffness case), the pattern's movement and the loaded TE's change
  per 0.1 mm of displacement and the edge-contact load share, from the V-H maps;
* :func:`life_table`: per cell (ISO 10300 with the K_v of each run, the FE
  loaded TCA aligned, at each crowning and at each corner of the envelope),
  the contact and root stresses of both types and the life ratio they imply.

Tables are long: one row per cell and quantity, columns ``cell``,
``quantity``, ``unit``, ``SBG``, ``LSBG``, ``better`` (the type with the lower
value, or ``tie`` within the claim's resolution).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import QUANTITY_LABELS, TYPE_ORDER
from lsbg.experiments.sensitivity import case_label, parse_case

__all__ = ["BASELINE", "CONTACT_STATE_RESOLUTION", "better_type", "stability_table",
           "stability_cells",
           "contact_state_table", "contact_state_by_angle", "life_table", "claim_verdict",
           "claim_scope", "VERDICT_WORDS", "claim_word", "claim_answer",
           "claims_by_angle"]

#: The label of the study's own settings in every claim's table.
BASELINE = "baseline (the study's settings)"

#: Relative differences of the contact-state figures below this are ties: the
#: case maps have 5 x 5 cells against the paper map's 9 x 9 (the pattern's
#: movement changed by 0.4 % between them) and the pattern is measured on a
#: 0.5 mm grid, about 3 % of its length [-].
CONTACT_STATE_RESOLUTION = 0.05


def better_type(sbg, lsbg, resolution):
    """The type with the lower value, or ``"tie"`` within ``resolution``.

    Parameters
    ----------
    sbg, lsbg : float
        The two types' values of one figure (lower is better).
    resolution : float
        Relative difference below which they tie [-].
    """
    if not (np.isfinite(sbg) and np.isfinite(lsbg)):
        return "—"
    scale = max(abs(sbg), abs(lsbg))
    if scale == 0 or abs(sbg - lsbg) <= resolution * scale:
        return "tie"
    return "SBG" if sbg < lsbg else "LSBG"


def _centre(ds):
    """The undisplaced cell of a V-H map (its axes' middle values)."""
    axes = ds.attrs["axes"].split()
    return ds.isel({a: ds.sizes[a] // 2 for a in axes})


def _corner(ds, corner):
    """The cell of a V-H map at an envelope corner's displacements (from the centre)."""
    from lsbg.tca.misalignment import corner_displacements

    centre = _centre(ds)
    return ds.sel({letter: float(centre[letter]) + shift
                   for letter, shift in corner_displacements(corner).items()}, method="nearest")


def _by_case(files):
    """{case name: {gear type: dataset}} of case files, by their ``sensitivity_case``
    attribute (``lsbg misalignment-map --case``, ``lsbg ltca --case``)."""
    from lsbg.aggregate.runs import gear_type

    out = {}
    for ds in files:
        out.setdefault(ds.attrs["sensitivity_case"], {})[gear_type(ds)] = ds
    return out


# ------------------------------------------------------------- stability
def stability_table(sensitivity, vh_maps, vh_cases=()):
    """Claim 1 per pair: fluctuation ratios and the loaded transmission error.

    Parameters
    ----------
    sensitivity : pandas.DataFrame
        :func:`lsbg.tables.line_model.sensitivity_table` with a ``case``
        column (the case name, or "" for the baseline and the cells of no
        case).
    vh_maps : dict
        ``{gear type: V-H map}`` at the study's crowning.
    vh_cases : iterable of xarray.Dataset
        The V-H maps of the crowning cases (:mod:`lsbg.experiments.sensitivity`).

    Returns
    -------
    pandas.DataFrame
        Per pair (baseline, each crowning case, each displaced corner):
        ``cell``, the ratio std(SBG)/std(LSBG) with its interval per
        quantity, ``calmer`` per quantity, and the loaded TE peak to peak of
        each type [µrad] (the V-H map's cell of that pair).
    """
    cases = _by_case(vh_cases)
    baseline = sensitivity["cell"].iloc[0] if len(sensitivity) else None
    rows = []
    for cell, part in sensitivity.groupby("cell", sort=False):
        case = part["case"].iloc[0]
        key, value = parse_case(case) if case else (None, None)
        if cell == baseline and vh_maps:
            te = {t: float(_centre(ds)["transmission_error_loaded_pp"])
                  for t, ds in vh_maps.items()}
        elif key == "crowning" and case in cases:
            te = {t: float(_centre(ds)["transmission_error_loaded_pp"])
                  for t, ds in cases[case].items()}
        elif key == "displacement" and vh_maps:
            te = {t: float(_corner(ds, value)["transmission_error_loaded_pp"])
                  for t, ds in vh_maps.items()}
        else:
            continue
        row = {"cell": cell}
        for r in part.itertuples():
            label = QUANTITY_LABELS.get(r.quantity, r.quantity)
            row[f"{label}: std(SBG)/std(LSBG)"] = (f"{r.ratio:.3g} ({r.ratio_low:.3g}–"
                                                   f"{r.ratio_high:.3g})")
            row[f"{label}: calmer"] = r.calmer
        for t in TYPE_ORDER:
            row[f"loaded TE p-p {t} [µrad]"] = te.get(t, float("nan"))
        rows.append(row)
    return pd.DataFrame(rows)


def stability_cells(sensitivity):
    """The sensitivity table in the claims' long form: ``better`` is the calmer type
    (``tie`` where no type is significantly calmer).

    Parameters
    ----------
    sensitivity : pandas.DataFrame
        :func:`lsbg.tables.line_model.sensitivity_table`.
    """
    out = sensitivity[["cell", "quantity", "ratio", "ratio_low", "ratio_high"]].copy()
    out["quantity"] = out["quantity"].map(lambda q: QUANTITY_LABELS.get(q, q))
    out["better"] = sensitivity["calmer"].replace({"neither": "tie"}).values
    return out


# --------------------------------------------------------- contact state
#: Figures of the contact state from a V-H map: (words, unit).
CONTACT_FIGURES = {
    "pattern_movement": ("bearing pattern's movement per 0.1 mm of displacement", "mm"),
    "te_change": ("loaded TE p-p change per 0.1 mm of displacement", "µrad"),
    "edge_load_share": ("edge-contact load share, aligned", "%"),
    "edge_load_share_envelope": ("edge-contact load share, worst cell of the map", "%"),
}


def _contact_figures(ds):
    from lsbg.tables.contact_state import pattern_movement

    axes = ds.attrs["axes"].split()
    return {
        "pattern_movement": pattern_movement(ds)["total"],
        "te_change": math.sqrt(sum(ds.attrs[f"transmission_error_loaded_pp_per_0_1_{a}"] ** 2
                                   for a in axes)),
        "edge_load_share": 100 * float(_centre(ds)["edge_load_share"]),
        "edge_load_share_envelope": 100 * float(ds["edge_load_share"].max()),
    }


def contact_state_table(vh_maps, vh_cases=()):
    """Claim 2 per cell: how far the pattern and the TE move, and the edge load.

    Parameters
    ----------
    vh_maps : dict
        ``{gear type: V-H map}`` at the study's settings (the baseline).
    vh_cases : iterable of xarray.Dataset
        V-H maps of the cases that reach the contact state (crowning, line
        stiffness), both types each.

    Returns
    -------
    pandas.DataFrame
        Long form (module docstring); lower is better for every figure; ties
        within :data:`CONTACT_STATE_RESOLUTION`.
    """
    cells = [(BASELINE, vh_maps)]
    cells += [(case_label(name), maps) for name, maps in _by_case(vh_cases).items()]
    rows = []
    for cell, maps in cells:
        if not {"SBG", "LSBG"} <= set(maps):
            continue
        figures = {t: _contact_figures(maps[t]) for t in ("SBG", "LSBG")}
        for name, (words, unit) in CONTACT_FIGURES.items():
            sbg, lsbg = figures["SBG"][name], figures["LSBG"][name]
            rows.append({"cell": cell, "quantity": words, "unit": unit, "SBG": sbg,
                         "LSBG": lsbg,
                         "better": better_type(sbg, lsbg, CONTACT_STATE_RESOLUTION)})
    return pd.DataFrame(rows)


def contact_state_by_angle(sweep):
    """The pattern's movement per 0.1 mm at every spiral angle of a sweep dataset.

    Parameters
    ----------
    sweep : xarray.Dataset
        :func:`lsbg.aggregate.combine.combine_runs` with the V-H maps' sensitivities
        (``pattern_shift_{lengthwise,profile}_per_0_1_{axis}`` over ``trace``
        and ``spiral_angle``).

    Returns
    -------
    pandas.DataFrame
        ``spiral_angle`` [deg], one column per gear type [mm] and ``better``
        (ties within :data:`CONTACT_STATE_RESOLUTION`); empty without them. Of a sweep
        with both SBGs, the published pair's (:func:`lsbg.aggregate.runs.pair_traces`;
        select the traces for another).
    """
    from lsbg.aggregate.runs import pair_traces

    axes = sorted({name.rsplit("_", 1)[1] for name in sweep.data_vars
                   if name.startswith("pattern_shift_lengthwise_per_0_1_")})
    if not axes:
        return pd.DataFrame()
    total = sum(sweep[f"pattern_shift_lengthwise_per_0_1_{a}"] ** 2
                + sweep[f"pattern_shift_profile_per_0_1_{a}"] ** 2 for a in axes) ** 0.5
    rows = []
    for angle in total["spiral_angle"].values:
        row = {"spiral_angle": float(angle)}
        for label, trace in pair_traces(total["trace"].values).items():
            row[label] = float(total.sel(trace=trace, spiral_angle=angle))
        row["better"] = better_type(row.get("SBG", np.nan), row.get("LSBG", np.nan),
                                CONTACT_STATE_RESOLUTION)
        rows.append(row)
    table = pd.DataFrame(rows)
    return table[["spiral_angle", *[t for t in TYPE_ORDER if t in table], "better"]]


# ------------------------------------------------------------------- life
#: The stresses of the life claim: (words, kind of the Basquin line).
LIFE_QUANTITIES = {"contact": ("contact stress (pitting)", "contact"),
                   "root_pinion": ("root stress, pinion", "bending"),
                   "root_gear": ("root stress, gear", "bending")}


def _fe_stresses(ds):
    """{quantity: MPa} of an FE loaded TCA (its largest over the mesh cycle)."""
    return {"contact": float(ds["max_contact_pressure"].max()),
            "root_pinion": float(ds["root_stress_pinion"].max()),
            "root_gear": float(ds["root_stress_gear"].max())}


def life_table(ratings, fe_ltcas=None, fe_cases=()):
    """Claim 3 per cell: both types' stresses and the life ratio they imply.

    Parameters
    ----------
    ratings : dict
        ``{gear type: rating dataset}`` (:func:`lsbg.rating.dataset.
        rating_dataset`), with the K_v cases (``case_*``) and the envelope
        (``fe_displaced_*``) where the study made them.
    fe_ltcas : dict, optional
        ``{gear type: FE loaded TCA}``, aligned, at the study's crowning.
    fe_cases : iterable of xarray.Dataset
        FE loaded TCAs of the crowning cases, both types each.

    Returns
    -------
    pandas.DataFrame
        Long form (module docstring) in MPa, plus ``life ratio LSBG/SBG`` at
        the stated exponent and its ``least``/``most`` over the exponents'
        range; ``better`` is the type that lives longer, a tie where the
        stresses differ by no more than
        :data:`lsbg.tables.rating.RESOLVED_STRESS_DIFFERENCE`.
    """
    from lsbg.rating.life import life_ratio
    from lsbg.tables.rating import RESOLVED_STRESS_DIFFERENCE

    cells = []
    if {"SBG", "LSBG"} <= set(ratings):
        iso = {t: {"contact": float(ds["contact_stress"]),
                   "root_pinion": float(ds["root_stress"].sel(member="pinion")),
                   "root_gear": float(ds["root_stress"].sel(member="gear"))}
               for t, ds in ratings.items()}
        cells.append(("ISO 10300 (K_v of the baseline run)", iso))
        first = ratings["SBG"]
        for case in (first["case"].values if "case" in first.coords else []):
            if "case" not in ratings["LSBG"].coords or case not in ratings["LSBG"]["case"]:
                continue
            cells.append((f"ISO 10300, K_v of {case_label(str(case))}", {
                t: {"contact": float(ds["case_contact_stress"].sel(case=case)),
                    "root_pinion": float(ds["case_root_stress"].sel(case=case, member="pinion")),
                    "root_gear": float(ds["case_root_stress"].sel(case=case, member="gear"))}
                for t, ds in ratings.items()}))
    if fe_ltcas and {"SBG", "LSBG"} <= set(fe_ltcas):
        cells.append(("FE loaded TCA, " + BASELINE,
                      {t: _fe_stresses(ds) for t, ds in fe_ltcas.items()}))
    for name, by_type in _by_case(fe_cases).items():
        cells.append((f"FE loaded TCA, {case_label(name)}",
                      {t: _fe_stresses(ds) for t, ds in by_type.items()}))
    if {"SBG", "LSBG"} <= set(ratings) and "corner" in ratings["SBG"].coords:
        for corner in ratings["SBG"]["corner"].values:
            cells.append((f"FE loaded TCA, displaced {corner} mm", {
                t: {"contact": float(ds["fe_displaced_max_contact_pressure"].sel(corner=corner)),
                    "root_pinion": float(ds["fe_displaced_max_root_stress"].sel(
                        corner=corner, member="pinion")),
                    "root_gear": float(ds["fe_displaced_max_root_stress"].sel(
                        corner=corner, member="gear"))}
                for t, ds in ratings.items()}))
    rows = []
    for cell, stresses in cells:
        if not {"SBG", "LSBG"} <= set(stresses):
            continue
        for name, (words, kind) in LIFE_QUANTITIES.items():
            sbg, lsbg = stresses["SBG"][name], stresses["LSBG"][name]
            life = life_ratio(lsbg, sbg, kind)
            rows.append({"cell": cell, "quantity": words, "unit": "MPa", "SBG": sbg,
                         "LSBG": lsbg, "life ratio LSBG/SBG": life["ratio"],
                         "least": life["low"], "most": life["high"],
                         "better": better_type(sbg, lsbg, RESOLVED_STRESS_DIFFERENCE)})
    return pd.DataFrame(rows)


# --------------------------------------------------------------- verdicts
def claim_verdict(table, better_words, where=""):
    """Per quantity: the ranking where every cell agrees, else plainly that none holds.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`contact_state_table` or :func:`life_table`.
    better_words : str
        What "better" means for the claim, e.g. "lives longer".
    where : str
        The design point, e.g. "at 35°".

    Returns
    -------
    dict
        ``"sentences"``: ``{quantity: sentence}`` (Markdown); ``"holds"``: the
        quantities whose ranking holds in every cell, ``{quantity: type}``;
        ``"wins"``: how many (cell, quantity) rows each type (and "tie") wins.
    """
    sentences, holds = {}, {}
    where_text = f" {where.strip()}" if where.strip() else ""
    for quantity, part in table.groupby("quantity", sort=False):
        counts = part["better"].value_counts()
        n = len(part)
        winners = [t for t in ("SBG", "LSBG") if counts.get(t, 0) == n]
        if winners:
            holds[quantity] = winners[0]
            cells = "in its only cell" if n == 1 else f"in every one of the {n} cells"
            sentences[quantity] = (f"**{quantity}**{where_text}: the **{winners[0]}** "
                                   f"{better_words} {cells}.")
            continue
        order = sorted(("LSBG", "SBG", "tie"), key=lambda t: -counts.get(t, 0))
        parts = []
        for t in order:
            k = counts.get(t, 0)
            if not k:
                continue
            who = "a tie" if t == "tie" else f"the {t}"
            text = f"{who} in {k}" + (f" of {n} cells" if not parts else "")
            if parts and k <= 3 and t != "tie":  # name the few dissenting cells
                text += f" ({', '.join(part.loc[part['better'] == t, 'cell'])})"
            parts.append(text)
        sentences[quantity] = (f"**{quantity}**{where_text}: {', '.join(parts)}; no ranking "
                               f"holds in every cell.")
    return {"sentences": sentences, "holds": holds,
            "wins": {t: int((table["better"] == t).sum()) for t in ("SBG", "LSBG", "tie")}}


def claim_scope(verdict):
    """``"LSBG"``, ``"SBG"`` or ``None``: the type a claim's verdict favours in every
    cell of every quantity (from :func:`claim_verdict`), or None where it does not."""
    holds = set(verdict["holds"].values())
    if len(verdict["holds"]) == len(verdict["sentences"]) and len(holds) == 1:
        return holds.pop()
    return None


#: The verdict words of a claim (:func:`claim_word`) and what each means, in the
#: order of the reports' legend.
VERDICT_WORDS = {
    "yes": "the LSBG is better in every cell",
    "no, the opposite": "the SBG is better in every cell",
    "no": "the SBG is better in some cells, the LSBG in none (ties elsewhere)",
    "not shown": "no ranking holds in every cell: the cells disagree, or the two types tie",
}


def claim_word(verdict, claimed="LSBG"):
    """A claim's verdict word (a key of :data:`VERDICT_WORDS`), from :func:`claim_verdict`.

    Parameters
    ----------
    verdict : dict
        :func:`claim_verdict`.
    claimed : str
        The type the paper's claim favours.

    Returns
    -------
    str
        "yes" (the claimed type wins every cell of every quantity), "no, the
        opposite" (the other type does), "no" (the other type wins some cell,
        the claimed type none) or "not shown" (the cells disagree, or every
        cell is a tie: a tie does not say "no").
    """
    scope = claim_scope(verdict)
    if scope == claimed:
        return "yes"
    if scope is not None:
        return "no, the opposite"
    other = sum(k for t, k in verdict["wins"].items() if t not in (claimed, "tie"))
    if not verdict["wins"].get(claimed) and other:
        return "no"
    return "not shown"


def claim_answer(verdict, claimed="LSBG"):
    """A claim's answer in a few words (Markdown), from :func:`claim_verdict`.

    Parameters
    ----------
    verdict, claimed
        As :func:`claim_word` takes them.

    Returns
    -------
    str
        The verdict word of :func:`claim_word` in bold, with who wins where it
        says "no" ("**no**: the LSBG is better in no cell"), "no, the opposite"
        (the type in every cell) or a tie everywhere.
    """
    word = claim_word(verdict, claimed)
    if word == "no, the opposite":
        return f"**no, the opposite** (the {claim_scope(verdict)} in every cell)"
    if word == "no":
        return f"**no**: the {claimed} is better in no cell"
    if word == "not shown" and not any(k for t, k in verdict["wins"].items() if t != "tie"):
        return "**not shown** (a tie in every cell)"
    return f"**{word}**"


def claims_by_angle(ratios, contact, rating):
    """The three claims' key figures at every spiral angle of a sweep.

    Parameters
    ----------
    ratios : pandas.DataFrame
        :func:`lsbg.tables.line_model.sweep_ratio_table` (line model), or
        empty.
    contact : pandas.DataFrame
        :func:`contact_state_by_angle`, or empty.
    rating : pandas.DataFrame
        :func:`lsbg.tables.rating.read_rating_sweep`, or empty.

    Returns
    -------
    pandas.DataFrame
        Per spiral angle [deg]: the calmer type per fluctuating quantity,
        the type whose pattern moves less (ties within
        :data:`CONTACT_STATE_RESOLUTION`), and the ISO 10300 stress ratios
        LSBG/SBG with the type that lives longer by them (ties within
        :data:`lsbg.tables.rating.RESOLVED_STRESS_DIFFERENCE`).
    """
    from lsbg.tables.rating import RESOLVED_STRESS_DIFFERENCE

    rows = {}
    def row(angle):
        return rows.setdefault(round(float(angle), 9), {"spiral angle [deg]": float(angle)})
    if not ratios.empty:
        for r in ratios.itertuples():
            label = QUANTITY_LABELS.get(r.quantity, r.quantity)
            row(r.spiral_angle_deg)[f"stability, {label}: calmer"] = r.calmer
    if not contact.empty:
        for r in contact.itertuples():
            row(r.spiral_angle)["contact state: pattern moves less"] = r.better
    if not rating.empty:
        wide = rating.pivot(index="spiral_angle", columns="gear_type")
        for angle in wide.index:
            for name, words in (("contact_stress", "contact stress"),
                                ("root_stress_pinion", "pinion root stress")):
                sbg, lsbg = wide.loc[angle, (name, "SBG")], wide.loc[angle, (name, "LSBG")]
                row(angle)[f"ISO 10300 {words} LSBG/SBG"] = lsbg / sbg
                row(angle)[f"ISO 10300 {words}: lives longer"] = better_type(
                    sbg, lsbg, RESOLVED_STRESS_DIFFERENCE)
    return pd.DataFrame([rows[k] for k in sorted(rows)])
