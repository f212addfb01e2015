"""The sweep dataset: the runs of one engine, the loaded TCAs and the contact state,
stacked (``lsbg combine``).

:func:`combine_runs` stacks one run per contact model and design point
(trace x spiral angle) on dims (contact_model, trace, spiral_angle, time), adds
one value per design point of its design attributes (:data:`POINT_VARIABLES`)
and of its loaded TCA (:data:`MESH_VARIABLES`), and the contact state
(:func:`add_contact_state`: the unloaded TCA, :data:`TCA_VARIABLES`, and the
V-H map with its sensitivities), and keeps the attributes common to every run
(CF-1.11). Units are the runs' (the paper's).
"""

from __future__ import annotations

import datetime
import re
from pathlib import Path

import numpy as np
import xarray as xr

import lsbg
from lsbg.contact.parameters import CONTACT_MODELS
from lsbg.gear.design import TRACES, TRACE_LABELS, TRACE_NAMES

#: The trace coordinate's long name: each trace's gear type and construction.
TRACE_LONG_NAME = "tooth trace (" + "; ".join(f"{t}: {n}" for t, n in TRACE_NAMES.items()) + ")"
from lsbg.dynamics.dataset import FULL_RATE_VARIABLES, VARIABLES, open_run
from lsbg.files import as_path_list, open_dataset
from lsbg.aggregate.runs import datasets_by_key, open_mesh, run_source, run_spiral_angle

__all__ = ["POINT_VARIABLES", "MESH_VARIABLES", "TCA_VARIABLES", "VH_PREFIX", "combine_runs",
           "add_contact_state", "open_tca", "open_vh_map", "contact_state_point",
           "sensitivity_attributes"]


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


#: Unloaded-TCA attribute (``lsbg tca``, :func:`lsbg.tca.analysis.tooth_contact_analysis`)
#: -> (variable of the sweep dataset, units, long_name): one value per design point.
TCA_VARIABLES = {
    "transmission_error_peak_to_peak_urad": (
        "unloaded_transmission_error_peak_to_peak", "urad",
        "peak-to-peak unloaded transmission error (tooth contact analysis of the real flanks)"),
    "pattern_centre_cone_distance_mm": (
        "pattern_centre_cone_distance", "mm",
        "bearing pattern's centre on the gear flank: distance from the apex"),
    "pattern_centre_height_mm": (
        "pattern_centre_height", "mm",
        "bearing pattern's centre on the gear flank: height above the root cone"),
    "pattern_length_mm": ("pattern_length", "mm", "bearing pattern's length along the face"),
    "pattern_length_per_face_width": ("pattern_length_per_face_width", "1",
                                      "bearing pattern's length over the face width"),
    "edge_contact_share": ("edge_contact_share", "1",
                           "share of mesh positions whose contact ellipse reaches an edge of "
                           "the active flank (unloaded)"),
    "backlash_min_urad": ("backlash_min", "urad",
                          "least backlash over the mesh cycle (free play of the gear, gear "
                          "rotation)"),
}
#: Prefix of the V-H map's variables in the sweep dataset (``vh_pattern_length`` ...).
VH_PREFIX = "vh_"
#: A V-H map's sensitivity attribute: ``{quantity}_per_0_1_{axis}``.
_SENSITIVITY = re.compile(r"^(\w+)_per_0_1_(E|P|G|Sigma)$")


def combine_runs(paths, meshes=(), tca=(), vh_maps=()) -> xr.Dataset:
    """Stack the runs of one engine, the loaded TCAs and the contact state into the
    sweep dataset.

    Parameters
    ----------
    paths : sequence of str or os.PathLike
        Run files (``lsbg simulate``), one per contact model and design
        point, all of the same engine and time axes.
    meshes : sequence of str or os.PathLike
        Loaded-TCA files (``lsbg ltca``), at most one per design point.
    tca, vh_maps : sequence of str or os.PathLike
        Unloaded-TCA files (``lsbg tca``, ``lsbg misalignment-map --tca-out``) and
        V-H maps (``lsbg misalignment-map``), at most one of each per design
        point (:func:`add_contact_state`).

    Returns
    -------
    xarray.Dataset
        Dims (contact_model, trace, spiral_angle, time) and time_full.
        Coordinates ``contact_model``, ``trace`` (with ``gear_type``:
        'LSBG'/'SBG'), ``spiral_angle`` [degree], ``time``, ``time_full`` [s];
        the run variables of :data:`lsbg.dynamics.dataset.VARIABLES` on (contact_model,
        trace, spiral_angle, time) and those of
        :data:`lsbg.dynamics.dataset.FULL_RATE_VARIABLES` on (..., time_full); per
        design point the variables of :data:`POINT_VARIABLES` and, from the
        loaded TCAs, :data:`MESH_VARIABLES` and the ``static_transmission_error``
        and ``mesh_stiffness`` curves on (trace, spiral_angle, mesh_phase);
        the contact state's variables (:func:`add_contact_state`).
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
    tcas = [open_tca(path) for path in as_path_list(tca)]
    maps = [open_vh_map(path) for path in as_path_list(vh_maps)]
    state = {contact_state_point(ds) for ds in [*tcas, *maps]}
    models = [m for m in CONTACT_MODELS if m in {k[0] for k in points}]
    present = {k[1] for k in points} | {k[0] for k in mesh_data} | {k[0] for k in state}
    traces = [t for t in TRACES if t in present] + sorted(present - set(TRACES))
    angles = sorted({k[2] for k in points} | {k[1] for k in mesh_data} | {k[1] for k in state})
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
        "trace": ("trace", traces, {"long_name": TRACE_LONG_NAME}),
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
            if key in ("units", "long_name", "standard_name", "description")})
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
        "source": f"lsbg {lsbg.__version__} (lsbg.aggregate.combine.combine_runs), engine {engine}",
        "institution": "lsbg reproducible research workflow",
        "history": f"{now} lsbg.aggregate.combine.combine_runs of {len(runs)} runs, {len(mesh_data)} "
                   f"loaded TCAs, {len(tcas)} unloaded TCAs and {len(maps)} V-H maps: "
                   + ", ".join(Path(p).name for p in [*paths, *as_path_list(meshes)])
                   + "".join(f", {Path(p).parent.name}/{Path(p).name}"
                             for p in [*as_path_list(tca), *as_path_list(vh_maps)]),
        "lsbg_version": lsbg.__version__,
        **{key: value for key, value in shared.items() if key != "lsbg_version"},
    })
    out.attrs["solver_engine"] = engine
    return add_contact_state(out, tcas, maps)


# ------------------------------------------------------------ contact state
def open_tca(path) -> xr.Dataset:
    """Read an unloaded-TCA dataset (``lsbg tca``) into memory.

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or not an unloaded-TCA dataset.
    """
    return open_dataset(path, "TCA", ("transmission_error",),
                        ("design_trace", "design_spiral_angle_deg", *TCA_VARIABLES),
                        "an unloaded-TCA dataset of lsbg.tca (lsbg tca)")


def open_vh_map(path) -> xr.Dataset:
    """Read a V-H map (``lsbg misalignment-map``) into memory.

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or not a V-H map.
    """
    ds = open_dataset(path, "V-H map", (), ("design_trace", "design_spiral_angle_deg", "axes"),
                      "a V-H map of lsbg.tca (lsbg misalignment-map)")
    axes = str(ds.attrs["axes"]).split()
    if len(axes) != 2 or not all(a in ds.dims for a in axes):
        raise ValueError(f"{path}: not a V-H map of lsbg.tca (its axes {axes} are not two of "
                         f"its dimensions {sorted(ds.dims)})")
    return ds


def contact_state_point(ds):
    """``(trace, spiral angle [deg])`` of a TCA or V-H map dataset (the angle rounded to
    1e-9 deg, as the runs')."""
    return ds.attrs["design_trace"], run_spiral_angle(ds)


def sensitivity_attributes(ds):
    """A V-H map's sensitivities: ``{attribute: (quantity, axis letter)}`` of its
    ``{quantity}_per_0_1_{axis}`` attributes (axes of the map), in the map's order."""
    axes = str(ds.attrs.get("axes", "")).split()
    out = {}
    for name in ds.attrs:
        match = _SENSITIVITY.match(name)
        if match and match.group(2) in axes:
            out[name] = (match.group(1), match.group(2))
    return out


def _by_point(datasets, what):
    return datasets_by_key(datasets, contact_state_point,
                           lambda key, other: f"{what} of design point {key[0]}, {key[1]:g} deg "
                                              f"already given by {other}")


def _with_points(sweep, keys):
    """``sweep`` with every design point of ``keys`` on its trace and spiral_angle axes
    (NaN where nothing was there), traces in lsbg's order, angles ascending."""
    have_traces = [str(t) for t in sweep["trace"].values] if "trace" in sweep.coords else []
    have_angles = ([float(a) for a in sweep["spiral_angle"].values]
                   if "spiral_angle" in sweep.coords else [])
    present = set(have_traces) | {k[0] for k in keys}
    traces = [t for t in TRACES if t in present] + sorted(present - set(TRACES))
    angles = sorted(set(have_angles) | {k[1] for k in keys})
    if traces == have_traces and angles == have_angles:
        return sweep
    attrs = {name: dict(sweep[name].attrs) if name in sweep.coords else default
             for name, default in (
                 ("trace", {"long_name": TRACE_LONG_NAME}),
                 ("gear_type", {"long_name": "gear type as named in the paper"}),
                 ("spiral_angle", {"units": "degree",
                                   "long_name": "mean spiral angle on the pitch cone"}))}
    sweep = sweep.drop_vars("gear_type", errors="ignore")
    sweep = sweep.reindex({name: values for name, values in (("trace", traces),
                                                            ("spiral_angle", angles))
                           if name in sweep.dims})
    return sweep.assign_coords(
        trace=("trace", traces, attrs["trace"]),
        gear_type=("trace", [TRACE_LABELS.get(t, t) for t in traces], attrs["gear_type"]),
        spiral_angle=("spiral_angle", np.asarray(angles, dtype=float), attrs["spiral_angle"]))


def add_contact_state(sweep, tcas=(), vh_maps=()) -> xr.Dataset:
    """The sweep dataset with the contact state of its design points.

    A pure function: datasets in, a new dataset out (``sweep`` is not changed).

    Parameters
    ----------
    sweep : xarray.Dataset
        With coordinates ``trace`` and ``spiral_angle`` (:func:`combine_runs`);
        design points of ``tcas`` and ``vh_maps`` it lacks are added (NaN for
        its other variables).
    tcas : sequence of xarray.Dataset
        Unloaded TCAs (:func:`lsbg.tca.analysis.tooth_contact_analysis`), at most
        one per design point (attributes ``design_trace``,
        ``design_spiral_angle_deg``).
    vh_maps : sequence of xarray.Dataset
        V-H maps (:func:`lsbg.tca.vh_map.misalignment_map`) on the same two axes,
        at most one per design point; their grids may differ (e.g. 9 values
        per axis at the paper's point, 5 at the others).

    Returns
    -------
    xarray.Dataset
        ``sweep`` and, on (trace, spiral_angle): the variables of
        :data:`TCA_VARIABLES`, and each sensitivity ``{quantity}_per_0_1_{axis}``
        of the maps (units e.g. ``mm/(0.1 mm)``, ``urad/(0.1 degree)``); on
        (trace, spiral_angle, axis 1, axis 2), the axes named by their letters
        (E, P, G, Sigma; mm or degree): each map variable as ``vh_<name>``
        on the union of the maps' grids (an outer join: NaN where a point's map
        has no cell). Every variable has ``units`` (``1`` for a share) and
        ``long_name``. Missing design points are NaN.

    Raises
    ------
    ValueError
        A design point given twice, or maps on different axes; naming the file.
    """
    tcas, vh_maps = list(tcas), list(vh_maps)
    if not tcas and not vh_maps:
        return sweep
    tca_points = _by_point(tcas, "unloaded TCA")
    map_points = _by_point(vh_maps, "V-H map")
    out = _with_points(sweep.copy(), set(tca_points) | set(map_points))
    traces = [str(t) for t in out["trace"].values]
    angles = [float(a) for a in out["spiral_angle"].values]
    shape = (len(traces), len(angles))

    def index(key):
        return traces.index(key[0]), angles.index(key[1])

    if tca_points:
        for attr, (name, units, long_name) in TCA_VARIABLES.items():
            values = np.full(shape, np.nan)
            for key, ds in tca_points.items():
                values[index(key)] = float(ds.attrs[attr])
            out[name] = (("trace", "spiral_angle"), values,
                         {"units": units, "long_name": long_name})
    if not map_points:
        return out
    first = next(iter(map_points.values()))
    axes = str(first.attrs["axes"]).split()
    for ds in map_points.values():
        if str(ds.attrs["axes"]).split() != axes:
            raise ValueError(f"{run_source(ds)}: V-H map on the axes {ds.attrs['axes']}, "
                             f"{run_source(first)} on {' '.join(axes)}; combine maps of one "
                             f"pair of axes")
    # the union of the grids (rounded to 1e-9: the 5 values of a sweep point's map are
    # values of the paper point's 9)
    grid = {a: np.unique(np.concatenate([np.round(ds[a].values.astype(float), 9)
                                         for ds in map_points.values()])) for a in axes}
    names = list(dict.fromkeys(name for ds in map_points.values()
                               for name, var in ds.data_vars.items()
                               if set(var.dims) == set(axes)))
    arrays = {name: np.full(shape + tuple(grid[a].size for a in axes), np.nan) for name in names}
    sensitivities = {}
    for key, ds in map_points.items():
        i, j = index(key)
        cells = np.ix_(*(np.searchsorted(grid[a], np.round(ds[a].values.astype(float), 9))
                         for a in axes))
        for name in names:
            if name in ds.data_vars:
                arrays[name][i, j][cells] = ds[name].transpose(*axes).values
        for attr, (quantity, letter) in sensitivity_attributes(ds).items():
            if attr not in sensitivities:
                source = ds[quantity].attrs if quantity in ds else {}
                per = ds[letter].attrs.get("units", "mm")
                sensitivities[attr] = (np.full(shape, np.nan), {
                    "units": f"{source.get('units', '1')}/(0.1 {per})",
                    "long_name": f"{source.get('long_name', quantity)}: change per 0.1 {per} "
                                 f"of {ds[letter].attrs.get('long_name', letter)} through the "
                                 f"aligned pair (V-H map)"})
            sensitivities[attr][0][i, j] = float(ds.attrs[attr])
    out = out.assign_coords({a: (a, grid[a], {
        key: value for key, value in first[a].attrs.items() if key in ("units", "long_name")})
        for a in axes})
    for name in names:
        attrs = {key: value for key, value in first[name].attrs.items()
                 if key in ("units", "long_name", "standard_name", "description")}
        attrs.setdefault("units", "1")
        attrs["long_name"] = f"V-H map: {attrs.get('long_name', name)}"
        out[f"{VH_PREFIX}{name}"] = (("trace", "spiral_angle", *axes), arrays[name], attrs)
    for attr, (values, attrs) in sensitivities.items():
        out[attr] = (("trace", "spiral_angle"), values, attrs)
    return out


def _same(a, b):
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return bool(np.array_equal(np.asarray(a), np.asarray(b)))
