"""Run datasets read back: which gear type, which samples, which theory.

A run is one NetCDF file of :mod:`lsbg.dynamics.dataset` (``lsbg simulate``). The
stages after the runs (:mod:`lsbg.aggregate.combine`, :mod:`lsbg.aggregate.summary`, the tables
and figures) see them through this module: the paper's names of the
quantities and of the gear types (SBG, LSBG, in the paper's order), the
steady-state samples, the full-rate record and the theoretical value
(Eq. 12–13) that goes with a quantity. Units are the datasets' (the paper's):
deg/s, N, N·m, µrad.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3–4.
"""

from __future__ import annotations

import numpy as np

from lsbg.stats.samples import steady_state
from lsbg.gear.design import TRACE_LABELS
from lsbg.solid.directory import read_record
from lsbg.files import as_path_list, open_dataset
from lsbg.dynamics.dataset import open_run

__all__ = [
    "QUANTITIES", "QUANTITY_LABELS", "THEORY_ATTRIBUTES", "FULL_RATE_OF", "TYPE_ORDER",
    "open_pair", "select_runs", "gear_type", "run_spiral_angle", "run_source", "steady",
    "quantity_label", "datasets_by_key", "runs_by_type", "full_rate_series", "open_mesh",
    "records_by_type", "run_theory", "run_mesh_frequency", "run_modes", "run_band_split",
    "pair_traces"
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


#: Summary quantity -> (full-rate variable of the run, divide by the outer
#: pitch radius d2/2).
FULL_RATE_OF = {
    "gear_speed": ("gear_speed_full", False),
    "tangential_force": ("tangential_force_full", False),
    "tangential_force_outer": ("contact_torque_full", True),
    "transmission_error": ("transmission_error_full", False),
    "contact_torque": ("contact_torque_full", False),
}


# Order of gear types in tables and figures: the paper's (a) SBG, (b) LSBG.
TYPE_ORDER = ("SBG", "LSBG")


def pair_traces(traces, sbg_trace=None):
    """The traces of the pair compared as SBG and LSBG among a study's traces.

    Parameters
    ----------
    traces : iterable of str
        The traces a sweep or study holds (:data:`lsbg.gear.design.TRACES`).
    sbg_trace : str, optional
        The SBG to compare (``circular``: the paper's arc; ``face_milled``: ISO 23509's).
        Default: the only SBG of ``traces``, or the paper's arc where they hold both
        (the published pair).

    Returns
    -------
    dict
        ``{'SBG': trace, 'LSBG': 'logarithmic'}``, without a type ``traces`` lacks.

    Raises
    ------
    ValueError
        If ``sbg_trace`` is not an SBG of ``traces``.
    """
    traces = [str(t) for t in traces]
    sbgs = [t for t in traces if TRACE_LABELS.get(t) == "SBG"]
    if sbg_trace is not None and sbg_trace not in sbgs:
        raise ValueError(f"sbg_trace {sbg_trace!r}: not an SBG of the traces {traces}")
    chosen = sbg_trace or ("circular" if "circular" in sbgs else next(iter(sbgs), None))
    pair = {"SBG": chosen, "LSBG": "logarithmic" if "logarithmic" in traces else None}
    return {label: trace for label, trace in pair.items() if trace is not None}


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
            raise ValueError(f"{run_source(ds)}: a {gear_type(ds)} run "
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
    return runs_by_type(chosen)


def gear_type(ds) -> str:
    """The paper's name of a run's gear type: 'LSBG' or 'SBG'."""
    trace = ds.attrs["design_trace"]
    return TRACE_LABELS.get(trace, trace)


def run_spiral_angle(ds):
    """The run's mean spiral angle [deg], rounded to 1e-9 deg (30, not 29.999999999999996)."""
    return round(float(ds.attrs["design_spiral_angle_deg"]), 9)


def run_source(ds):
    return ds.encoding.get("source", "<dataset>")


def steady(ds, name, start=None) -> np.ndarray:
    """Steady-state samples (time > ``start``) of a run variable [its units].

    Parameters
    ----------
    ds : xarray.Dataset
        Run dataset.
    name : str
        Variable, e.g. ``'gear_speed'``.
    start : float, optional
        End of the transient [s]: the study's ``statistics.steady_state_after_s``
        (an extension: ``STUDY.config["statistics"]["steady_state_after_s"]``).
        Default: the end of the run's own speed ramp (``solver_ramp_time_s``, the
        paper's 0.2 s).

    Returns
    -------
    numpy.ndarray
    """
    if start is None:
        start = float(ds.attrs["solver_ramp_time_s"])
    return steady_state(ds[name].values, ds["time"].values, start)


def quantity_label(ds, name):
    """(axis label, units) of a run variable."""
    return QUANTITY_LABELS.get(name, name.replace("_", " ")), ds[name].attrs.get("units", "")


def datasets_by_key(datasets, key_of, clash):
    """``{key: dataset}`` of datasets of which no two share a key.

    Parameters
    ----------
    datasets : iterable of xarray.Dataset
    key_of : callable
        ``key_of(ds)``: the dataset's key (a gear type, a design point).
    clash : callable
        ``clash(key, other)``: the words of the error for a second dataset of
        ``key``, ``other`` the source of the first.

    Returns
    -------
    dict
        In the order of ``datasets``.

    Raises
    ------
    ValueError
        ``"{source}: {clash(key, other)}"`` for the first dataset whose key
        was taken.
    """
    found = {}
    for ds in datasets:
        key = key_of(ds)
        if key in found:
            raise ValueError(f"{run_source(ds)}: {clash(key, run_source(found[key]))}")
        found[key] = ds
    return found


def runs_by_type(runs):
    """{gear type: dataset} in the paper's order, from a dict or a list of runs."""
    if isinstance(runs, dict):
        items = dict(runs)
    else:
        items = datasets_by_key(runs, gear_type,
                                lambda label, other: f"a second {label} run (also {other})")
    order = [t for t in TYPE_ORDER if t in items] + [t for t in items if t not in TYPE_ORDER]
    return {t: items[t] for t in order}


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


def run_mesh_frequency(ds):
    """The run's tooth-mesh frequency [Hz], from its pinion speed and teeth."""
    from lsbg.stats.spectra import mesh_frequency

    return float(mesh_frequency(float(ds.attrs["solver_pinion_speed_deg_s"]),
                                int(ds.attrs["design_pinion_teeth"])))


def run_modes(ds):
    """The natural frequencies [Hz] a run records: its mesh mode's
    (``mesh_natural_frequency_hz``, the line model's gear on the mean mesh stiffness), or
    none (a point-model run)."""
    value = ds.attrs.get("mesh_natural_frequency_hz")
    return () if value is None else (float(value),)


def run_band_split(ds, quantity, start=0.2, modes=None):
    """A quantity's full-rate variance by mesh-harmonic band (:func:`lsbg.stats.bands.band_split`).

    Parameters
    ----------
    ds, quantity, start
        The run, the quantity and the start of its steady state [s], as
        :func:`full_rate_series` takes them.
    modes : sequence of float, optional
        Mode frequencies [Hz]; default :func:`run_modes`.

    Returns
    -------
    lsbg.stats.bands.BandSplit
        [unit of the quantity, squared].
    """
    from lsbg.stats.bands import band_split

    return band_split(full_rate_series(ds, quantity, start), float(ds.attrs["solver_full_rate_hz"]),
                      run_mesh_frequency(ds), run_modes(ds) if modes is None else modes)


def open_mesh(path):
    """Read a loaded-TCA dataset (``lsbg ltca``) into memory.

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or not a loaded-TCA dataset.
    """
    return open_dataset(path, "mesh", ("transmission_error", "mesh_stiffness"),
                        ("design_trace", "transmission_error_harmonic_1_urad"),
                        "a loaded-TCA dataset of lsbg.tca.loaded")


# ------------------------------------------------------- the paper's report
def records_by_type(geometry_dirs):
    """{gear type: design.json record} in the paper's order."""
    if isinstance(geometry_dirs, dict):
        records = {label: read_record(d) for label, d in geometry_dirs.items()}
    else:
        records = {}
        for d in as_path_list(geometry_dirs):
            record = read_record(d)
            label = TRACE_LABELS.get(record["trace"], record["trace"])
            records[label] = record
    order = [t for t in TYPE_ORDER if t in records] + [t for t in records
                                                       if t not in TYPE_ORDER]
    return {t: records[t] for t in order}


def run_theory(ds, quantity):
    return float(ds.attrs[THEORY_ATTRIBUTES[quantity]])
