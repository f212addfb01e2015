"""Tables of the verification report: engines agree, runs converge, the geometry is exact.

* :func:`engine_agreement`: each engine's statistics against the reference
  engine's (:data:`REFERENCE_ENGINES`), per contact model with
  :func:`agreement_by_model`;
* :func:`read_convergence` and :func:`convergence_table`: the statistics under
  halving the time step or tightening the tolerance (``lsbg convergence``);
* :func:`pressure_angle_table`: the normal pressure angles measured on the
  flanks (the design record of ``lsbg geometry``);
* :func:`read_checks`, :func:`ltca_check_table`, :func:`contact_state_check_table`,
  :func:`conjugacy_table`, :func:`check_settings` and :func:`resonance_of`:
  the checks of a design point that ``lsbg checks`` computed
  (:mod:`lsbg.experiments.point_checks`), read and tabulated;
* :func:`setting_label`, :func:`convergence_display` and :func:`by_gear_type`:
  the tables as the verification report shows them (narrow; nothing computed);
* :func:`verification_checks`: every check's value against a bound derived from
  its discretisation, with the reason.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg.gear.design import TRACE_LABELS
from lsbg.gear.plane import face_milled_spiral_angle
from lsbg.files import as_path_list
from lsbg.aggregate.runs import records_by_type, run_spiral_angle, steady
from lsbg.stats.samples import format_number

__all__ = [
    "REFERENCE_ENGINES", "engine_agreement", "agreement_by_model", "read_convergence",
    "convergence_table",
    "pressure_angle_table", "read_checks", "ltca_check_table", "contact_state_check_table",
    "conjugacy_table", "check_settings", "resonance_of", "setting_label",
    "CONVERGENCE_DISPLAY_COLUMNS", "convergence_display", "by_gear_type",
    "verification_checks"
]


#: Engines in the order they serve as the reference of :func:`engine_agreement`
#: (the compiled DOP853 loop agrees with scipy's LSODA at rtol 1e-10 within
#: 1e-10, tests/dynamics/test_model.py).
REFERENCE_ENGINES = ("compiled", "scipy", "pybullet")


def engine_agreement(runs, start=0.2, quantities=("gear_speed", "tangential_force"),
                     reference=None, tolerance=0.03) -> pd.DataFrame:
    """Standard deviations of each engine against the reference engine's.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        Runs of one or more design points with several engines.
    start : float, default 0.2
        End of the transient [s].
    quantities : sequence of str
        Run variables to compare.
    reference : str, optional
        Engine the others are compared with; default, per design point, the
        first of :data:`REFERENCE_ENGINES` that ran there.
    tolerance : float, default 0.03
        Accepted relative difference of the standard deviations [-]
        (DESIGN.md §3: 3 %).

    Returns
    -------
    pandas.DataFrame
        Per design point, engine and quantity: ``std``, ``reference_std``,
        ``std_ratio`` (engine / reference), ``mean_difference_percent`` and
        ``within_tolerance`` (|ratio − 1| <= tolerance). Empty if no design
        point has a reference run and another one.
    """
    groups = {}
    for ds in runs:
        key = (ds.attrs["design_trace"], run_spiral_angle(ds))
        groups.setdefault(key, {})[ds.attrs["solver_engine"]] = ds
    rows = []
    for (trace, angle), engines in groups.items():
        chosen = reference or next((e for e in REFERENCE_ENGINES if e in engines), None)
        if chosen not in engines or len(engines) < 2:
            continue
        ref = engines[chosen]
        for engine, ds in engines.items():
            if engine == chosen:
                continue
            for quantity in quantities:
                x, y = steady(ds, quantity, start), steady(ref, quantity, start)
                ratio = x.std(ddof=1) / y.std(ddof=1)
                rows.append({"gear_type": TRACE_LABELS.get(trace, trace),
                             "spiral_angle_deg": angle, "engine": engine,
                             "reference": chosen, "quantity": quantity,
                             "std": float(x.std(ddof=1)), "reference_std": float(y.std(ddof=1)),
                             "std_ratio": float(ratio),
                             "mean_difference_percent": float(100 * (x.mean() - y.mean())
                                                              / abs(y.mean())),
                             "within_tolerance": bool(abs(ratio - 1.0) <= tolerance)})
    columns = ["gear_type", "spiral_angle_deg", "engine", "reference", "quantity", "std",
               "reference_std", "std_ratio", "mean_difference_percent", "within_tolerance"]
    return pd.DataFrame(rows, columns=columns)


def agreement_by_model(runs, start=0.2, quantities=("gear_speed", "tangential_force"),
                       models=("point", "line")) -> pd.DataFrame:
    """:func:`engine_agreement` per contact model, stacked.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
    start : float
        End of the transient [s].
    quantities : sequence of str
    models : sequence of str
        Contact models, in the order of the result.

    Returns
    -------
    pandas.DataFrame
        :func:`engine_agreement`'s rows of each model with a column
        ``contact_model``; empty (no columns) if no model has two engines.
    """
    groups = []
    for model in models:
        part = engine_agreement([ds for ds in runs if ds.attrs["contact_model"] == model],
                                start, quantities=quantities)
        if not part.empty:
            groups.append(part.assign(contact_model=model))
    return pd.concat(groups, ignore_index=True) if groups else pd.DataFrame()


# -------------------------------------------------------------- verification
def read_convergence(paths) -> pd.DataFrame:
    """Read and stack convergence tables (``lsbg convergence``).

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or lacks a column of
        :data:`lsbg.experiments.verification.COLUMNS`.
    """
    from lsbg.experiments.verification import COLUMNS

    tables = []
    for path in as_path_list(paths):
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such convergence table")
        table = pd.read_csv(path)
        missing = [c for c in COLUMNS if c not in table.columns]
        if missing:
            raise ValueError(f"{path}: not a convergence table (missing columns {missing})")
        tables.append(table[list(COLUMNS)])
    if not tables:
        raise ValueError("no convergence tables given")
    return pd.concat(tables, ignore_index=True)


def convergence_table(table) -> pd.DataFrame:
    """Convergence table with the relative difference to the tightest tolerance run.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`read_convergence`.

    Returns
    -------
    pandas.DataFrame
        ``table`` plus, per design point and contact model,
        ``<column>_rel_diff_percent`` for the output samples' and the
        full-rate standard deviations of gear speed and tangential force:
        100 (std − std_ref) / std_ref with std_ref from the run of the
        smallest rtol (the scipy run where scipy and compiled tie), and
        ``reference``, that run's engine and rtol.
    """
    out = table.copy()
    for column in _CONVERGENCE_DIFFERENCES:
        out[f"{column}_rel_diff_percent"] = np.nan
    out["reference"] = ""
    for _, part in out.groupby(["trace", "spiral_angle_deg", "contact_model"]):
        tolerance = part[part["parameter"] == "rtol"]
        if tolerance.empty:
            continue
        tightest = tolerance[np.isclose(tolerance["value"], tolerance["value"].min(), rtol=1e-9, atol=0)]
        ref = tightest.sort_values("engine", key=lambda e: e != "scipy").iloc[0]
        out.loc[part.index, "reference"] = f"{ref['engine']} rtol {ref['value']:g}"
        for column, source in _CONVERGENCE_DIFFERENCES.items():
            out.loc[part.index, f"{column}_rel_diff_percent"] = (
                100 * (part[source] - ref[source]) / ref[source])
    return out


# Relative difference columns of convergence_table -> their source column.
_CONVERGENCE_DIFFERENCES = {
    "gear_speed_std": "gear_speed_std_deg_s",
    "tangential_force_std": "tangential_force_std_N",
    "gear_speed_full_std": "gear_speed_full_std_deg_s",
    "tangential_force_full_std": "tangential_force_full_std_N",
}


def pressure_angle_table(geometry_dirs) -> pd.DataFrame:
    """Normal pressure angles measured on the flanks at the mean point.

    Returns
    -------
    pandas.DataFrame
        Per gear type, member and side: ``measured_deg``, ``design_deg``
        (the design's αn) and ``deviation_deg``.
    """
    rows = []
    for label, record in records_by_type(geometry_dirs).items():
        for member in ("pinion", "gear"):
            for side in ("drive", "coast"):
                measured = record[f"normal_pressure_angle_mean_{member}_{side}_deg"]
                design = record["normal_pressure_angle_deg"]
                rows.append({"gear_type": label, "member": member, "side": side,
                             "measured_deg": measured, "design_deg": design,
                             "deviation_deg": measured - design})
    return pd.DataFrame(rows)


# ------------------------------------------------ the checks (lsbg checks)
#: Columns of :func:`ltca_check_table` read from the design point's loaded TCA
#: (``lsbg ltca``): column -> its attribute.
_MESH_COLUMNS = {"mean_stiffness_N_per_um": "mesh_stiffness_mean_N_per_um",
                 "closed_form_N_per_um": "mean_mesh_stiffness_closed_form_N_per_um",
                 "c_gamma_N_per_mm_um": "mesh_stiffness_per_face_width_N_per_mm_um"}
#: Columns of :func:`ltca_check_table` from ``lsbg checks`` and of
#: :func:`contact_state_check_table`: column -> variable of the checks' dataset.
_LTCA_COLUMNS = {"unloaded_te_max_rad": "unloaded_te_max", "linearity_error": "linearity_error",
                 "te_pp_slices_x2_change_percent": "te_pp_slices_x2_change",
                 "te_pp_slices_x4_change_percent": "te_pp_slices_x4_change",
                 "k_l_for_c_gamma_20_N_per_mm_um": "calibrated_line_stiffness"}
_CONTACT_STATE_COLUMNS = {"conjugate_te_pp_rad": "conjugate_te_pp",
                          "backlash_error": "backlash_error",
                          "crowned_te_pp_urad": "crowned_te_pp",
                          "designed_te_pp_urad": "designed_te_pp",
                          "line_model_te_difference": "line_model_te_difference",
                          "pattern_shift_plus_mm": "pattern_shift_plus",
                          "pattern_shift_minus_mm": "pattern_shift_minus"}


def read_checks(paths, types=None) -> dict:
    """The checks of the design points (``lsbg checks``), by gear type.

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        Files of :func:`lsbg.experiments.point_checks.design_point_checks`.
    types : sequence of str, optional
        The gear types a report needs, in its order.

    Returns
    -------
    dict
        ``{gear type: xarray.Dataset}`` in the order of ``types``, else of
        ``paths``.

    Raises
    ------
    lsbg.files.InputError
        Naming a file that is missing or not a checks dataset.
    ValueError
        Naming a gear type of ``types`` that no file holds.
    """
    from lsbg.experiments.point_checks import CHECK_VARIABLES, CONJUGACY_VARIABLES
    from lsbg.files import open_dataset

    checks = {}
    for path in as_path_list(paths):
        ds = open_dataset(path, "checks", (*CHECK_VARIABLES, *CONJUGACY_VARIABLES),
                          ("design_trace", "load_torque_N_m", "contact_slices"),
                          "a checks dataset of lsbg checks")
        checks[TRACE_LABELS.get(ds.attrs["design_trace"], ds.attrs["design_trace"])] = ds
    if types is None:
        return checks
    missing = [t for t in types if t not in checks]
    if missing:
        raise ValueError(f"checks_files: no checks of the {', '.join(missing)} (lsbg checks "
                         f"at its design point)")
    return {t: checks[t] for t in types}


def ltca_check_table(checks, meshes) -> pd.DataFrame:
    """The loaded TCA's checks, one row per gear type.

    Parameters
    ----------
    checks : dict
        ``{gear type: dataset}`` of :func:`read_checks`; the rows follow it.
    meshes : dict
        ``{gear type: dataset}`` of the same design points' loaded TCAs
        (``lsbg ltca``): their mean mesh stiffness, its closed form and c_gamma.

    Returns
    -------
    pandas.DataFrame
        ``gear_type``, ``unloaded_te_max_rad``, ``mean_stiffness_N_per_um``,
        ``closed_form_N_per_um``, ``c_gamma_N_per_mm_um``,
        ``linearity_error``, ``te_pp_slices_x2_change_percent``,
        ``te_pp_slices_x4_change_percent``, ``k_l_for_c_gamma_20_N_per_mm_um``.
    """
    rows = []
    for label, ds in checks.items():
        row = {"gear_type": label, "unloaded_te_max_rad": float(ds["unloaded_te_max"])}
        row.update({column: meshes[label].attrs[name] for column, name in _MESH_COLUMNS.items()})
        row.update({column: float(ds[name]) for column, name in _LTCA_COLUMNS.items()
                    if column not in row})
        rows.append(row)
    return pd.DataFrame(rows)


def contact_state_check_table(checks) -> pd.DataFrame:
    """The contact state's checks, one row per gear type.

    Parameters
    ----------
    checks : dict
        ``{gear type: dataset}`` of :func:`read_checks`; the rows follow it.

    Returns
    -------
    pandas.DataFrame
        ``gear_type`` and the answers of
        :func:`lsbg.experiments.point_checks.contact_state_checks`
        (``conjugate_te_pp_rad``, ``backlash_error``, ``crowned_te_pp_urad``,
        ``designed_te_pp_urad``, ``line_model_te_difference``,
        ``pattern_shift_plus_mm``, ``pattern_shift_minus_mm``), then
        ``designed_te_difference``: the surfaces' TE over the closed form − 1.
    """
    table = pd.DataFrame([{"gear_type": label, **{column: float(ds[name]) for column, name
                                                   in _CONTACT_STATE_COLUMNS.items()}}
                          for label, ds in checks.items()])
    table["designed_te_difference"] = table.crowned_te_pp_urad / table.designed_te_pp_urad - 1
    return table


def conjugacy_table(ds) -> pd.DataFrame:
    """A design point's conjugacy errors (``lsbg checks``) as a table.

    Returns
    -------
    pandas.DataFrame
        Per mesh position: ``phase_deg``, ``pinion_distance_m``,
        ``gear_distance_m`` [m] and ``normal_mismatch`` [-], as
        :func:`lsbg.experiments.point_checks.conjugacy_errors` gives them.
    """
    return pd.DataFrame({"phase_deg": ds["phase"].values,
                         "pinion_distance_m": ds["conjugacy_pinion_distance"].values,
                         "gear_distance_m": ds["conjugacy_gear_distance"].values,
                         "normal_mismatch": ds["conjugacy_normal_mismatch"].values})


def check_settings(checks) -> dict:
    """``{gear type: (load torque [N m], slices)}`` of the loaded TCAs the checks ran."""
    return {label: (float(ds.attrs["load_torque_N_m"]), ds.attrs["contact_slices"])
            for label, ds in checks.items()}


def resonance_of(checks, engine=None) -> dict:
    """The contact resonance of each gear type (``lsbg checks``).

    Parameters
    ----------
    checks : dict
        ``{gear type: dataset}`` of :func:`read_checks`.
    engine : str, optional
        The engine whose point-model run the report discusses: a check
        computed on another engine's run is refused.

    Returns
    -------
    dict
        ``{gear type: {"frequency_hz", "frequency_min_hz", "frequency_max_hz",
        "stiffness_N_m_per_rad"}}`` as
        :func:`lsbg.experiments.point_checks.contact_resonance` gives them.

    Raises
    ------
    ValueError
        Naming the gear type whose checks ran on another engine's run.
    """
    out = {}
    for label, ds in checks.items():
        ran = ds.attrs.get("resonance_run_engine", "")
        if engine is not None and ran != engine:
            raise ValueError(f"{ds.encoding.get('source', label)}: its resonance is of the "
                             f"{ran} engine's run, not the {engine} engine's")
        out[label] = {key: float(ds[name]) for key, name in (
            ("frequency_hz", "resonance_frequency"), ("frequency_min_hz", "resonance_frequency_min"),
            ("frequency_max_hz", "resonance_frequency_max"),
            ("stiffness_N_m_per_rad", "resonance_stiffness"))}
    return out


# ------------------------------------------------------------- as shown
def setting_label(engine, parameter, value, is_default=False) -> str:
    """An engine setting of the convergence study as words.

    Parameters
    ----------
    engine : str
    parameter : str
        ``time_step_s`` or ``rtol`` (others are shown as ``parameter = value``).
    value : float
    is_default : bool
        Whether it is the engine's default (the study's runs); adds "(default)".

    Returns
    -------
    str
        e.g. "pybullet dt = 1 µs (default)", "compiled rtol = 10⁻⁸".
    """
    value = float(value)
    if parameter == "time_step_s":
        text = f"dt = {value * 1e6:.4g} µs"
    else:
        text = (f"{'rtol' if parameter == 'rtol' else parameter.replace('_', ' ')} = "
                f"{format_number(value, 3)}")
    return f"{engine} {text}" + (" (default)" if is_default else "")


#: Columns of :func:`convergence_display` after ``gear_type`` and ``setting``:
#: each standard deviation followed by its relative difference to the reference run.
CONVERGENCE_DISPLAY_COLUMNS = (
    "gear_speed_std_deg_s", "gear_speed_std_rel_diff_percent",
    "gear_speed_full_std_deg_s", "gear_speed_full_std_rel_diff_percent",
    "tangential_force_std_N", "tangential_force_std_rel_diff_percent",
    "tangential_force_full_std_N", "tangential_force_full_std_rel_diff_percent",
    "wall_time_s",
)


def convergence_display(table) -> pd.DataFrame:
    """A convergence table (:func:`convergence_table`) narrowed for a page.

    One row per run, in the table's order: ``gear_type`` (LSBG, SBG),
    ``setting`` (:func:`setting_label`: engine, parameter and value in one
    cell), the four standard deviations each followed by its relative
    difference to the reference run, and the wall time
    (:data:`CONVERGENCE_DISPLAY_COLUMNS`). The columns that are the same in
    every row of one report table (trace with gear type, spiral angle,
    contact model, reference) and the means and step counts are left out;
    the complete table is the one to attach.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`convergence_table`, typically one contact model's rows.

    Returns
    -------
    pandas.DataFrame
        A new table; the numbers are the input's.
    """
    shown = pd.DataFrame({
        "gear_type": [TRACE_LABELS.get(t, t) for t in table["trace"]],
        "setting": [setting_label(e, p, v, d) for e, p, v, d in
                    zip(table["engine"], table["parameter"], table["value"],
                        table["is_default"])],
    }, index=table.index)
    for column in CONVERGENCE_DISPLAY_COLUMNS:
        shown[column] = table[column].to_numpy()
    return shown.reset_index(drop=True)


def by_gear_type(table, rows, types=("SBG", "LSBG")) -> pd.DataFrame:
    """A table with one row per gear type turned to one row per quantity.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per gear type (column ``gear_type``).
    rows : sequence of (str, str, str)
        ``(column, label, unit)`` per row of the result, in order.
    types : sequence of str
        Gear types as columns, in this order; those absent from ``table`` are
        left out.

    Returns
    -------
    pandas.DataFrame
        Columns ``check`` (the label), ``unit`` and one per gear type.
    """
    by_type = table.set_index("gear_type")
    present = [t for t in types if t in by_type.index]
    out = pd.DataFrame({"check": [label for _, label, _ in rows],
                        "unit": [unit for _, _, unit in rows]})
    for gear in present:
        out[gear] = [float(by_type.at[gear, column]) for column, _, _ in rows]
    return out


# ------------------------------------ the checks, each against a derived bound
def _engine_rows(add, convergence, agreement):
    """The engines' checks: each difference against both runs' integration errors."""
    stats = ["gear_speed_std_rel_diff_percent", "tangential_force_std_rel_diff_percent"]

    def error(part, value):   # [%] the change from the next coarser setting; first-order
        row, coarser = part[np.isclose(part.value, value)], part[part.value > value * 1.000001]
        if row.empty or coarser.empty:   # Richardson (over 2 - 1) for a time step
            return float("nan")
        coarse = coarser.sort_values("value").iloc[0]
        change = max(abs(float(row[q].iloc[0]) - float(coarse[q])) for q in stats)
        return change / (coarse.value / value - 1) if coarse.parameter == "time_step_s" \
            else change

    errors = {}   # (trace, model, engine): its default run's error, the reference's [%]
    for (trace, model), part in convergence.groupby(["trace", "contact_model"]):
        ref = str(part.reference.iloc[0]).split() or ["", "", "nan"]
        own = error(part[part.engine == ref[0]], float(ref[2]))
        for r in part[part.is_default].itertuples():
            errors[trace, model, r.engine] = (error(part[part.engine == r.engine], r.value), own)
    default = convergence[convergence.is_default]
    pybullet = default[default.engine == "pybullet"].groupby("contact_model", sort=False)
    for model, part in [*pybullet, (None, default[default.engine == "compiled"])]:
        if not part.empty:
            add(f"pybullet_{model}" if model else "compiled",
                (f"{model} model: PyBullet at its default time step" if model else
                 "compiled engine at its default rtol") + " agrees with the reference run",
                part[stats].abs().max(axis=1),
                [sum(errors[r.trace, r.contact_model, r.engine]) for r in part.itertuples()],
                " %", ("first-order time-step error, by Richardson from twice the step" if model
                       else "the change from 100 rtol") + ", plus the reference run's own")
    if agreement is not None and not agreement.empty:
        trace = {label: t for t, label in TRACE_LABELS.items()}
        add("agreement", "engines agree on the standard deviations",
            100 * (agreement.std_ratio - 1).abs(),
            [sum(errors.get((trace.get(r.gear_type), r.contact_model, e), (np.nan,))[0]
                 for e in (r.engine, r.reference)) for r in agreement.itertuples()], " %",
            "both engines' errors as above: one model from one state differs by integration "
            "error, not by sampling (Section 2: the study's 3 % band)")


def verification_checks(checks, meshes, records, convergence=None, agreement=None):
    """The verification report's checks, each value against its bound and the reason.

    Parameters
    ----------
    checks, meshes, records : dict
        ``{gear type: ...}``: the checks (:func:`read_checks`), loaded TCAs
        (``lsbg ltca``) and design records (``lsbg geometry``); may be empty.
    convergence, agreement : pandas.DataFrame, optional
        :func:`convergence_table`, :func:`agreement_by_model` (the engines').

    Returns
    -------
    pandas.DataFrame
        Per check (docs/model.md, "The verification checks' bounds"): ``key``,
        ``check``, ``value``, ``bound`` [``unit``] of the case shown (the
        largest, or the worst failing), ``result``, ``bound_text`` as shown,
        ``reason``, ``pass`` (every case within its bound).
    """
    from lsbg.experiments.point_checks import EPS, ROUNDINGS, point_check_rows

    columns = ["key", "check", "value", "bound", "unit", "result", "bound_text", "reason",
               "pass"]
    rows, eps = [], ROUNDINGS * EPS   # float64 round-off of a computed point, normal or angle

    def add(key, what, values, bounds, unit, reason, result=None, bound_text=None, ok=None):
        values = np.atleast_1d(np.asarray(values, float))
        bounds = np.broadcast_to(np.asarray(bounds, float), values.shape)
        good = values <= bounds
        i = int(np.argmax(values if good.all() else np.where(good, -np.inf, values / bounds)))
        rows.append({"key": key, "check": what, "value": values[i], "bound": bounds[i],
                     "unit": unit.strip(), "result": result or f"{_number(values[i])}{unit}",
                     "bound_text": bound_text or (f"≤ {_number(bounds[i])}{unit}" if np.isfinite(
                         bounds[i]) else "none: what it needs is missing"),
                     "reason": reason, "pass": bool(good.all() if ok is None else ok)})

    if convergence is not None and not convergence.empty:
        _engine_rows(add, convergence, agreement)
    for label, r in records.items():   # the trace's closed form, sin beta_p(rho) of a circle
        rho, beta = np.asarray(r["cone_distance_along_face_mm"]), r["spiral_angle_along_face_deg"]
        plane, rm, rc = (math.radians(abs(r["plane_spiral_angle_mean_deg"])) + 0 * rho,
                         r["mean_cone_distance_mm"], r["cutter_radius_mm"])
        if r["trace"] == "circular":
            plane = np.arcsin((rho**2 - rm**2 + 2 * rm * rc * np.sin(plane)) / (2 * rho * rc))
        milled = r["trace"] == "face_milled"  # ISO 23509's closed form, at every R
        curve = np.degrees(face_milled_spiral_angle(
            rho, rm, rc, math.radians(r["spiral_angle_deg"])) if milled else np.arctan(
            np.tan(plane) / math.cos(math.radians(r["plane_of_action_tilt_deg"]))))
        closed = np.ptp(curve)
        # the tangent: a central difference over +-1e-6 R_e of points off by eps R_e
        bound = 2 * math.degrees((eps * 1e6 + 2 * EPS) / math.sin(math.radians(min(beta)))
                                 + (1e-6 * r["outer_cone_distance_mm"] / rho.min())**2)
        add(f"spiral_{label}", f"{label} spiral angle " + ("varies along the face as its "
            "cutter's circle" if closed else "constant along the face"),
            np.abs(np.asarray(beta) - curve) if milled else abs(np.ptp(beta) - closed), bound,
            "°", ("ISO 23509's sin β(R) of the circle in the pitch plane at every R" if milled
                  else "closed form tan β = tan β_p(ρ)/cos γ") + ", ± "
            "twice the round-off of an arccos of points 16 ε R_e off, ±10⁻⁶ R_e apart",
            result=f"{_number(np.ptp(beta), 3 if closed else 2)}°",
            bound_text=f"{_number(closed, 6)} ± {_number(bound)}°" if closed else None)
    if not checks:
        return pd.DataFrame(rows, columns=columns)
    names = [f"normal_pressure_angle_mean_{m}_{s}_deg" for m in ("pinion", "gear")
             for s in ("drive", "coast")]
    add("pressure_angle", "normal pressure angle equals the design value",
        [abs(r[n] - r["normal_pressure_angle_deg"]) for r in records.values() for n in names],
        [math.degrees(eps / math.cos(math.radians(r["normal_pressure_angle_deg"])))
         for r in records.values() for n in names], "°",
        "round-off: the arcsin of a dot product of unit vectors 16 ε off, over cos α_n")
    r = [records[label] for label in checks]
    add("conjugacy", "flanks conjugate: distance to the contact line",
        [max(d.conjugacy_pinion_distance.max(), d.conjugacy_gear_distance.max())
         for d in checks.values()],
        [(eps + 2 * EPS / math.sin(math.radians(x["base_cone_angle_pinion_deg"])))
         * x["outer_cone_distance_mm"] * 1e-3 for x in r], " m", "round-off at the flank's "
        "scale: 16 ε R_e, and 2 ε R_e / sin δ_b1 from the polar angle's arccos")
    point_check_rows(add, checks, meshes, r, eps, _number)
    return pd.DataFrame(rows, columns=columns)


def _number(value, digits=2):
    return format_number(float(value), digits)

