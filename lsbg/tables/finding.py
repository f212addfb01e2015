"""The paper report's finding: its cells, the claims' table and the sentences around them.

The paper report opens with what it found (DESIGN.md; docs/architecture.md,
"a table in a report"): the three claims of the paper, each answered in every
cell of its model-form sensitivity table, with the baseline's figures and
where the answers hold. The pieces are built here from the tables of the
other modules, so that the notebook only shows them:

* :func:`sensitivity_cells` and :func:`case_cells`: the cells of the stability claim
  (runs by case);
* :func:`finding_table`: the line model's answer beside the point model's and
  the paper's;
* :func:`paper_claims`, :func:`claim_counts`, :func:`claims_table` and
  :func:`claim_bullets`: the three claims, their cells and baseline figures;
* :func:`scope_text` and :func:`load_ratio_text`: where the answers hold;
* :func:`flanks_text`, :func:`sampling_sentence`, :func:`shape_sentence` and
  :func:`integrator_sentence`: sentences of Sections 9 and 13.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from lsbg import stats
from lsbg.aggregate.runs import QUANTITY_LABELS, select_runs
from lsbg.tables import claims as claim_tables
from lsbg.tables import line_model as line_tables
from lsbg.tables import paper as paper_tables

__all__ = ["CLAIMED", "CLAIM_SECTIONS", "sensitivity_cells", "case_cells", "finding_table", "paper_claims",
           "claim_counts", "claims_table", "claim_bullets", "scope_text", "load_ratio_text",
           "flanks_text", "sampling_sentence", "shape_sentence", "integrator_sentence"]

#: The paper's three claims, in words.
CLAIMED = {"stability": "the LSBG's gear speed and contact force fluctuate less",
           "contact state": "the LSBG's tooth contact state is better",
           "service life": "the LSBG lives longer"}
#: The paper report's section of each claim.
CLAIM_SECTIONS = {"stability": 15, "contact state": 16, "service life": 18}


def sensitivity_cells(runs, sensitivity, engine):
    """The cells of the stability claim's model-form sensitivity table.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        The runs at the paper's design point (every engine and contact model).
    sensitivity : sequence of xarray.Dataset
        The sensitivity runs (``lsbg sensitivity``), named
        ``{trace}_beta{spiral}_{case}.nc``.
    engine : str
        The engine of the line-model and sensitivity runs.

    Returns
    -------
    cells : list of (str, dict, bool)
        For :func:`lsbg.tables.line_model.sensitivity_table`: the line model
        (baseline), the point model, each case in the order of its name, and
        the baseline at 500 samples per second (full rate False).
    cases : dict
        ``{cell label: case name}`` of the cases.
    """
    base = select_runs(runs, "line", engine)
    cells, cases = case_cells(sensitivity)
    cells = [("line model (baseline)", base, True),
             ("point model", select_runs(runs, "point", engine), True), *cells,
             ("500-Hz sampling", base, False)]
    return cells, cases


def case_cells(sensitivity):
    """The stability cells of a pair's sensitivity runs, one per case.

    Parameters
    ----------
    sensitivity : sequence of xarray.Dataset
        Sensitivity runs (``lsbg sensitivity``), named
        ``{trace}_beta{spiral}_{case}.nc``, of one pair.

    Returns
    -------
    cells : list of (str, dict, bool)
        ``(case label, {gear type: run}, True)`` in the order of the case names
        (:func:`lsbg.tables.line_model.sensitivity_table`'s cells).
    cases : dict
        ``{cell label: case name}``.
    """
    from lsbg.experiments.sensitivity import case_label

    by_case = {}
    for ds in sensitivity:
        stem = Path(ds.encoding["source"]).stem
        case = stem.split("_beta", 1)[1].split("_", 1)[1]
        by_case.setdefault(case, []).append(ds)
    cells, cases = [], {}
    for case in sorted(by_case):
        cells.append((case_label(case), select_runs(by_case[case]), True))
        cases[case_label(case)] = case
    return cells, cases


def _ratio_text(ratio, low, high):
    return f"{ratio:.3g} ({low:.3g}–{high:.3g})"


def finding_table(full, comparisons, sensitivity):
    """The line model's answer at the design point beside the point model's and the paper's.

    Parameters
    ----------
    full : pandas.DataFrame
        :func:`lsbg.tables.line_model.fluctuation_table`'s full-rate rows,
        indexed by quantity.
    comparisons : dict
        ``{quantity: FluctuationComparison}`` of the point model
        (:func:`lsbg.tables.paper.compare_types`).
    sensitivity : pandas.DataFrame
        :func:`lsbg.tables.line_model.sensitivity_table`.

    Returns
    -------
    pandas.DataFrame
        Per quantity: the line model's ratio std(SBG)/std(LSBG) with its
        interval over windows of the run and calmer type, the least and largest
        ratio over the sensitivity cells (the interval over cells) and whether the
        ranking holds in every cell, the point model's ratio at 500 samples (its
        interval over windows) and the paper's.
    """
    from lsbg.stats.bootstrap import OVER_WINDOWS

    holds = sensitivity.groupby("quantity", sort=False)["holds"].all()
    spread = sensitivity.groupby("quantity", sort=False)["ratio"].agg(["min", "max"])
    n_cells = sensitivity["cell"].nunique()
    rows = []
    for q in full.index:
        c = comparisons.get(q)
        paper = paper_tables.PAPER
        rows.append({
            "quantity": q,
            f"line model, full rate: ratio (95 % CI {OVER_WINDOWS})": _ratio_text(
                full.loc[q, "ratio"], full.loc[q, "ratio_low"], full.loc[q, "ratio_high"]),
            "line model: calmer": full.loc[q, "calmer"],
            f"ratio over the {n_cells} cells, least–most":
                f"{spread.loc[q, 'min']:.3g}–{spread.loc[q, 'max']:.3g}" if q in spread.index
                else "—",
            f"holds in all {n_cells} sensitivity cells":
                ("yes" if holds.get(q, False) else "no") if q in holds else "not tested",
            f"point model, 500 samples: ratio (95 % CI {OVER_WINDOWS})":
                _ratio_text(c.ratio, c.ci.low, c.ci.high) if c else "—",
            "paper's ratio": f"{paper[('SBG', q)]['std'] / paper[('LSBG', q)]['std']:.3g}"
                             if ("SBG", q) in paper else "—",
        })
    return pd.DataFrame(rows)


def paper_claims(sensitivity, vh_maps, vh_cases, ratings, fe_ltcas, fe_cases, where=""):
    """The paper's three claims, each answered in every cell of its sensitivity table.

    Parameters
    ----------
    sensitivity : pandas.DataFrame
        :func:`lsbg.tables.line_model.sensitivity_table` (stability).
    vh_maps : dict
        ``{gear type: V-H map}`` at the design point; the contact state is
        answered where both types have one.
    vh_cases, ratings, fe_ltcas, fe_cases
        As :func:`lsbg.tables.claims.contact_state_table` and
        :func:`lsbg.tables.claims.life_table` take them.
    where : str
        The design point in words ("at 35°").

    Returns
    -------
    claims : dict
        ``{claim: verdict}`` (:func:`lsbg.tables.claims.claim_verdict`) of
        the claims this study answers, in the order of :data:`CLAIMED`.
    contact_claim, life_claim : pandas.DataFrame
        The cells of the contact state and the service life (empty where
        not answered).
    """
    claims = {"stability": claim_tables.claim_verdict(
        claim_tables.stability_cells(sensitivity), "fluctuates less", where)}
    contact_claim = (claim_tables.contact_state_table(vh_maps, vh_cases) if len(vh_maps) == 2
                     else pd.DataFrame())
    if not contact_claim.empty:
        claims["contact state"] = claim_tables.claim_verdict(contact_claim, "is lower", where)
    life_claim = claim_tables.life_table(ratings, fe_ltcas, fe_cases)
    if not life_claim.empty:
        claims["service life"] = claim_tables.claim_verdict(life_claim, "lives longer", where)
    return claims, contact_claim, life_claim


def claim_counts(sensitivity, contact_claim, life_claim):
    """``{claim: number of cells}`` of the three claims' tables (0 where not answered)."""
    def count(table):
        return table["cell"].nunique() if not table.empty else 0

    return {"stability": sensitivity["cell"].nunique(),
            "contact state": count(contact_claim), "service life": count(life_claim)}


def _pair_text(table, quantity, cell=claim_tables.BASELINE, digits=3):
    row = table[(table["cell"].str.endswith(cell)) & (table["quantity"] == quantity)].iloc[0]
    return f"SBG {row.SBG:.{digits}g}, LSBG {row.LSBG:.{digits}g} {row.unit}"


def claims_table(claims, counts, full, contact_claim, life_claim, spiral_angle):
    """The finding's table: each claim, lsbg's answer, the baseline's figures, its cells.

    Parameters
    ----------
    claims, counts : dict
        :func:`paper_claims` and :func:`claim_counts`.
    full : pandas.DataFrame
        The line model's full-rate fluctuations by quantity (as
        :func:`finding_table` takes them).
    contact_claim, life_claim : pandas.DataFrame
        :func:`paper_claims`.
    spiral_angle : float
        The design point [deg].

    Returns
    -------
    pandas.DataFrame
        One row per claim answered.
    """
    numbers = {"stability": "; ".join(
        f"{QUANTITY_LABELS[q]}: std(SBG)/std(LSBG) {full.loc[q, 'ratio']:.3g}"
        for q in ("gear_speed", "tangential_force") if q in full.index)}
    if "contact state" in claims:
        figures = claim_tables.CONTACT_FIGURES
        numbers["contact state"] = (
            "pattern moves " + _pair_text(contact_claim, figures["pattern_movement"][0])
            + " per 0.1 mm; edge load "
            + _pair_text(contact_claim, figures["edge_load_share"][0], digits=2))
    if "service life" in claims:
        fe_rows = life_claim[life_claim["cell"] == "FE loaded TCA, " + claim_tables.BASELINE]
        numbers["service life"] = "; ".join(
            f"{r['quantity']}: SBG {stats.format_number(r['SBG'])}, LSBG "
            f"{stats.format_number(r['LSBG'])} MPa, life ×{r['life ratio LSBG/SBG']:.2g}"
            for _, r in fe_rows.iterrows()) + " (FE, aligned)"
    return pd.DataFrame([
        {"the paper's claim": CLAIMED[name],
         f"lsbg's answer at {spiral_angle:g}°":
             claim_tables.claim_answer(verdict).replace("**", ""),
         "baseline figures": numbers.get(name, ""),
         "cells": counts[name], "section": CLAIM_SECTIONS[name]}
        for name, verdict in claims.items()])


def claim_bullets(claims, counts):
    """The claims as Markdown bullets: claimed, cells, section, answer, per quantity.

    A claim the study could not answer (no V-H maps or ratings at the design
    point) gets its bullet saying so.
    """
    bullets = "\n".join(
        f"- **{name.capitalize()}** ({CLAIMED[name]}; {counts[name]} "
        f"cell{'' if counts[name] == 1 else 's'}, Section "
        f"{CLAIM_SECTIONS[name]}): {claim_tables.claim_answer(verdict)}. "
        + " ".join(verdict["sentences"].values())
        for name, verdict in claims.items())
    missing = [name for name in ("contact state", "service life") if name not in claims]
    if missing:
        bullets += "\n" + "\n".join(f"- **{name.capitalize()}**: not tested by this study "
                                    "(no V-H maps or ratings at this design point)."
                                    for name in missing)
    return bullets


def _by_angle_text(table):
    groups = {t: [a for a, b in zip(table.spiral_angle, table.better) if b == t]
              for t in ("LSBG", "SBG", "tie")}
    words = {"LSBG": "the LSBG's pattern moves less", "SBG": "the SBG's pattern moves less",
             "tie": "no resolved difference"}
    return "; ".join(f"{words[t]} at {line_tables.angle_ranges(a, list(table.spiral_angle))}"
                     for t, a in groups.items() if a)


def scope_text(spiral_angle, load_torque, cases, flanks, vh_maps, sweep_scope=None,
               contact_by_angle=None, parameter_sweeps=()):
    """Where the finding's answers hold: the load, crowning, displacements and angles.

    Parameters
    ----------
    spiral_angle : float
        The design point [deg].
    load_torque : float
        The load on the gear [N m].
    cases : iterable of str
        The sensitivity cases' names (:mod:`lsbg.experiments.sensitivity`).
    flanks : dict
        The line-model run's attributes (its ``flank_modification_*_um``).
    vh_maps : dict
        ``{gear type: V-H map}`` at the design point (its axes and range).
    sweep_scope : pandas.DataFrame, optional
        :func:`lsbg.tables.line_model.calmer_by_angle` of the sweep, by
        quantity; None where the study ran no other angle under the line model.
    contact_by_angle : pandas.DataFrame, optional
        :func:`lsbg.tables.claims.contact_state_by_angle` of the sweep.
    parameter_sweeps : sequence of xarray.Dataset
        The study's parameter sweeps (:func:`lsbg.aggregate.sweep_dataset.sweep_dataset`):
        a sweep of the load names the loads it ran.

    Returns
    -------
    str
        Markdown, one paragraph.
    """
    from lsbg.experiments.sensitivity import parse_case

    crown = sorted(float(parse_case(c)[1]) for c in cases if parse_case(c)[0] == "crowning")
    crown_text = (f"crowning ×{min(crown + [1]):g}–×{max(crown + [1]):g} of the study's"
                  if crown else "the study's crowning only")
    vh_any = next(iter(vh_maps.values()), None)
    if vh_any is not None:
        axes = vh_any.attrs["axes"].split()
        reach = float(vh_any.attrs.get("range", np.abs(vh_any[axes[0]]).max()))
        displacement_text = f"displacements up to ±{reach:g} mm in {' and '.join(axes)}"
    else:
        displacement_text = "the aligned pair only"
    lines = [f"**Where these answers hold.** Each was shown at {spiral_angle:g}° and "
             f"{load_torque:g} N·m on the gear, over {crown_text} (lengthwise "
             f"{float(flanks.get('flank_modification_lengthwise_crowning_um', 0)):g} µm, "
             f"profile {float(flanks.get('flank_modification_profile_crowning_um', 0)):g} µm; "
             f"×0: conjugate flanks) and {displacement_text}, in the cells of each claim's "
             f"sensitivity table. {other_loads_text(parameter_sweeps, load_torque)}"]
    if sweep_scope is None:
        lines.append("This study ran no other spiral angle under the line model.")
    else:
        lines.append("Across the sweep's spiral angles, stability (line model): " + "; ".join(
            f"{QUANTITY_LABELS[q]}: " + ", ".join(
                f"{what} at {getattr(r, column)}" for column, what in
                (("LSBG", "LSBG calmer"), ("SBG", "SBG calmer"),
                 ("neither", "no significant difference"))
                if getattr(r, column) != "none") for q, r in sweep_scope.iterrows()) + ".")
    if contact_by_angle is not None and not contact_by_angle.empty:
        lines.append("Contact state across the sweep (the pattern's movement under the V-H "
                     "map, the study's crowning): " + _by_angle_text(contact_by_angle) + ".")
    lines.append("Service life: the teeth's own stresses (FE) at the paper's point only "
                 "(contact.compliance: fe computes them everywhere); ISO 10300 rates the two "
                 "types alike at every spiral angle (sweep.html, its service-life section).")
    return " ".join(lines)


#: The swept key of the load (lsbg.experiments.sweeps: a section's key by its path).
LOAD_KEY = "simulation.load_torque_N_m"


def other_loads_text(parameter_sweeps, load_torque):
    """The other loads the study ran, from its parameter sweeps, or that it ran none.

    Parameters
    ----------
    parameter_sweeps : sequence of xarray.Dataset
        The study's parameter sweeps (a coordinate per swept key).
    load_torque : float
        The load of the claims' cells [N m].

    Returns
    -------
    str
        One sentence.
    """
    loads = {float(v) for ds in parameter_sweeps if LOAD_KEY in ds.coords
             for v in np.atleast_1d(ds[LOAD_KEY].values)} - {float(load_torque)}
    if not loads:
        return (f"No other load was run (a sweep of {LOAD_KEY} runs others: docs/usage.md, "
                f"\"Sweeping any setting\").")
    names = [ds.attrs.get("sweep_name", "?") for ds in parameter_sweeps if LOAD_KEY in ds.coords]
    return (f"Other loads ran in the parameter sweep{'s' if len(names) > 1 else ''} "
            f"{', '.join(repr(n) for n in names)} ({', '.join(f'{v:g}' for v in sorted(loads))} "
            f"N·m: sweep.html, its parameter sweeps), outside the claims' cells.")


def load_ratio_text(ratings):
    """The paper's load against ISO 10300's pitting rating, in words (the finding's last line).

    Parameters
    ----------
    ratings : dict
        ``{gear type: rating dataset}`` (``lsbg rate``), possibly empty.
    """
    if not ratings:
        return "not rated by ISO 10300 in this study"
    first = next(iter(ratings.values()))
    pitting = min(float(ds["rated_gear_torque_contact"]) for ds in ratings.values())
    return (f"{float(first['gear_torque']) / pitting:.2g} times the torque at which "
            f"ISO 10300 rates this pair for pitting ({pitting:.0f} N·m, Section 18): "
            "every life figure here is for an overloaded pair")


def flanks_text(attrs):
    """The flanks a line-model run ran on, in words (its ``flank_modification_*_um``).

    Returns
    -------
    str
        "crowned flanks (lengthwise crowning 25 µm, profile crowning 5 µm)",
        with the bias where it is not zero, or "conjugate flanks".
    """
    if not any(k.startswith("flank_modification_") for k in attrs):
        return "conjugate flanks"
    bias = float(attrs.get("flank_modification_bias_um", 0))
    return (f"crowned flanks (lengthwise crowning "
            f"{float(attrs['flank_modification_lengthwise_crowning_um']):g} µm, "
            f"profile crowning {float(attrs['flank_modification_profile_crowning_um']):g} µm"
            + (f", bias {float(attrs['flank_modification_bias_um']):g} µm" if bias else "")
            + ")")


def sampling_sentence(resonance, sample_rate):
    """Whether the output samples resolve the contact vibration, in words.

    Parameters
    ----------
    resonance : dict
        ``{gear type: {"frequency_hz": ...}}`` (:func:`lsbg.tables.verification.resonance_of`).
    sample_rate : float
        Output samples per second [Hz].
    """
    if min(r["frequency_hz"] for r in resonance.values()) > 4 * sample_rate:
        return ("Each sample therefore catches the contact vibration at an effectively random "
                "phase: the standard deviation measures the vibration's amplitude, and the "
                "time series is aliased rather than resolved.")
    return "The output resolves the contact vibration."


def shape_sentence(rejected, series, kurtosis):
    """How the samples are distributed, in words (Section 5's tests, summed up).

    Parameters
    ----------
    rejected : int
        Series whose normality Anderson–Darling rejects at 5 %.
    series : int
        Series tested.
    kurtosis : dict
        Excess kurtosis of each series.
    """
    negative = sum(k < 0 for k in kurtosis.values())
    shape = f"Normality is rejected at 5 % for {rejected} of the {series} series (Section 5)"
    if rejected and negative == len(kurtosis):
        return shape + (", and all have negative excess kurtosis: the samples are distributed "
                        "like a sampled oscillation rather than normally.")
    return shape + f"; {negative} of {len(kurtosis)} have negative excess kurtosis."


def integrator_sentence(speed_ratio, force_ratio):
    """Why the paper's force fluctuations may be smaller than ours (its integrator), in words.

    Parameters
    ----------
    speed_ratio, force_ratio : sequence of float
        Our standard deviations over the paper's, gear speed and tangential
        force, per gear type.
    """
    if min(force_ratio) > 2:
        text = (f"The paper ran Adams, whose default stiff integrator (a BDF method with error "
                f"control and numerical damping of high-frequency modes) would damp such a "
                f"vibration: a plausible reason why its force fluctuations are "
                f"{min(force_ratio):.2g}–{max(force_ratio):.2g} times smaller than ours.")
        if min(force_ratio) > max(speed_ratio):
            text += (" The force differs more than the speed, as expected: the force follows "
                     "the contact deflection directly, while the heavy gear's speed integrates "
                     "it.")
        return text
    return "Our force fluctuations are of the same order as the paper's."


def angles_words(angles):
    """The spiral angles a study ran, in words: "one spiral angle, 35°" or "11 spiral
    angles, 20–45°".

    Parameters
    ----------
    angles : sequence of float
        [deg]

    Returns
    -------
    str
    """
    angles = sorted(set(float(a) for a in angles))
    if len(angles) == 1:
        return f"one spiral angle, {angles[0]:g}°"
    return f"{len(angles)} spiral angles, {angles[0]:g}–{angles[-1]:g}°"


def ranking_words(scope, angles):
    """What the sweep's rankings say across its angles: whether they depend on the angle.

    Parameters
    ----------
    scope : pandas.DataFrame
        :func:`lsbg.tables.line_model.calmer_by_angle`: per quantity, the angles where
        the LSBG, the SBG and neither is calmer (``"none"`` where none).
    angles : sequence of float
        The sweep's spiral angles [deg].

    Returns
    -------
    str
        A sentence, or ``""`` where one angle ran (nothing to say across angles).
    """
    if len(set(angles)) < 2 or scope.empty:
        return ""
    outcomes = [sum(getattr(row, c) != "none" for c in ("LSBG", "SBG", "neither"))
                for row in scope.itertuples()]
    if any(n > 1 for n in outcomes):
        return ("So the ranking depends on the spiral angle: a statement about one design "
                "point does not carry over to the others.")
    return "The ranking is the same at every spiral angle of the sweep."
