"""The pair as a designer would make it, in the reports: its design, its claims, its curves.

The paper's three claims are answered for the practice design
(:mod:`lsbg.practice`) at its own load, its rated torque, from the files of
the practice design point (results/practice/), in the cells of the published
pair's tables (the sensitivity cases of ``practice.sensitivity``): stability
from its line-model runs (at full rate, at 500 samples per second, each
case's), the contact state from its V-H maps (each case's that reaches it),
the service life from its ISO rating (with each case's K_v), its FE loaded
TCA aligned, at each crowning case and at the envelope's corners, and, by
Miner's rule, under the load spectrum (:mod:`lsbg.practice.spectrum`) from
its load curves.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import TYPE_ORDER, gear_type
from lsbg.tables import claims as claim_tables

__all__ = ["PRACTICE_CELL", "FE_ISO_BAND", "SPECTRUM_QUANTITIES", "by_type", "practice_claims",
           "practice_design_table", "design_words", "sbg_words", "load_curve_table", "fe_iso_ratio_table",
           "spectrum_life_table", "read_practice", "practice_load", "practice_text",
           "claims_text", "with_answers"]

#: The practice design's stability cell.
PRACTICE_CELL = "line model, the practice design at its load"

#: The band the FE loaded TCA's largest pressure at the rated torque should lie in,
#: as a multiple of ISO 10300's sigma_H at that torque (docs/model.md, "Edges"):
#: below it the FE model would miss the load concentration K_Hbeta stands for,
#: above it an edge the relief did not reach [-].
FE_ISO_BAND = (0.6, 1.6)


def by_type(datasets):
    """``{gear type: dataset}`` of datasets of both traces, in TYPE_ORDER."""
    found = {gear_type(ds): ds for ds in datasets}
    return {t: found[t] for t in TYPE_ORDER if t in found}


def practice_claims(runs, vh_maps, ratings, fe_ltcas, curves=None, spectrum=None,
                    start=0.2, where="", sensitivity=(), vh_cases=(), fe_cases=()):
    """The three claims for the practice design at its load, in the published pair's cells.

    Parameters
    ----------
    runs : dict
        ``{gear type: line-model run}`` at the practice load.
    vh_maps, ratings, fe_ltcas : dict
        ``{gear type: dataset}``: V-H maps, ISO ratings (with the FE envelope
        and the K_v of each case's run) and FE loaded TCAs of the practice
        design point.
    curves : dict, optional
        ``{gear type: load curve}`` of the practice design: the service life
        is also answered under ``spectrum`` (Miner's rule).
    spectrum : dict, optional
        ``torque_fractions``, ``cycle_shares`` (the ``practice.load_spectrum``
        section) and ``load_torque_N_m`` (the design load they refer to).
    start : float
        Start of the steady state [s].
    where : str
        The design point in words.
    sensitivity : sequence of xarray.Dataset
        The line-model runs of the pair's sensitivity cases (``lsbg
        sensitivity``, :func:`lsbg.tables.finding.case_cells`).
    vh_cases, fe_cases : sequence of xarray.Dataset
        The V-H maps and FE loaded TCAs of the cases that reach them, both
        types each (:func:`lsbg.tables.claims.contact_state_table`,
        :func:`lsbg.tables.claims.life_table`).

    Returns
    -------
    claims : dict
        ``{claim: verdict}`` (:func:`lsbg.tables.claims.claim_verdict`).
    tables : dict
        ``stability``, ``contact state``, ``service life`` in the claims' long
        form (the spectrum's cell among the service life's rows): the cells of
        the published pair's tables, the point model's aside.
    """
    from lsbg.tables.finding import case_cells
    from lsbg.tables.line_model import sensitivity_table
    from lsbg.tables.rating import RESOLVED_STRESS_DIFFERENCE

    cases, _ = case_cells(sensitivity)
    cells = [(PRACTICE_CELL, runs, True), *cases,
             (PRACTICE_CELL + ", 500-Hz sampling", runs, False)]
    stability = claim_tables.stability_cells(sensitivity_table(cells, start))
    claims = {"stability": claim_tables.claim_verdict(stability, "fluctuates less", where)}
    tables = {"stability": stability}
    if len(vh_maps) == 2:
        tables["contact state"] = claim_tables.contact_state_table(vh_maps, vh_cases)
        claims["contact state"] = claim_tables.claim_verdict(tables["contact state"],
                                                             "is lower", where)
    life = claim_tables.life_table(ratings, fe_ltcas, fe_cases)
    if curves and len(curves) == 2 and spectrum:
        life = pd.concat([life, spectrum_life_table(
            curves, spectrum["load_torque_N_m"], spectrum["torque_fractions"],
            spectrum["cycle_shares"], RESOLVED_STRESS_DIFFERENCE)], ignore_index=True)
    if not life.empty:
        tables["service life"] = life
        claims["service life"] = claim_tables.claim_verdict(life, "lives longer", where)
    return claims, tables


def design_words(record, profile_shift="gleason", addendum_rule="iso23509"):
    """The practice design in a few words, from its design.json record.

    Parameters
    ----------
    record : dict
        :func:`lsbg.solid.directory.read_record` of a practice geometry.
    profile_shift, addendum_rule : str or float
        The study's ``practice.profile_shift`` and ``practice.addendum_rule``: the
        rule that gave x_hm1 (:func:`lsbg.practice.design.shift_rule`).
    """
    from lsbg.practice.design import shift_rule

    shift = float(record.get("profile_shift", 0.0))
    thickness = float(record.get("thickness_modification", 0.0))
    rule = shift_rule({"profile_shift": profile_shift, "addendum_rule": addendum_rule})
    return (f"profile shift x_hm1 = {shift:.3f} ({rule}), thickness "
            f"modification x_smn1 = {thickness:.3f} (equal root stresses), undercut refused")


def practice_design_table(published, practice, ratings_published, ratings_practice):
    """The two designs side by side: shift, addenda, thickness, contact ratio, ratings.

    Parameters
    ----------
    published, practice : dict
        design.json records (:func:`lsbg.solid.directory.read_record`) of one trace.
    ratings_published, ratings_practice : xarray.Dataset
        Their ISO ratings (``lsbg rate``).

    Returns
    -------
    pandas.DataFrame
        ``quantity``, ``unit``, ``as published``, ``as a designer would make it``.
    """
    rows = []
    for words, unit, key in (
            ("profile shift x_hm1", "-", "profile_shift"),
            ("thickness modification x_smn1", "-", "thickness_modification"),
            ("pinion outer addendum", "mm", "outer_addendum_pinion_mm"),
            ("gear outer addendum", "mm", "outer_addendum_gear_mm"),
            ("pinion mean normal tooth thickness", "mm", "mean_normal_tooth_thickness_pinion_mm"),
            ("gear mean normal tooth thickness", "mm", "mean_normal_tooth_thickness_gear_mm"),
            ("pinion undercut", "deg", "undercut_pinion_deg"),
            ("pinion top land, mean", "mm", "top_land_mean_pinion_mm"),
            ("total contact ratio", "-", "contact_ratio")):
        rows.append((words, unit, float(published.get(key, 0.0)), float(practice.get(key, 0.0))))
    for words, key in (("rated gear torque, pitting (ISO 10300)", "rated_gear_torque_contact"),
                       ("rated gear torque, root (ISO 10300)", "rated_gear_torque_bending")):
        rows.append((words, "N·m", _rated(ratings_published, key), _rated(ratings_practice, key)))
    return pd.DataFrame(rows, columns=["quantity", "unit", "as published",
                                       "as a designer would make it"])


def _rated(ds, key):
    """The smaller member's rated gear torque of a rating dataset [N m] (nan if absent)."""
    if ds is None or key not in ds:
        return np.nan
    return float(np.min(ds[key].values))


def load_curve_table(curves):
    """Each load curve at its design's rated torque (the torque nearest to it).

    Parameters
    ----------
    curves : dict
        ``{(design set, gear type): load curve}``.

    Returns
    -------
    pandas.DataFrame
        Per design and type: the rated torque, TE peak to peak and first
        harmonic, pattern length and width, largest pressure (all and off
        the edges), edge load share, root stresses, and ISO 10300's sigma_H
        and sigma_F at that torque.
    """
    rows = []
    for (design_set, kind), ds in curves.items():
        rated = float(ds.attrs["rated_torque_pitting_N_m"])
        at = ds.isel(torque=int(np.argmin(np.abs(ds["torque"].values - rated))))
        rows.append({
            "design": design_set, "type": kind, "torque [N·m]": float(at["torque"]),
            "TE p-p [µrad]": float(at["transmission_error_peak_to_peak"]),
            "TE 1st harmonic [µrad]": float(at["transmission_error_first_harmonic"]),
            "pattern length [mm]": float(at["pattern_length"]),
            "pattern width [mm]": float(at["pattern_width"]),
            "largest pressure [MPa]": float(at["max_contact_pressure"].max()),
            "off the edges [MPa]": float(at["max_flank_pressure"].max()),
            "edge load share [%]": 100 * float(at["edge_load_share"].max()),
            "ISO σ_H [MPa]": float(at["iso_contact_stress"]),
            "root stress pinion / gear [MPa]":
                f"{float(at['root_stress_pinion'].max()):.0f} / "
                f"{float(at['root_stress_gear'].max()):.0f}",
            "ISO σ_F pinion / gear [MPa]":
                f"{float(at['iso_root_stress_pinion']):.0f} / "
                f"{float(at['iso_root_stress_gear']):.0f}"})
    return pd.DataFrame(rows)


def fe_iso_ratio_table(fe_ltcas, ratings):
    """The FE loaded TCA's largest pressure over ISO 10300's sigma_H at the same load.

    Parameters
    ----------
    fe_ltcas, ratings : dict
        ``{gear type: dataset}`` of one design at one load.

    Returns
    -------
    pandas.DataFrame
        Per type: the largest FE pressure (all, and off the edges), sigma_H,
        their ratio and whether it lies in :data:`FE_ISO_BAND`.
    """
    rows = []
    for kind in TYPE_ORDER:
        if kind not in fe_ltcas or kind not in ratings:
            continue
        fe, iso = fe_ltcas[kind], ratings[kind]
        largest = float(fe["max_contact_pressure"].max())
        sigma_h = float(iso["contact_stress"])  # [MPa], as the rating dataset holds it
        ratio = largest / sigma_h
        rows.append({"type": kind, "load [N·m]": float(fe.attrs["load_torque_N_m"]),
                     "FE largest pressure [MPa]": largest,
                     "FE off the edges [MPa]": float(fe["max_flank_pressure"].max())
                     if "max_flank_pressure" in fe else np.nan,
                     "edge load share [%]": 100 * float(fe["edge_load_share"].max())
                     if "edge_load_share" in fe else np.nan,
                     "ISO σ_H [MPa]": sigma_h, "FE / ISO": ratio,
                     f"within {FE_ISO_BAND[0]:g}–{FE_ISO_BAND[1]:g}":
                         "yes" if FE_ISO_BAND[0] <= ratio <= FE_ISO_BAND[1] else "no"})
    return pd.DataFrame(rows)


#: The spectrum's quantities: load-curve variable -> the life table's quantity
#: (:data:`lsbg.tables.claims.LIFE_QUANTITIES`: its words and Basquin line).
SPECTRUM_QUANTITIES = {"max_contact_pressure": "contact", "root_stress_pinion": "root_pinion",
                       "root_stress_gear": "root_gear"}


def spectrum_life_table(curves, load_torque, torque_fractions, cycle_shares, resolution):
    """The service-life claim's cell under the load spectrum: both types by Miner's rule.

    Parameters
    ----------
    curves : dict
        ``{"SBG": load curve, "LSBG": load curve}`` of one design.
    load_torque : float
        The design load the spectrum's fractions refer to [N m].
    torque_fractions, cycle_shares : sequence of float
        The spectrum (:func:`check_spectrum`).
    resolution : float
        Relative stress difference below which the types tie [-].

    Returns
    -------
    pandas.DataFrame
        The long form of :func:`lsbg.tables.claims.life_table`: per quantity
        the damage-equivalent stresses [MPa] of both types, the life ratio
        LSBG/SBG and its range, and the ``better`` type.
    """
    from lsbg.practice.spectrum import (
        check_spectrum,
        spectrum_life_ratio,
        spectrum_stresses,
    )

    levels, shares = check_spectrum(torque_fractions, cycle_shares)
    torques = levels * float(load_torque)
    rows = []
    for variable, quantity in SPECTRUM_QUANTITIES.items():
        words, kind = claim_tables.LIFE_QUANTITIES[quantity]
        stress = {t: spectrum_stresses(curves[t], variable, torques) for t in ("SBG", "LSBG")}
        life = spectrum_life_ratio(stress["LSBG"], stress["SBG"], shares, kind)
        sbg, lsbg = life["reference_equivalent"], life["equivalent"]
        rows.append({"cell": f"FE loaded TCA, load spectrum (Miner, {levels.size} levels)",
                     "quantity": words, "unit": "MPa", "SBG": sbg, "LSBG": lsbg,
                     "life ratio LSBG/SBG": life["ratio"], "least": life["low"],
                     "most": life["high"], "better": claim_tables.better_type(sbg, lsbg, resolution)})
    return pd.DataFrame(rows)


# ------------------------------------------------------------ in the paper report
def read_practice(runs, vh_maps, ratings, fe_ltcas, geometry_dirs, load_curves, engine,
                  sensitivity=(), vh_cases=(), fe_cases=()):
    """The practice design point's files, read: ``{gear type: dataset}`` of each kind.

    Parameters
    ----------
    runs, vh_maps, ratings, fe_ltcas, geometry_dirs, load_curves : sequence of str
        The files (``results/practice/``, ``results/load_curves/``); any may be empty.
    engine : str
        The engine of the line-model runs.
    sensitivity, vh_cases, fe_cases : sequence of str
        The files of the pair's sensitivity cases: line-model runs, V-H maps, FE
        loaded TCAs (``results/practice/sensitivity/``, ``vh/``, ``tooth/``).

    Returns
    -------
    dict
        ``runs``, ``vh_maps``, ``ratings``, ``fe_ltcas``, ``records`` (design.json),
        ``curves`` (``{(design set, gear type): load curve}``); empty dicts where no file;
        ``sensitivity``, ``vh_cases``, ``fe_cases``: lists of datasets.
    """
    import xarray as xr

    from lsbg.aggregate.runs import select_runs
    from lsbg.dynamics.dataset import open_runs
    from lsbg.files import as_path_list
    from lsbg.gear.design import TRACE_LABELS
    from lsbg.solid.directory import read_record

    def load(paths):
        return by_type([xr.load_dataset(p) for p in as_path_list(paths)])

    records = {TRACE_LABELS[r["trace"]]: r for r in map(read_record, as_path_list(geometry_dirs))}
    curves = {}
    for path in as_path_list(load_curves):
        ds = xr.load_dataset(path)
        curves[(ds.attrs["design_set"], gear_type(ds))] = ds
    run_files = as_path_list(runs)
    return {"runs": select_runs(open_runs(run_files), "line", engine) if run_files else {},
            "vh_maps": load(vh_maps), "ratings": load(ratings), "fe_ltcas": load(fe_ltcas),
            "sensitivity": open_runs(as_path_list(sensitivity)),
            "vh_cases": [xr.load_dataset(p) for p in as_path_list(vh_cases)],
            "fe_cases": [xr.load_dataset(p) for p in as_path_list(fe_cases)],
            "records": {t: records[t] for t in TYPE_ORDER if t in records},
            "curves": dict(sorted(curves.items(), key=lambda kv: (kv[0][0] != "paper",
                                                                  TYPE_ORDER.index(kv[0][1]))))}


def practice_load(practice):
    """The practice design's load on the gear [N m] (its runs', else its ratings'), or None."""
    for ds in practice["runs"].values():
        return float(ds.attrs["solver_load_torque_N_m"])
    for ds in practice["ratings"].values():
        return float(ds["gear_torque"])
    return None


def claims_text(claims, heading):
    """A design's claims as Markdown: its heading, then one bullet per claim."""
    lines = [heading]
    for name, verdict in claims.items():
        lines.append(f"- **{name.capitalize()}**: {claim_tables.claim_answer(verdict)}. "
                     + " ".join(verdict["sentences"].values()))
    return "\n".join(lines)


def practice_text(claims, practice, where, profile_shift="gleason", addendum_rule="iso23509"):
    """The finding's paragraph on the practice design: what it is, each claim's answer.

    Parameters
    ----------
    claims : dict
        :func:`practice_claims`.
    practice : dict
        :func:`read_practice`.
    where : str
        The design point and load in words ("at 35°, 585 N·m").
    profile_shift, addendum_rule : str or float
        The study's practice rules of x_hm1 (:func:`design_words`).

    Returns
    -------
    str
        Markdown; empty without a practice design.
    """
    if not claims or not practice["records"]:
        return ""
    record = next(iter(practice["records"].values()))
    flanks = next(iter(practice["runs"].values())).attrs if practice["runs"] else {}
    relief = flanks.get("flank_modification_pinion_tip_relief_um")
    relief_words = (f", both tips relieved by {float(relief):.3g} µm" if relief is not None
                    else "")
    return claims_text(claims, f"**As a designer would make it** ("
                               f"{design_words(record, profile_shift, addendum_rule)}"
                               f"{relief_words}; {sbg_words(practice['records'])}), {where}, "
                               f"its rated pitting torque:")


def sbg_words(records):
    """Which SBG a design's records hold, in words ("SBG, ISO 23509 face-milled, cutter
    radius 76.2 mm"), or "no SBG".

    Parameters
    ----------
    records : dict
        ``{gear type: design.json record}`` (:func:`read_practice`'s ``records``).
    """
    from lsbg.gear.design import TRACE_NAMES

    record = records.get("SBG")
    if record is None:
        return "no SBG"
    return f"{TRACE_NAMES[record['trace']]}, cutter radius {float(record['cutter_radius_mm']):g} mm"


def with_answers(table, claims, column, at=2):
    """The finding's claims table with another design's answers in a column.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`lsbg.tables.finding.claims_table`.
    claims : dict
        :func:`practice_claims` of that design (none: the table as it is).
    column : str
        The column's heading: the design and its load.
    at : int
        Where the column goes.
    """
    if not claims:
        return table
    from lsbg.tables.finding import CLAIMED

    names = {text: name for name, text in CLAIMED.items()}
    out = table.copy()
    out.insert(at, column, [claim_tables.claim_answer(claims[names[c]]).replace("**", "")
                            if names.get(c) in claims else "—"
                            for c in out["the paper's claim"]])
    return out
