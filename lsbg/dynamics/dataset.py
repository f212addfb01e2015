"""Time series of a meshing run as a CF-annotated NetCDF dataset.

Inside lsbg the record is SI; the dataset speaks the paper's units: speeds in
deg/s, forces in N, penetration in µm and the transmission error in µrad,
each variable with ``units`` and ``long_name`` (CF-1.11).
"""

from __future__ import annotations

import datetime
import functools
import math
import platform

import numpy as np
import xarray as xr

import lsbg
from lsbg.gear import theory
from lsbg.files import as_path_list, open_dataset, short_labels

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


@functools.lru_cache(maxsize=1)
def _library_versions():
    """``{version_<name>: version}`` of the libraries a run depends on.

    Looked up once per process (about 6 ms a time: each looks through the
    installed distributions); a running process keeps the versions it imported.
    """
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
    variables = {name: ("time", data[name], {"units": units, "long_name": long_name})
                 for name, (units, long_name) in VARIABLES.items()}
    for name, source in FULL_RATE_VARIABLES.items():
        units, long_name = VARIABLES[source]
        variables[name] = ("time_full", full[source], {"units": units,
                                                       "long_name": f"{long_name}, full rate"})
    # one merge for all of them (a merge per variable costs milliseconds each); the
    # variables still follow the coordinates, in this order
    ds.update(variables)
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"Meshing simulation of a {design.trace} spiral bevel gear pair "
                 f"({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg, "
                 f"{model.contact.params.model} contact model)",
        "source": f"lsbg {lsbg.__version__}, engine {settings.engine}",
        "institution": "lsbg reproducible research workflow",
        "history": f"{datetime.datetime.now(datetime.timezone.utc).isoformat(timespec='seconds')} "
                   f"{command or 'lsbg.dynamics.dataset.run_dataset'}",
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
                     mesh_natural_frequency_hz=model.contact.natural_frequency(model.contact.gear_inertia),
                     mean_mesh_stiffness_N_per_m=model.contact.mean_mesh_stiffness())
    if model.driveline is not None and settings.boundary == "driveline":
        contact = model.contact
        stiffness = contact.mean_torsional_stiffness() if contact.params.model == "line" \
            else float("nan")
        attrs.update(model.driveline.attrs(stiffness, contact.e1 / contact.e2))
    if "driveline_mode3_hz" in attrs:  # the mesh mode of the linearised driveline
        attrs["mesh_natural_frequency_hz"] = attrs["driveline_mode3_hz"]
    attrs.update({f"solver_{k}": v for k, v in settings.to_dict().items()})
    attrs.update(_library_versions())
    ds.attrs.update({k: (float(v) if isinstance(v, (np.floating, np.integer)) else v)
                     for k, v in attrs.items()})
    return short_labels(ds)


#: Attributes every run dataset carries (checked by :func:`open_run`).
REQUIRED_ATTRIBUTES = ("design_trace", "design_spiral_angle_deg", "solver_engine",
                       "contact_model", "solver_full_rate_hz", "solver_load_torque_N_m",
                       "theory_gear_speed_deg_s", "theory_tangential_force_N")


def open_run(path) -> xr.Dataset:
    """Read a run dataset (:func:`run_dataset`, written by ``lsbg simulate``) into memory.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file.

    Returns
    -------
    xarray.Dataset
        As :func:`lsbg.files.open_dataset` returns it, with the variables of
        a run and :data:`REQUIRED_ATTRIBUTES`.

    Raises
    ------
    lsbg.files.InputError
        See :func:`lsbg.files.open_dataset`.
    """
    return open_dataset(path, "run", ("time", "time_full", *VARIABLES, *FULL_RATE_VARIABLES),
                        REQUIRED_ATTRIBUTES, "a run dataset of lsbg.dynamics.dataset")


def open_runs(paths) -> list:
    """:func:`open_run` for each path (a single path is accepted too)."""
    return [open_run(p) for p in as_path_list(paths)]
