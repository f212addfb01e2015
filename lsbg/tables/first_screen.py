"""A report's first screen: the verdict matrix, its legend, and the coarse configuration's banner.

The paper report opens with the three claims against each level the study
ran (the pair as published, as a designer would make it, each type at its best
ease-off, the trace: front against front and matched designs), each cell coloured by its verdict (:data:`lsbg.tables.claims.VERDICT_WORDS`)
and carrying the number of model-form cells behind it, with a legend that
defines every verdict word. Every report of a configuration coarser than the
study's defaults (the schema's, which ``workflow/config.yaml`` keeps for every
setting compared) opens
with a banner naming what ran coarser, from the settings its own input files
record (:func:`recorded_settings`).

* :func:`verdict_matrix`, :func:`matrix_html`, :func:`legend_html`,
  :func:`screen_html`, :func:`verdict_sentence`: the matrix and its words;
* :func:`study_defaults`, :func:`recorded_settings`, :func:`coarse_settings`,
  :func:`coarse_banner` and :func:`banner_of_files`: the banner.
"""

from __future__ import annotations

import html

import pandas as pd

from lsbg.tables import claims as claim_tables

__all__ = ["LEVELS", "VERDICT_COLOURS", "verdict_matrix", "matrix_html", "legend_html",
           "screen_html",
           "verdict_sentence", "COMPARED_KEYS", "study_defaults", "recorded_settings",
           "coarse_settings", "coarse_banner", "banner_of_files"]

#: The levels of the study, in the matrix's order: (key, column heading).
LEVELS = {"published": "as published", "practice": "as a designer would make it",
          "best": "each at its best ease-off",
          "trace": "the trace (front against front, matched designs)"}

#: The claims, in the matrix's order: (name, row heading).
CLAIM_ROWS = {"stability": "The LSBG meshes more stably",
              "contact state": "The LSBG's contact state is better",
              "service life": "The LSBG lives longer"}

#: Background colour of a cell by its verdict word ("not tested": the level made no
#: analysis of the claim).
VERDICT_COLOURS = {"yes": "#b7e1b5", "no, the opposite": "#f4b6b6", "no": "#f9d9a8",
                   "not shown": "#dcdcdc", "not tested": "#ffffff"}


def verdict_matrix(levels):
    """The claims against the levels the study ran: each cell's verdict word and cells.

    Parameters
    ----------
    levels : dict
        ``{level: (claims, cells)}`` for the levels of :data:`LEVELS` the study
        ran (a level left out, or with no claims, is not a column): ``claims``
        ``{claim: verdict}``, each verdict :func:`lsbg.tables.claims.claim_verdict`'s
        or already its word (a key of :data:`VERDICT_COLOURS`, as
        :func:`lsbg.tables.trace_level.trace_claims` gives the trace level's), and
        ``cells`` ``{claim: number of cells}``.

    Returns
    -------
    pandas.DataFrame
        One row per claim and level ran: ``claim``, ``level`` (the column
        heading), ``verdict`` (a word of :data:`lsbg.tables.claims.VERDICT_WORDS`,
        or "not tested") and ``cells`` (0 where not tested).
    """
    unknown = set(levels) - set(LEVELS)
    if unknown:
        raise ValueError(f"levels: unknown {sorted(unknown)}; known: {list(LEVELS)}")
    rows = []
    for key, heading in LEVELS.items():
        if key not in levels or not levels[key][0]:
            continue
        claims, cells = levels[key]
        for name in CLAIM_ROWS:
            word = _word(claims[name]) if name in claims else "not tested"
            rows.append({"claim": name, "level": heading, "verdict": word,
                         "cells": int(cells.get(name, 0)) if word != "not tested" else 0})
    return pd.DataFrame(rows, columns=["claim", "level", "verdict", "cells"])


def _word(verdict):
    """A claim's verdict word: a word as given (checked), else :func:`claim_word` of it."""
    if isinstance(verdict, str):
        if verdict not in VERDICT_COLOURS:
            raise ValueError(f"verdict {verdict!r}: not one of {list(VERDICT_COLOURS)}")
        return verdict
    return claim_tables.claim_word(verdict)


def matrix_html(matrix):
    """The verdict matrix as an HTML table: claims as rows, levels as columns, cells coloured.

    Parameters
    ----------
    matrix : pandas.DataFrame
        :func:`verdict_matrix`.

    Returns
    -------
    str
        ``<table class="lsbg-verdicts">``; each cell reads its verdict and
        "n cells".
    """
    levels = list(dict.fromkeys(matrix["level"]))
    head = "".join(f"<th>{html.escape(level)}</th>" for level in levels)
    body = []
    for name, row_heading in CLAIM_ROWS.items():
        part = matrix[matrix["claim"] == name].set_index("level")
        cells = []
        for level in levels:
            verdict, n = part.loc[level, "verdict"], int(part.loc[level, "cells"])
            count = f"{n} cell{'' if n == 1 else 's'}" if verdict != "not tested" else "—"
            cells.append(f'<td style="background:{VERDICT_COLOURS[verdict]};text-align:center;'
                         f'padding:6px 14px"><b>{html.escape(verdict)}</b><br>'
                         f'<small>{count}</small></td>')
        body.append(f"<tr><th style=\"text-align:left\">{html.escape(row_heading)}</th>"
                    + "".join(cells) + "</tr>")
    return ('<table class="lsbg-verdicts" style="border-collapse:separate;border-spacing:3px;'
            'font-size:1.05em"><thead><tr><th>the paper\'s claim</th>' + head
            + "</tr></thead><tbody>" + "".join(body) + "</tbody></table>")


def legend_html():
    """One line defining every verdict word, each with its colour (HTML)."""
    words = dict(claim_tables.VERDICT_WORDS,
                 **{"not tested": "the level made no analysis of the claim"})
    return ('<p class="lsbg-legend" style="font-size:0.92em">' + "; ".join(
        f'<span style="background:{VERDICT_COLOURS[w]};padding:0 4px;border:1px solid #bbb">'
        f'<b>{html.escape(w)}</b></span>: {html.escape(meaning)}'
        for w, meaning in words.items())
        + ". A cell is one model-form variant of the analysis (a setting scaled, a "
        "crowning, a displaced assembly); a tie is a difference within the claim's "
        "resolution.</p>")


#: The reports' empty code cells (no input shown, no output) take no room on the first screen.
EMPTY_CELLS_CSS = ("<style>.jp-Cell.jp-mod-noOutputs.jp-mod-noInput{display:none}</style>")


def screen_html(matrix, heading, banner=""):
    """The first screen's block: the banner, a heading line, the matrix and its legend (HTML).

    Parameters
    ----------
    matrix : pandas.DataFrame
        :func:`verdict_matrix`.
    heading : str
        The line above the matrix (HTML).
    banner : str
        :func:`coarse_banner` ("" for none).
    """
    # a finding box (lsbg-finding) too: what the reports' check finds on the first screen
    return (f'{EMPTY_CELLS_CSS}<div class="lsbg-finding lsbg-first-screen">{banner}'
            f"<p>{heading}</p>{matrix_html(matrix)}{legend_html()}</div>")


def verdict_sentence(matrix):
    """The matrix in one sentence: each level's verdicts, claim by claim (plain text).

    Parameters
    ----------
    matrix : pandas.DataFrame
        :func:`verdict_matrix`.
    """
    parts = []
    for level, part in matrix.groupby("level", sort=False):
        words = ", ".join(f"{name} {verdict}" for name, verdict in
                          zip(part["claim"], part["verdict"]))
        parts.append(f"{level}: {words}")
    return "The paper's claims for the LSBG, " + "; ".join(parts) + "."


# ------------------------------------------------------------- the banner
#: Settings whose larger value is the coarser one (an element size); for every other
#: setting of :func:`recorded_settings` the smaller value is the coarser.
COARSER_WHEN_LARGER = {"tooth.element_size_module", "tooth.rim_element_factor"}

#: ``{attribute: key}`` of the settings each kind of file records.
RECORDED = {
    "runs": {"solver_duration_s": "simulation.duration_s", "solver_samples": "simulation.samples"},
    "tcas": {"positions": "tca.positions"},
    "vh_maps": {"positions": "misalignment_map.positions"},
    "sweep_vh_maps": {"positions": "misalignment_map.positions"},
    "fe_ltcas": {"fe_tooth_size": "tooth.element_size_module",
                 "fe_body_size": "tooth.rim_element_factor",
                 "fe_face_points": "tooth.face_points",
                 "fe_profile_points": "tooth.profile_points",
                 "phases": "tooth.ltca_positions"},
    "fronts": {"population": "optimise.population", "generations": "optimise.generations"},
}

#: Every setting the banner compares: the recorded ones and the V-H maps' steps.
COMPARED_KEYS = tuple(dict.fromkeys(
    [key for keys in RECORDED.values() for key in keys.values()]
    + ["misalignment_map.steps", "misalignment_map.sweep_steps"]))


def study_defaults():
    """The study's defaults: the schema's (lsbg's package data), every section filled in.

    ``workflow/config.yaml`` keeps the schema's default of every setting in
    :data:`COMPARED_KEYS` (a test checks it), so a pip-installed lsbg that has no
    checkout decides "coarse" as the workflow does.

    Returns
    -------
    dict
        Every section, its keys filled in.
    """
    from lsbg.config import resolve_config

    return resolve_config()


def recorded_settings(**datasets):
    """The settings a report's input files record, as configuration keys.

    Parameters
    ----------
    **datasets : iterable of xarray.Dataset
        By kind (a key of :data:`RECORDED`: ``runs`` (a sweep dataset too),
        ``tcas``, ``vh_maps`` at the paper's design point, ``sweep_vh_maps`` at
        every point of the sweep, ``fe_ltcas``, ``fronts``); a V-H map also
        records its axes' length, ``misalignment_map.steps`` at the paper's
        point, ``misalignment_map.sweep_steps`` in the sweep (its least).

    Returns
    -------
    dict
        ``{key: value}``; where files of one kind differ, the coarsest value.
    """
    unknown = set(datasets) - set(RECORDED)
    if unknown:
        raise ValueError(f"recorded_settings: unknown kinds {sorted(unknown)}; "
                         f"known: {list(RECORDED)}")
    out = {}

    def keep(key, value):
        coarser = max if key in COARSER_WHEN_LARGER else min
        out[key] = coarser(out[key], value) if key in out else value

    for kind, items in datasets.items():
        for ds in items:
            for attribute, key in RECORDED[kind].items():
                if attribute in ds.attrs:
                    keep(key, float(ds.attrs[attribute]))
            if kind in ("vh_maps", "sweep_vh_maps") and "axes" in ds.attrs:
                keep("misalignment_map." + ("steps" if kind == "vh_maps" else "sweep_steps"),
                     float(min(ds.sizes[a] for a in ds.attrs["axes"].split())))
    return out


def coarse_settings(recorded, defaults):
    """The recorded settings coarser than the study's defaults.

    Parameters
    ----------
    recorded : dict
        ``{key: value}`` (:func:`recorded_settings`), keys ``section.name``.
    defaults : dict
        The study's configuration (:func:`study_defaults`).

    Returns
    -------
    list of (str, float, float)
        ``(key, value, default)`` of each coarser setting, in ``recorded``'s order.
    """
    out = []
    for key, value in recorded.items():
        section, name = key.split(".", 1)
        default = defaults.get(section, {}).get(name)
        if default is None:
            continue
        larger = key in COARSER_WHEN_LARGER
        if (value > float(default)) if larger else (value < float(default)):
            out.append((key, value, float(default)))
    return out


def coarse_banner(coarse, report="report"):
    """The banner of a coarse configuration's report (HTML), or "" where nothing is coarser.

    Parameters
    ----------
    coarse : list of (str, float, float)
        :func:`coarse_settings`.
    report : str
        What the banner stands on, e.g. "this report".
    """
    if not coarse:
        return ""
    named = "; ".join(f"{key} {value:g} (study: {default:g})" for key, value, default in coarse)
    return ('<div class="lsbg-coarse" style="background:#fff3cd;border:2px solid #d39e00;'
            'padding:8px 12px;margin:8px 0;font-size:1.05em"><b>Coarse configuration: '
            f"the numbers of {html.escape(report)} are not the study's.</b> Coarser than the "
            f"study's defaults (workflow/config.yaml): {html.escape(named)}. Run the study "
            "(<code>snakemake -j2</code>) for its numbers.</div>")


def banner_of_files(report="this report", **paths):
    """:func:`coarse_banner` of the settings a report's input files record.

    Parameters
    ----------
    report : str
        What the banner stands on.
    **paths : str, pathlib.Path or sequence of them
        The files by kind, as :func:`recorded_settings` takes their datasets
        ("" or [] for none).

    Returns
    -------
    str
        HTML, or "" where no setting is coarser than the study's defaults.
    """
    import contextlib

    import xarray as xr

    from lsbg.files import as_path_list

    with contextlib.ExitStack() as stack:
        datasets = {kind: [stack.enter_context(xr.open_dataset(p)) for p in as_path_list(items)]
                    for kind, items in paths.items()}
        recorded = recorded_settings(**datasets)
    return coarse_banner(coarse_settings(recorded, study_defaults()), report)
