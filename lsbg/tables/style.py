"""One table style for every report: readable headers with units, 3–4 significant figures.

The tables of :mod:`lsbg.tables` are DataFrames whose column names are code
(``tangential_force_std_low``) and whose cells keep full precision; this module
turns them into what a reader should see, so that every report shows its
tables the same way:

* :func:`column_header`: a column name as a header with its unit in brackets
  (``gear_speed_std_deg_s`` -> "gear angular velocity std [deg/s]"), from
  :data:`COLUMN_HEADERS` where a name is listed, else by rule (unit suffixes,
  words); a header never shows an underscore;
* :func:`display_unit`: the units of the datasets' attributes as printed
  (``urad`` -> µrad, ``N/um`` -> N/µm);
* :func:`format_number`: 4 significant figures by default, powers of ten as
  ×10⁻⁵ rather than ``e-05``, a dash for a missing value;
* :func:`cell_label`: category values as words (``tangential_force`` ->
  "tangential contact force", ``logarithmic`` -> LSBG, run ids -> "LSBG 35°,
  line model, compiled, line stiffness ×0.5");
* :func:`with_interval`: a value and its interval in one column, "0.81 (0.78–0.85)",
  which keeps tables with confidence intervals narrow;
* :func:`format_table`: all of it, to an HTML table.

None of it computes a result: the numbers are the tables' own.
"""

from __future__ import annotations

import html
import math
import numbers
import re

import pandas as pd

from lsbg.gear.design import TRACE_LABELS, TRACE_NAMES
from lsbg.aggregate.runs import QUANTITY_LABELS
from lsbg.stats import samples

__all__ = ["UNIT_DISPLAY", "COLUMN_HEADERS", "CELL_LABELS", "display_unit", "column_header",
           "format_number", "cell_label", "run_label", "with_interval", "format_table",
           "DEFAULT_DIGITS", "DEFAULT_FORMATS"]

#: Significant figures of a number without a column format [-].
DEFAULT_DIGITS = 4

#: Units as the datasets write them (ASCII, UDUNITS-like) -> as a reader reads them.
UNIT_DISPLAY = {
    "urad": "µrad", "um": "µm", "N/um": "N/µm", "N/(mm um)": "N/(mm·µm)",
    "N/(mm*um)": "N/(mm·µm)", "N s/mm": "N·s/mm", "N m": "N·m", "N*m": "N·m", "degree": "deg", "1": "-",
}

#: Unit suffixes of column names (longest first) -> the unit they mean.
_UNIT_SUFFIXES = (
    ("_N_per_mm_um", "N/(mm·µm)"), ("_N_per_um", "N/µm"), ("_N_per_m2", "N/m²"),
    ("_deg_s", "deg/s"), ("_percent", "%"), ("_urad", "µrad"), ("_rad", "rad"),
    ("_deg", "deg"), ("_mm", "mm"), ("_um", "µm"), ("_hz", "Hz"), ("_Hz", "Hz"),
    ("_N_m", "N·m"), ("_N", "N"), ("_m", "m"), ("_s", "s"),
)

#: Headers of the column names the tables use (others follow :func:`column_header`'s rule).
COLUMN_HEADERS = {
    "gear_type": "type", "trace": "trace", "quantity": "quantity", "unit": "unit",
    "origin": "origin", "engine": "engine", "reference": "reference engine",
    "contact_model": "contact model", "spiral_angle_deg": "spiral angle [deg]",
    "statistic": "statistic", "simulated": "simulated mean", "theory": "theory (Eq. 12/13)",
    "difference": "difference", "error_rate_percent": "error rate [%]",
    "paper_simulated": "paper: simulated mean", "paper_error_rate_percent": "paper: error rate [%]",
    "paper": "paper", "this_work": "this work", "ratio": "ratio SBG/LSBG",
    "std_SBG": "std SBG", "std_LSBG": "std LSBG", "ci_low": "CI low", "ci_high": "CI high",
    "confidence": "confidence", "brown_forsythe_p": "Brown–Forsythe p",
    "ess_SBG": "effective samples SBG", "ess_LSBG": "effective samples LSBG",
    "paper_ratio": "paper's ratio", "std": "std", "reference_std": "reference std",
    "std_ratio": "std ratio", "mean_difference_percent": "mean difference [%]",
    "within_tolerance": "within 3 %", "mean": "mean", "ad_statistic": "A²", "ad_pvalue": "p (AD)",
    "out_of_control": "subgroups out of control", "parameter": "parameter", "value": "value",
    "is_default": "default", "wall_time_s": "wall time [s]", "steps": "steps",
    "low": "CI low", "high": "CI high", "excludes_one": "CI excludes 1", "member": "member",
    "side": "side", "measured_deg": "measured [deg]", "design_deg": "design [deg]",
    "deviation_deg": "deviation [deg]", "contact_ratio": "contact ratio",
    "contact_ratio_profile": "profile contact ratio", "contact_ratio_face": "face contact ratio",
    "calmer": "calmer", "holds": "holds", "cell": "cell", "sampling": "sampling",
    "run": "run", "figure": "figure", "full_rate_std": "full-rate std",
    "sampled_std": "500-sample std", "phase_std_min": "least over phases",
    "phase_std_median": "median over phases", "phase_std_max": "largest over phases",
    "spread_percent": "spread [%]", "dynamic_factor": "dynamic factor [-]",
    "peak_to_peak": "peak to peak", "harmonic_1": "1st harmonic", "harmonic_2": "2nd harmonic",
    "harmonic_3": "3rd harmonic", "spearman_rho": "Spearman ρ", "spearman_p": "p (Spearman)",
    "reversals": "reversals", "possible": "possible reversals", "angles": "spiral angles",
    "column": "series", "check": "check", "result": "result", "setting": "setting",
    "SBG": "SBG", "LSBG": "LSBG",
    "static_transmission_error_peak_to_peak": "static TE peak to peak [µrad]",
    "static_transmission_error_harmonic_1": "static TE 1st harmonic [µrad]",
    "mesh_stiffness_variation": "mesh stiffness variation [%]",
    "mesh_stiffness_per_face_width": "mesh stiffness per face width [N/(mm·µm)]",
}

#: Words of category cells (quantities, series, traces) as a reader reads them.
CELL_LABELS = {
    **QUANTITY_LABELS,
    **TRACE_NAMES,  # a trace by its construction: the two SBGs apart
    "gear_speed_sampled_std": "500-sample std of the gear angular velocity",
    "tangential_force_sampled_std": "500-sample std of the tangential contact force",
    "gear_speed_std": "full-rate std of the gear angular velocity",
    "tangential_force_std": "full-rate std of the tangential contact force",
    "transmission_error_std": "full-rate std of the transmission error",
    "static_transmission_error_peak_to_peak": "static transmission error, peak to peak",
    "mesh_stiffness_variation": "mesh stiffness variation",
    "mesh_stiffness": "mesh stiffness",
    "static_transmission_error": "static transmission error",
    **{unit: shown for unit, shown in UNIT_DISPLAY.items() if unit != "1"},
}

#: Formats of columns whose values are settings, not measurements (30, not 30.00).
DEFAULT_FORMATS = {"spiral_angle_deg": "{:g}"}

_WORDS = {"std": "std", "ess": "effective samples", "te": "TE", "pp": "peak to peak",
          "x2": "×2", "x4": "×4", "rel": "relative", "diff": "difference", "max": "largest",
          "min": "least", "n": "n", "k": "k"}



def display_unit(unit) -> str:
    """A unit string as a reader reads it (µrad, N/µm, N/(mm·µm)); others unchanged.

    Parameters
    ----------
    unit : str
        As written in a dataset's ``units`` attribute.
    """
    text = str(unit).strip()
    return UNIT_DISPLAY.get(text, text)


def column_header(name, headers=None) -> str:
    """The header of a table column: words, and the unit in brackets where the name has one.

    Parameters
    ----------
    name : str
        Column name of an lsbg table.
    headers : dict, optional
        ``{name: header}`` over :data:`COLUMN_HEADERS`.

    Returns
    -------
    str
        Never contains an underscore: ``tangential_force_std_low`` ->
        "tangential contact force std, CI low".
    """
    name = str(name)
    table = {**COLUMN_HEADERS, **(headers or {})}
    if name in table:
        return table[name]
    rest, unit = name, ""
    for suffix, shown in _UNIT_SUFFIXES:
        if rest.endswith(suffix) and len(rest) > len(suffix):
            rest, unit = rest[: -len(suffix)], shown
            break
    tail = ""
    for end, shown in (("_low", ", CI low"), ("_high", ", CI high")):
        if rest.endswith(end):
            rest, tail = rest[: -len(end)], shown
            break
    words = rest
    for quantity in sorted(QUANTITY_LABELS, key=len, reverse=True):
        if words == quantity or words.startswith(quantity + "_"):
            words = QUANTITY_LABELS[quantity] + words[len(quantity):]
            break
    words = " ".join(_WORDS.get(w, w) for w in words.split("_") if w)
    return f"{words}{tail}" + (f" [{unit}]" if unit else "")


def format_number(value, digits=DEFAULT_DIGITS) -> str:
    """A number with ``digits`` significant figures, as a reader reads it.

    Integers are shown whole; ``True``/``False`` as yes/no; a missing value
    (None, NaN, pandas' NA) as a dash; numbers below 1e-3 or from 1e6 on in
    powers of ten written ×10ⁿ (8.6×10⁻⁵, not 8.61287e-05).

    Parameters
    ----------
    value : object
    digits : int
        Significant figures [-].

    Returns
    -------
    str
    """
    if _missing(value):
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if not isinstance(value, numbers.Real):
        return str(value)
    return samples.format_number(value, digits)


def _missing(value) -> bool:
    """None, pandas' NA or a float NaN."""
    return value is None or value is pd.NA or (isinstance(value, float) and math.isnan(value))


def run_label(run) -> str:
    """A run id of the workflow as words.

    Parameters
    ----------
    run : str
        File stem of a run, ``{trace}_beta{angle}_{model}_{engine}``, of a
        sensitivity run, ``{trace}_beta{angle}_{key}_x{factor}``, or of a
        design point's loaded TCA, ``{trace}_beta{angle}``.

    Returns
    -------
    str
        e.g. "LSBG 35°, line model, compiled" or "LSBG 35°, line stiffness ×0.5";
        the id itself when it has neither form.
    """
    match = re.fullmatch(r"(?P<trace>[a-z]+)_beta(?P<angle>[0-9.]+)(_(?P<rest>.+))?", str(run))
    if not match or match["trace"] not in TRACE_LABELS:
        return str(run)
    head = f"{TRACE_LABELS[match['trace']]} {match['angle']}°"
    rest = match["rest"]
    if rest is None:     # a design point's own file (its loaded TCA)
        return head
    parts = rest.split("_")
    if len(parts) == 2 and parts[0] in ("point", "line"):
        return f"{head}, {parts[0]} model, {parts[1]}"
    key, _, factor = rest.rpartition("_x")
    if key and factor:
        return f"{head}, {column_header(key).split(' [')[0]} ×{factor}"
    return f"{head}, {rest.replace('_', ' ')}"


def cell_label(value):
    """A category cell as words (:data:`CELL_LABELS`, run ids by :func:`run_label`); others unchanged."""
    if isinstance(value, str):
        if value in CELL_LABELS:
            return CELL_LABELS[value]
        if "_beta" in value:
            return run_label(value)
    return value


def with_interval(df, column, low=None, high=None, digits=3, header=None) -> pd.DataFrame:
    """Put a value and its interval into one text column, "0.81 (0.78–0.85)".

    Parameters
    ----------
    df : pandas.DataFrame
    column : str
        The value's column; replaced in place (same position).
    low, high : str, optional
        The interval's columns (default ``{column}_low``, ``{column}_high``);
        dropped.
    digits : int
        Significant figures [-].
    header : str, optional
        New name of the column (default: the column's header with
        "(95 % CI)" added).

    Returns
    -------
    pandas.DataFrame
        A copy.
    """
    low = low or f"{column}_low"
    high = high or f"{column}_high"
    out = df.copy()
    text = [f"{format_number(v, digits)} ({format_number(lo, digits)}–{format_number(hi, digits)})"
            if not (pd.isna(lo) or pd.isna(hi)) else format_number(v, digits)
            for v, lo, hi in zip(out[column], out[low], out[high])]
    name = header or f"{column_header(column)} (95 % CI)"
    position = list(out.columns).index(column)
    out = out.drop(columns=[column, low, high])
    out.insert(min(position, len(out.columns)), name, text)
    return out


def format_table(df, formats=None, index=False, digits=DEFAULT_DIGITS, headers=None) -> str:
    """A DataFrame as an HTML table in the reports' one style.

    Parameters
    ----------
    df : pandas.DataFrame
    formats : dict, optional
        ``{column: format string, callable or int}``, over
        :data:`DEFAULT_FORMATS`; an int is that column's significant figures
        (:func:`format_number`); other numbers get ``digits`` of them.
    index : bool, default False
        Show the index.
    digits : int
        Significant figures of numbers without a format [-].
    headers : dict, optional
        Column headers, over :data:`COLUMN_HEADERS`.

    Returns
    -------
    str
        ``<table class="dataframe lsbg-table">`` with readable headers
        (:func:`column_header`), category cells in words (:func:`cell_label`),
        numbers right-aligned, and a dash for every missing value.
    """
    formats = {**DEFAULT_FORMATS, **(formats or {})}
    columns = list(df.columns)
    numeric = {c: pd.api.types.is_numeric_dtype(df[c]) and not pd.api.types.is_bool_dtype(df[c])
               for c in columns}

    def fmt(value, rule):
        if _missing(value):      # before a column's own format, which cannot take one
            return "—"
        if isinstance(rule, int) and not isinstance(rule, bool):
            return format_number(value, rule)
        if rule is not None:
            return rule(value) if callable(rule) else rule.format(value)
        if isinstance(value, (numbers.Number, bool)):
            return format_number(value, digits)
        return str(cell_label(value))

    head = "".join(f"<th>{html.escape(column_header(c, headers))}</th>" for c in columns)
    if index:
        head = f"<th>{html.escape(str(df.index.name or ''))}</th>" + head
    rows = []
    for label, row in zip(df.index, df.itertuples(index=False)):
        cells = "".join(
            f'<td class="{"num" if numeric[c] else "text"}">{html.escape(fmt(v, formats.get(c)))}</td>'
            for c, v in zip(columns, row))
        if index:
            cells = f"<th>{html.escape(str(cell_label(label)))}</th>" + cells
        rows.append(f"<tr>{cells}</tr>")
    return (f'<table class="dataframe lsbg-table"><thead><tr>{head}</tr></thead>'
            f'<tbody>{"".join(rows)}</tbody></table>')
