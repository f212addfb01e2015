"""Settings of a meshing simulation and the pinion's prescribed motion (SI units).

:class:`SimulationSettings` holds the input, load, output and solver settings;
:meth:`SimulationSettings.from_config` reads the workflow's ``simulation``
section (paper units). :func:`pinion_state` is the paper's input: a STEP ramp
of the pinion speed (Fig. 8) and its closed-form integral.

Output instants
---------------
A run records the state at ``samples + 1`` instants over its duration (the
paper: 500 intervals over 1 s, its statistic's sampling) and, from
``full_rate_after`` on, at ``full_rate`` per second: fast enough to resolve
the contact resonances (about 9 kHz for the point model, 2 kHz for the line
model), so that spectra, RMS fluctuations and peaks are not aliased. The
sample instants inside that window are instants of the full-rate grid too.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from lsbg.contact.law import step_scalar

#: Boundaries of a meshing run (``simulation.boundary``; :mod:`lsbg.dynamics.driveline`).
BOUNDARIES = ("prescribed_pinion", "driveline")

#: Integrators: the multibody engine, scipy's LSODA (or another solve_ivp
#: method), and the compiled embedded Runge-Kutta loop (:mod:`lsbg.dynamics.compiled_engine`).
ENGINES = ("pybullet", "scipy", "compiled")
#: Methods of the scipy engine: LSODA through odeint, the others through solve_ivp.
SCIPY_METHODS = ("DOP853", "LSODA", "RK45", "Radau", "BDF")
#: Embedded Runge-Kutta pairs of the compiled engine.
COMPILED_METHODS = ("DOP853", "RK45")


class SimulationError(RuntimeError):
    """The integration blew up (NaN, penetration beyond the law's limit, runaway speed)."""


@dataclass(frozen=True)
class SimulationSettings:
    """Input, load, output and solver settings of a meshing simulation (SI units).

    Parameters
    ----------
    engine : {"pybullet", "scipy", "compiled"}
    duration : float
        Simulated time [s].
    samples : int
        Number of output intervals; the output holds ``samples + 1`` instants
        from 0 to ``duration`` (the paper: 500 over 1 s).
    pinion_speed : float
        Final pinion speed [rad/s] (paper: 7703 deg/s).
    ramp_time : float
        Duration of the STEP ramp of the pinion speed from 0 [s].
    load_torque : float
        Resisting torque on the gear [N m].
    time_step : float
        Fixed step of the PyBullet engine [s].
    rtol : float
        Relative tolerance of the scipy and compiled engines [-].
    atol_angle, atol_speed : float
        Absolute tolerances on angle [rad] and speed [rad/s] (scipy and
        compiled engines).
    method : str
        Method of the scipy engine: LSODA (through :func:`scipy.integrate.odeint`)
        or another :func:`scipy.integrate.solve_ivp` method.
    compiled_method : {"DOP853", "RK45"}
        Embedded Runge-Kutta pair of the compiled engine.
    full_rate : float
        Rate of the full-rate record [1/s]; the output interval
        ``duration / samples`` must be a whole multiple of its interval.
    full_rate_after : float, optional
        Start of the full-rate record [s]; an output instant. Default: the
        first output instant at or after the end of the ramp (the paper's
        steady state starts there).
    runaway_factor : float
        A gear speed beyond this multiple of the theoretical speed (or below
        minus it) stops the run [-].
    progress_interval : float
        Wall time between progress reports in the log [s].
    boundary : {"prescribed_pinion", "driveline"}
        The paper's pinion on its prescribed speed (the gear the only
        inertia), or the torsional driveline of :mod:`lsbg.dynamics.driveline`
        (its drive end at ``pinion_speed`` from the start; ``ramp_time`` is
        not used).
    """

    engine: str = "pybullet"
    duration: float = 1.0
    samples: int = 500
    pinion_speed: float = math.radians(7703.0)
    ramp_time: float = 0.2
    load_torque: float = 1964.99
    time_step: float = 1e-6
    rtol: float = 1e-8
    atol_angle: float = 1e-12
    atol_speed: float = 1e-8
    method: str = "LSODA"
    compiled_method: str = "DOP853"
    full_rate: float = 50000.0
    full_rate_after: float | None = None
    runaway_factor: float = 2.0
    progress_interval: float = 5.0
    boundary: str = "prescribed_pinion"

    def __post_init__(self):
        def fail(name, why):
            raise ValueError(f"{name} = {getattr(self, name)!r}: {why}")

        if self.engine not in ENGINES:
            fail("engine", f"must be one of {ENGINES}")
        if self.method not in SCIPY_METHODS:
            fail("method", f"must be one of {SCIPY_METHODS}")
        if self.compiled_method not in COMPILED_METHODS:
            fail("compiled_method", f"must be one of {COMPILED_METHODS}")
        if self.boundary not in BOUNDARIES:
            fail("boundary", f"must be one of {BOUNDARIES}")
        if self.boundary == "driveline" and self.engine == "pybullet":
            fail("boundary", "the pybullet engine runs the prescribed pinion only (its URDF "
                             "holds the pair, not the driveline): use the compiled or scipy engine")
        for name in ("duration", "pinion_speed", "time_step", "rtol", "atol_angle",
                     "atol_speed", "progress_interval", "full_rate"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                fail(name, "must be a positive number")
        for name in ("ramp_time", "load_torque") + (("full_rate_after",)
                                                    if self.full_rate_after is not None else ()):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                fail(name, "must be a non-negative number")
        if isinstance(self.samples, bool) or not float(self.samples).is_integer() or self.samples < 1:
            fail("samples", "must be a positive whole number")
        if self.ramp_time > self.duration:
            fail("ramp_time", f"exceeds the duration {self.duration!r} s")
        interval = self.duration / self.samples
        if self.time_step > interval:
            fail("time_step", f"exceeds the output interval {interval!r} s")
        if self.runaway_factor <= 1:
            fail("runaway_factor", "must exceed 1")
        if self.rtol < 1e-13:
            fail("rtol", "is below what double precision can deliver (1e-13)")
        if not _is_whole(interval * self.full_rate):
            fail("full_rate", f"must divide the output interval {interval!r} s into whole "
                              f"intervals (e.g. a multiple of {1 / interval:g} per s)")
        if self.engine == "pybullet" and not _is_whole(1.0 / (self.full_rate * self.time_step)):
            fail("time_step", f"must divide the full-rate interval {1.0 / self.full_rate!r} s "
                              f"into whole steps (the pybullet engine records on its steps)")
        start = self.full_rate_start
        if start >= self.duration or not _is_whole(start / interval):
            fail("full_rate_after", f"must be an output instant (a multiple of {interval!r} s) "
                                    f"before the end of the run, {self.duration!r} s")

    @classmethod
    def from_config(cls, config, **overrides) -> "SimulationSettings":
        """Settings from the workflow's ``simulation`` section (paper units).

        Parameters
        ----------
        config : dict
            Keys of :data:`SIMULATION_CONFIG_KEYS`, e.g. ``duration_s``,
            ``pinion_speed_deg_s``, ``load_torque_N_m``, ``time_step_s``,
            ``method``, ``rtol``, ``full_rate_hz``; missing keys take the
            paper's values.
        **overrides
            Dataclass fields (SI) that take precedence, e.g. ``engine``.

        Raises
        ------
        ValueError
            Naming the configuration key and value.
        """
        kwargs = {}
        for key, value in config.items():
            if key not in SIMULATION_CONFIG_KEYS:
                raise ValueError(f"simulation.{key} = {value!r}: unknown key "
                                 f"(known: {sorted(SIMULATION_CONFIG_KEYS)})")
            field, to_si = SIMULATION_CONFIG_KEYS[key]
            try:
                kwargs[field] = to_si(value) if to_si is not None else value
            except (TypeError, ValueError):
                raise ValueError(f"simulation.{key} = {value!r}: must be a number") from None
        kwargs.update(overrides)
        try:
            return cls(**kwargs)
        except ValueError as err:
            field = str(err).split(" ", 1)[0]
            keys = [k for k, (f, _) in SIMULATION_CONFIG_KEYS.items() if f == field]
            if keys and keys[0] in config:
                raise ValueError(f"simulation.{keys[0]} = {config[keys[0]]!r}: {err}") from None
            raise

    def replace(self, **changes) -> "SimulationSettings":
        """A copy with some settings changed, validated again."""
        return dataclasses.replace(self, **changes)

    @property
    def sample_times(self) -> np.ndarray:
        """Output instants k duration / samples, k = 0 .. samples [s]."""
        return np.linspace(0.0, self.duration, int(self.samples) + 1)

    @property
    def full_rate_start(self) -> float:
        """Start of the full-rate record [s]: ``full_rate_after``, else the first
        output instant at or after the end of the ramp."""
        if self.full_rate_after is not None:
            return self.full_rate_after
        interval = self.duration / self.samples
        k = math.ceil(self.ramp_time / interval - 1e-9)
        return min(k, int(self.samples) - 1) * interval

    @property
    def full_rate_interval(self) -> float:
        """Interval of the full-rate record [s]."""
        return 1.0 / self.full_rate

    def record_grid(self):
        """Every instant a run records: the output instants before
        ``full_rate_start``, then every full-rate instant to the end.

        Returns
        -------
        ticks : numpy.ndarray of int
            The instants as whole multiples of :attr:`full_rate_interval`.
        times : numpy.ndarray
            The instants, ticks / full_rate [s].
        is_sample : numpy.ndarray of bool
            Which of them are output instants (``samples + 1`` of them).
        """
        per_sample = int(round(self.duration / self.samples * self.full_rate))
        start = int(round(self.full_rate_start * self.full_rate))
        end = int(self.samples) * per_sample
        ticks = np.concatenate([np.arange(0, start, per_sample), np.arange(start, end + 1)])
        times = ticks / (end / self.duration)
        times[-1] = self.duration
        return ticks, times, ticks % per_sample == 0

    def to_dict(self) -> dict:
        """Settings as output attributes, keys carrying their unit."""
        return {
            "engine": self.engine, "duration_s": self.duration, "samples": int(self.samples),
            "pinion_speed_deg_s": math.degrees(self.pinion_speed), "ramp_time_s": self.ramp_time,
            "load_torque_N_m": self.load_torque, "time_step_s": self.time_step,
            "rtol": self.rtol, "atol_angle_rad": self.atol_angle,
            "atol_speed_rad_s": self.atol_speed, "method": self.method,
            "compiled_method": self.compiled_method, "full_rate_hz": self.full_rate,
            "full_rate_after_s": self.full_rate_start, "runaway_factor": self.runaway_factor,
            "boundary": self.boundary,
        }


def _is_whole(value, tolerance=1e-9):
    return abs(value - round(value)) <= tolerance * max(1.0, abs(value))


#: Key of the workflow's ``simulation`` section -> (settings field, conversion to SI).
SIMULATION_CONFIG_KEYS = {
    "duration_s": ("duration", float),
    "samples": ("samples", None),
    "pinion_speed_deg_s": ("pinion_speed", lambda v: math.radians(float(v))),
    "ramp_time_s": ("ramp_time", float),
    "load_torque_N_m": ("load_torque", float),
    "time_step_s": ("time_step", float),
    "method": ("method", None),
    "compiled_method": ("compiled_method", None),
    "rtol": ("rtol", float),
    "engine": ("engine", None),
    "full_rate_hz": ("full_rate", float),
    "full_rate_after_s": ("full_rate_after", float),
    "boundary": ("boundary", None),
}


@njit(cache=True)
def pinion_state(t, speed, ramp_time):
    """Prescribed pinion rotation and speed at one instant (floats, compiled).

    omega1(t) = STEP(t, 0, 0, t_r, W), the paper's ramp (Fig. 8); its
    integral is closed form, phi1 = W t_r (D^3 - D^4 / 2) with D = t / t_r
    during the ramp.

    Parameters
    ----------
    t : float
        Time [s].
    speed : float
        Final speed W [rad/s].
    ramp_time : float
        Ramp duration t_r [s].

    Returns
    -------
    angle, speed : float
        Forward rotation phi1 [rad] and speed omega1 [rad/s].
    """
    if t >= ramp_time:
        return speed * (0.5 * ramp_time + (t - ramp_time)), speed
    if t <= 0.0:
        return 0.0, 0.0
    d = t / ramp_time
    return speed * ramp_time * (d**3 - 0.5 * d**4), step_scalar(t, 0.0, 0.0, ramp_time, speed)


def pinion_motion(t, settings: SimulationSettings):
    """Prescribed pinion rotation and speed over times (:func:`pinion_state`).

    Parameters
    ----------
    t : array_like
        Time [s].
    settings : SimulationSettings

    Returns
    -------
    angle : numpy.ndarray
        Forward rotation phi1 [rad].
    speed : numpy.ndarray
        Forward speed omega1 [rad/s].
    """
    state = np.vectorize(lambda time: pinion_state(float(time), settings.pinion_speed,
                                                   settings.ramp_time), otypes=[float, float])
    return state(t)
