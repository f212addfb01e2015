"""A study of many runs: the sweep dataset, the summary table and report pieces.

The workflow simulates every design point (trace x spiral angle) with one
engine and the paper's design point with reference engines too; each run is
one NetCDF file of :mod:`lsbg.results`. This module is the stage after the
runs (DESIGN.md §1):

* :func:`combine_runs` stacks the runs of one engine into the sweep dataset
  (dims trace, spiral_angle, time; CF-1.11), ``lsbg combine``;
* :func:`summary_table` tabulates the paper's §4 statistics of every run and
  quantity (mean, std, Anderson–Darling, Table 3 error, Xbar-R alarms),
  ``lsbg summary``;
* the remaining functions build the tables and figures of the reports
  (``workflow/notebooks/*.ipynb``), so that the notebooks only call them and
  phrase the results. All statistics come from :mod:`lsbg.stats`.

Units are those of the run datasets (the paper's): speeds in deg/s, forces in
N, angles in degrees, lengths in mm.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3–4, Figs. 8–18 and
   Tables 1–3.
"""

from __future__ import annotations

import datetime
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

import lsbg
from lsbg import stats
from lsbg.contact.law import CONTACT_MODELS
from lsbg.design import TRACE_LABELS, TRACES
from lsbg.files import read_record
from lsbg.figures.base import TYPE_COLORS, new_figure, type_color
from lsbg.results import (FULL_RATE_VARIABLES, VARIABLES, as_path_list, open_dataset, open_run,
                          open_runs)

__all__ = [
    "TRACE_LABELS", "QUANTITIES", "QUANTITY_LABELS", "THEORY_ATTRIBUTES", "SUMMARY_QUANTITIES",
    "FULL_RATE_OF", "SUMMARY_COLUMNS", "POINT_VARIABLES", "STATISTICS_KEYS", "PAPER",
    "full_rate_series", "mesh_summary", "open_mesh",
    "open_run", "open_runs", "open_pair", "select_runs", "gear_type", "steady", "as_path_list",
    "combine_runs", "statistics_options", "quantity_summary", "summary_table",
    "design_table", "theory_table", "paper_comparison_table",
    "compare_types", "fluctuation_table", "fluctuation_conclusion", "engine_agreement",
    "contact_resonance", "control_charts",
    "plot_pair_pictures", "plot_time_series", "plot_steady_scatter", "plot_normality",
    "plot_boxplots",
    "plot_control_charts",
    "sweep_table", "sweep_ratio_table", "plot_sweep", "plot_sweep_ratio",
    "read_convergence", "convergence_table", "plot_convergence", "plot_engine_agreement",
    "pressure_angle_table", "plot_spiral_angle_along_face", "plot_pressure_angles",
    "conjugacy_errors", "plot_conjugacy",
]


#: Quantities of the summary table (variables of a run dataset).
QUANTITIES = ("gear_speed", "tangential_force", "tangential_force_outer")
#: Axis labels of run variables (units come from the dataset).
QUANTITY_LABELS = {
    "pinion_speed": "pinion angular velocity",
    "gear_speed": "gear angular velocity",
    "tangential_force": "tangential contact force",
    "tangential_force_outer": "tangential force at d2/2",
    "contact_torque": "contact torque",
    "normal_force": "normal contact force",
    "contact_pairs": "tooth pairs in contact",
    "max_penetration": "maximum penetration",
    "transmission_error": "transmission error",
}
#: Quantity -> run attribute holding its theoretical value (Eq. 12 / Eq. 13;
#: the contact torque must balance the load).
THEORY_ATTRIBUTES = {
    "gear_speed": "theory_gear_speed_deg_s",
    "tangential_force": "theory_tangential_force_N",
    "tangential_force_outer": "theory_tangential_force_N",
    "contact_torque": "solver_load_torque_N_m",
}
#: Quantities of the summary table: the paper's, the transmission error and
#: the contact torque.
SUMMARY_QUANTITIES = QUANTITIES + ("transmission_error", "contact_torque")
#: Summary quantity -> (full-rate variable of the run, divide by the outer
#: pitch radius d2/2).
FULL_RATE_OF = {
    "gear_speed": ("gear_speed_full", False),
    "tangential_force": ("tangential_force_full", False),
    "tangential_force_outer": ("contact_torque_full", True),
    "transmission_error": ("transmission_error_full", False),
    "contact_torque": ("contact_torque_full", False),
}
#: Columns of :func:`summary_table`. Runs: the paper's §4 statistics of the
#: output samples, then the full-rate ones (std, the spread of the sample
#: std over sampling phases, the dynamic factor on the contact-torque row).
#: Loaded TCA (engine "ltca"): the static transmission error's peak to peak
#: and mesh harmonics, and the mesh stiffness.
SUMMARY_COLUMNS = ("trace", "spiral_angle_deg", "contact_model", "engine", "run", "quantity",
                   "mean", "std", "ad_statistic", "ad_pvalue", "theory", "error_rate_percent",
                   "out_of_control", "full_rate_std", "sampling_std_min", "sampling_std_max",
                   "dynamic_factor", "peak_to_peak", "harmonic_1", "harmonic_2", "harmonic_3")
#: Run attribute -> (variable of the sweep dataset, units, long_name): one
#: value per design point.
POINT_VARIABLES = {
    "design_contact_ratio": ("contact_ratio", "1", "total contact ratio (drive side)"),
    "design_contact_ratio_profile": ("contact_ratio_profile", "1",
                                     "profile (transverse) contact ratio"),
    "design_contact_ratio_face": ("contact_ratio_face", "1", "face (overlap) contact ratio"),
    "theory_gear_speed_deg_s": ("theory_gear_speed", "deg/s",
                                "gear angular velocity of a rigid pair, Eq. 12"),
    "theory_tangential_force_N": ("theory_tangential_force", "N",
                                  "load torque over the outer pitch radius d2/2, Eq. 13"),
    "design_base_cone_angle_pinion_deg": ("base_cone_angle_pinion", "degree",
                                          "base cone angle of the pinion"),
    "design_base_cone_angle_gear_deg": ("base_cone_angle_gear", "degree",
                                        "base cone angle of the gear"),
    "design_plane_spiral_angle_mean_deg": ("plane_spiral_angle", "degree",
                                           "angle of the generating curve to the ray at the "
                                           "mean point, in the plane of action"),
    "axial_inertia_gear_kg_m2": ("axial_inertia_gear", "kg m2",
                                 "axial moment of inertia of the gear"),
    "axial_inertia_pinion_kg_m2": ("axial_inertia_pinion", "kg m2",
                                   "axial moment of inertia of the pinion"),
    "wall_time_s": ("wall_time", "s", "wall-clock time of the run"),
    "integrator_steps": ("integrator_steps", "1", "integrator steps (right-hand side "
                                                  "evaluations for scipy)"),
}
#: Keys of the study configuration's ``statistics`` section -> keyword of
#: :func:`summary_table`.
STATISTICS_KEYS = {"steady_state_after_s": "steady_state_after",
                   "control_chart_window_s": "window", "subgroup_size": "subgroup_size"}

#: The paper's published results (§4.1 and Table 3), per gear type and
#: quantity: mean, std, A², p, Table 3's theory, difference and error rate.
PAPER = {
    ("SBG", "gear_speed"): dict(mean=1872.69, std=21.55, ad_statistic=0.293, ad_pvalue=0.601,
                                theory=1873.703, difference=1.013, error_rate_percent=0.054),
    ("LSBG", "gear_speed"): dict(mean=1873.77, std=12.67, ad_statistic=0.264, ad_pvalue=0.697,
                                 theory=1873.703, difference=0.067,
                                 error_rate_percent=0.0036),
    ("SBG", "tangential_force"): dict(mean=24799.9, std=550.4, ad_statistic=0.514,
                                      ad_pvalue=0.192, theory=23603.48, difference=1196.42,
                                      error_rate_percent=4.82),
    ("LSBG", "tangential_force"): dict(mean=24747.5, std=280.0, ad_statistic=0.581,
                                       ad_pvalue=0.130, theory=23603.48, difference=1144.02,
                                       error_rate_percent=4.85),
}

# Per-run attributes that do not describe the whole sweep.
_PER_RUN_ATTRIBUTES = {"Conventions", "title", "source", "history", "institution"}
# Order of gear types in tables and figures: the paper's (a) SBG, (b) LSBG.
_TYPE_ORDER = ("SBG", "LSBG")


# ---------------------------------------------------------------- run files
def open_pair(sbg_path, lsbg_path):
    """The SBG and LSBG runs of one design point, checked to be of those types.

    Parameters
    ----------
    sbg_path, lsbg_path : str or os.PathLike
        Run files; both ``""`` (or ``None``) means "not given".

    Returns
    -------
    dict or None
        ``{'SBG': run, 'LSBG': run}``, or None if neither path is given.

    Raises
    ------
    ValueError
        If only one path is given, or a run is of the other gear type.
    """
    given = [bool(as_path_list(p)) for p in (sbg_path, lsbg_path)]
    if not any(given):
        return None
    if not all(given):
        raise ValueError(f"give both the SBG and the LSBG run, or neither "
                         f"(got SBG {sbg_path!r}, LSBG {lsbg_path!r})")
    runs = {"SBG": open_run(sbg_path), "LSBG": open_run(lsbg_path)}
    for label, ds in runs.items():
        if gear_type(ds) != label:
            raise ValueError(f"{_source(ds)}: a {gear_type(ds)} run "
                             f"({ds.attrs['design_trace']} trace) given as the {label} run")
    return runs


def select_runs(runs, contact_model=None, engine=None) -> dict:
    """The SBG and LSBG run of one contact model and engine.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
    contact_model : str, optional
        ``contact_model`` attribute to match.
    engine : str, optional
        ``solver_engine`` attribute to match.

    Returns
    -------
    dict
        ``{gear type: run}`` in the paper's order.

    Raises
    ------
    ValueError
        If a gear type matches twice.
    """
    chosen = [ds for ds in runs
              if (contact_model is None or ds.attrs["contact_model"] == contact_model)
              and (engine is None or ds.attrs["solver_engine"] == engine)]
    return _by_type(chosen)


def gear_type(ds) -> str:
    """The paper's name of a run's gear type: 'LSBG' or 'SBG'."""
    trace = ds.attrs["design_trace"]
    return TRACE_LABELS.get(trace, trace)


def _spiral_angle(ds):
    """The run's mean spiral angle [deg], rounded to 1e-9 deg (30, not 29.999999999999996)."""
    return round(float(ds.attrs["design_spiral_angle_deg"]), 9)


def _source(ds):
    return ds.encoding.get("source", "<dataset>")


def steady(ds, name, start=0.2) -> np.ndarray:
    """Steady-state samples (time > ``start``) of a run variable [its units].

    Parameters
    ----------
    ds : xarray.Dataset
        Run dataset.
    name : str
        Variable, e.g. ``'gear_speed'``.
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    numpy.ndarray
    """
    return stats.steady_state(ds[name].values, ds["time"].values, start)


def _label(ds, name):
    """(axis label, units) of a run variable."""
    return QUANTITY_LABELS.get(name, name.replace("_", " ")), ds[name].attrs.get("units", "")


def _by_type(runs):
    """{gear type: dataset} in the paper's order, from a dict or a list of runs."""
    if isinstance(runs, dict):
        items = dict(runs)
    else:
        items = {}
        for ds in runs:
            label = gear_type(ds)
            if label in items:
                raise ValueError(f"{_source(ds)}: a second {label} run (also "
                                 f"{_source(items[label])})")
            items[label] = ds
    order = [t for t in _TYPE_ORDER if t in items] + [t for t in items if t not in _TYPE_ORDER]
    return {t: items[t] for t in order}


# ----------------------------------------------------------------- combine
#: Loaded-TCA attribute -> (variable of the sweep dataset, units, long_name).
MESH_VARIABLES = {
    "transmission_error_peak_to_peak_urad": (
        "static_transmission_error_peak_to_peak", "urad",
        "peak-to-peak loaded static transmission error (line model)"),
    "transmission_error_harmonic_1_urad": (
        "static_transmission_error_harmonic_1", "urad",
        "first mesh harmonic of the loaded static transmission error"),
    "transmission_error_harmonic_2_urad": (
        "static_transmission_error_harmonic_2", "urad",
        "second mesh harmonic of the loaded static transmission error"),
    "transmission_error_harmonic_3_urad": (
        "static_transmission_error_harmonic_3", "urad",
        "third mesh harmonic of the loaded static transmission error"),
    "mesh_stiffness_mean_N_per_um": ("mesh_stiffness_mean", "N/um",
                                     "mean mesh stiffness along the line of action"),
    "mesh_stiffness_per_face_width_N_per_mm_um": (
        "mesh_stiffness_per_face_width", "N/(mm um)",
        "mean mesh stiffness per unit face width (c_gamma)"),
    "mesh_stiffness_peak_to_peak_N_per_um": (
        "mesh_stiffness_peak_to_peak", "N/um", "peak-to-peak mesh stiffness over a mesh cycle"),
    "mesh_stiffness_variation_percent": (
        "mesh_stiffness_variation", "percent",
        "peak-to-peak mesh stiffness over its mean"),
}


def combine_runs(paths, meshes=()) -> xr.Dataset:
    """Stack the runs of one engine, and the loaded TCAs, into the sweep dataset.

    Parameters
    ----------
    paths : sequence of str or os.PathLike
        Run files (``lsbg simulate``), one per contact model and design
        point, all of the same engine and time axes.
    meshes : sequence of str or os.PathLike
        Loaded-TCA files (``lsbg ltca``), at most one per design point.

    Returns
    -------
    xarray.Dataset
        Dims (contact_model, trace, spiral_angle, time) and time_full.
        Coordinates ``contact_model``, ``trace`` (with ``gear_type``:
        'LSBG'/'SBG'), ``spiral_angle`` [degree], ``time``, ``time_full`` [s];
        the run variables of :data:`lsbg.results.VARIABLES` on (contact_model,
        trace, spiral_angle, time) and those of
        :data:`lsbg.results.FULL_RATE_VARIABLES` on (..., time_full); per
        design point the variables of :data:`POINT_VARIABLES` and, from the
        loaded TCAs, :data:`MESH_VARIABLES` and the ``static_transmission_error``
        and ``mesh_stiffness`` curves on (trace, spiral_angle, mesh_phase).
        Missing combinations are NaN. Global attributes: CF-1.11 ``title``,
        ``source``, ``history``, ``Conventions``, and every run attribute
        that all runs share (e.g. ``solver_engine``).

    Raises
    ------
    ValueError
        If no run is given, a file is not a run or loaded-TCA dataset, the
        engines or the time axes differ, or a point occurs twice; the message
        names the file.
    FileNotFoundError
        If a file is missing.
    """
    paths = as_path_list(paths)
    if not paths:
        raise ValueError("no run files given")
    runs = [open_run(p) for p in paths]
    first, first_path = runs[0], paths[0]
    engine = first.attrs["solver_engine"]
    axes = {name: first[name].values for name in ("time", "time_full")}
    points = {}
    for path, ds in zip(paths, runs):
        if ds.attrs["solver_engine"] != engine:
            raise ValueError(f"{path}: engine {ds.attrs['solver_engine']!r} differs from "
                             f"{engine!r} of {first_path}; combine the runs of one engine")
        for name, axis in axes.items():
            t = ds[name].values
            spacing = float(np.median(np.diff(axis))) if axis.size > 1 else 1.0
            if t.shape != axis.shape or not np.allclose(t, axis, rtol=0.0, atol=1e-9 * spacing):
                raise ValueError(f"{path}: {name} axis ({t.size} samples, {t[0]:g}–{t[-1]:g} s) "
                                 f"differs from that of {first_path} ({axis.size} samples, "
                                 f"{axis[0]:g}–{axis[-1]:g} s)")
        key = (ds.attrs["contact_model"], ds.attrs["design_trace"], _spiral_angle(ds))
        if key in points:
            raise ValueError(f"{path}: design point {key[1]}, {key[2]:g} deg ({key[0]} model) "
                             f"already given by {points[key][0]}")
        points[key] = (path, ds)
    mesh_data = {}
    for path in as_path_list(meshes):
        ds = open_mesh(path)
        key = (ds.attrs["design_trace"], round(float(ds.attrs["design_spiral_angle_deg"]), 9))
        if key in mesh_data:
            raise ValueError(f"{path}: design point {key[0]}, {key[1]:g} deg already given by "
                             f"{mesh_data[key][0]}")
        mesh_data[key] = (path, ds)
    models = [m for m in CONTACT_MODELS if m in {k[0] for k in points}]
    present = {k[1] for k in points} | {k[0] for k in mesh_data}
    traces = [t for t in TRACES if t in present] + sorted(present - set(TRACES))
    angles = sorted({k[2] for k in points} | {k[1] for k in mesh_data})
    shape = (len(models), len(traces), len(angles))
    names = {name: "time" for name in VARIABLES if all(name in ds for ds in runs)}
    names.update({name: "time_full" for name in FULL_RATE_VARIABLES if all(name in ds for ds in runs)})
    data = {name: np.full(shape + axes[axis].shape, np.nan) for name, axis in names.items()}
    point_data = {attr: np.full(shape[1:], np.nan) for attr in POINT_VARIABLES}
    for (model, trace, angle), (_, ds) in points.items():
        m, i, j = models.index(model), traces.index(trace), angles.index(angle)
        for name in names:
            data[name][m, i, j] = ds[name].values
        for attr in POINT_VARIABLES:
            if attr in ds.attrs:
                point_data[attr][i, j] = float(ds.attrs[attr])
    out = xr.Dataset(coords={
        "contact_model": ("contact_model", models, {
            "long_name": "contact model (point: the paper's IMPACT incident per tooth pair; "
                         "line: sliced contact lines)"}),
        "trace": ("trace", traces, {"long_name": "tooth trace (logarithmic: LSBG, "
                                                 "circular: SBG)"}),
        "gear_type": ("trace", [TRACE_LABELS.get(t, t) for t in traces],
                      {"long_name": "gear type as named in the paper"}),
        "spiral_angle": ("spiral_angle", np.asarray(angles, dtype=float),
                         {"units": "degree", "long_name": "mean spiral angle on the pitch cone"}),
        "time": ("time", axes["time"], dict(first["time"].attrs)),
        "time_full": ("time_full", axes["time_full"], dict(first["time_full"].attrs)),
    })
    for name, axis in names.items():
        out[name] = (("contact_model", "trace", "spiral_angle", axis), data[name], {
            key: value for key, value in first[name].attrs.items()
            if key in ("units", "long_name", "standard_name")})
    for attr, (name, units, long_name) in POINT_VARIABLES.items():
        if np.isfinite(point_data[attr]).any():
            out[name] = (("trace", "spiral_angle"), point_data[attr],
                         {"units": units, "long_name": long_name})
    if mesh_data:
        phases = next(iter(mesh_data.values()))[1]["mesh_phase"]
        curves = {name: np.full(shape[1:] + phases.shape, np.nan)
                  for name in ("transmission_error", "mesh_stiffness")}
        values = {attr: np.full(shape[1:], np.nan) for attr in MESH_VARIABLES}
        for (trace, angle), (path, ds) in mesh_data.items():
            if ds.sizes["mesh_phase"] != phases.size:
                raise ValueError(f"{path}: {ds.sizes['mesh_phase']} mesh phases, the others "
                                 f"{phases.size}")
            i, j = traces.index(trace), angles.index(angle)
            for attr in MESH_VARIABLES:
                values[attr][i, j] = float(ds.attrs[attr])
            for name in curves:
                curves[name][i, j] = ds[name].values
        out = out.assign_coords(mesh_phase=("mesh_phase", phases.values, dict(phases.attrs)))
        for attr, (name, units, long_name) in MESH_VARIABLES.items():
            out[name] = (("trace", "spiral_angle"), values[attr],
                         {"units": units, "long_name": long_name})
        for name, curve in curves.items():
            source = next(iter(mesh_data.values()))[1][name]
            out[f"static_{name}" if name == "transmission_error" else name] = (
                ("trace", "spiral_angle", "mesh_phase"), curve, dict(source.attrs))
    shared = {key: value for key, value in first.attrs.items()
              if key not in _PER_RUN_ATTRIBUTES and key not in POINT_VARIABLES
              and all(key in ds.attrs and _same(ds.attrs[key], value) for ds in runs)}
    now = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    out.attrs.update({
        "Conventions": "CF-1.11",
        "title": f"Meshing simulations of spiral bevel gear pairs: "
                 f"{', '.join(TRACE_LABELS.get(t, t) for t in traces)} at spiral angles "
                 f"{', '.join(f'{a:g}' for a in angles)} deg ({engine} engine, "
                 f"{' and '.join(models)} contact model)",
        "source": f"lsbg {lsbg.__version__} (lsbg.study.combine_runs), engine {engine}",
        "institution": "lsbg reproducible research workflow",
        "history": f"{now} lsbg.study.combine_runs of {len(runs)} runs and {len(mesh_data)} "
                   f"loaded TCAs: " + ", ".join(Path(p).name for p in [*paths, *as_path_list(meshes)]),
        "lsbg_version": lsbg.__version__,
        **{key: value for key, value in shared.items() if key != "lsbg_version"},
    })
    out.attrs["solver_engine"] = engine
    return out


def _same(a, b):
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return bool(np.array_equal(np.asarray(a), np.asarray(b)))


# ----------------------------------------------------------------- summary
def statistics_options(config) -> dict:
    """Keywords of :func:`summary_table` from the study's ``statistics`` section.

    Parameters
    ----------
    config : dict or None
        Keys of :data:`STATISTICS_KEYS`: ``steady_state_after_s`` [s],
        ``control_chart_window_s`` ([start, stop], s) and ``subgroup_size``.

    Returns
    -------
    dict
        ``steady_state_after``, ``window``, ``subgroup_size`` for the keys given.

    Raises
    ------
    ValueError
        Naming ``statistics.<key>`` for an unknown key or a bad value.
    """
    if config is None:
        return {}
    if not isinstance(config, dict):
        raise ValueError(f"statistics = {config!r}: must be a mapping of keys")
    out = {}
    for key, value in config.items():
        if key not in STATISTICS_KEYS:
            raise ValueError(f"statistics.{key} = {value!r}: unknown key "
                             f"(known: {sorted(STATISTICS_KEYS)})")

        def bad(why, key=key, value=value):
            return ValueError(f"statistics.{key} = {value!r}: {why}")

        if key == "steady_state_after_s":
            if not _is_number(value) or value < 0:
                raise bad("must be a non-negative number [s]")
            out["steady_state_after"] = float(value)
        elif key == "control_chart_window_s":
            if (not isinstance(value, (list, tuple)) or len(value) != 2
                    or not all(_is_number(v) for v in value) or not 0 <= value[0] < value[1]):
                raise bad("must be [start, stop] with 0 <= start < stop [s]")
            out["window"] = (float(value[0]), float(value[1]))
        else:
            if isinstance(value, bool) or not isinstance(value, int) or value < 2:
                raise bad("must be a whole number >= 2")
            out["subgroup_size"] = int(value)
    return out


def _is_number(value):
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


def full_rate_series(ds, quantity, start=0.2):
    """The full-rate record of a summary quantity from ``start`` on (inclusive).

    Parameters
    ----------
    ds : xarray.Dataset
        Run dataset with a full-rate record.
    quantity : str
        One of :data:`FULL_RATE_OF`.
    start : float
        Start of the steady state [s].

    Returns
    -------
    numpy.ndarray
        [unit of the quantity].
    """
    name, per_outer_radius = FULL_RATE_OF[quantity]
    time = ds["time_full"].values
    spacing = float(time[1] - time[0]) if time.size > 1 else 1.0
    values = ds[name].values[time >= start - 1e-6 * spacing]
    if per_outer_radius:
        values = values / (float(ds.attrs["design_pitch_diameter_gear_mm"]) / 2e3)
    return values


def quantity_summary(ds, quantity, steady_state_after=0.2, window=(0.8, 1.0),
                     subgroup_size=4) -> dict:
    """The statistics of one quantity of one run: one row of :func:`summary_table`.

    Parameters
    ----------
    ds : xarray.Dataset
        Run dataset.
    quantity : str
        One of :data:`SUMMARY_QUANTITIES`.
    steady_state_after : float, default 0.2
        End of the transient [s]; the statistics use the samples after it.
    window : (float, float), default (0.8, 1.0)
        Window of the Xbar-R chart, start excluded, stop included [s].
    subgroup_size : int, default 4
        Subgroup size of the Xbar-R chart [-].

    Returns
    -------
    dict
        Keys :data:`SUMMARY_COLUMNS`: mean and std (ddof = 1) [unit of the
        quantity], A² and p, the theoretical value (from the run attributes;
        NaN for the transmission error), ``error_rate_percent`` =
        100 |mean − theory| / theory, ``out_of_control``, the number of
        subgroups beyond the Xbar or R limits; from the full-rate record its
        std, the least and largest std of the output sampling over all
        sampling phases, and (contact torque) the dynamic factor.

    Raises
    ------
    ValueError
        If the windows do not fit the run (e.g. no subgroups of that size).
    """
    from lsbg import spectra

    if quantity not in SUMMARY_QUANTITIES:
        raise ValueError(f"quantity = {quantity!r}: must be one of {SUMMARY_QUANTITIES}")
    values, time = ds[quantity].values, ds["time"].values
    x = stats.steady_state(values, time, steady_state_after)
    description = stats.describe(x)
    ad = stats.anderson_darling(x)
    theory_value = (float(ds.attrs[THEORY_ATTRIBUTES[quantity]])
                    if quantity in THEORY_ATTRIBUTES else np.nan)
    chart = stats.xbar_r_chart(stats.subgroups_from_window(values, time, window[0], window[1],
                                                           subgroup_size))
    full = full_rate_series(ds, quantity, steady_state_after)
    sample_rate = float(ds.attrs["solver_samples"]) / float(ds.attrs["solver_duration_s"])
    spread = spectra.sampling_phase_spread(full, float(ds.attrs["solver_full_rate_hz"]),
                                           sample_rate)
    return {
        "trace": ds.attrs["design_trace"],
        "spiral_angle_deg": _spiral_angle(ds),
        "contact_model": ds.attrs["contact_model"],
        "engine": ds.attrs["solver_engine"],
        "run": _run_name(ds),
        "quantity": quantity,
        "mean": description.mean,
        "std": description.std,
        "ad_statistic": ad.statistic,
        "ad_pvalue": ad.pvalue,
        "theory": theory_value,
        "error_rate_percent": (stats.compare_to_theory(description.mean,
                                                       theory_value).error_rate_percent
                               if np.isfinite(theory_value) else np.nan),
        "out_of_control": int(chart.out_of_control.size),
        "full_rate_std": spectra.rms_fluctuation(full),
        "sampling_std_min": float(spread.min()),
        "sampling_std_max": float(spread.max()),
        "dynamic_factor": (spectra.dynamic_factor(full, float(ds.attrs["solver_load_torque_N_m"]))
                           if quantity == "contact_torque" else np.nan),
    }


def _run_name(ds):
    """The run's file name without its extension ("" for a dataset not from a file)."""
    source = ds.encoding.get("source")
    return Path(source).stem if source else ""


def mesh_summary(ds) -> list:
    """Summary rows of a loaded TCA (:func:`lsbg.ltca.loaded_tca`).

    Returns
    -------
    list of dict
        Two rows, keys :data:`SUMMARY_COLUMNS` (engine "ltca"): the static
        transmission error [urad] (mean, std over the mesh cycle, peak to
        peak, first three mesh harmonics) and the mesh stiffness [N/um]
        (mean, std, peak to peak).
    """
    base = {column: np.nan for column in SUMMARY_COLUMNS}
    base.update(trace=ds.attrs["design_trace"],
                spiral_angle_deg=round(float(ds.attrs["design_spiral_angle_deg"]), 9),
                contact_model="line", engine="ltca", run=_run_name(ds), out_of_control=None)
    te, stiffness = ds["transmission_error"].values, ds["mesh_stiffness"].values
    harmonics = {f"harmonic_{h}": float(ds.attrs[f"transmission_error_harmonic_{h}_urad"])
                 for h in (1, 2, 3)}
    return [
        {**base, "quantity": "static_transmission_error", "mean": float(te.mean()),
         "std": float(te.std(ddof=1)), "peak_to_peak": float(np.ptp(te)), **harmonics},
        {**base, "quantity": "mesh_stiffness", "mean": float(stiffness.mean()),
         "std": float(stiffness.std(ddof=1)), "peak_to_peak": float(np.ptp(stiffness))},
    ]


def open_mesh(path):
    """Read a loaded-TCA dataset (``lsbg ltca``) into memory.

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or not a loaded-TCA dataset.
    """
    return open_dataset(path, "mesh", ("transmission_error", "mesh_stiffness"),
                        ("design_trace", "transmission_error_harmonic_1_urad"),
                        "a loaded-TCA dataset of lsbg.ltca")


def summary_table(paths, steady_state_after=0.2, window=(0.8, 1.0),
                  subgroup_size=4, meshes=()) -> pd.DataFrame:
    """The statistics of every run and quantity, and of every loaded TCA.

    Parameters
    ----------
    paths : sequence of str or os.PathLike
        Run files.
    steady_state_after : float, default 0.2
        End of the transient [s] (paper: 0.2 s, 400 samples).
    window : (float, float), default (0.8, 1.0)
        Xbar-R window [s] (paper: 0.8–1.0 s).
    subgroup_size : int, default 4
        Xbar-R subgroup size (paper: 4, 25 subgroups).
    meshes : sequence of str or os.PathLike
        Loaded-TCA files (``lsbg ltca``).

    Returns
    -------
    pandas.DataFrame
        One row per run and quantity of :data:`SUMMARY_QUANTITIES` (see
        :func:`quantity_summary`), then two per loaded TCA (see
        :func:`mesh_summary`); columns :data:`SUMMARY_COLUMNS`.

    Raises
    ------
    ValueError
        Naming the file and quantity when a statistic cannot be computed.
    """
    rows = []
    for path in as_path_list(paths):
        ds = open_run(path)
        for quantity in SUMMARY_QUANTITIES:
            try:
                rows.append(quantity_summary(ds, quantity, steady_state_after, window,
                                             subgroup_size))
            except ValueError as err:
                raise ValueError(f"{path}: {quantity}: {err}") from None
    for path in as_path_list(meshes):
        rows.extend(mesh_summary(open_mesh(path)))
    table = pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS))
    table["out_of_control"] = table["out_of_control"].astype("Int64")
    return table


# ------------------------------------------------------- the paper's report
def _by_type_records(geometry_dirs):
    """{gear type: design.json record} in the paper's order."""
    if isinstance(geometry_dirs, dict):
        records = {label: read_record(d) for label, d in geometry_dirs.items()}
    else:
        records = {}
        for d in as_path_list(geometry_dirs):
            record = read_record(d)
            label = TRACE_LABELS.get(record["trace"], record["trace"])
            records[label] = record
    order = [t for t in _TYPE_ORDER if t in records] + [t for t in records
                                                       if t not in _TYPE_ORDER]
    return {t: records[t] for t in order}


# (key of design.json, description, unit, origin)
_DESIGN_ROWS = [
    ("pinion_teeth", "number of teeth z1 (pinion)", "-", "Table 1"),
    ("gear_teeth", "number of teeth z2 (gear)", "-", "Table 1"),
    ("module_mm", "outer transverse module m", "mm", "Table 1"),
    ("shaft_angle_deg", "shaft angle Σ", "deg", "Table 1"),
    ("pinion_hand", "hand of spiral of the pinion", "-", "Table 1"),
    ("pitch_diameter_pinion_mm", "outer pitch diameter d1", "mm", "Table 1"),
    ("pitch_diameter_gear_mm", "outer pitch diameter d2", "mm", "Table 1"),
    ("normal_pressure_angle_deg", "normal pressure angle αn", "deg", "Table 1"),
    ("spiral_angle_deg", "mean spiral angle βm", "deg", "Table 1"),
    ("addendum_mm", "addendum ha", "mm", "Table 1"),
    ("dedendum_mm", "dedendum hf", "mm", "Table 1"),
    ("trace", "tooth trace", "-", "type"),
    ("face_width_mm", "face width b", "mm", "assumed"),
    ("cutter_radius_mm", "cutter radius rc (SBG only)", "mm", "assumed"),
    ("backlash_mm", "backlash", "mm", "assumed"),
    ("base_cone_rule", "base cone rule", "-", "assumed"),
    ("pitch_angle_pinion_deg", "pitch angle δ1", "deg", "derived"),
    ("pitch_angle_gear_deg", "pitch angle δ2", "deg", "derived"),
    ("outer_cone_distance_mm", "outer cone distance Re", "mm", "derived"),
    ("mean_cone_distance_mm", "mean cone distance Rm", "mm", "derived"),
    ("inner_cone_distance_mm", "inner cone distance Ri", "mm", "derived"),
    ("base_cone_angle_pinion_deg", "base cone angle δb1", "deg", "derived"),
    ("base_cone_angle_gear_deg", "base cone angle δb2", "deg", "derived"),
    ("plane_spiral_angle_mean_deg", "spiral angle in the plane of action βp", "deg", "derived"),
    ("normal_pressure_angle_mean_deg", "normal pressure angle at the mean point", "deg",
     "measured"),
    ("contact_ratio", "total contact ratio", "-", "measured"),
    ("contact_ratio_profile", "profile contact ratio", "-", "measured"),
    ("contact_ratio_face", "face contact ratio", "-", "measured"),
    ("undercut_pinion_deg", "undercut of the pinion (roll angle)", "deg", "measured"),
    ("undercut_gear_deg", "undercut of the gear (roll angle)", "deg", "measured"),
    ("top_land_mean_pinion_mm", "top land at Rm, pinion", "mm", "measured"),
    ("top_land_mean_gear_mm", "top land at Rm, gear", "mm", "measured"),
    ("mass_pinion_kg", "mass of the pinion", "kg", "measured"),
    ("mass_gear_kg", "mass of the gear", "kg", "measured"),
    ("axial_inertia_pinion_kg_m2", "axial moment of inertia, pinion", "kg m²", "measured"),
    ("axial_inertia_gear_kg_m2", "axial moment of inertia, gear", "kg m²", "measured"),
]


def design_table(geometry_dirs) -> pd.DataFrame:
    """Table 1 and the derived and measured quantities of the compared designs.

    Parameters
    ----------
    geometry_dirs : dict or sequence
        ``{gear type: geometry directory}``, or directories (the gear type is
        read from ``design.json``).

    Returns
    -------
    pandas.DataFrame
        Columns ``quantity``, ``unit``, ``origin`` ('Table 1', 'assumed' for
        what the paper leaves open, 'derived' from the design formulas,
        'measured' on the exact flanks and solids) and one column per gear
        type (SBG first), values as in ``design.json`` (the cutter radius
        only for circular traces, NaN otherwise).
    """
    records = _by_type_records(geometry_dirs)
    rows = []
    for key, description, unit, origin in _DESIGN_ROWS:
        row = {"quantity": description, "unit": unit, "origin": origin}
        for label, record in records.items():
            unused = key == "cutter_radius_mm" and record.get("trace") != "circular"
            row[label] = np.nan if unused else record.get(key, np.nan)
        rows.append(row)
    return pd.DataFrame(rows)


def _theory(ds, quantity):
    return float(ds.attrs[THEORY_ATTRIBUTES[quantity]])


def theory_table(runs, start=0.2, quantities=QUANTITIES) -> pd.DataFrame:
    """Simulated means against Eq. 12–13, the paper's Table 3 (ours and its).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs (gear type from the attributes).
    start : float, default 0.2
        End of the transient [s].
    quantities : sequence of str
        Quantities of :data:`QUANTITIES`.

    Returns
    -------
    pandas.DataFrame
        Per gear type and quantity: ``simulated``, ``theory``, ``difference``
        (simulated − theory), ``error_rate_percent`` (100 |difference| /
        theory) [unit of the quantity, %], and the paper's ``paper_simulated``
        and ``paper_error_rate_percent`` where it has them.
    """
    rows = []
    for label, ds in _by_type(runs).items():
        for quantity in quantities:
            comparison = stats.compare_to_theory(steady(ds, quantity, start).mean(),
                                                 _theory(ds, quantity))
            paper = PAPER.get((label, quantity), {})
            rows.append({"gear_type": label, "quantity": quantity,
                         "unit": ds[quantity].attrs.get("units", ""),
                         "simulated": comparison.simulated, "theory": comparison.theory,
                         "difference": comparison.difference,
                         "error_rate_percent": comparison.error_rate_percent,
                         "paper_simulated": paper.get("mean", np.nan),
                         "paper_error_rate_percent": paper.get("error_rate_percent", np.nan)})
    return pd.DataFrame(rows)


def paper_comparison_table(runs, start=0.2) -> pd.DataFrame:
    """The paper's §4.1 statistics beside ours (mean, std, A², p).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs.
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    pandas.DataFrame
        Per gear type, quantity (gear_speed, tangential_force) and statistic:
        ``paper``, ``this_work`` and ``ratio`` (this work / paper).
    """
    rows = []
    for label, ds in _by_type(runs).items():
        for quantity in ("gear_speed", "tangential_force"):
            x = steady(ds, quantity, start)
            ad = stats.anderson_darling(x)
            ours = {"mean": float(x.mean()), "std": float(x.std(ddof=1)),
                    "ad_statistic": ad.statistic, "ad_pvalue": ad.pvalue}
            paper = PAPER.get((label, quantity), {})
            for statistic, value in ours.items():
                published = paper.get(statistic, np.nan)
                rows.append({"gear_type": label, "quantity": quantity, "statistic": statistic,
                             "unit": (ds[quantity].attrs.get("units", "")
                                      if statistic in ("mean", "std") else "-"),
                             "paper": published, "this_work": value,
                             "ratio": value / published if published else np.nan})
    return pd.DataFrame(rows)


def compare_types(runs, quantity, start=0.2, **options) -> stats.FluctuationComparison:
    """Which gear type fluctuates less in ``quantity``: SBG against LSBG.

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        One SBG and one LSBG run.
    quantity : str
        Run variable.
    start : float, default 0.2
        End of the transient [s].
    **options
        Passed to :func:`lsbg.stats.compare_fluctuation` (``confidence``,
        ``n_boot``, ``block_length``, ``seed``, ``method``).

    Returns
    -------
    lsbg.stats.FluctuationComparison
        Ratio std(SBG)/std(LSBG) with its block-bootstrap interval.
    """
    by_type = _by_type(runs)
    missing = [t for t in _TYPE_ORDER if t not in by_type]
    if missing:
        raise ValueError(f"compare_types needs an SBG and an LSBG run; missing {missing}")
    sbg, lsbg_run = by_type["SBG"], by_type["LSBG"]
    return stats.compare_fluctuation(steady(sbg, quantity, start),
                                     steady(lsbg_run, quantity, start), names=("SBG", "LSBG"),
                                     units=sbg[quantity].attrs.get("units", ""), **options)


def fluctuation_table(comparisons) -> pd.DataFrame:
    """:func:`compare_types` results as a table, with the paper's ratio.

    Parameters
    ----------
    comparisons : dict
        ``{quantity: lsbg.stats.FluctuationComparison}`` (SBG as a, LSBG as b).

    Returns
    -------
    pandas.DataFrame
        Per quantity: both standard deviations, ratio std(SBG)/std(LSBG), its
        interval, the Brown–Forsythe p, the effective sample sizes and the
        paper's ratio.
    """
    rows = []
    for quantity, c in comparisons.items():
        paper = [PAPER.get((name, quantity), {}).get("std", np.nan) for name in c.names]
        rows.append({"quantity": quantity, f"std_{c.names[0]}": c.std[0],
                     f"std_{c.names[1]}": c.std[1], "ratio": c.ratio, "ci_low": c.ci.low,
                     "ci_high": c.ci.high, "confidence": c.ci.confidence,
                     "brown_forsythe_p": c.brown_forsythe_pvalue,
                     f"ess_{c.names[0]}": c.effective_sample_size[0],
                     f"ess_{c.names[1]}": c.effective_sample_size[1],
                     "paper_ratio": paper[0] / paper[1]})
    return pd.DataFrame(rows)


def fluctuation_conclusion(comparisons) -> str:
    """One paragraph: which type fluctuates less, by what factor, how sure.

    Parameters
    ----------
    comparisons : dict
        ``{quantity: lsbg.stats.FluctuationComparison}`` with names
        ('SBG', 'LSBG'), as from :func:`compare_types`.

    Returns
    -------
    str
        Markdown built only from the numbers, set against the paper's claim
        that the LSBG fluctuates less.
    """
    sentences, calmer = [], set()
    for quantity, c in comparisons.items():
        label = QUANTITY_LABELS.get(quantity, quantity)
        if c.ratio >= 1.0:
            calm, factor, lo, hi = c.names[1], c.ratio, c.ci.low, c.ci.high
        else:
            calm, factor, lo, hi = c.names[0], 1.0 / c.ratio, 1.0 / c.ci.high, 1.0 / c.ci.low
        other = c.names[0] if calm == c.names[1] else c.names[1]
        sure = ("the interval excludes 1" if c.ci.excludes_one
                else "the interval includes 1, so the difference is not significant")
        if c.ci.excludes_one:
            calmer.add(calm)
        sentences.append(
            f"In the **{label}**, the {calm} fluctuates less than the {other} by a factor "
            f"{factor:.3g} (standard deviation ratio; {100 * c.ci.confidence:g} % "
            f"block-bootstrap interval {lo:.3g}–{hi:.3g}: {sure}).")
        paper = [PAPER.get((name, quantity), {}).get("std") for name in c.names]
        if all(paper):
            sentences[-1] += (f" The paper's ratio std(SBG)/std(LSBG) is "
                              f"{paper[0] / paper[1]:.3g}; ours is {c.ratio:.3g}.")
    if calmer == {"LSBG"}:
        verdict = ("The data support the paper's conclusion that the LSBG runs more "
                   "smoothly than the SBG, for every quantity where the difference is "
                   "significant.")
    elif calmer == {"SBG"}:
        verdict = ("The data contradict the paper's conclusion: in this model the "
                   "conventional SBG fluctuates less than the LSBG wherever the difference "
                   "is significant.")
    elif not calmer:
        verdict = ("No difference is significant: the data neither support nor contradict "
                   "the paper's conclusion that the LSBG runs more smoothly.")
    else:
        verdict = ("The quantities disagree on which type fluctuates less, so the data do "
                   "not support a general claim either way.")
    return " ".join(sentences) + " " + verdict


#: Engines in the order they serve as the reference of :func:`engine_agreement`
#: (the compiled DOP853 loop agrees with scipy's LSODA at rtol 1e-10 within
#: 1e-10, tests/test_dynamics.py).
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
        key = (ds.attrs["design_trace"], _spiral_angle(ds))
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


def _contact_parameters(ds):
    """ContactParameters from a run's ``contact_*`` attributes (the paper's if absent)."""
    from lsbg.contact import ContactParameters

    return ContactParameters.from_dict({} if ds is None else ds.attrs, prefix="contact_")


def contact_resonance(geometry_dir, run=None, positions=12) -> dict:
    """Torsional resonance of the gear on the linearised contact at the static load.

    The pinion follows its prescribed motion, so the gear (inertia J2) rests
    on the mesh spring k = −dT/dφ2 of the IMPACT law at the deflection that
    carries the load: f = √(k/J2) / 2π. The stiffness varies with the mesh
    position (the number of tooth pairs and their lines change), so it is
    evaluated at ``positions`` pinion angles over one pinion pitch.

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        Geometry directory of the design point.
    run : xarray.Dataset, optional
        Run dataset whose contact parameters and load torque to use (the
        paper's otherwise).
    positions : int, default 12
        Mesh positions over one pinion pitch [-].

    Returns
    -------
    dict
        ``frequency_hz`` (mean), ``frequency_min_hz``, ``frequency_max_hz``
        [Hz] and ``stiffness_N_m_per_rad`` (mean) [N m/rad].
    """
    from lsbg.dynamics import SimulationSettings, load_model

    model = load_model(geometry_dir, _contact_parameters(run))
    load = (float(run.attrs["solver_load_torque_N_m"])
            if run is not None and "solver_load_torque_N_m" in run.attrs
            else SimulationSettings().load_torque)
    z1 = model.pair.design.pinion_teeth
    stiffness = []
    for phi1 in np.linspace(0.0, 2 * math.pi / z1, positions, endpoint=False):
        phi2 = model.contact.static_gear_angle(load, pinion_angle=phi1)
        h = 1e-7
        plus = model.contact.forces(phi1, phi2 + h).gear_torque
        minus = model.contact.forces(phi1, phi2 - h).gear_torque
        stiffness.append(abs(plus - minus) / (2 * h))
    stiffness = np.asarray(stiffness)
    freq = np.sqrt(stiffness / model.gear_inertia) / (2 * math.pi)
    return {"frequency_hz": float(freq.mean()), "frequency_min_hz": float(freq.min()),
            "frequency_max_hz": float(freq.max()),
            "stiffness_N_m_per_rad": float(stiffness.mean())}


def control_charts(runs, quantity, window=(0.8, 1.0), subgroup_size=4) -> dict:
    """Xbar-R charts of one quantity for each gear type (Fig. 17–18).

    Returns
    -------
    dict
        ``{gear type: lsbg.stats.XbarRChart}`` in the paper's order.
    """
    return {label: stats.xbar_r_chart(stats.subgroups_from_window(
        ds[quantity].values, ds["time"].values, window[0], window[1], subgroup_size))
        for label, ds in _by_type(runs).items()}


# ---------------------------------------------------------------- figures
def plot_pair_pictures(geometry_dirs) -> Figure:
    """The pictures of the assembled pairs (``pair.png``) side by side, SBG first.

    Parameters
    ----------
    geometry_dirs : dict or sequence
        ``{gear type: geometry directory}``, or directories.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.image import imread

    if isinstance(geometry_dirs, dict):
        dirs = {label: as_path_list(d)[0] for label, d in geometry_dirs.items()}
    else:
        dirs = {TRACE_LABELS.get(read_record(d)["trace"], str(d)): d
                for d in as_path_list(geometry_dirs)}
    order = [t for t in _TYPE_ORDER if t in dirs] + [t for t in dirs if t not in _TYPE_ORDER]
    fig, axes = new_figure(1, len(order), width=4.8, height=4.0)
    for ax, label in zip(axes[0], order):
        picture = Path(dirs[label]) / "pair.png"
        if not picture.is_file():
            raise FileNotFoundError(f"{dirs[label]}: no pair.png")
        ax.imshow(imread(picture))
        ax.set_title(f"{label} ({read_record(dirs[label])['trace']} trace)")
        ax.set_axis_off()
    return fig


def plot_time_series(runs, names, theory=None, overlay=False, xlim=None) -> Figure:
    """Time series of run variables (Fig. 8, 9–10, 12), one panel per gear type.

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs.
    names : str or sequence of str
        Run variables to draw (same units).
    theory : {'gear_speed', 'tangential_force'}, optional
        Add the rigid-pair prediction: Eq. 12 applied to the simulated pinion
        speed (the paper's Fig. 10), or the constant of Eq. 13.
    overlay : bool, default False
        Draw every run on one axes instead of one panel per run.
    xlim : (float, float), optional
        Time limits [s].

    Returns
    -------
    matplotlib.figure.Figure
        Panels share both axes.
    """
    names = [names] if isinstance(names, str) else list(names)
    by_type = _by_type(runs)
    ncols = 1 if overlay else len(by_type)
    fig, axes = new_figure(1, ncols, sharex=True, sharey=True)
    styles = ["-", "--", ":", "-."]
    for i, (label, ds) in enumerate(by_type.items()):
        ax = axes[0, 0 if overlay else i]
        t = ds["time"].values
        for k, name in enumerate(names):
            text, units = _label(ds, name)
            ax.plot(t, ds[name].values, lw=0.9,
                    ls=styles[i % 4] if overlay else "-",
                    color=type_color(label) if overlay or k == 0 else f"C{k + 1}",
                    label=f"{label}: {text}")
        if theory == "gear_speed":
            ratio = ds.attrs["design_pinion_teeth"] / ds.attrs["design_gear_teeth"]
            ax.plot(t, ds["pinion_speed"].values * ratio, "k--", lw=0.9,
                    label="Eq. 12: pinion speed × z1/z2")
        elif theory == "tangential_force":
            ax.axhline(_theory(ds, "tangential_force"), color="k", ls="--", lw=0.9,
                       label=f"Eq. 13: {_theory(ds, 'tangential_force'):.6g} N")
        ax.set_xlabel("time [s]")
        if not overlay:
            ax.set_title(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small", loc="best", framealpha=0.85)
    first = next(iter(by_type.values()))
    text, units = _label(first, names[0])
    axes[0, 0].set_ylabel(f"{text if len(names) == 1 else 'force'} [{units}]")
    if xlim is not None:
        axes[0, 0].set_xlim(xlim)
    return fig


def plot_steady_scatter(runs, name, start=0.2) -> Figure:
    """Scatter of the steady-state samples of all runs on one axes (Fig. 11).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
    name : str
        Run variable, e.g. ``'gear_speed'``.
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=8.0)
    ax = axes[0, 0]
    by_type = _by_type(runs)
    for label, ds in by_type.items():
        t = ds["time"].values
        keep = t - start > 1e-9 * np.median(np.diff(t))
        x = ds[name].values[keep]
        ax.plot(t[keep], x, "o", ms=2.5, color=type_color(label),
                label=f"{label} (std {x.std(ddof=1):.4g})")
    first = next(iter(by_type.values()))
    if name in THEORY_ATTRIBUTES:
        ax.axhline(_theory(first, name), color="k", ls="--", lw=0.9,
                   label=f"theory {_theory(first, name):.6g}")
    text, units = _label(first, name)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{text} [{units}]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


def _common_limits(arrays, margin=0.05):
    lo = min(float(np.min(a)) for a in arrays)
    hi = max(float(np.max(a)) for a in arrays)
    pad = margin * (hi - lo) if hi > lo else 1.0
    return lo - pad, hi + pad


def plot_normality(runs, name, start=0.2) -> Figure:
    """Normal probability plots with A² and p, one panel per type (Fig. 13–14).

    Returns
    -------
    matplotlib.figure.Figure
        Panels with a shared x axis range.
    """
    by_type = _by_type(runs)
    series = {label: steady(ds, name, start) for label, ds in by_type.items()}
    xlim = _common_limits(series.values())
    fig, axes = new_figure(1, len(series))
    first = next(iter(by_type.values()))
    text, units = _label(first, name)
    for ax, (label, x) in zip(axes[0], series.items()):
        stats.plot_normal_probability(x, ax=ax, label=text, units=units, xlim=xlim)
        ax.set_title(label)
    return fig


def plot_boxplots(runs, names=("gear_speed", "tangential_force"), start=0.2) -> Figure:
    """Box plots of the steady state of each type, one panel per quantity (Fig. 16)."""
    by_type = _by_type(runs)
    fig, axes = new_figure(1, len(names))
    first = next(iter(by_type.values()))
    for ax, name in zip(axes[0], names):
        text, units = _label(first, name)
        stats.plot_boxplot({label: steady(ds, name, start) for label, ds in by_type.items()},
                           label=text, units=units, ax=ax)
    return fig


def plot_control_charts(charts, label="", units="") -> list:
    """Xbar-R charts of the gear types with shared scales (Fig. 17–18).

    Parameters
    ----------
    charts : dict
        ``{gear type: lsbg.stats.XbarRChart}`` from :func:`control_charts`.
    label, units : str
        Quantity and unit for the axes.

    Returns
    -------
    list of matplotlib.figure.Figure
        One figure per gear type, all with the same y-limits.
    """
    xbar_ylim, r_ylim = stats.xbar_r_ylims(*charts.values())
    return [stats.plot_xbar_r(chart, label=label, units=units, title=name,
                              xbar_ylim=xbar_ylim, r_ylim=r_ylim)
            for name, chart in charts.items()]


# -------------------------------------------------------------------- sweep
def _point_runs(sweep):
    """Yield (trace, spiral angle, one-point dataset) of the points with data."""
    for trace in sweep["trace"].values:
        for angle in sweep["spiral_angle"].values:
            point = sweep.sel(trace=trace, spiral_angle=angle)
            if np.isfinite(point["gear_speed"].values).all():
                yield str(trace), float(angle), point


def sweep_table(sweep, start=0.2, confidence=0.95, n_boot=2000, seed=0) -> pd.DataFrame:
    """Fluctuation and contact ratio of every design point of a sweep.

    Parameters
    ----------
    sweep : xarray.Dataset
        From :func:`combine_runs`.
    start : float, default 0.2
        End of the transient [s].
    confidence : float, default 0.95
        Level of the intervals [-].
    n_boot : int, default 2000
        Bootstrap replicates [-].
    seed : int, default 0
        Seed of the bootstrap.

    Returns
    -------
    pandas.DataFrame
        Per (gear type, spiral angle): contact ratios (total, profile, face),
        mean tangential force (both definitions) [N], and for gear_speed,
        tangential_force and tangential_force_outer the standard deviation
        with its block-bootstrap interval (:func:`lsbg.stats.std_ci`),
        columns ``<quantity>_std``, ``_std_low``, ``_std_high``. Rows: SBG
        first, then by spiral angle.
    """
    rows = []
    for trace, angle, point in _point_runs(sweep):
        row = {"gear_type": TRACE_LABELS.get(trace, trace), "trace": trace,
               "spiral_angle_deg": angle}
        for name in ("contact_ratio", "contact_ratio_profile", "contact_ratio_face"):
            row[name] = float(point[name]) if name in point else np.nan
        for quantity in QUANTITIES:
            x = steady(point, quantity, start)
            ci = stats.std_ci(x, confidence=confidence, n_boot=n_boot, seed=seed)
            if quantity != "gear_speed":
                row[f"{quantity}_mean"] = float(x.mean())
            row[f"{quantity}_std"] = ci.std
            row[f"{quantity}_std_low"] = ci.low
            row[f"{quantity}_std_high"] = ci.high
        rows.append(row)
    order = {label: k for k, label in enumerate(_TYPE_ORDER)}
    rows.sort(key=lambda r: (order.get(r["gear_type"], len(order)), r["spiral_angle_deg"]))
    return pd.DataFrame(rows)


def sweep_ratio_table(sweep, quantities=("gear_speed", "tangential_force"), start=0.2,
                      confidence=0.95, n_boot=2000, seed=0) -> pd.DataFrame:
    """std(SBG)/std(LSBG) at each spiral angle where both types were run.

    Returns
    -------
    pandas.DataFrame
        Per spiral angle and quantity: ``ratio`` with ``low``/``high`` from
        :func:`lsbg.stats.std_ratio_ci`; > 1 means the LSBG fluctuates less.
    """
    by_trace = {}
    for trace, angle, point in _point_runs(sweep):
        by_trace.setdefault(angle, {})[TRACE_LABELS.get(trace, trace)] = point
    rows = []
    for angle in sorted(by_trace):
        points = by_trace[angle]
        if not {"SBG", "LSBG"} <= set(points):
            continue
        for quantity in quantities:
            ci = stats.std_ratio_ci(steady(points["SBG"], quantity, start),
                                    steady(points["LSBG"], quantity, start),
                                    confidence=confidence, n_boot=n_boot, seed=seed)
            rows.append({"spiral_angle_deg": angle, "quantity": quantity, "ratio": ci.ratio,
                         "low": ci.low, "high": ci.high,
                         "excludes_one": ci.excludes_one})
    return pd.DataFrame(rows, columns=["spiral_angle_deg", "quantity", "ratio", "low", "high",
                                       "excludes_one"])


def _errorbar(ax, table, column, label, color, marker):
    y = table[column].to_numpy()
    err = np.vstack([y - table[f"{column}_low"].to_numpy(),
                     table[f"{column}_high"].to_numpy() - y])
    ax.errorbar(table["spiral_angle_deg"], y, yerr=err, fmt=marker + "-", color=color,
                capsize=3, ms=4, lw=1, label=label)


def plot_sweep(table, units=None) -> Figure:
    """Fluctuation, contact ratio and mean force against spiral angle.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`sweep_table`.
    units : dict, optional
        Units of gear_speed and the forces (default deg/s and N).

    Returns
    -------
    matplotlib.figure.Figure
        2 x 2 panels: std of gear speed and of tangential force with their
        intervals, contact ratios (total, profile, face), mean forces.
    """
    units = {"gear_speed": "deg/s", "tangential_force": "N", **(units or {})}
    fig, axes = new_figure(2, 2, sharex=True)
    (a, b), (c, d) = axes
    for label, part in table.groupby("gear_type", sort=False):
        part = part.sort_values("spiral_angle_deg")
        color = type_color(label)
        _errorbar(a, part, "gear_speed_std", label, color, "o")
        _errorbar(b, part, "tangential_force_std", f"{label}: points of action", color, "o")
        _errorbar(b, part, "tangential_force_outer_std", f"{label}: at d2/2", color, "s")
        for name, style in (("contact_ratio", "-"), ("contact_ratio_profile", "--"),
                            ("contact_ratio_face", ":")):
            c.plot(part["spiral_angle_deg"], part[name], "o" + style, color=color, ms=4,
                   label=f"{label}: {name.replace('contact_ratio', 'total').replace('total_', '')}")
        d.plot(part["spiral_angle_deg"], part["tangential_force_mean"], "o-", color=color,
               ms=4, label=f"{label}: points of action")
        d.plot(part["spiral_angle_deg"], part["tangential_force_outer_mean"], "s--",
               color=color, ms=4, label=f"{label}: at d2/2")
    angles = np.unique(table["spiral_angle_deg"].to_numpy())
    for ax in (c, d):
        ax.set_xticks(angles, [f"{v:g}" for v in angles])
    a.set_ylabel(f"std of gear angular velocity [{units['gear_speed']}]")
    b.set_ylabel(f"std of tangential force [{units['tangential_force']}]")
    c.set_ylabel("contact ratio [-]")
    d.set_ylabel(f"mean tangential force [{units['tangential_force']}]")
    for ax in (c, d):
        ax.set_xlabel("mean spiral angle βm [deg]")
    for ax in (a, b, c, d):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="x-small")
    return fig


def plot_sweep_ratio(ratios) -> Figure:
    """std(SBG)/std(LSBG) against spiral angle with intervals, per quantity.

    Parameters
    ----------
    ratios : pandas.DataFrame
        From :func:`sweep_ratio_table`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=7.0)
    ax = axes[0, 0]
    for i, (quantity, part) in enumerate(ratios.groupby("quantity", sort=False)):
        y = part["ratio"].to_numpy()
        err = np.vstack([y - part["low"].to_numpy(), part["high"].to_numpy() - y])
        ax.errorbar(part["spiral_angle_deg"] + 0.3 * (i - 0.5), y, yerr=err, fmt="o-",
                    capsize=3, ms=4, lw=1, color=f"C{i + 2}",
                    label=QUANTITY_LABELS.get(quantity, quantity))
    ax.axhline(1.0, color="k", lw=0.8)
    angles = np.unique(ratios["spiral_angle_deg"].to_numpy())
    ax.set_xticks(angles, [f"{v:g}" for v in angles])
    ax.set_xlabel("mean spiral angle βm [deg]")
    ax.set_ylabel("std(SBG) / std(LSBG) [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


# -------------------------------------------------------------- verification
def read_convergence(paths) -> pd.DataFrame:
    """Read and stack convergence tables (``lsbg convergence``).

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or lacks a column of
        :data:`lsbg.verification.COLUMNS`.
    """
    from lsbg.verification import COLUMNS

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
        tightest = tolerance[np.isclose(tolerance["value"], tolerance["value"].min())]
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


def plot_convergence(table) -> Figure:
    """Standard deviations and their difference to the tightest tolerance run.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`convergence_table`.

    Returns
    -------
    matplotlib.figure.Figure
        Rows: pybullet against its time step, scipy and compiled against
        their rtol (log axes). Columns: std of gear speed, std of tangential
        force, relative difference to the tightest tolerance run. Default
        settings are ringed.
    """
    engines = [e for e in ("pybullet", "scipy", "compiled") if (table["engine"] == e).any()]
    fig, axes = new_figure(len(engines), 3, width=3.6, height=2.9)
    # x is log10 of the setting on a linear axis labelled with the settings: a
    # log axis draws the same for the three values at several times the cost
    columns = (("gear_speed_std_deg_s", "std of gear angular velocity [deg/s]"),
               ("tangential_force_std_N", "std of tangential force [N]"))
    for r, engine in enumerate(engines):
        part = table[table["engine"] == engine]
        xlabel = "time step [s]" if engine == "pybullet" else "relative tolerance rtol [-]"
        for k, (trace, rows) in enumerate(part.groupby("trace", sort=False)):
            rows = rows.sort_values("value")
            label = TRACE_LABELS.get(trace, trace)
            x = np.log10(rows["value"].to_numpy())
            for c, (column, ylabel) in enumerate(columns):
                ax = axes[r, c]
                ax.plot(x, rows[column], "o-", color=type_color(label), ms=4, label=label)
                default = rows["is_default"].to_numpy()
                ax.plot(x[default], rows[column][default], "o", ms=11, mfc="none",
                        color="k", label="default" if k == 0 else None)
                ax.set_ylabel(ylabel)
            ax = axes[r, 2]
            for name, marker in (("gear_speed_std", "o"), ("tangential_force_std", "s")):
                ax.plot(x, rows[f"{name}_rel_diff_percent"], marker + "-",
                        color=type_color(label), ms=4,
                        label=f"{label}: {'speed' if name == 'gear_speed_std' else 'force'}")
            ax.set_ylabel("difference to tightest tolerance run [%]")
        values = np.unique(part["value"].to_numpy())
        for ax in axes[r]:
            ax.set_xticks(np.log10(values), [f"{v:g}" for v in values])
            ax.set_xlim(np.log10(values.min()) - 0.3, np.log10(values.max()) + 0.3)
            ax.set_xlabel(xlabel)
            ax.set_title(engine, fontsize="medium")
            ax.grid(True, alpha=0.3, which="both")
            ax.legend(fontsize="x-small")
    return fig


def plot_engine_agreement(agreement, tolerance=0.03) -> Figure:
    """Ratio of standard deviations of each engine to the reference, with the band.

    Parameters
    ----------
    agreement : pandas.DataFrame
        From :func:`engine_agreement`.
    tolerance : float, default 0.03
        Half-width of the accepted band around 1 [-].

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    short = {"gear_speed": "speed", "tangential_force": "force",
             "tangential_force_outer": "force at d2/2"}
    labels = [f"{r.gear_type} {r.spiral_angle_deg:g}°\n{r.engine}: "
              f"{short.get(r.quantity, r.quantity)}" for r in agreement.itertuples()]
    colors = ["C2" if ok else "C3" for ok in agreement["within_tolerance"]]
    ax.bar(range(len(agreement)), agreement["std_ratio"], color=colors)
    ax.axhspan(1 - tolerance, 1 + tolerance, color="0.85", zorder=0,
               label=f"±{100 * tolerance:g} %")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(range(len(agreement)), labels, fontsize="small")
    values = agreement["std_ratio"].to_numpy()
    span = max(tolerance * 2, float(np.max(np.abs(values - 1))) * 1.3) if values.size else 0.1
    ax.set_ylim(1 - span, 1 + span)
    ax.set_ylabel("std(engine) / std(reference) [-]")
    ax.legend(fontsize="small")
    ax.grid(True, axis="y", alpha=0.3)
    return fig


def pressure_angle_table(geometry_dirs) -> pd.DataFrame:
    """Normal pressure angles measured on the flanks at the mean point.

    Returns
    -------
    pandas.DataFrame
        Per gear type, member and side: ``measured_deg``, ``design_deg``
        (the design's αn) and ``deviation_deg``.
    """
    rows = []
    for label, record in _by_type_records(geometry_dirs).items():
        for member in ("pinion", "gear"):
            for side in ("drive", "coast"):
                measured = record[f"normal_pressure_angle_mean_{member}_{side}_deg"]
                design = record["normal_pressure_angle_deg"]
                rows.append({"gear_type": label, "member": member, "side": side,
                             "measured_deg": measured, "design_deg": design,
                             "deviation_deg": measured - design})
    return pd.DataFrame(rows)


def plot_spiral_angle_along_face(geometry_dirs) -> Figure:
    """Spiral angle on the gear's pitch cone along the face width (design.json).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    for label, record in _by_type_records(geometry_dirs).items():
        ax.plot(record["cone_distance_along_face_mm"], record["spiral_angle_along_face_deg"],
                "o-", ms=3, color=type_color(label), label=f"{label} ({record['trace']} trace)")
        ax.axvline(record["mean_cone_distance_mm"], color="0.5", lw=0.8, ls=":")
    ax.set_xlabel("cone distance from the apex [mm]")
    ax.set_ylabel("spiral angle on the pitch cone [deg]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


def plot_pressure_angles(table) -> Figure:
    """|measured − design| normal pressure angle per flank (log scale).

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`pressure_angle_table`.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    deviation = np.abs(table["deviation_deg"].to_numpy())
    floor = 1e-16
    labels = [f"{r.gear_type}\n{r.member} {r.side}" for r in table.itertuples()]
    colors = [type_color(t) for t in table["gear_type"]]
    ax.bar(range(len(table)), np.maximum(deviation, floor), color=colors)
    for k in np.flatnonzero(deviation < floor):
        ax.annotate("0", (k, floor), xytext=(0, 2), textcoords="offset points", ha="center",
                    fontsize="small")
    ax.set_yscale("log")
    ax.set_xticks(range(len(table)), labels, fontsize="x-small")
    ax.set_ylabel("|measured − design αn| [deg]")
    ax.grid(True, axis="y", alpha=0.3)
    return fig


def conjugacy_errors(design, side="drive", phases=25, n=17) -> pd.DataFrame:
    """Distance between the pinion and gear flanks on the contact lines.

    At each mesh position (turn Ψ of the generating curve) both members are
    turned so that tooth 0's contact line lies at Ψ; the flank points of both
    members at the contact-line points (same cone distance and polar angle)
    must coincide with the line and their normals must be opposite: exact
    line contact (DESIGN.md §2).

    Parameters
    ----------
    design : lsbg.design.GearPairDesign
    side : {'drive', 'coast'}
    phases : int, default 25
        Mesh positions across the field of contact (and a little beyond) [-].
    n : int, default 17
        Points per contact line; the end points (possibly on the base cone,
        where the polar angle is a singular parameter) are left out [-].

    Returns
    -------
    pandas.DataFrame
        Per mesh position with a contact line: ``phase_deg``,
        ``pinion_distance_m`` and ``gear_distance_m`` (largest distance of a
        member's flank point from the contact line point) [m] and
        ``normal_mismatch`` (largest |n1 + n2|) [-].
    """
    from lsbg.geometry import GearPair, rotate

    pair = GearPair(design)
    lo, hi = pair.planes[side].field[:2]
    rows = []
    for phase in np.linspace(lo - 0.3, hi + 0.3, phases):
        rho, points, _ = pair.contact_line(side, phase, n=n)
        if rho.size < 3:
            continue
        rho, points = rho[1:-1], points[1:-1]
        flanks = []
        for member in (1, 2):
            u = pair.rotation_axis[member]
            rotation = (phase / pair.axis_normal_component(member, side)
                        - pair.flank_offset[(member, side)])
            polar = np.arccos(points @ pair.axis[member] / np.linalg.norm(points, axis=1))
            body, normals = pair.flank(member, side, rho, polar)
            flanks.append((rotate(body, u, rotation), rotate(normals, u, rotation)))
        (p1, n1), (p2, n2) = flanks
        rows.append({"phase_deg": math.degrees(phase),
                     "pinion_distance_m": float(np.max(np.linalg.norm(p1 - points, axis=1))),
                     "gear_distance_m": float(np.max(np.linalg.norm(p2 - points, axis=1))),
                     "normal_mismatch": float(np.max(np.linalg.norm(n1 + n2, axis=1)))})
    return pd.DataFrame(rows, columns=["phase_deg", "pinion_distance_m", "gear_distance_m",
                                       "normal_mismatch"])


def plot_conjugacy(errors) -> Figure:
    """Flank-to-contact-line distances against mesh position (log scale).

    Parameters
    ----------
    errors : dict
        ``{gear type: DataFrame}`` from :func:`conjugacy_errors`.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    floor = 1e-18
    for label, table in errors.items():
        ax.semilogy(table["phase_deg"], np.maximum(table["pinion_distance_m"], floor), "o-",
                    ms=3, color=type_color(label), label=f"{label}: pinion flank")
        ax.semilogy(table["phase_deg"], np.maximum(table["gear_distance_m"], floor), "s--",
                    ms=3, color=type_color(label), label=f"{label}: gear flank")
    ax.axhline(1e-9, color="C3", ls=":", lw=1, label="1 nm (test tolerance)")
    ax.set_ylim(1e-18, 1e-6)
    ax.set_xlabel("mesh position: turn Ψ of the contact line [deg]")
    ax.set_ylabel("largest distance to the contact line [m]")
    ax.grid(True, alpha=0.3, which="both")
    ax.legend(fontsize="small")
    return fig
