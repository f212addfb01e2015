"""A parameter sweep's runs as one dataset, and as summary rows.

The runs of one sweep (``lsbg sweep-run``, :mod:`lsbg.experiments.sweeps`) record their
swept values as attributes ``sweep_<section>_<key>``. :func:`sweep_dataset`
stacks their statistics over the trace, the spiral angle and the points: a
sweep of one key gets that key as a dimension, a product sweep its grid (one
dimension per key), a list of combinations a ``point`` dimension with a
coordinate per key. Statistics per run and quantity (:func:`lsbg.aggregate.summary.
quantity_summary`): the mean, the std of the output samples, the full-rate std
and its parts by mesh-harmonic band (:data:`lsbg.aggregate.summary.BAND_COLUMNS`) and,
of the contact torque, the dynamic factor; per point, its quasi-static contact
(:data:`lsbg.experiments.sweeps.CONTACT_FIGURES`: the loaded TCA's transmission error
and the bearing pattern, recorded by ``lsbg sweep-run``). Every variable has ``units``
(the runs' own, paper units) and a ``long_name`` ("transmission error, full-rate std");
a swept key's coordinate is labelled in words without its unit suffix ("lengthwise
crowning", units "um": its configuration units).
"""

from __future__ import annotations

import pandas as pd

from lsbg.aggregate.summary import BAND_COLUMNS

__all__ = ["SWEEP_STATISTICS", "sweep_rows", "sweep_dataset", "sweep_long"]

#: Statistics of each quantity stacked into the dataset: summary column -> name suffix.
#: The full-rate std by band (:data:`lsbg.aggregate.summary.BAND_COLUMNS`) stacks too.
SWEEP_STATISTICS = {"mean": "mean", "std": "std", "full_rate_std": "full_rate_std",
                    **{column: column for column in BAND_COLUMNS}}

#: The words of a statistic in a variable's ``long_name``: name suffix -> words.
_STATISTIC_WORDS = {"mean": "mean", "std": "std", "full_rate_std": "full-rate std",
                    "full_rate_std_below_1": "full-rate std below the 1st mesh harmonic",
                    "full_rate_std_1_3": "full-rate std in mesh harmonics 1-3",
                    "full_rate_std_4_7": "full-rate std in mesh harmonics 4-7",
                    "full_rate_std_8_up": "full-rate std in mesh harmonics 8 and up",
                    "full_rate_std_mode": "full-rate std within one mesh frequency of the "
                                          "mesh mode"}


def _swept(ds):
    """(sweep name, kind, {key: value}) of a run of ``lsbg sweep-run``."""
    from lsbg.experiments.sweeps import swept_attribute

    if "sweep_name" not in ds.attrs:
        raise ValueError(f"{ds.encoding.get('source', '<run>')}: not a run of a sweep "
                         f"(lsbg sweep-run): no sweep_name attribute")
    keys = str(ds.attrs["sweep_keys"]).split()
    return (str(ds.attrs["sweep_name"]), str(ds.attrs.get("sweep_kind", "values")),
            {k: ds.attrs[swept_attribute(k)] for k in keys})


def sweep_rows(runs, steady_state_after=0.2, window=(0.8, 1.0), subgroup_size=4):
    """The summary rows of a sweep's runs with a column per swept key.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        Runs of one sweep.
    steady_state_after, window, subgroup_size
        As :func:`lsbg.aggregate.summary.quantity_summary` [s, s, -].

    Returns
    -------
    pandas.DataFrame
        :data:`lsbg.aggregate.summary.SUMMARY_COLUMNS`'s run columns, ``sweep`` and one
        column per swept key (``contact.dynamic_friction``).
    """
    from lsbg.aggregate.summary import SUMMARY_QUANTITIES, quantity_summary

    swept = [_swept(ds) for ds in runs]
    names = {name for name, _, _ in swept}
    if len(names) > 1:
        raise ValueError(f"runs of several sweeps: {', '.join(sorted(names))}")
    from lsbg.experiments.sweeps import CONTACT_FIGURES

    rows = []
    for ds, (name, _, values) in zip(runs, swept):
        # (the quasi-static contact of the point, on each of its rows: lsbg sweep-run)
        static = {figure: float(ds.attrs[f"static_{figure}"]) for figure in CONTACT_FIGURES
                  if f"static_{figure}" in ds.attrs}
        for quantity in SUMMARY_QUANTITIES:
            if quantity in ds:
                rows.append({"sweep": name, **values,
                             **quantity_summary(ds, quantity, steady_state_after, window,
                                                subgroup_size), **static})
    return pd.DataFrame(rows)


def sweep_dataset(runs, steady_state_after=0.2, window=(0.8, 1.0), subgroup_size=4, rows=None):
    """One sweep's runs as a dataset with a coordinate per swept key.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        Runs of one sweep (all its points at its design points).
    steady_state_after, window, subgroup_size
        As :func:`lsbg.aggregate.summary.quantity_summary` [s, s, -].
    rows : pandas.DataFrame, optional
        :func:`sweep_rows` of these runs with these options, if already computed.

    Returns
    -------
    xarray.Dataset
        Dimensions ``trace``, ``spiral_angle`` [deg] and the swept keys (a
        product or one key) or ``point`` (combinations); variables
        ``{quantity}_{statistic}``, ``dynamic_factor`` and, where the runs recorded
        them, the quasi-static figures of :data:`lsbg.experiments.sweeps.CONTACT_FIGURES`
        (``loaded_te_peak_to_peak`` [urad], ``pattern_length`` [mm], ...); attributes
        ``sweep_name``, ``sweep_kind``, ``sweep_keys``.

    Raises
    ------
    ValueError
        Runs of several sweeps, or two runs of the same point.
    """
    import xarray as xr

    from lsbg.experiments.sweeps import CONTACT_FIGURES

    if rows is None:
        rows = sweep_rows(runs, steady_state_after, window, subgroup_size)
    first = runs[0]
    name, kind, values = _swept(first)
    keys = list(values)
    index = ["trace", "spiral_angle_deg", *keys]
    if kind == "combinations":
        points = rows[keys].drop_duplicates().reset_index(drop=True)
        rows = rows.merge(points.reset_index().rename(columns={"index": "point"}), on=keys)
        index = ["trace", "spiral_angle_deg", "point"]
    wide = {}
    for quantity, part in rows.groupby("quantity", sort=False):
        part = part.set_index(index)
        if part.index.duplicated().any():
            raise ValueError(f"two runs of the same point: {part.index[part.index.duplicated()][0]}")
        for column, suffix in SWEEP_STATISTICS.items():
            wide[f"{quantity}_{suffix}"] = part[column]
        if quantity == "contact_torque":
            wide["dynamic_factor"] = part["dynamic_factor"]
        for figure in CONTACT_FIGURES:
            if figure in part:
                wide.setdefault(figure, part[figure])
    ds = xr.Dataset.from_dataframe(pd.DataFrame(wide))
    ds = ds.rename({"spiral_angle_deg": "spiral_angle"})
    for variable in ds.data_vars:
        ds[variable].attrs.update(_variable_attributes(str(variable), first))
    if kind == "combinations":
        for key in keys:
            ds[key] = ("point", points[key].to_numpy())
        ds = ds.set_coords(keys)
    for key in keys:
        section, field = key.split(".", 1)
        ds[key].attrs.update({"long_name": _config_words(field), "units": _config_unit(field),
                              "description": f"swept {key} (configuration units)"})
    ds["spiral_angle"].attrs.update(units="degree", long_name="mean spiral angle")
    ds["trace"].attrs.update(units="1", long_name="tooth trace")
    if kind == "combinations":
        ds["point"].attrs.update(units="1", long_name="point of the sweep")
    ds.attrs.update({"title": f"parameter sweep {name!r} of lsbg", "sweep_name": name,
                     "sweep_kind": kind, "sweep_keys": " ".join(keys),
                     "steady_state_after_s": float(steady_state_after),
                     "runs": len(runs), "Conventions": "CF-1.11"})
    return ds


#: A configuration key's unit from its suffix (the configuration's units).
_SUFFIX_UNITS = {"_mm": "mm", "_deg": "degree", "_deg_s": "degree/s", "_N_m": "N m",
                 "_um": "um", "_s": "s", "_hz": "Hz", "_mm_s": "mm/s",
                 "_N_per_mm_um": "N/(mm um)", "_N_s_per_mm": "N s/mm",
                 "_N_per_mm1_5": "N/mm^1.5", "_kg_m3": "kg/m^3", "_GPa": "GPa"}


def _config_suffix(field):
    """The unit suffix of a configuration key ("" for a plain number)."""
    return next((suffix for suffix in sorted(_SUFFIX_UNITS, key=len, reverse=True)
                 if field.endswith(suffix)), "")


def _config_unit(field):
    """A configuration key's unit from its suffix ("1" for a plain number)."""
    return _SUFFIX_UNITS.get(_config_suffix(field), "1")


def _config_words(field):
    """A configuration key in words without its unit suffix: ``lengthwise crowning``."""
    return field.removesuffix(_config_suffix(field)).replace("_", " ")


def _variable_attributes(variable, run):
    """``units`` and ``long_name`` of a sweep dataset's variable; ``run``: one of its runs
    (the quantities' own units and names)."""
    from lsbg.experiments.sweeps import CONTACT_FIGURES

    if variable in CONTACT_FIGURES:
        _, _, units, long_name = CONTACT_FIGURES[variable]
        return {"units": units, "long_name": long_name}
    if variable == "dynamic_factor":
        return {"units": "1", "long_name": "dynamic factor"}
    quantity, suffix = next((variable[:-len(s) - 1], s) for s in
                            sorted(SWEEP_STATISTICS.values(), key=len, reverse=True)
                            if variable.endswith("_" + s))
    attrs = run[quantity].attrs
    return {"units": attrs.get("units", "1"),
            "long_name": f"{attrs.get('long_name', quantity.replace('_', ' '))}, "
                         f"{_STATISTIC_WORDS[suffix]}"}


def sweep_long(ds, variables):
    """A sweep dataset in long form, for tables and figures against the swept keys.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`sweep_dataset`.
    variables : sequence of str
        Its variables to keep.

    Returns
    -------
    pandas.DataFrame
        ``gear_type`` (the trace's construction, :data:`lsbg.gear.design.TRACE_NAMES`:
        "LSBG", "SBG, paper's arc", "SBG, ISO 23509 face-milled"), ``spiral_angle_deg``,
        a column per swept key and per variable; rows of points not run (a product's
        holes) left out.
    """
    from lsbg.gear.design import TRACE_NAMES

    keys = str(ds.attrs["sweep_keys"]).split()
    table = ds[list(variables)].to_dataframe().reset_index()
    table = table.dropna(subset=list(variables), how="all")
    table.insert(0, "gear_type", table.pop("trace").map(lambda t: TRACE_NAMES.get(t, t)))
    table = table.rename(columns={"spiral_angle": "spiral_angle_deg"})
    return table[["gear_type", "spiral_angle_deg", *keys, *variables]]
