"""The dynamic-factor curve: a pinion-speed sweep through the mesh resonance.

The line model's mesh mode (the gear on the mean mesh stiffness, the pinion
on its prescribed speed) has one natural frequency f_n
(:meth:`lsbg.contact.mesh.MeshContact.natural_frequency`, 1.83 kHz for the
paper's pair). The mesh excites it at the tooth-mesh frequency
f_m = z1 n1 and its harmonics, so the dynamic response peaks where
f_m = f_n and, weaker, where a harmonic meets it (f_m = f_n / 2, f_n / 3).
This module sets up one run per pinion speed (:func:`speed_settings`: the
ramp, a settling time and a steady window of whole mesh cycles, the full-rate
record fast enough for the mesh harmonics) and turns the runs into the curve
a gear engineer reads (:func:`speed_curve`): RMS dynamic transmission error,
dynamic factor (peak dynamic mesh force over static) and gear-speed
fluctuation against pinion speed, with each run's transmission-error
spectrum on a common frequency grid for a Campbell-style map.

SI inside; the dataset carries the paper's units (deg/s, urad, Hz).
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.stats import spectra
from lsbg.dynamics.settings import SimulationSettings

__all__ = ["speed_keywords", "SPEED_QUANTITIES", "speed_grid", "resonance_speeds", "speed_settings",
           "speed_point", "speed_curve"]

#: Scalars of each speed: name -> (units, long name).
SPEED_QUANTITIES = {
    "dte_rms": ("urad", "RMS dynamic transmission error (about its mean)"),
    "dynamic_factor": ("1", "dynamic factor: peak dynamic mesh force over static"),
    "gear_speed_std": ("deg/s", "standard deviation of the gear speed"),
    "gear_speed_fluctuation": ("%", "standard deviation of the gear speed over its mean"),
    "tangential_force_std": ("N", "standard deviation of the tangential contact force"),
}
#: Output samples per second of each run (the paper's 500 per second) [1/s].
OUTPUT_RATE = 500.0


def speed_grid(start, stop, count):
    """Pinion speeds spaced evenly on a log scale (equal ratio between neighbours).

    Parameters
    ----------
    start, stop : float
        First and last pinion speed [rad/s], 0 < start < stop.
    count : int
        Number of speeds, >= 2 [-].

    Returns
    -------
    numpy.ndarray
        [rad/s]
    """
    if not (0 < start < stop and math.isfinite(stop)):
        raise ValueError(f"start, stop = {start!r}, {stop!r}: need 0 < start < stop [rad/s]")
    if int(count) != count or count < 2:
        raise ValueError(f"count = {count!r}: must be a whole number >= 2")
    return np.geomspace(start, stop, int(count))


def resonance_speeds(natural_frequency, pinion_teeth, orders=(1, 2, 3)):
    """Pinion speeds at which the k-th mesh harmonic meets the natural frequency.

    Parameters
    ----------
    natural_frequency : float
        f_n of the mesh mode [Hz].
    pinion_teeth : int
        z1 [-].
    orders : sequence of int
        Harmonic orders k [-]: f_m = f_n / k.

    Returns
    -------
    numpy.ndarray
        Pinion speed of each order [rad/s].
    """
    return np.array([2 * math.pi * natural_frequency / (k * pinion_teeth) for k in orders])


def speed_keywords(section):
    """Keywords of :func:`speed_settings` from the configuration's ``speed_sweep`` section.

    Parameters
    ----------
    section : dict
        ``mesh_cycles``, ``min_window_s``, ``settle_time_s``, ``ramp_time_s`` and
        ``samples_per_mesh`` (the schema's defaults filled in).

    Returns
    -------
    dict
    """
    return {"mesh_cycles": section["mesh_cycles"], "min_window": section["min_window_s"],
            "settle_time": section["settle_time_s"], "ramp_time": section["ramp_time_s"],
            "samples_per_mesh": section["samples_per_mesh"]}


def speed_settings(base: SimulationSettings, pinion_speed, pinion_teeth, mesh_cycles=100,
                   min_window=0.05, settle_time=0.05, ramp_time=0.05, samples_per_mesh=32):
    """Settings of the run at one pinion speed of the sweep.

    The pinion ramps to its speed in ``ramp_time``; the response settles for
    ``settle_time`` (the line model's mesh mode decays with the time constant
    1 / (zeta omega_n), 1.7 ms for the paper's pair); the steady window that
    follows holds at least ``mesh_cycles`` mesh cycles and lasts at least
    ``min_window``. The full-rate record covers the window at no less than
    the base settings' rate and ``samples_per_mesh`` samples per mesh cycle,
    a whole multiple of the 500 per second output rate.

    Parameters
    ----------
    base : SimulationSettings
        Everything else (engine, load, tolerances).
    pinion_speed : float
        [rad/s]
    pinion_teeth : int
        z1 [-].
    mesh_cycles : int
        Least mesh cycles in the steady window [-].
    min_window, settle_time, ramp_time : float
        [s]
    samples_per_mesh : int
        Least full-rate samples per mesh cycle [-].

    Returns
    -------
    SimulationSettings
    """
    for name, value in (("pinion_speed", pinion_speed), ("mesh_cycles", mesh_cycles),
                        ("min_window", min_window), ("samples_per_mesh", samples_per_mesh)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r}: must be positive")
    for name, value in (("settle_time", settle_time), ("ramp_time", ramp_time)):
        if not (math.isfinite(value) and value >= 0):
            raise ValueError(f"{name} = {value!r}: must be zero or positive [s]")
    mesh = pinion_speed * pinion_teeth / (2 * math.pi)
    interval = 1.0 / OUTPUT_RATE
    start = math.ceil((ramp_time + settle_time) / interval - 1e-9) * interval
    window = max(min_window, mesh_cycles / mesh)
    samples = int(math.ceil((start + window) / interval - 1e-9))
    per_output = max(math.ceil(base.full_rate / OUTPUT_RATE - 1e-9),
                     math.ceil(samples_per_mesh * mesh / OUTPUT_RATE - 1e-9))
    return base.replace(pinion_speed=float(pinion_speed), ramp_time=float(ramp_time),
                        duration=samples * interval, samples=samples,
                        full_rate=per_output * OUTPUT_RATE, full_rate_after=start)


def speed_point(ds):
    """The curve's values of one run (its full-rate record).

    Parameters
    ----------
    ds : xarray.Dataset
        A run of the sweep (:func:`lsbg.dynamics.simulate` with
        :func:`speed_settings`).

    Returns
    -------
    values : dict
        ``pinion_speed`` [deg/s], ``mesh_frequency`` [Hz] and the
        :data:`SPEED_QUANTITIES` in their units.
    frequency, amplitude : numpy.ndarray
        Amplitude spectrum of the transmission error [Hz, urad].
    """
    rate = float(ds.attrs["solver_full_rate_hz"])
    start = float(ds.attrs["solver_full_rate_after_s"])
    time = ds["time_full"].values
    keep = time >= start - 0.5 / rate
    te = ds["transmission_error_full"].values[keep]
    torque = ds["contact_torque_full"].values[keep]
    speed = ds["gear_speed_full"].values[keep]
    force = ds["tangential_force_full"].values[keep]
    pinion_speed = float(ds.attrs["solver_pinion_speed_deg_s"])
    values = {
        "pinion_speed": pinion_speed,
        "mesh_frequency": float(spectra.mesh_frequency(pinion_speed,
                                                       int(ds.attrs["design_pinion_teeth"]))),
        "dte_rms": spectra.rms_fluctuation(te),
        "dynamic_factor": spectra.dynamic_factor(torque, float(ds.attrs["solver_load_torque_N_m"])),
        "gear_speed_std": spectra.rms_fluctuation(speed),
        "gear_speed_fluctuation": 100 * spectra.rms_fluctuation(speed) / abs(float(speed.mean())),
        "tangential_force_std": spectra.rms_fluctuation(force),
    }
    frequency, amplitude = spectra.amplitude_spectrum(te, rate)
    return values, frequency, amplitude


def _binned_peak(frequency, amplitude, edges):
    """Largest amplitude of the spectrum within each frequency bin.

    A bin narrower than the spectrum's resolution may hold no line: it takes
    the spectrum interpolated at its centre; beyond the spectrum's top, NaN.
    """
    index = np.searchsorted(edges, frequency, side="right") - 1
    inside = (index >= 0) & (index < edges.size - 1)
    out = np.full(edges.size - 1, -np.inf)
    np.maximum.at(out, index[inside], amplitude[inside])
    centre = 0.5 * (edges[1:] + edges[:-1])
    empty = ~np.isfinite(out)
    out[empty] = np.interp(centre[empty], frequency, amplitude, right=np.nan)
    return out


def speed_curve(runs, max_frequency=None, bins=300, orders=3):
    """The dynamic-factor curve of a set of speed-sweep runs.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        Runs of one contact model at one spiral angle, any traces, each
        trace at the same pinion speeds.
    max_frequency : float, optional
        Top of the spectrum map [Hz]; default 3 f_n of the highest natural
        frequency or 1.2 times the highest mesh frequency, whichever is more.
    bins : int
        Frequency bins of the spectrum map [-] (each holds the peak amplitude
        of the run's spectrum inside it, so narrow lines stay visible).
    orders : int
        The mesh harmonics 1..orders whose resonance speeds are given [-].

    Returns
    -------
    xarray.Dataset
        Dimensions ``trace`` and ``pinion_speed`` [deg/s] (and ``frequency``
        [Hz] for ``dte_spectrum`` [urad]); ``mesh_frequency`` [Hz], the
        :data:`SPEED_QUANTITIES`, ``natural_frequency`` per trace [Hz] and
        ``resonance_speed`` per trace and order (f_m = f_n / k) [deg/s].

    Raises
    ------
    ValueError
        If the runs are empty, mix contact models or spiral angles, lack the
        mesh mode's natural frequency, mix boundaries, or the traces differ in their
        speeds.
    """
    import xarray as xr

    runs = list(runs)
    if not runs:
        raise ValueError("runs: no speed-sweep runs given")
    for key in ("contact_model", "design_spiral_angle_deg", "solver_boundary"):
        found = sorted({str(ds.attrs.get(key, "prescribed_pinion")) for ds in runs})
        if len(found) > 1:
            raise ValueError(f"runs: mixed {key} {found}; a curve is one model at one angle under one boundary")
    missing = [ds.encoding.get("source", "?") for ds in runs
               if "mesh_natural_frequency_hz" not in ds.attrs]
    if missing:
        raise ValueError(f"runs {missing}: no mesh_natural_frequency_hz attribute (the speed "
                         f"sweep needs the line model)")
    points = {}
    for ds in runs:
        trace = str(ds.attrs["design_trace"])
        values, frequency, amplitude = speed_point(ds)
        points.setdefault(trace, []).append((values, frequency, amplitude,
                                             float(ds.attrs["mesh_natural_frequency_hz"])))
    traces = sorted(points)
    for trace in traces:
        points[trace].sort(key=lambda point: point[0]["pinion_speed"])
    speeds = np.array([point[0]["pinion_speed"] for point in points[traces[0]]])
    for trace in traces[1:]:
        other = np.array([point[0]["pinion_speed"] for point in points[trace]])
        if other.shape != speeds.shape or not np.allclose(other, speeds, rtol=1e-9):
            raise ValueError(f"runs: trace {trace} has pinion speeds {other.tolist()}, "
                             f"{traces[0]} has {speeds.tolist()} [deg/s]; they must match")
    natural = np.array([points[t][0][3] for t in traces])
    mesh = np.array([point[0]["mesh_frequency"] for point in points[traces[0]]])
    top = max_frequency or max(3 * natural.max(), 1.2 * mesh.max())
    edges = np.linspace(0.0, top, bins + 1)
    teeth = int(runs[0].attrs["design_pinion_teeth"])
    orders = np.arange(1, int(orders) + 1)
    data = {
        "mesh_frequency": (("pinion_speed",), mesh,
                           {"units": "Hz", "long_name": "tooth-mesh frequency"}),
        "natural_frequency": (("trace",), natural,
                              {"units": "Hz", "long_name": "natural frequency of the mesh mode"}),
        "resonance_speed": (("trace", "order"),
                            np.degrees([resonance_speeds(f, teeth, orders) for f in natural]),
                            {"units": "deg/s",
                             "long_name": "pinion speed at which the mesh frequency is f_n / order"}),
        "dte_spectrum": (("trace", "pinion_speed", "frequency"),
                         np.array([[_binned_peak(p[1], p[2], edges) for p in points[t]]
                                   for t in traces]),
                         {"units": "urad", "long_name": "peak amplitude of the transmission "
                                                        "error spectrum in the frequency bin"}),
    }
    for name, (units, long_name) in SPEED_QUANTITIES.items():
        data[name] = (("trace", "pinion_speed"),
                      np.array([[p[0][name] for p in points[t]] for t in traces]),
                      {"units": units, "long_name": long_name})
    first = runs[0].attrs
    return xr.Dataset(
        data,
        coords={"trace": ("trace", traces),
                "pinion_speed": ("pinion_speed", speeds,
                                 {"units": "deg/s", "long_name": "pinion speed"}),
                "order": ("order", orders, {"long_name": "mesh harmonic meeting f_n"}),
                "frequency": ("frequency", 0.5 * (edges[1:] + edges[:-1]),
                              {"units": "Hz", "long_name": "centre of the frequency bin"})},
        attrs={"title": "Dynamic-factor curve: pinion-speed sweep through the mesh resonance",
               "contact_model": str(first["contact_model"]),
               "design_spiral_angle_deg": float(first["design_spiral_angle_deg"]),
               "solver_engine": str(first["solver_engine"]),
               "solver_boundary": str(first.get("solver_boundary", "prescribed_pinion")),
               "solver_load_torque_N_m": float(first["solver_load_torque_N_m"]),
               "design_pinion_teeth": teeth},
    )
