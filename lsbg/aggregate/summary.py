"""The summary table: the paper's §4 statistics of every run and quantity (``lsbg summary``).

One row per run and quantity (:data:`SUMMARY_COLUMNS`): mean, std,
Anderson–Darling A² and p, the theoretical value of Eq. 12–13 and the error
rate of Table 3, Xbar-R alarms, and from the full-rate record the std, its
spread over the sampling phases and the dynamic factor. Loaded TCAs add two
rows each (static transmission error and mesh stiffness); the contact state
(engine "tca") a row per unloaded TCA (its transmission error) and, per V-H
map, four rows per displacement axis (:data:`CONTACT_STATE_QUANTITIES`). All
statistics come from :mod:`lsbg.stats` and :mod:`lsbg.stats.spectra`.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4 and Table 3.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from lsbg import stats
from lsbg.gear.design import CONFIG_KEYS
from lsbg.aggregate.combine import open_tca, open_vh_map
from lsbg.dynamics.dataset import VARIABLES, open_run
from lsbg.files import as_path_list
from lsbg.aggregate.runs import (QUANTITIES, THEORY_ATTRIBUTES, full_rate_series, open_mesh,
                                 run_band_split, run_spiral_angle)

__all__ = [
    "SUMMARY_QUANTITIES", "SUMMARY_UNITS", "SUMMARY_COLUMNS", "STATISTICS_KEYS", "statistics_options",
    "CONTACT_STATE_QUANTITIES", "BAND_COLUMNS", "quantity_summary", "band_columns",
    "mesh_summary", "tca_summary", "vh_summary", "summary_table", "run_dynamic_factor"
]


#: Quantities of the summary table: the paper's, the transmission error and
#: the contact torque.
SUMMARY_QUANTITIES = QUANTITIES + ("transmission_error", "contact_torque")

#: The V-H map's sensitivities in the summary table: quantity -> its unit. Each
#: gives a row ``{quantity}_per_0_1_{axis}`` per axis of the map: the change per
#: 0.1 mm (0.1 deg for Sigma) through the aligned pair (:mod:`lsbg.tca.vh_map`):
#: the pattern's movement towards the heel and towards the gear's tip, and the
#: unloaded and loaded transmission error's peak to peak.
CONTACT_STATE_QUANTITIES = {"pattern_shift_lengthwise": "mm", "pattern_shift_profile": "mm",
                            "transmission_error_unloaded_pp": "urad",
                            "transmission_error_loaded_pp": "urad"}
#: Unit of each displacement of a V-H map (:data:`lsbg.tca.misalignment.DISPLACEMENTS`).
_AXIS_UNITS = {"E": "mm", "P": "mm", "G": "mm", "Sigma": "degree"}

#: Unit of each quantity of the summary table's rows, as the datasets write it: the
#: runs' (:data:`lsbg.dynamics.dataset.VARIABLES`), the loaded TCA's rows (:mod:`lsbg.tca.loaded`)
#: and the contact state's (:mod:`lsbg.tca`; ``mm/(0.1 mm)``: mm per 0.1 mm).
SUMMARY_UNITS = {**{q: VARIABLES[q][0] for q in SUMMARY_QUANTITIES},
                 "static_transmission_error": "urad", "mesh_stiffness": "N/um",
                 "unloaded_transmission_error": "urad",
                 **{f"{q}_per_0_1_{axis}": f"{unit}/(0.1 {per})"
                    for q, unit in CONTACT_STATE_QUANTITIES.items()
                    for axis, per in _AXIS_UNITS.items()}}


#: The full-rate std by band (:mod:`lsbg.stats.bands`): column -> band of
#: :data:`lsbg.stats.bands.HARMONIC_BANDS`, or ``"mode"`` (within one mesh frequency of
#: the run's mesh mode, ``mesh_natural_frequency_hz``; overlaps the others). Each is the
#: square root of the band's part of the variance over whole mesh periods, so the
#: squares of the four harmonic bands add up to that variance (≈ ``full_rate_std``²).
BAND_COLUMNS = {"full_rate_std_below_1": "below 1", "full_rate_std_1_3": "1-3",
                "full_rate_std_4_7": "4-7", "full_rate_std_8_up": "8 and up",
                "full_rate_std_mode": "mode"}

#: Columns of :func:`summary_table`. Runs: the paper's §4 statistics of the
#: output samples, then the full-rate ones (std, the spread of the sample
#: std over sampling phases, the dynamic factor on the contact-torque row,
#: the std by band of :data:`BAND_COLUMNS`).
#: Loaded TCA (engine "ltca"): the static transmission error's peak to peak
#: and mesh harmonics, and the mesh stiffness. Contact state (engine "tca"): the
#: unloaded transmission error (mean, std, peak to peak) and the V-H map's
#: sensitivities (in ``mean``).
SUMMARY_COLUMNS = ("trace", "spiral_angle_deg", "contact_model", "engine", "run", "quantity",
                   "mean", "std", "ad_statistic", "ad_pvalue", "theory", "error_rate_percent",
                   "out_of_control", "full_rate_std", "sampling_std_min", "sampling_std_max",
                   "dynamic_factor", "peak_to_peak", "harmonic_1", "harmonic_2", "harmonic_3",
                   *BAND_COLUMNS)


#: Keys of the study configuration's ``statistics`` section -> keyword of
#: :func:`summary_table`.
STATISTICS_KEYS = {"steady_state_after_s": "steady_state_after",
                   "control_chart_window_s": "window", "subgroup_size": "subgroup_size"}


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
        sampling phases, (contact torque) the dynamic factor and the full-rate std
        by band (:data:`BAND_COLUMNS`; NaN in the mode's column for a run without
        a mesh mode).

    Raises
    ------
    ValueError
        If the windows do not fit the run (e.g. no subgroups of that size).
    """
    from lsbg.stats import spectra

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
        "spiral_angle_deg": run_spiral_angle(ds),
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
        "dynamic_factor": (run_dynamic_factor(ds, steady_state_after)
                           if quantity == "contact_torque" else np.nan),
        **band_columns(run_band_split(ds, quantity, steady_state_after)),
    }


def band_columns(split) -> dict:
    """The :data:`BAND_COLUMNS` of one band split [unit of the quantity].

    Parameters
    ----------
    split : lsbg.stats.bands.BandSplit
        Of a run's full-rate record (:func:`lsbg.aggregate.runs.run_band_split`).
    """
    mode = sum(split.mode_variance.values()) if split.mode_variance else np.nan
    return {column: float(np.sqrt(mode if band == "mode" else split.variance[band]))
            for column, band in BAND_COLUMNS.items()}


def run_dynamic_factor(ds, steady_state_after=0.2):
    """A run's dynamic factor: its largest full-rate contact torque over the static load.

    Parameters
    ----------
    ds : xarray.Dataset
        A run (:func:`lsbg.dynamics.dataset.open_run`).
    steady_state_after : float
        Start of the steady state [s].

    Returns
    -------
    float
        [-] (:func:`lsbg.stats.spectra.dynamic_factor`).
    """
    from lsbg.stats import spectra

    full = full_rate_series(ds, "contact_torque", steady_state_after)
    return spectra.dynamic_factor(full, float(ds.attrs["solver_load_torque_N_m"]))


def _run_name(ds):
    """The run's file name without its extension ("" for a dataset not from a file)."""
    source = ds.encoding.get("source")
    return Path(source).stem if source else ""


def mesh_summary(ds) -> list:
    """Summary rows of a loaded TCA (:func:`lsbg.tca.loaded.loaded_tca`).

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


def _contact_state_base(ds):
    base = {column: np.nan for column in SUMMARY_COLUMNS}
    base.update(trace=ds.attrs["design_trace"],
                spiral_angle_deg=round(float(ds.attrs["design_spiral_angle_deg"]), 9),
                contact_model=None, engine="tca", run=_run_name(ds), out_of_control=None)
    return base


def tca_summary(ds) -> list:
    """Summary row of an unloaded TCA (:func:`lsbg.tca.analysis.tooth_contact_analysis`).

    Returns
    -------
    list of dict
        One row, keys :data:`SUMMARY_COLUMNS` (engine "tca", no contact model: the
        flank surfaces): the unloaded transmission error [urad], its mean and std
        over the mesh cycle and its peak to peak.
    """
    te = ds["transmission_error"].values
    return [{**_contact_state_base(ds), "quantity": "unloaded_transmission_error",
             "mean": float(te.mean()), "std": float(te.std(ddof=1)),
             "peak_to_peak": float(ds.attrs["transmission_error_peak_to_peak_urad"])}]


def vh_summary(ds) -> list:
    """Summary rows of a V-H map (:func:`lsbg.tca.vh_map.misalignment_map`).

    Returns
    -------
    list of dict
        Per axis of the map (its ``axes`` attribute, in order) one row per
        quantity of :data:`CONTACT_STATE_QUANTITIES`, keys :data:`SUMMARY_COLUMNS`
        (engine "tca"): quantity ``{quantity}_per_0_1_{axis}``, the change per
        0.1 mm (0.1 deg) through the aligned pair in ``mean`` (unit:
        :data:`SUMMARY_UNITS`); NaN where the map lacks it.
    """
    base = _contact_state_base(ds)
    return [{**base, "quantity": f"{q}_per_0_1_{axis}",
             "mean": float(ds.attrs.get(f"{q}_per_0_1_{axis}", np.nan))}
            for axis in str(ds.attrs["axes"]).split() for q in CONTACT_STATE_QUANTITIES]


def summary_table(paths, steady_state_after=0.2, window=(0.8, 1.0),
                  subgroup_size=4, meshes=(), tca=(), vh_maps=()) -> pd.DataFrame:
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
    tca, vh_maps : sequence of str or os.PathLike
        Unloaded-TCA files (``lsbg tca``) and V-H maps (``lsbg misalignment-map``).

    Returns
    -------
    pandas.DataFrame
        One row per run and quantity of :data:`SUMMARY_QUANTITIES` (see
        :func:`quantity_summary`), then two per loaded TCA (see
        :func:`mesh_summary`), one per unloaded TCA (:func:`tca_summary`) and
        four per axis of each V-H map (:func:`vh_summary`); columns
        :data:`SUMMARY_COLUMNS`, then the design keys (``design_*``, in the
        configuration's units) and the load (``load_torque_N_m``) that are not
        the same for every row.

    Raises
    ------
    ValueError
        Naming the file and quantity when a statistic cannot be computed.
    """
    rows, designs = [], []
    for path in as_path_list(paths):
        ds = open_run(path)
        for quantity in SUMMARY_QUANTITIES:
            try:
                rows.append(quantity_summary(ds, quantity, steady_state_after, window,
                                             subgroup_size))
            except ValueError as err:
                raise ValueError(f"{path}: {quantity}: {err}") from None
            designs.append(_design_columns(ds))
    for files, read, summarise in ((meshes, open_mesh, mesh_summary), (tca, open_tca, tca_summary),
                                   (vh_maps, open_vh_map, vh_summary)):
        for path in as_path_list(files):
            ds = read(path)
            found = summarise(ds)
            rows.extend(found)
            designs.extend([_design_columns(ds)] * len(found))
    table = pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS))
    table["out_of_control"] = table["out_of_control"].astype("Int64")
    return _with_varying(table, pd.DataFrame(designs, index=table.index))


#: The design keys a dataset records (``design_<key>``) beyond the trace and spiral angle,
#: which the summary has as columns already.
_DESIGN_COLUMNS = tuple(f"design_{key}" for key in CONFIG_KEYS
                        if key not in ("trace", "spiral_angle_deg"))


def _design_columns(ds):
    """The design keys and the load a dataset records, as summary columns."""
    columns = {k: ds.attrs[k] for k in _DESIGN_COLUMNS if k in ds.attrs}
    load = ds.attrs.get("solver_load_torque_N_m", ds.attrs.get("load_torque_N_m"))
    if load is not None:
        columns["load_torque_N_m"] = load
    return columns


def _with_varying(table, designs):
    """``table`` with the columns of ``designs`` whose value is not the same on every row
    (a design or a load that varies across the study's runs), after its own."""
    varying = [c for c in designs.columns if designs[c].dropna().astype(str).nunique() > 1]
    return pd.concat([table, designs[varying]], axis=1) if varying else table
