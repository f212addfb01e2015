"""Time series of a meshing run as a CF-annotated NetCDF dataset.

Inside lsbg the record is SI; the dataset speaks the paper's units: speeds in
deg/s, forces in N, penetration in µm and the transmission error in µrad,
each variable with ``units`` and ``long_name`` (CF-1.11).
"""

from __future__ import annotations

import datetime
import math
import os
import platform
from pathlib import Path

import numpy as np
import xarray as xr

import lsbg
from lsbg import theory
from lsbg.files import (InputError, InputFileNotFoundError, remove_stale_temporaries,
                        temporary_beside)

#: Variables of a run dataset on ``time``: name -> (units, long_name).
VARIABLES = {
    "pinion_speed": ("deg/s", "pinion angular velocity"),
    "gear_speed": ("deg/s", "gear angular velocity"),
    "tangential_force": ("N", "contact force on the gear along its circumferential "
                              "direction at each point of action, summed over tooth pairs"),
    "tangential_force_outer": ("N", "contact torque on the gear divided by the outer pitch "
                                    "radius d2/2 (the quantity of Eq. 13)"),
    "contact_torque": ("N m", "contact torque on the gear about its axis"),
    "normal_force": ("N", "sum of the normal contact forces of all tooth pairs"),
    "contact_pairs": ("1", "number of tooth pairs carrying load"),
    "max_penetration": ("um", "deepest normal approach of the flanks"),
    "transmission_error": ("urad", "gear rotation behind its kinematic position "
                                   "phi1 z1/z2 - phi2"),
}
#: Variables of a run dataset on ``time_full`` (the full-rate record):
#: name -> variable of :data:`VARIABLES` it samples at the full rate.
FULL_RATE_VARIABLES = {
    "gear_speed_full": "gear_speed",
    "tangential_force_full": "tangential_force",
    "transmission_error_full": "transmission_error",
    "contact_torque_full": "contact_torque",
}


def _series_data(series, design):
    """The dataset's variables (paper units) from a :class:`lsbg.dynamics.Series`."""
    z1, z2 = design.teeth
    te = series.pinion_angle * z1 / z2 - series.gear_angle
    return {
        "pinion_speed": np.degrees(series.pinion_speed),
        "gear_speed": np.degrees(series.gear_speed),
        "tangential_force": series.tangential_force,
        "tangential_force_outer": series.gear_torque / (design.pitch_diameter(2) / 2),
        "contact_torque": series.gear_torque,
        "normal_force": series.normal_force,
        "contact_pairs": series.contact_pairs,
        "max_penetration": series.max_penetration * 1e6,
        "transmission_error": te * 1e6,
    }


def _library_versions():
    import importlib.metadata as md

    out = {}
    for name in ("numpy", "scipy", "pybullet", "xarray", "netCDF4"):
        try:
            out[f"version_{name}"] = md.version(name)
        except md.PackageNotFoundError:
            out[f"version_{name}"] = "not installed"
    return out


def run_dataset(record, model, settings, command=""):
    """Build the dataset of one run.

    Parameters
    ----------
    record : lsbg.dynamics.RunRecord
        Raw SI time series.
    model : lsbg.dynamics.MeshingModel
        The simulated system (design, contact parameters, inertias).
    settings : lsbg.dynamics.SimulationSettings
    command : str
        Command line that produced the run, for ``history``.

    Returns
    -------
    xarray.Dataset
        Coordinates ``time`` and ``time_full`` [s], the variables of
        :data:`VARIABLES` on ``time`` and of :data:`FULL_RATE_VARIABLES` on
        ``time_full``.
    """
    design = model.pair.design
    z1, z2 = design.teeth
    data = _series_data(record.samples, design)
    full = _series_data(record.full_rate, design)
    ds = xr.Dataset(coords={
        "time": ("time", record.samples.time, {"units": "s", "long_name": "time",
                                               "standard_name": "time"}),
        "time_full": ("time_full", record.full_rate.time, {
            "units": "s", "long_name": f"time of the full-rate record "
                                      f"({settings.full_rate:g} per s)"}),
    })
    for name, (units, long_name) in VARIABLES.items():
        ds[name] = ("time", data[name], {"units": units, "long_name": long_name})
    for name, source in FULL_RATE_VARIABLES.items():
        units, long_name = VARIABLES[source]
        ds[name] = ("time_full", full[source], {"units": units,
                                                "long_name": f"{long_name}, full rate"})
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"Meshing simulation of a {design.trace} spiral bevel gear pair "
                 f"({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg, "
                 f"{model.contact.params.model} contact model)",
        "source": f"lsbg {lsbg.__version__}, engine {settings.engine}",
        "institution": "lsbg reproducible research workflow",
        "history": f"{datetime.datetime.now(datetime.timezone.utc).isoformat(timespec='seconds')} "
                   f"{command or 'lsbg.results.run_dataset'}",
        "lsbg_version": lsbg.__version__,
        "python_version": platform.python_version(),
        "theory_gear_speed_deg_s": theory.gear_speed(math.degrees(settings.pinion_speed), z1, z2),
        "theory_tangential_force_N": theory.tangential_force(settings.load_torque,
                                                             design.pitch_diameter(2)),
        "axial_inertia_gear_kg_m2": model.gear_inertia,
        "axial_inertia_pinion_kg_m2": model.pinion_inertia,
        "wall_time_s": record.wall_time,
        "integrator_steps": record.steps,
    }
    separation = model.contact.separation
    if separation is not None:  # real flanks: their modification and displacements
        attrs.update(separation.attrs)
    attrs.update({f"design_{k}": v for k, v in design.to_config().items()})
    attrs.update({f"design_{k}": v for k, v in design.derived().items()})
    ratio = model.pair.contact_ratio()
    attrs.update(design_contact_ratio=ratio["total"], design_contact_ratio_profile=ratio["profile"],
                 design_contact_ratio_face=ratio["face"])
    attrs.update({f"contact_{k}": v for k, v in model.contact.params.to_dict().items()})
    if model.contact.slice_stiffness is not None:  # the tooth's own compliance
        attrs.update({f"slice_stiffness_{k}": v
                      for k, v in model.contact.slice_stiffness.attrs.items()})
    if model.contact.params.model == "line":
        attrs.update(contact_line_damping_N_s_per_m2=model.contact.damping_coefficient,
                     mesh_natural_frequency_hz=model.contact.natural_frequency(model.gear_inertia),
                     mean_mesh_stiffness_N_per_m=model.contact.mean_mesh_stiffness())
    attrs.update({f"solver_{k}": v for k, v in settings.to_dict().items()})
    attrs.update(_library_versions())
    ds.attrs.update({k: (float(v) if isinstance(v, (np.floating, np.integer)) else v)
                     for k, v in attrs.items()})
    return ds


def write_atomically(path, write):
    """Write a file through a temporary file beside it, renamed at the end.

    A failure (or an interrupt) leaves neither a half-written ``path`` nor the
    temporary file behind; the temporaries of ``path`` that a killed writer
    left (``.<name>.<random>.part``, :func:`lsbg.files.temporary_beside`) are
    removed before writing. The previous ``path`` stays until the new one is
    complete.

    Parameters
    ----------
    path : str or pathlib.Path
        Target file; its folder is created if needed.
    write : callable
        ``write(tmp_path)`` writes the content to the temporary path (a str).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path)
    tmp = temporary_beside(path, "part")
    try:
        write(str(tmp))
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def write_dataset(ds, path):
    """Write a dataset to NetCDF atomically (see :func:`write_atomically`).

    Data variables on ``time_full`` (the full-rate record) are compressed
    (zlib level 1, lossless). Every numeric array carries a Fletcher-32
    checksum, so that reading a corrupted file fails (:func:`open_dataset`)
    instead of returning wrong numbers; it costs about 13 % of the size.

    Parameters
    ----------
    ds : xarray.Dataset
    path : str or pathlib.Path
    """
    encoding = {}
    for name, var in ds.variables.items():
        # HDF5 checksums chunked storage only: not scalars, empty arrays or strings
        if var.dtype.kind in "fiu" and var.ndim and var.size:
            encoding[name] = {"fletcher32": True}
            if name in ds.data_vars and "time_full" in var.dims:
                encoding[name].update(zlib=True, complevel=1, shuffle=True)
    write_atomically(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


#: Attributes every run dataset carries (checked by :func:`open_run`).
REQUIRED_ATTRIBUTES = ("design_trace", "design_spiral_angle_deg", "solver_engine",
                       "contact_model", "solver_full_rate_hz", "solver_load_torque_N_m",
                       "theory_gear_speed_deg_s", "theory_tangential_force_N")


def as_path_list(value) -> list:
    """A list of paths from a path, a list of paths, or ``""``/``None`` (empty).

    Parameters
    ----------
    value : str, os.PathLike, sequence of them, or None

    Returns
    -------
    list of pathlib.Path
    """
    if value is None or (isinstance(value, str) and not value.strip()):
        return []
    if isinstance(value, (str, Path)):
        return [Path(value)]
    return [Path(v) for v in value if str(v).strip()]


def open_run(path) -> xr.Dataset:
    """Read a run dataset (:func:`run_dataset`, written by ``lsbg simulate``) into memory.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file.

    Returns
    -------
    xarray.Dataset
        Loaded (the file is closed); ``encoding['source']`` is the path.

    Raises
    ------
    lsbg.files.InputError
        See :func:`open_dataset`.
    """
    return open_dataset(path, "run", ("time", "time_full", *VARIABLES, *FULL_RATE_VARIABLES),
                        REQUIRED_ATTRIBUTES, "a run dataset of lsbg.results")


def open_dataset(path, kind, variables, attributes, what) -> xr.Dataset:
    """Read a NetCDF file of lsbg into memory, checking what it must hold.

    Parameters
    ----------
    path : str or os.PathLike
    kind : str
        Named in the message for a missing file ("run", "mesh").
    variables, attributes : sequence of str
        Names the dataset must have.
    what : str
        Named in the message for a file that lacks them.

    Returns
    -------
    xarray.Dataset
        Loaded (the file is closed); ``encoding['source']`` is the path.

    Raises
    ------
    lsbg.files.InputError
        In one line naming the file: it does not exist
        (:class:`lsbg.files.InputFileNotFoundError`), is a directory, cannot be
        read, is not NetCDF, is truncated or corrupt (a failed checksum of
        :func:`write_dataset`), or lacks ``variables`` or ``attributes``.
    """
    path = Path(path)
    if not path.exists():
        raise InputFileNotFoundError(f"{path}: no such {kind} file")
    if not path.is_file():
        raise InputError(f"{path}: a directory, not a {kind} file")
    again = "delete it and rerun snakemake (or the lsbg command that wrote it)"
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds = ds.load()
    except PermissionError:
        raise InputError(f"{path}: {kind} file not readable (permission denied)") from None
    # netCDF4 reports a truncated or corrupt file as OSError or RuntimeError
    # ("NetCDF: HDF error", also a failed checksum) or AttributeError (an
    # unreadable attribute); the try holds nothing but the reading.
    except (OSError, ValueError, RuntimeError, AttributeError) as err:
        # the reason without the path again (an OSError's strerror), in one line
        detail = getattr(err, "strerror", None) or (str(err).splitlines() or [repr(err)])[0]
        raise InputError(f"{path}: not a readable NetCDF file, truncated or corrupt "
                         f"({detail}); {again}") from None
    missing = [name for name in variables if name not in ds.variables]
    missing += [name for name in attributes if name not in ds.attrs]
    if missing:
        more = f" and {len(missing) - 5} more" if len(missing) > 5 else ""
        raise InputError(f"{path}: not {what} (missing {missing[:5]}{more}); {again}")
    ds.encoding["source"] = str(path)
    return ds


def open_runs(paths) -> list:
    """:func:`open_run` for each path (a single path is accepted too)."""
    return [open_run(p) for p in as_path_list(paths)]
