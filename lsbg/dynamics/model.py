"""The simulated system and its run records: what every engine shares.

The model is the paper's §3: the pinion follows a prescribed speed (STEP ramp
from 0 to 7703 deg/s over 0-0.2 s), the gear carries a constant resisting
torque (1964.99 N m), and the two are coupled only by the contact of
:class:`lsbg.contact.MeshContact` (point or line model), evaluated from the
exact geometry (DESIGN.md §3: Bullet's own collision shapes are too coarse for
micrometre penetrations). The state starts at rest with the drive flanks
pressed together by the static approach that carries the load, so the run
starts without an impact.

An engine (:mod:`lsbg.dynamics.pybullet_engine`,
:mod:`lsbg.dynamics.scipy_engine`, :mod:`lsbg.dynamics.compiled_engine`)
integrates the state and returns it at the record instants of
:meth:`lsbg.dynamics.settings.SimulationSettings.record_grid`;
:meth:`MeshingModel.record` evaluates the contact outputs there with one
compiled loop, checks for blow-ups and splits the output instants from the
full-rate record.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np

from lsbg.contact import MeshContact
from lsbg.contact import kernels
from lsbg.dynamics.settings import SimulationError, SimulationSettings

log = logging.getLogger(__name__)


@dataclass
class Series:
    """Time series of a run at some instants (SI units).

    Attributes are arrays over ``time`` [s]: angles [rad], speeds [rad/s],
    torques [N m], forces [N], penetration [m], and the number of tooth pairs
    carrying load.
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

    def select(self, keep):
        """The series at the instants where ``keep`` (a boolean mask) holds."""
        return Series(*(getattr(self, name)[keep] for name in self.__dataclass_fields__))


@dataclass
class RunRecord:
    """What a run produced.

    Attributes
    ----------
    samples : Series
        At the output instants (``samples + 1`` of them; the paper's sampling).
    full_rate : Series
        At the full-rate instants from ``full_rate_start`` to the end.
    wall_time : float
        Wall-clock time of the integration [s].
    steps : int
        Integrator steps (PyBullet and compiled) or right-hand side
        evaluations (scipy) [-].
    """

    samples: Series
    full_rate: Series
    wall_time: float = 0.0
    steps: int = 0


class MeshingModel:
    """The simulated system: gear pair geometry, contact kernel and inertias.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Its ``gear_inertia`` must be ``gear_inertia`` for the line model
        (the damping ratio refers to the mesh mode of this gear).
    gear_inertia : float
        Axial moment of inertia of the gear about its axis [kg m^2].
    pinion_inertia : float
        Axial moment of inertia of the pinion [kg m^2] (PyBullet engine only:
        the other engines prescribe the pinion's motion, or take the
        driveline's pinion, its solid and its shaft and flange).
    urdf : str or pathlib.Path, optional
        URDF of the assembled pair, for the PyBullet engine.
    driveline : lsbg.dynamics.driveline.Driveline, optional
        The torsional driveline of runs under ``boundary = "driveline"``; the
        line contact's ``gear_inertia`` is then its two-inertia mesh mode's
        (:meth:`~lsbg.dynamics.driveline.Driveline.mesh_mode_inertia`).
    """

    def __init__(self, contact: MeshContact, gear_inertia: float, pinion_inertia: float, urdf=None,
                 driveline=None):
        if not gear_inertia > 0:
            raise ValueError(f"gear_inertia = {gear_inertia!r}: must be positive [kg m^2]")
        if not pinion_inertia > 0:
            raise ValueError(f"pinion_inertia = {pinion_inertia!r}: must be positive [kg m^2]")
        self.contact = contact
        self.driveline = driveline
        self.pair = contact.pair
        self.gear_inertia = float(gear_inertia)
        self.pinion_inertia = float(pinion_inertia)
        self.urdf = urdf
        mode_inertia = self.gear_inertia if driveline is None else \
            driveline.mesh_mode_inertia(contact.e1 / contact.e2)
        if contact.params.model == "line" and contact.gear_inertia != mode_inertia:
            raise ValueError(f"gear_inertia = {mode_inertia!r}: the line contact's damping was "
                             f"set for a gear inertia of {contact.gear_inertia!r} kg m^2")
        self.ratio = self.pair.design.pinion_teeth / self.pair.design.gear_teeth

    def driveline_problem(self, settings):
        """A driveline run's initial state and its equations' parameters.

        Returns
        -------
        y0 : numpy.ndarray, shape (6,)
            :func:`lsbg.dynamics.driveline.initial_state`.
        system : numpy.ndarray
            :meth:`lsbg.dynamics.driveline.Driveline.system`.

        Raises
        ------
        ValueError
            If the model has no driveline.
        """
        from lsbg.dynamics.driveline import initial_state

        if self.driveline is None:
            raise ValueError("boundary = 'driveline': the model was loaded without a driveline")
        y0, offset = initial_state(self.driveline, self.contact, settings.pinion_speed,
                                   settings.load_torque)
        return y0, self.driveline.system(settings.pinion_speed, offset,
                                         self.contact.e1 / self.contact.e2, settings.load_torque)

    @property
    def penetration_limit(self):
        """Approach beyond which the contact law no longer holds [m].

        The IMPACT depth d for the point model, the line model's approach limit.
        """
        params = self.contact.params
        return params.d if params.model == "point" else params.approach_limit

    def speed_limit(self, settings):
        """Gear speed beyond which a run is a runaway [rad/s]."""
        return settings.runaway_factor * settings.pinion_speed * self.ratio

    # ---------------------------------------------------------- diagnostics
    def check_state(self, t, gear_speed, deepest, settings):
        """Raise :class:`SimulationError` on NaN, a penetration beyond the
        law's limit or a runaway speed."""
        limit = self.speed_limit(settings)
        depth = self.penetration_limit
        if not (math.isfinite(gear_speed) and math.isfinite(deepest)):
            raise SimulationError(f"t = {t:.9f} s: non-finite state (gear speed {gear_speed!r} "
                                  f"rad/s, penetration {deepest!r} m)")
        if deepest > depth:
            raise SimulationError(
                f"t = {t:.9f} s: penetration {deepest * 1e3:.6g} mm exceeds the "
                f"{self.contact.params.model} model's limit {depth * 1e3:.6g} mm; the contact "
                f"law no longer holds (time step too large, or the load far beyond the "
                f"contact's capacity)")
        if abs(gear_speed) > limit:
            raise SimulationError(
                f"t = {t:.9f} s: gear speed {math.degrees(gear_speed):.6g} deg/s is beyond "
                f"{settings.runaway_factor:g} x the theoretical "
                f"{math.degrees(limit / settings.runaway_factor):.6g} deg/s")

    def check_states(self, settings, times, phi1, phi2, w1, w2):
        """:meth:`check_state` at many states, at once.

        Parameters
        ----------
        settings : SimulationSettings
        times : numpy.ndarray
            Instants of the states [s].
        phi1, phi2, w1, w2 : array_like
            Pinion and gear rotation [rad] and speed [rad/s].

        Returns
        -------
        arrays : list of numpy.ndarray
            ``phi1, phi2, w1, w2`` as contiguous float arrays.
        mesh : numpy.ndarray, shape (n, 6)
            :func:`lsbg.contact.kernels.mesh_series` at the states.

        Raises
        ------
        SimulationError
            At the first bad state.
        """
        arrays = [np.ascontiguousarray(a, dtype=float) for a in (phi1, phi2, w1, w2)]
        mesh = kernels.mesh_series(*arrays, *self.contact.arrays)
        deepest = mesh[:, 2]
        bad = ~(np.isfinite(arrays[3]) & np.isfinite(deepest)) | (deepest > self.penetration_limit) \
            | (np.abs(arrays[3]) > self.speed_limit(settings))
        if bad.any():
            i = int(np.argmax(bad))
            self.check_state(times[i], arrays[3][i], deepest[i], settings)
        return arrays, mesh

    def initial_gear_angle(self, settings):
        """Gear rotation at which the drive flanks carry the load at rest [rad]."""
        return self.contact.static_gear_angle(settings.load_torque)

    def progress(self, t, settings, start, last_report):
        """Log progress every ``settings.progress_interval`` s of wall time."""
        now = time.monotonic()
        if now - last_report < settings.progress_interval:
            return last_report
        wall = now - start
        left = wall * (settings.duration - t) / t if t > 0 else float("nan")
        log.info("simulated %.4f of %.4g s, wall %.1f s, about %.1f s left",
                 t, settings.duration, wall, left)
        return now

    def record(self, settings, times, phi1, phi2, w1, w2, wall_time, steps):
        """The run record from the states at the record instants.

        Parameters
        ----------
        settings : SimulationSettings
        times : numpy.ndarray
            The record instants of :meth:`SimulationSettings.record_grid` [s].
        phi1, phi2, w1, w2 : numpy.ndarray
            Pinion and gear rotation [rad] and speed [rad/s] there.
        wall_time : float
            Wall time of the integration [s].
        steps : int
            Integrator steps [-].

        Returns
        -------
        RunRecord

        Raises
        ------
        SimulationError
            At the first instant with a non-finite state, a penetration
            beyond the law's limit or a runaway speed.
        """
        arrays, out = self.check_states(settings, times, phi1, phi2, w1, w2)
        deepest = out[:, 2]
        series = Series(np.asarray(times, dtype=float), *arrays, out[:, 0], out[:, 1], out[:, 3],
                        out[:, 4], out[:, 5].astype(np.int32), np.maximum(deepest, 0.0))
        _, _, is_sample = settings.record_grid()
        full = series.time >= settings.full_rate_start - 0.5 * settings.full_rate_interval
        return RunRecord(series.select(is_sample), series.select(full), wall_time, steps)

    # -------------------------------------------------------------- engines
    def run(self, settings: SimulationSettings) -> RunRecord:
        """Integrate with the engine named in ``settings``."""
        if settings.boundary == "driveline" and self.driveline is None:
            raise ValueError("boundary = 'driveline': the model was loaded without a driveline")
        if settings.engine == "scipy":
            from lsbg.dynamics.scipy_engine import run_scipy

            return run_scipy(self, settings)
        if settings.engine == "compiled":
            from lsbg.dynamics.compiled_engine import run_compiled

            return run_compiled(self, settings)
        from lsbg.dynamics.pybullet_engine import run_pybullet

        return run_pybullet(self, settings)


def load_model(geometry_dir, contact_params=None, flanks=None,
               slice_stiffness=None, driveline=None) -> MeshingModel:
    """The meshing model of a geometry directory written by ``lsbg geometry``.

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
        Directory with ``design.json`` (design and inertias) and ``pair.urdf``.
    contact_params : lsbg.contact.ContactParameters, optional
        Contact model and law; the paper's by default.
    flanks : lsbg.tca.separation.RealFlanks, optional
        Flank modification and assembly displacements: the line model's
        slices start from their separation field (the point model, the
        paper's reproduction, keeps the conjugate flanks). Default: the
        conjugate, aligned pair.
    slice_stiffness : lsbg.contact.slices.SliceStiffness, optional
        The tooth's own stiffness per slice (from the loaded TCA with the FE
        compliance of this design point and these flanks); required by, and
        only allowed with, the line model under ``compliance = "fe"``.
    driveline : dict, optional
        The ``driveline`` section (:meth:`lsbg.dynamics.driveline.Driveline.from_config`,
        on this point's solids): the model of runs under the driveline boundary.

    Returns
    -------
    MeshingModel

    Raises
    ------
    ValueError
        If ``slice_stiffness`` and the contact's ``compliance`` disagree.
    """
    from pathlib import Path

    from lsbg.solid.directory import FILE_NAMES, read_design, read_record
    from lsbg.gear.geometry import GearPair

    geometry_dir = Path(geometry_dir)
    record = read_record(geometry_dir)
    pair = GearPair(read_design(geometry_dir))
    gear_inertia = record["axial_inertia_gear_kg_m2"]
    line = contact_params is not None and contact_params.model == "line"
    separation = flanks.separation(pair) if flanks is not None and line else None
    own = line and contact_params.compliance == "fe"
    if own and slice_stiffness is None:
        raise ValueError("contact.compliance = 'fe': the line model needs the tooth's slice "
                         "stiffness (the loaded TCA with the FE compliance of this design "
                         "point: lsbg ltca under contact.compliance: fe, given as --fe-ltca)")
    if slice_stiffness is not None and not own:
        raise ValueError("a slice stiffness (the tooth's compliance) was given, but the contact "
                         "is not the line model with compliance = 'fe'")
    pinion_inertia = record["axial_inertia_pinion_kg_m2"]
    mode_inertia = gear_inertia
    if driveline is not None:
        from lsbg.dynamics.driveline import Driveline

        driveline = Driveline.from_config(driveline, pinion_inertia, gear_inertia)
        # rho = e1 / e2 as MeshContact computes it
        e1, e2 = (math.sin(pair.design.base_cone_angle(m)) for m in (1, 2))
        mode_inertia = driveline.mesh_mode_inertia(e1 / e2)
    contact = MeshContact(pair, contact_params, gear_inertia=mode_inertia, separation=separation,
                          slice_stiffness=slice_stiffness)
    return MeshingModel(contact, gear_inertia, pinion_inertia,
                        urdf=geometry_dir / FILE_NAMES["urdf"], driveline=driveline)


def simulate(geometry_dir, settings: SimulationSettings, contact_params=None, command="",
             flanks=None, slice_stiffness=None, driveline=None):
    """Run one meshing simulation and return its CF dataset.

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
        Output directory of ``lsbg geometry``.
    settings : SimulationSettings
    contact_params : lsbg.contact.ContactParameters, optional
    command : str
        Command line, recorded in the dataset's ``history``.
    flanks : lsbg.tca.separation.RealFlanks, optional
        As :func:`load_model`.
    slice_stiffness : lsbg.contact.slices.SliceStiffness, optional
        As :func:`load_model`.
    driveline : dict, optional
        The ``driveline`` section, read under ``settings.boundary = "driveline"``
        (its defaults if None); ignored under the prescribed pinion.

    Returns
    -------
    xarray.Dataset
        See :mod:`lsbg.dynamics.dataset`.

    Raises
    ------
    SimulationError
        If the integration blows up; nothing is returned then.
    """
    from lsbg.dynamics.dataset import run_dataset

    section = (driveline or {}) if settings.boundary == "driveline" else None
    model = load_model(geometry_dir, contact_params, flanks, slice_stiffness, section)
    log.info("%s boundary, %s engine, %s model, %s trace, spiral angle %.4g deg: %.4g s simulated",
             settings.boundary, settings.engine, model.contact.params.model, model.pair.design.trace,
             math.degrees(model.pair.design.spiral_angle), settings.duration)
    record = model.run(settings)
    log.info("done: %d steps in %.1f s wall", record.steps, record.wall_time)
    return run_dataset(record, model, settings, command)
