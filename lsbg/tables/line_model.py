"""Tables of the line model's verdict: LSBG against SBG, with the model form varied.

Built from run datasets (:mod:`lsbg.dynamics.dataset`, opened with
:func:`lsbg.dynamics.dataset.open_run`), loaded TCAs (:mod:`lsbg.tca.loaded`) and the sweep
dataset (:func:`lsbg.aggregate.combine.combine_runs`); every statistic comes from
:mod:`lsbg.stats` and :mod:`lsbg.stats.spectra`. Units are the datasets' (deg/s, N,
µrad, N/µm).

* :func:`mesh_table`: the loaded TCA of both gear types side by side;
* :func:`fluctuation_table`: full-rate fluctuations with block-bootstrap
  intervals, the paper's 500-sample statistic beside them, and the ratio
  SBG/LSBG with its interval;
* :func:`sampling_luck_table`: the 500-sample std at every sampling phase;
* :func:`sensitivity_table` and :func:`verdict`: the ratio in every cell of
  the model-form sensitivity, and a ranking stated only where every cell
  agrees;
* :func:`sweep_fluctuation_table` and :func:`trend_table`: the same against
  spiral angle, and whether a series follows a trend or zig-zags;
* :func:`speed_curve_table` and :func:`speed_ratio_table`: the dynamic-factor
  curve's resonances and peaks, and SBG over LSBG at each pinion speed.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import stats as sps

from lsbg import stats
from lsbg.stats import spectra
from lsbg.gear.design import TRACE_NAMES
from lsbg.aggregate.runs import QUANTITY_LABELS, TYPE_ORDER, full_rate_series, pair_traces, steady

#: Quantities compared under the line model (full-rate variables exist for them).
VERDICT_QUANTITIES = ("gear_speed", "tangential_force", "transmission_error")

#: Loaded-TCA figures of :func:`mesh_table`: attribute -> (label, unit).
MESH_FIGURES = {
    "transmission_error_peak_to_peak_urad": ("static transmission error, peak to peak", "urad"),
    "transmission_error_harmonic_1_urad": ("  its 1st mesh harmonic", "urad"),
    "transmission_error_harmonic_2_urad": ("  its 2nd mesh harmonic", "urad"),
    "transmission_error_harmonic_3_urad": ("  its 3rd mesh harmonic", "urad"),
    "transmission_error_mean_urad": ("static transmission error, mean", "urad"),
    "mesh_stiffness_mean_N_per_um": ("mesh stiffness, mean", "N/um"),
    "mesh_stiffness_per_face_width_N_per_mm_um": ("  per unit face width (c_γ)", "N/(mm um)"),
    "mesh_stiffness_peak_to_peak_N_per_um": ("mesh stiffness, peak to peak", "N/um"),
    "mesh_stiffness_variation_percent": ("  over its mean", "%"),
}


def _ordered(by_type):
    return {t: by_type[t] for t in TYPE_ORDER if t in by_type}


def mesh_table(meshes) -> pd.DataFrame:
    """The loaded TCA of the gear types side by side (smaller is smoother).

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}``.

    Returns
    -------
    pandas.DataFrame
        Rows of :data:`MESH_FIGURES` and the contact length's range; columns
        ``figure``, ``unit``, one per gear type and ``ratio`` (SBG / LSBG).
    """
    meshes = _ordered(meshes)
    rows = []
    for attr, (label, unit) in MESH_FIGURES.items():
        row = {"figure": label, "unit": unit}
        row.update({t: float(ds.attrs[attr]) for t, ds in meshes.items()})
        rows.append(row)
    for label, reduce in (("contact length, least", np.min), ("contact length, most", np.max)):
        row = {"figure": label, "unit": "mm"}
        row.update({t: float(reduce(ds["contact_length"].values)) for t, ds in meshes.items()})
        rows.append(row)
    table = pd.DataFrame(rows)
    if set(TYPE_ORDER) <= set(meshes):
        table["ratio"] = table["SBG"] / table["LSBG"]
    return table


def _series(ds, quantity, start, full_rate):
    return full_rate_series(ds, quantity, start) if full_rate else steady(ds, quantity, start)


def compare_fluctuation(runs, quantity, start=0.2, full_rate=True, confidence=0.95,
                        n_boot=2000, seed=0) -> dict:
    """std(SBG) / std(LSBG) of one quantity, with block-bootstrap intervals.

    Parameters
    ----------
    runs : dict
        ``{'SBG': run, 'LSBG': run}``.
    quantity : str
        A key of :data:`lsbg.aggregate.runs.FULL_RATE_OF`.
    start : float
        Start of the steady state [s].
    full_rate : bool
        The full-rate record (True) or the output samples (the paper's 500 Hz).
    confidence, n_boot, seed
        Of the block bootstrap (:func:`lsbg.stats.std_ci`, :func:`lsbg.stats.std_ratio_ci`).

    Returns
    -------
    dict
        ``std_SBG``, ``std_SBG_low``, ``std_SBG_high`` (the same for LSBG),
        ``ratio``, ``ratio_low``, ``ratio_high`` and ``calmer``: the gear type
        with the smaller fluctuation where the interval of the ratio excludes
        1, else ``"neither"``.
    """
    series = {t: _series(runs[t], quantity, start, full_rate) for t in TYPE_ORDER}
    row = {}
    for t, x in series.items():
        ci = stats.std_ci(x, confidence=confidence, n_boot=n_boot, seed=seed)
        row.update({f"std_{t}": ci.std, f"std_{t}_low": ci.low, f"std_{t}_high": ci.high})
    ratio = stats.std_ratio_ci(series["SBG"], series["LSBG"], confidence=confidence,
                               n_boot=n_boot, seed=seed)
    calmer = "LSBG" if ratio.low > 1.0 else "SBG" if ratio.high < 1.0 else "neither"
    row.update(ratio=ratio.ratio, ratio_low=ratio.low, ratio_high=ratio.high, calmer=calmer)
    return row


def fluctuation_table(runs, start=0.2, quantities=VERDICT_QUANTITIES, **options) -> pd.DataFrame:
    """Full-rate fluctuations of SBG and LSBG, the 500-sample statistic beside them.

    Parameters
    ----------
    runs : dict
        ``{'SBG': run, 'LSBG': run}`` of one contact model and engine.
    start : float
        Start of the steady state [s].
    quantities : sequence of str
    **options
        Passed to :func:`compare_fluctuation`.

    Returns
    -------
    pandas.DataFrame
        Per quantity and sampling ("full rate", "output samples"): the
        columns of :func:`compare_fluctuation`, plus ``unit`` and, on the
        full-rate rows, the dynamic factor of each type (contact torque: peak
        over static).
    """
    rows = []
    for quantity in quantities:
        unit = runs["SBG"][quantity].attrs.get("units", "")
        for full_rate, sampling in ((True, "full rate"), (False, "output samples")):
            row = {"quantity": quantity, "unit": unit, "sampling": sampling}
            row.update(compare_fluctuation(runs, quantity, start, full_rate, **options))
            rows.append(row)
    table = pd.DataFrame(rows)
    for t in TYPE_ORDER:
        torque = full_rate_series(runs[t], "contact_torque", start)
        table[f"dynamic_factor_{t}"] = spectra.dynamic_factor(
            torque, float(runs[t].attrs["solver_load_torque_N_m"]))
    return table


def sampling_luck_table(runs, start=0.2, quantities=("gear_speed", "tangential_force")):
    """The paper's 500-sample std at every sampling phase, against the full rate.

    Parameters
    ----------
    runs : dict
        ``{label: run}`` (e.g. per gear type and contact model).
    start : float
        Start of the steady state [s].
    quantities : sequence of str

    Returns
    -------
    pandas.DataFrame
        Per run and quantity: ``sampled_std`` (the run's own output sampling),
        ``phase_std_min``, ``phase_std_median``, ``phase_std_max`` over every
        sampling phase, ``full_rate_std`` and ``spread_percent`` (max − min
        over the median).
    """
    rows = []
    for label, ds in runs.items():
        rate = float(ds.attrs["solver_samples"]) / float(ds.attrs["solver_duration_s"])
        for quantity in quantities:
            full = full_rate_series(ds, quantity, start)
            spread = spectra.sampling_phase_spread(full, float(ds.attrs["solver_full_rate_hz"]),
                                                   rate)
            median = float(np.median(spread))
            rows.append({"run": label, "quantity": quantity,
                         "unit": ds[quantity].attrs.get("units", ""),
                         "sampled_std": float(steady(ds, quantity, start).std(ddof=1)),
                         "phase_std_min": float(spread.min()), "phase_std_median": median,
                         "phase_std_max": float(spread.max()),
                         "full_rate_std": spectra.rms_fluctuation(full),
                         "spread_percent": 100 * float(np.ptp(spread)) / median})
    return pd.DataFrame(rows)


def sensitivity_table(cells, start=0.2, quantities=("gear_speed", "tangential_force"),
                      **options) -> pd.DataFrame:
    """The ratio SBG/LSBG in every cell of a model-form sensitivity study.

    Parameters
    ----------
    cells : sequence of (str, dict, bool)
        (label, ``{'SBG': run, 'LSBG': run}``, full_rate) per cell; the first
        cell is the baseline the others are compared with.
    start : float
        Start of the steady state [s].
    quantities : sequence of str
        Run variables compared in every cell.
    **options
        Passed to :func:`compare_fluctuation`.

    Returns
    -------
    pandas.DataFrame
        Per cell and quantity: ``ratio`` with ``ratio_low``/``ratio_high``,
        ``calmer`` and ``holds``: the cell's interval excludes 1 on the same
        side as the baseline's (False when the baseline itself names no
        calmer type).
    """
    rows = []
    baseline = {}
    for k, (label, runs, full_rate) in enumerate(cells):
        for quantity in quantities:
            result = compare_fluctuation(runs, quantity, start, full_rate, **options)
            if k == 0:
                baseline[quantity] = result["calmer"]
            holds = baseline[quantity] != "neither" and result["calmer"] == baseline[quantity]
            rows.append({"cell": label, "quantity": quantity, "ratio": result["ratio"],
                         "ratio_low": result["ratio_low"], "ratio_high": result["ratio_high"],
                         "calmer": result["calmer"], "holds": bool(holds)})
    return pd.DataFrame(rows)


def verdict(sensitivity, where="") -> str:
    """One paragraph: which type meshes more smoothly, stated only where every cell agrees.

    Parameters
    ----------
    sensitivity : pandas.DataFrame
        From :func:`sensitivity_table`.
    where : str, optional
        The design point the cells were run at (e.g. "at 35°"); each ranking
        is stated for it alone.

    Returns
    -------
    str
        Markdown built from the numbers.
    """
    sentences = []
    where_text = f" {where.strip()}" if where.strip() else ""
    for quantity, part in sensitivity.groupby("quantity", sort=False):
        label = QUANTITY_LABELS.get(quantity, quantity)
        baseline = part.iloc[0]
        low, high = part["ratio"].min(), part["ratio"].max()
        if part["holds"].all():
            sentences.append(
                f"**{label}**: the {baseline['calmer']} fluctuates less{where_text} in every one of the "
                f"{len(part)} cells (std(SBG)/std(LSBG) {low:.3g}–{high:.3g} over the cells, "
                f"each cell's interval over windows of its run excluding 1): this ranking "
                f"survives the model form.")
        elif baseline["calmer"] == "neither":
            calmer = [f"{row.cell} ({row.calmer} calmer, {row.ratio:.3g})"
                      for row in part.itertuples() if row.calmer != "neither"]
            sentences.append(
                f"**{label}**: in the baseline no type is significantly calmer (ratio "
                f"{baseline['ratio']:.3g}, interval over windows of the run "
                f"{baseline['ratio_low']:.3g}–"
                f"{baseline['ratio_high']:.3g}), so no ranking is stated"
                + (f"; a type is significantly calmer only in: {', '.join(calmer)}." if calmer
                   else "; no cell finds a significant difference."))
        else:
            failing = ", ".join(
                f"{row.cell} ({row.ratio:.3g}, "
                f"{'no significant difference' if row.calmer == 'neither' else row.calmer + ' calmer'})"
                for row in part.itertuples() if not row.holds)
            sentences.append(
                f"**{label}**: the {baseline['calmer']} is calmer in the baseline (ratio "
                f"{baseline['ratio']:.3g}; {low:.3g}–{high:.3g} over the {len(part)} cells), but "
                f"the ranking does not survive the model form: it fails in {failing}.")
    return " ".join(sentences)


# -------------------------------------------------------------------- sweep
def sweep_fluctuation_table(sweep, start=0.2, quantities=VERDICT_QUANTITIES, confidence=0.95,
                            n_boot=1000, seed=0) -> pd.DataFrame:
    """Fluctuations of every design point and contact model of a sweep.

    Parameters
    ----------
    sweep : xarray.Dataset
        From :func:`lsbg.aggregate.combine.combine_runs` (with full-rate variables).
    start : float
        Start of the steady state [s].
    quantities : sequence of str
    confidence, n_boot, seed
        Of the block bootstrap.

    Returns
    -------
    pandas.DataFrame
        Per (contact model, gear type, spiral angle): ``gear_type`` names the trace's
        construction (:data:`lsbg.gear.design.TRACE_NAMES`: "SBG, paper's arc", "SBG,
        ISO 23509 face-milled"), ``trace`` the trace; for each quantity the
        full-rate std with its interval (``<q>_std``, ``_low``, ``_high``) and
        the std of the output samples (``<q>_sampled_std``); the dynamic
        factor; and, where the sweep has loaded TCAs, their figures.
    """
    rows = []
    time_full = sweep["time_full"].values
    keep_full = time_full >= start - 1e-9
    time = sweep["time"].values
    for model in sweep["contact_model"].values:
        for trace in sweep["trace"].values:
            for angle in sweep["spiral_angle"].values:
                point = sweep.sel(contact_model=model, trace=trace, spiral_angle=angle)
                if not np.isfinite(point["gear_speed"].values).all():
                    continue
                row = {"contact_model": str(model),
                       "gear_type": TRACE_NAMES.get(str(trace), str(trace)),
                       "trace": str(trace), "spiral_angle_deg": float(angle)}
                for quantity in quantities:
                    full = point[f"{quantity}_full"].values[keep_full]
                    ci = stats.std_ci(full, confidence=confidence, n_boot=n_boot, seed=seed)
                    row.update({f"{quantity}_std": ci.std, f"{quantity}_std_low": ci.low,
                                f"{quantity}_std_high": ci.high,
                                f"{quantity}_sampled_std": float(stats.steady_state(
                                    point[quantity].values, time, start).std(ddof=1))})
                torque = point["contact_torque_full"].values[keep_full]
                row["dynamic_factor"] = spectra.dynamic_factor(
                    torque, float(sweep.attrs.get("solver_load_torque_N_m", np.nan)))
                for name in ("static_transmission_error_peak_to_peak",
                             "static_transmission_error_harmonic_1", "mesh_stiffness_variation",
                             "mesh_stiffness_per_face_width", "contact_ratio"):
                    if name in sweep:
                        row[name] = float(sweep[name].sel(trace=trace, spiral_angle=angle))
                rows.append(row)
    return pd.DataFrame(rows)


def sweep_ratio_table(sweep, contact_model="line", quantities=VERDICT_QUANTITIES, start=0.2,
                      full_rate=True, sbg_trace=None, **options) -> pd.DataFrame:
    """std(SBG)/std(LSBG) with its interval at every spiral angle of a sweep.

    Parameters
    ----------
    sweep : xarray.Dataset
        From :func:`lsbg.aggregate.combine.combine_runs`.
    contact_model : str
    sbg_trace : str, optional
        The SBG compared (:func:`lsbg.aggregate.runs.pair_traces`: by default the sweep's
        only SBG, or the paper's arc where it holds both).
    quantities : sequence of str
    start : float
        Start of the steady state [s].
    full_rate : bool
        The full-rate record (True) or the output samples.
    **options
        Passed to :func:`compare_fluctuation`.

    Returns
    -------
    pandas.DataFrame
        Per spiral angle with both types and quantity: ``sbg`` (the SBG's name,
        :data:`lsbg.gear.design.TRACE_NAMES`), ``ratio``, ``ratio_low``, ``ratio_high``
        and ``calmer``.
    """
    model = sweep.sel(contact_model=contact_model)
    types = pair_traces(model["trace"].values, sbg_trace)
    sbg = TRACE_NAMES.get(types.get("SBG"), "SBG")
    rows = []
    for angle in model["spiral_angle"].values:
        point = {t: model.sel(trace=trace, spiral_angle=angle) for t, trace in types.items()}
        if not all(t in point and np.isfinite(point[t]["gear_speed"].values).all() for t in TYPE_ORDER):
            continue
        for quantity in quantities:
            result = compare_fluctuation(point, quantity, start, full_rate, **options)
            rows.append({"spiral_angle_deg": float(angle), "quantity": quantity, "sbg": sbg,
                         **{k: result[k] for k in ("ratio", "ratio_low", "ratio_high", "calmer")}})
    return pd.DataFrame(rows, columns=["spiral_angle_deg", "quantity", "sbg", "ratio", "ratio_low",
                                       "ratio_high", "calmer"])


def angle_ranges(angles, grid=None) -> str:
    """Spiral angles as runs of neighbours on the sweep's grid, "20–25°, 40°".

    Parameters
    ----------
    angles : sequence of float
        The spiral angles to name [deg].
    grid : sequence of float, optional
        Every spiral angle of the sweep [deg] (default: ``angles``); two
        angles are neighbours when no angle of the grid lies between them.

    Returns
    -------
    str
        "" for no angle.
    """
    grid = sorted({round(float(a), 9) for a in (angles if grid is None else grid)})
    chosen = {round(float(a), 9) for a in angles}
    groups, current = [], []
    for angle in grid:
        if angle in chosen:
            current.append(angle)
        elif current:
            groups.append(current)
            current = []
    if current:
        groups.append(current)
    return ", ".join(f"{g[0]:g}°" if len(g) == 1 else f"{g[0]:g}–{g[-1]:g}°" for g in groups)


def calmer_by_angle(ratios, grid=None) -> pd.DataFrame:
    """Where in a sweep each type is significantly calmer, per quantity.

    Parameters
    ----------
    ratios : pandas.DataFrame
        From :func:`sweep_ratio_table`.
    grid : sequence of float, optional
        The sweep's spiral angles [deg], to tell runs of neighbours apart
        (default: the angles of ``ratios``).

    Returns
    -------
    pandas.DataFrame
        Per quantity (and SBG, where ``ratios`` has an ``sbg`` column: one row per SBG
        compared, ``sbg`` its name): ``LSBG``, ``SBG`` and ``neither``: the spiral angles
        where that type has the significantly smaller fluctuation (its 95 %
        interval of std(SBG)/std(LSBG) excluding 1), as :func:`angle_ranges`
        text, and ``angles``: how many spiral angles were compared.
    """
    rows = []
    everything = list(grid) if grid is not None else list(ratios["spiral_angle_deg"])
    keys = ["quantity"] + (["sbg"] if "sbg" in ratios.columns else [])
    for key, part in ratios.groupby(keys, sort=False):
        row = dict(zip(keys, key))
        for calmer in ("LSBG", "SBG", "neither"):
            chosen = part.loc[part.calmer == calmer, "spiral_angle_deg"]
            row[calmer] = angle_ranges(chosen, everything) or "none"
        row["angles"] = int(part["spiral_angle_deg"].nunique())
        rows.append(row)
    return pd.DataFrame(rows, columns=[*keys, "LSBG", "SBG", "neither", "angles"])


def trend_table(table, columns, along="spiral_angle_deg", by=()) -> pd.DataFrame:
    """Does a series follow the spiral angle (or another swept value), or zig-zag from one
    value to the next?

    Parameters
    ----------
    table : pandas.DataFrame
        With ``along``, ``gear_type`` and optionally ``contact_model`` columns,
        e.g. from :func:`sweep_fluctuation_table`.
    columns : sequence of str
        Columns to judge.
    along : str
        The column the series runs along: the spiral angle [deg], or a swept
        key of a parameter sweep.
    by : sequence of str
        Further columns that tell series apart (the other keys of a product
        sweep).

    Returns
    -------
    pandas.DataFrame
        Per (contact model, gear type, ``by``, column): the number of values
        (``angles``), the values themselves (``values``, text), Spearman's rank
        correlation with ``along`` and its p-value (:func:`spearman`: exact for
        few values), and ``reversals``: how often the change from one value to
        the next flips sign, out of ``possible`` (n − 2). A monotone trend has
        none; a neighbour-to-neighbour zig-zag has about all of them. Groups
        with fewer than 3 values are left out.
    """
    keys = [k for k in ("contact_model", "gear_type", *by) if k in table.columns]
    rows = []
    for group, part in table.groupby(keys, sort=False):
        part = part.sort_values(along)
        group = group if isinstance(group, tuple) else (group,)
        if len(part) < 3:  # too few values to tell a trend from a zig-zag
            continue
        for column in columns:
            if column not in part or part[column].isna().all():
                continue
            values = part[column].to_numpy()
            change = np.sign(np.diff(values))
            reversals = int(np.sum(change[1:] * change[:-1] < 0))
            rho, p = spearman(part[along].to_numpy(), values)
            rows.append({**dict(zip(keys, group)), "column": column, "angles": len(values),
                         "values": ", ".join(f"{v:g}" for v in part[along]),
                         "spearman_rho": rho, "spearman_p": p,
                         "reversals": reversals, "possible": max(len(values) - 2, 0)})
    return pd.DataFrame(rows)


#: Up to this many values, :func:`spearman`'s p-value is the exact one (every ordering).
EXACT_SPEARMAN_UP_TO = 8


def spearman(x, y):
    """Spearman's rank correlation of two series and its two-sided p-value.

    Up to :data:`EXACT_SPEARMAN_UP_TO` values the p-value is exact: the share of all
    n! orderings of ``y`` whose correlation is as far from 0 (Pearson's r of the ranks
    under :class:`scipy.stats.PermutationMethod` with every ordering); three monotone
    points give 1/3, not the t approximation's 0. Beyond, scipy's t approximation.

    Parameters
    ----------
    x, y : numpy.ndarray
        Paired values (any units).

    Returns
    -------
    tuple of float
        (rho, p) [-]; both NaN where either series is constant.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if np.ptp(x) == 0 or np.ptp(y) == 0:
        return float("nan"), float("nan")
    rho, p = sps.spearmanr(x, y)
    if x.size <= EXACT_SPEARMAN_UP_TO:
        p = sps.pearsonr(sps.rankdata(x), sps.rankdata(y),
                         method=sps.PermutationMethod(n_resamples=np.inf)).pvalue
    return float(rho), float(min(1.0, p))


# ------------------------------------------------------------ speed sweep
def speed_curve_table(curve) -> pd.DataFrame:
    """Per gear type: the mesh mode, the resonance speeds and the peaks of the curves.

    Parameters
    ----------
    curve : xarray.Dataset
        From :func:`lsbg.experiments.speed.speed_curve`: per trace its
        ``natural_frequency`` [Hz], ``resonance_speed`` per order [deg/s] and
        the curves over ``pinion_speed`` [deg/s].

    Returns
    -------
    pandas.DataFrame
        ``gear_type``, ``natural_frequency_hz``, ``resonance_speed_deg_s``
        (f_mesh = f_n) and ``..._half``/``..._third`` (f_n/2, f_n/3), and for
        RMS DTE [urad], dynamic factor [-] and gear-speed fluctuation [%] the
        peak and the pinion speed where it occurs [deg/s].
    """
    speeds = curve["pinion_speed"].values
    rows = []
    for trace in curve["trace"].values:
        row = {"gear_type": TRACE_NAMES.get(str(trace), str(trace)),
               "natural_frequency_hz": float(curve["natural_frequency"].sel(trace=trace))}
        for order, suffix in ((1, ""), (2, "_half"), (3, "_third")):
            row[f"resonance_speed{suffix}_deg_s"] = float(
                curve["resonance_speed"].sel(trace=trace, order=order))
        for name, label in (("dte_rms", "dte_rms_peak_urad"),
                            ("dynamic_factor", "dynamic_factor_peak"),
                            ("gear_speed_fluctuation", "gear_speed_fluctuation_peak_percent")):
            values = curve[name].sel(trace=trace).values
            k = int(np.nanargmax(values))
            row[label] = float(values[k])
            row[f"{name}_peak_speed_deg_s"] = float(speeds[k])
        rows.append(row)
    return pd.DataFrame(rows)


def speed_ratio_table(curve) -> pd.DataFrame:
    """SBG over LSBG at each pinion speed (empty unless both traces ran).

    Returns
    -------
    pandas.DataFrame
        ``pinion_speed_deg_s``, ``mesh_frequency_over_fn`` (the LSBG's f_n),
        and the ratios SBG/LSBG of the RMS DTE, of the dynamic increment
        (dynamic factor − 1) and of the gear-speed fluctuation [-].
    """
    traces = [str(t) for t in curve["trace"].values]
    if not {"logarithmic", "circular"} <= set(traces):
        return pd.DataFrame()
    sbg, lsbg = curve.sel(trace="circular"), curve.sel(trace="logarithmic")
    return pd.DataFrame({
        "pinion_speed_deg_s": curve["pinion_speed"].values,
        "mesh_frequency_over_fn": curve["mesh_frequency"].values
        / float(lsbg["natural_frequency"]),
        "dte_rms_ratio": sbg["dte_rms"].values / lsbg["dte_rms"].values,
        "dynamic_increment_ratio": (sbg["dynamic_factor"].values - 1)
        / (lsbg["dynamic_factor"].values - 1),
        "gear_speed_fluctuation_ratio": sbg["gear_speed_fluctuation"].values
        / lsbg["gear_speed_fluctuation"].values,
    })
