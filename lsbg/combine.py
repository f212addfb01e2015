"""The sweep dataset: the runs of one engine and the loaded TCAs, stacked (``lsbg combine``).

:func:`combine_runs` stacks one run per contact model and design point
(trace x spiral angle) on dims (contact_model, trace, spiral_angle, time), adds
one value per design point of its design attributes (:data:`POINT_VARIABLES`)
and of its loaded TCA (:data:`MESH_VARIABLES`), and keeps the attributes
common to every run (CF-1.11). Units are the runs' (the paper's).
"""

from __future__ import annotations

import datetime
from pathlib import Path

import numpy as np
import xarray as xr

import lsbg
from lsbg.contact.parameters import CONTACT_MODELS
from lsbg.design import TRACES, TRACE_LABELS
from lsbg.results import FULL_RATE_VARIABLES, VARIABLES, as_path_list, open_run
from lsbg.runs import open_mesh, run_spiral_angle

__all__ = ["POINT_VARIABLES", "MESH_VARIABLES", "combine_runs"]


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


# Per-run attributes that do not describe the whole sweep.
_PER_RUN_ATTRIBUTES = {"Conventions", "title", "source", "history", "institution"}


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
        key = (ds.attrs["contact_model"], ds.attrs["design_trace"], run_spiral_angle(ds))
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
        "source": f"lsbg {lsbg.__version__} (lsbg.combine.combine_runs), engine {engine}",
        "institution": "lsbg reproducible research workflow",
        "history": f"{now} lsbg.combine.combine_runs of {len(runs)} runs and {len(mesh_data)} "
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
