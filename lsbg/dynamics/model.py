"""Meshing dynamics of the gear pair: a PyBullet engine and a scipy reference.

The model is the paper's §3: the pinion follows a prescribed speed (STEP ramp
from 0 to 7703 deg/s over 0-0.2 s) through a velocity servo, the gear carries
a constant resisting torque (1964.99 N m), and the two are coupled only by the
IMPACT contact of :class:`lsbg.contact.MeshContact`, evaluated from the exact
geometry at every step (DESIGN.md §3: Bullet's own collision shapes are too
coarse for 5 µm penetrations).

Two independent integrators solve it:

* ``"pybullet"``: the URDF of the assembled pair in PyBullet (DIRECT mode),
  each gear on its revolute joint with the inertia of its solid mesh, the
  pinion driven by Bullet's velocity motor, the contact torques applied to
  both links every fixed step (semi-implicit Euler, 1 µs by default).
* ``"scipy"``: the gear's equation of motion J2 phi2'' = T_contact - T_load
  with the pinion's prescribed motion in closed form, solved by
  :func:`scipy.integrate.solve_ivp` (LSODA, rtol 1e-8 by default; DOP853
  agrees to 0.02 % in the standard deviations and takes 3x longer).

Angles are forward rotations [rad] (``GearPair.rotation_axis``), speeds [rad/s].
The state starts at rest with the drive flanks pressed together by the
static approach that carries the load, so the run starts without an impact.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from dataclasses import dataclass

import numpy as np

from lsbg.contact import MeshContact, step_scalar

log = logging.getLogger(__name__)

ENGINES = ("pybullet", "scipy")
SCIPY_METHODS = ("DOP853", "LSODA", "RK45", "Radau", "BDF")


class SimulationError(RuntimeError):
    """The integration blew up (NaN, penetration beyond d, runaway speed)."""


@dataclass(frozen=True)
class SimulationSettings:
    """Input, load and solver settings of a meshing simulation (SI units).

    Parameters
    ----------
    engine : {"pybullet", "scipy"}
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
        Relative tolerance of the scipy engine [-].
    atol_angle, atol_speed : float
        Absolute tolerances of the scipy engine on angle [rad] and speed [rad/s].
    method : str
        :func:`scipy.integrate.solve_ivp` method of the scipy engine.
    runaway_factor : float
        A gear speed beyond this multiple of the theoretical speed (or below
        minus it) stops the run [-].
    progress_interval : float
        Wall time between progress reports in the log [s].
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
    runaway_factor: float = 2.0
    progress_interval: float = 5.0

    def __post_init__(self):
        def fail(name, why):
            raise ValueError(f"{name} = {getattr(self, name)!r}: {why}")

        if self.engine not in ENGINES:
            fail("engine", f"must be one of {ENGINES}")
        if self.method not in SCIPY_METHODS:
            fail("method", f"must be one of {SCIPY_METHODS}")
        for name in ("duration", "pinion_speed", "time_step", "rtol", "atol_angle",
                     "atol_speed", "progress_interval"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                fail(name, "must be a positive number")
        for name in ("ramp_time", "load_torque"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                fail(name, "must be a non-negative number")
        if isinstance(self.samples, bool) or not float(self.samples).is_integer() or self.samples < 1:
            fail("samples", "must be a positive whole number")
        if self.ramp_time > self.duration:
            fail("ramp_time", f"exceeds the duration {self.duration!r} s")
        if self.time_step > self.duration / self.samples:
            fail("time_step", f"exceeds the output interval {self.duration / self.samples!r} s")
        if self.runaway_factor <= 1:
            fail("runaway_factor", "must exceed 1")
        if self.rtol < 1e-13:
            fail("rtol", "is below what double precision can deliver (1e-13)")

    @classmethod
    def from_config(cls, config, **overrides) -> "SimulationSettings":
        """Settings from the workflow's ``simulation`` section (paper units).

        Parameters
        ----------
        config : dict
            Keys of :data:`SIMULATION_CONFIG_KEYS`, e.g. ``duration_s``,
            ``pinion_speed_deg_s``, ``load_torque_N_m``, ``time_step_s``,
            ``method``, ``rtol``; missing keys take the paper's values.
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

    def to_dict(self) -> dict:
        """Settings as output attributes, keys carrying their unit."""
        return {
            "engine": self.engine, "duration_s": self.duration, "samples": int(self.samples),
            "pinion_speed_deg_s": math.degrees(self.pinion_speed), "ramp_time_s": self.ramp_time,
            "load_torque_N_m": self.load_torque, "time_step_s": self.time_step,
            "rtol": self.rtol, "atol_angle_rad": self.atol_angle,
            "atol_speed_rad_s": self.atol_speed, "method": self.method,
            "runaway_factor": self.runaway_factor,
        }


#: Key of the workflow's ``simulation`` section -> (settings field, conversion to SI).
SIMULATION_CONFIG_KEYS = {
    "duration_s": ("duration", float),
    "samples": ("samples", None),
    "pinion_speed_deg_s": ("pinion_speed", lambda v: math.radians(float(v))),
    "ramp_time_s": ("ramp_time", float),
    "load_torque_N_m": ("load_torque", float),
    "time_step_s": ("time_step", float),
    "method": ("method", None),
    "rtol": ("rtol", float),
    "engine": ("engine", None),
}


def pinion_state(t, speed, ramp_time):
    """Prescribed pinion rotation and speed at one instant (floats, hot paths).

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
    state = np.vectorize(pinion_state, otypes=[float, float])
    return state(t, settings.pinion_speed, settings.ramp_time)


@dataclass
class RunRecord:
    """Raw time series of a run at the output instants (SI units).

    Attributes are arrays over ``time`` [s]: angles [rad], speeds [rad/s],
    torques [N m], forces [N], penetration [m], and the number of tooth pairs
    in contact.
    """

    time: np.ndarray
    pinion_angle: np.ndarray
    gear_angle: np.ndarray
    pinion_speed: np.ndarray
    gear_speed: np.ndarray
    gear_torque: np.ndarray
    pinion_torque: np.ndarray
    tangential_force: np.ndarray
    normal_force: np.ndarray
    contact_pairs: np.ndarray
    max_penetration: np.ndarray
    wall_time: float = 0.0
    steps: int = 0


class MeshingModel:
    """The simulated system: gear pair geometry, contact kernel and inertias.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
    gear_inertia : float
        Axial moment of inertia of the gear about its axis [kg m^2].
    pinion_inertia : float
        Axial moment of inertia of the pinion [kg m^2] (PyBullet engine only:
        the scipy engine prescribes the pinion's motion).
    urdf : str or pathlib.Path, optional
        URDF of the assembled pair, for the PyBullet engine.
    """

    def __init__(self, contact: MeshContact, gear_inertia: float, pinion_inertia: float, urdf=None):
        if not gear_inertia > 0:
            raise ValueError(f"gear_inertia = {gear_inertia!r}: must be positive [kg m^2]")
        if not pinion_inertia > 0:
            raise ValueError(f"pinion_inertia = {pinion_inertia!r}: must be positive [kg m^2]")
        self.contact = contact
        self.pair = contact.pair
        self.gear_inertia = float(gear_inertia)
        self.pinion_inertia = float(pinion_inertia)
        self.urdf = urdf
        self.ratio = self.pair.design.pinion_teeth / self.pair.design.gear_teeth

    # ---------------------------------------------------------- diagnostics
    def check_state(self, t, gear_speed, deepest, settings):
        """Raise :class:`SimulationError` on NaN, penetration beyond d or runaway speed."""
        limit = settings.runaway_factor * settings.pinion_speed * self.ratio
        d = self.contact.params.d
        if not (math.isfinite(gear_speed) and math.isfinite(deepest)):
            raise SimulationError(f"t = {t:.9f} s: non-finite state (gear speed {gear_speed!r} "
                                  f"rad/s, penetration {deepest!r} m)")
        if deepest > d:
            raise SimulationError(
                f"t = {t:.9f} s: penetration {deepest * 1e3:.6g} mm exceeds the contact depth "
                f"d = {d * 1e3:.6g} mm; the contact law no longer holds (time step too large, "
                f"or the load far beyond the contact's capacity)")
        if abs(gear_speed) > limit:
            raise SimulationError(
                f"t = {t:.9f} s: gear speed {math.degrees(gear_speed):.6g} deg/s is beyond "
                f"{settings.runaway_factor:g} x the theoretical {math.degrees(limit / settings.runaway_factor):.6g} deg/s")

    def sample(self, record_lists, t, phi1, phi2, w1, w2):
        """Append the output quantities of one state to ``record_lists``."""
        details = []
        gear_torque, pinion_torque, deepest = self.contact.evaluate(phi1, phi2, w1, w2, details)
        values = (t, phi1, phi2, w1, w2, gear_torque, pinion_torque,
                  sum(p.tangential_force for p in details), sum(p.normal_force for p in details),
                  sum(1 for p in details if p.normal_force > 0.0), max(deepest, 0.0))
        for lst, v in zip(record_lists, values):
            lst.append(v)

    def _record(self, lists, wall, steps):
        arrays = [np.asarray(v, dtype=float) for v in lists]
        arrays[-2] = arrays[-2].astype(np.int32)
        return RunRecord(*arrays, wall_time=wall, steps=steps)

    def initial_gear_angle(self, settings):
        """Gear rotation at which the drive flanks carry the load at rest [rad]."""
        return self.contact.static_gear_angle(settings.load_torque)

    def _progress(self, t, settings, start, last_report):
        now = time.monotonic()
        if now - last_report < settings.progress_interval:
            return last_report
        wall = now - start
        left = wall * (settings.duration - t) / t if t > 0 else float("nan")
        log.info("simulated %.4f of %.4g s, wall %.1f s, about %.1f s left",
                 t, settings.duration, wall, left)
        return now

    # -------------------------------------------------------------- engines
    def run(self, settings: SimulationSettings) -> RunRecord:
        """Integrate with the engine named in ``settings``."""
        if settings.engine == "scipy":
            return self.run_scipy(settings)
        return self.run_pybullet(settings)

    def run_scipy(self, settings: SimulationSettings) -> RunRecord:
        """Reference engine: the gear's equation of motion with scipy's solve_ivp."""
        from scipy.integrate import solve_ivp

        evaluate = self.contact.evaluate
        inertia, load = self.gear_inertia, settings.load_torque
        w, tr = settings.pinion_speed, settings.ramp_time
        counter = {"n": 0, "last": time.monotonic()}
        start = time.monotonic()

        def rhs(t, y):
            phi1, w1 = pinion_state(t, w, tr)
            phi2, w2 = float(y[0]), float(y[1])
            torque, _, deepest = evaluate(phi1, phi2, w1, w2)
            counter["n"] += 1
            if counter["n"] % 20000 == 0:
                self.check_state(t, w2, deepest, settings)
                counter["last"] = self._progress(t, settings, start, counter["last"])
            return (w2, (torque - load) / inertia)

        times = settings.sample_times
        y0 = [self.initial_gear_angle(settings), 0.0]
        solution = solve_ivp(rhs, (0.0, settings.duration), y0, method=settings.method,
                             t_eval=times, rtol=settings.rtol,
                             atol=[settings.atol_angle, settings.atol_speed],
                             max_step=settings.duration / settings.samples)
        if solution.status != 0:
            raise SimulationError(f"solve_ivp ({settings.method}) failed: {solution.message}")
        lists = [[] for _ in range(11)]
        for t, phi2, w2 in zip(solution.t, solution.y[0], solution.y[1]):
            phi1, w1 = pinion_state(t, w, tr)
            self.sample(lists, t, phi1, phi2, w1, w2)
            self.check_state(t, w2, lists[-1][-1], settings)
        return self._record(lists, time.monotonic() - start, counter["n"])

    def run_pybullet(self, settings: SimulationSettings) -> RunRecord:
        """Multibody engine: the URDF in PyBullet with lsbg's contact torques."""
        import pybullet

        if self.urdf is None:
            raise ValueError("urdf = None: the pybullet engine needs the pair's URDF")
        client = pybullet.connect(pybullet.DIRECT)
        try:
            return self._run_pybullet(pybullet, client, settings)
        finally:
            pybullet.disconnect(client)

    def load_pybullet(self, pb, client, settings):
        """Load the pair into a PyBullet client as the engine runs it.

        Zero gravity and damping, the fixed time step of ``settings``, the
        joint speed cap raised, the gear's default joint motor freed, and the
        links' axial inertias checked against the geometry's.

        Parameters
        ----------
        pb : module
            :mod:`pybullet`.
        client : int
            Physics client id (DIRECT mode).
        settings : SimulationSettings

        Returns
        -------
        body, pinion_joint, gear_joint : int
        """
        dt = settings.time_step
        pb.setGravity(0, 0, 0, physicsClientId=client)
        pb.setPhysicsEngineParameter(fixedTimeStep=dt, numSubSteps=0, deterministicOverlappingPairs=1,
                                     physicsClientId=client)
        body = pb.loadURDF(str(self.urdf), useFixedBase=True, flags=pb.URDF_USE_INERTIA_FROM_FILE,
                           physicsClientId=client)
        joints = {pb.getJointInfo(body, j, physicsClientId=client)[1].decode(): j
                  for j in range(pb.getNumJoints(body, physicsClientId=client))}
        pj, gj = joints["pinion_joint"], joints["gear_joint"]
        # DESIGN.md §3 pitfalls: damping and the joint speed cap belong to the
        # multibody (set them on the base, in separate calls, and read back).
        pb.changeDynamics(body, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
        pb.changeDynamics(body, -1, maxJointVelocity=100.0 * settings.pinion_speed, physicsClientId=client)
        for link in (pj, gj):
            pb.changeDynamics(body, link, jointDamping=0.0, physicsClientId=client)
            info = pb.getDynamicsInfo(body, link, physicsClientId=client)
            expected = self.pinion_inertia if link == pj else self.gear_inertia
            axial = info[2][2]
            if not math.isclose(axial, expected, rel_tol=1e-6):
                raise ValueError(f"urdf = {self.urdf}: link {link} axial inertia {axial!r} kg m^2 "
                                 f"differs from the geometry's {expected!r}")
        # Revolute joints carry a default velocity motor that acts as friction: free the gear.
        pb.setJointMotorControl2(body, gj, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=client)
        return body, pj, gj

    def _run_pybullet(self, pb, client, settings):
        dt = settings.time_step
        body, pj, gj = self.load_pybullet(pb, client, settings)
        phi2_0 = self.initial_gear_angle(settings)
        pb.resetJointState(body, pj, 0.0, 0.0, physicsClientId=client)
        pb.resetJointState(body, gj, phi2_0, 0.0, physicsClientId=client)

        u1 = self.pair.rotation_axis[1]
        u2 = self.pair.rotation_axis[2]
        u1x, u1y, u1z = map(float, u1)
        u2x, u2y, u2z = map(float, u2)
        servo_force = 1e3 * max(settings.load_torque, 1.0)
        load = settings.load_torque
        evaluate = self.contact.evaluate
        get_states = pb.getJointStates
        apply_torque = pb.applyExternalTorque
        step_sim = pb.stepSimulation
        motor = pb.setJointMotorControl2
        world, velocity = pb.WORLD_FRAME, pb.VELOCITY_CONTROL
        w_final, tr = settings.pinion_speed, settings.ramp_time

        steps_per_sample = int(round(settings.duration / settings.samples / dt))
        if abs(steps_per_sample * dt * settings.samples - settings.duration) > 1e-9 * settings.duration:
            raise ValueError(f"time_step = {dt!r}: must divide the output interval "
                             f"{settings.duration / settings.samples!r} s into whole steps")
        lists = [[] for _ in range(11)]
        self.sample(lists, 0.0, 0.0, phi2_0, 0.0, 0.0)
        start = last = time.monotonic()
        n = 0
        for k in range(1, int(settings.samples) + 1):
            for _ in range(steps_per_sample):
                (q1, w1, _, _), (q2, w2, _, _) = get_states(body, (pj, gj), physicsClientId=client)
                gear_torque, pinion_torque, deepest = evaluate(q1, q2, w1, w2)
                if deepest > self.contact.params.d or w2 != w2:
                    self.check_state(n * dt, w2, deepest, settings)
                t_next = (n + 1) * dt
                if t_next <= tr:
                    motor(body, pj, velocity, targetVelocity=pinion_state(t_next, w_final, tr)[1],
                          force=servo_force, physicsClientId=client)
                elif n * dt <= tr:
                    motor(body, pj, velocity, targetVelocity=w_final, force=servo_force,
                          physicsClientId=client)
                net = gear_torque - load
                apply_torque(body, gj, (net * u2x, net * u2y, net * u2z), world, physicsClientId=client)
                apply_torque(body, pj, (pinion_torque * u1x, pinion_torque * u1y, pinion_torque * u1z),
                             world, physicsClientId=client)
                step_sim(physicsClientId=client)
                n += 1
            (q1, w1, _, _), (q2, w2, _, _) = get_states(body, (pj, gj), physicsClientId=client)
            t = n * dt
            self.sample(lists, t, q1, q2, w1, w2)
            self.check_state(t, w2, lists[-1][-1], settings)
            last = self._progress(t, settings, start, last)
        return self._record(lists, time.monotonic() - start, n)


def load_model(geometry_dir, contact_params=None) -> MeshingModel:
    """The meshing model of a geometry directory written by ``lsbg geometry``.

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
        Directory with ``design.json`` (design and inertias) and ``pair.urdf``.
    contact_params : lsbg.contact.ContactParameters, optional
        Contact law; the paper's by default.

    Returns
    -------
    MeshingModel
    """
    import json
    from pathlib import Path

    from lsbg.export import FILE_NAMES, read_design
    from lsbg.geometry import GearPair

    geometry_dir = Path(geometry_dir)
    record = json.loads((geometry_dir / FILE_NAMES["design"]).read_text())
    pair = GearPair(read_design(geometry_dir))
    return MeshingModel(MeshContact(pair, contact_params), record["axial_inertia_gear_kg_m2"],
                        record["axial_inertia_pinion_kg_m2"], urdf=geometry_dir / FILE_NAMES["urdf"])


def simulate(geometry_dir, settings: SimulationSettings, contact_params=None, command=""):
    """Run one meshing simulation and return its CF dataset.

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
        Output directory of ``lsbg geometry``.
    settings : SimulationSettings
    contact_params : lsbg.contact.ContactParameters, optional
    command : str
        Command line, recorded in the dataset's ``history``.

    Returns
    -------
    xarray.Dataset
        See :mod:`lsbg.results`.

    Raises
    ------
    SimulationError
        If the integration blows up; nothing is returned then.
    """
    from lsbg.results import run_dataset

    model = load_model(geometry_dir, contact_params)
    log.info("%s engine, %s trace, spiral angle %.4g deg: %.4g s simulated",
             settings.engine, model.pair.design.trace,
             math.degrees(model.pair.design.spiral_angle), settings.duration)
    record = model.run(settings)
    log.info("done: %d steps in %.1f s wall", record.steps, record.wall_time)
    return run_dataset(record, model, settings, command)
