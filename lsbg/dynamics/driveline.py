"""The torsional driveline around the mesh: inertias, shafts, its modes and its equations.

The chain, each coordinate a forward rotation [rad]::

    drive end --k_p, c_p-- J1 (pinion) ==mesh== J2 (gear + carrier) --k_h, c_h-- J_v (vehicle)

* the drive end is the engine and gearbox, of inertia J_d reflected to the
  pinion shaft. Under ``simulation.boundary: driveline`` its motion is
  prescribed at the constant speed W (the engine held on its speed by its
  governor; the limit J_d -> infinity of the run's equations): J_d enters the
  free driveline's modes (:meth:`Driveline.modes` with ``held=False``), not a
  run;
* k_p: the propeller shaft and the pinion shaft in series, c_p in parallel;
* J1: the pinion with its shaft and companion flange;
* the mesh between J1 and J2 is the line model's (or point model's) contact of
  :func:`lsbg.contact.kernels.mesh_forces`, the same kernel as the prescribed
  pinion's: linearised, the potential 0.5 K (e1 phi1 - e2 phi2)^2 with
  K = k_theta / e2^2, k_theta the gear's mean torsional mesh stiffness
  (:meth:`lsbg.contact.MeshContact.mean_torsional_stiffness`) and
  e_i = sin(delta_b,i), so the pinion sees rho^2 k_theta with rho = e1 / e2
  (= z1 / z2);
* J2: the gear with the differential carrier;
* k_h: both half-shafts in parallel (the differential splits the torque
  equally), c_h in parallel;
* J_v: the vehicle's mass m reflected to the axle through the tyre radius r,
  m r^2; the load torque acts on it.

**Damping** is stated per element: each shaft's viscous coefficient is
c = 2 zeta k / omega from a damping ratio zeta of that shaft's own mode
(:meth:`Driveline.propshaft_frequency`, :meth:`Driveline.half_shaft_frequency`);
the mesh's damping ratio (``contact.mesh_damping_ratio``) refers to the
two-inertia mesh mode of pinion and gear (:meth:`Driveline.mesh_mode_inertia`).

**The run** starts in motion, every inertia at its kinematic speed and the
shafts twisted to carry the mean torques of the mesh at the load
(:func:`initial_state`): a vehicle cannot be brought from rest to speed in
the paper's 0.2 s ramp (the ramp's acceleration of J_v alone would need tens
of times the load at the gear), so ``simulation.ramp_time_s`` is not used.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numba import njit

from lsbg.contact.kernels import mesh_forces, mesh_series
from lsbg.dynamics.settings import BOUNDARIES  # noqa: F401  (exported by lsbg.dynamics)

#: Key of the ``driveline`` section -> (default, rule): the rule "positive",
#: "non-negative" or "ratio" (0 <= value < 1). SI units, named in the keys.
DRIVELINE_CONFIG_KEYS = {
    "drive_inertia_kg_m2": (0.30, "positive"),
    "propshaft_stiffness_N_m_per_rad": (3.3e4, "positive"),
    "propshaft_damping_ratio": (0.05, "ratio"),
    "pinion_added_inertia_kg_m2": (2.0e-3, "non-negative"),
    "carrier_inertia_kg_m2": (0.025, "non-negative"),
    "half_shaft_stiffness_N_m_per_rad": (1.7e4, "positive"),
    "half_shaft_damping_ratio": (0.05, "ratio"),
    "vehicle_mass_kg": (3500.0, "positive"),
    "tyre_radius_m": (0.35, "positive"),
}

_RULES = {
    "positive": (lambda v: v > 0, "must be a positive number"),
    "non-negative": (lambda v: v >= 0, "must be a non-negative number"),
    "ratio": (lambda v: 0 <= v < 1, "must be a damping ratio, 0 <= value < 1"),
}

# Indices of the compiled equations' ``system`` array.
(Y_SPEED, Y_DRIVE_OFFSET, Y_KP, Y_CP, Y_KH, Y_CH, Y_J1, Y_J2, Y_JV, Y_LOAD) = range(10)
#: States of a driveline run: pinion, gear and vehicle rotation [rad], then their speeds [rad/s].
STATES = 6


@dataclass(frozen=True)
class Driveline:
    """The torsional driveline of the final drive (SI units; module docstring).

    Parameters
    ----------
    drive_inertia : float
        Engine and gearbox reflected to the pinion shaft, J_d [kg m^2].
    propshaft_stiffness : float
        Propeller and pinion shaft in series, k_p [N m/rad].
    pinion_inertia : float
        Pinion with its shaft and flange, J1 [kg m^2].
    gear_inertia : float
        Gear with the differential carrier, J2 [kg m^2].
    half_shaft_stiffness : float
        Both half-shafts in parallel, k_h [N m/rad].
    vehicle_inertia : float
        The vehicle reflected to the axle, J_v = m r^2 [kg m^2].
    propshaft_damping_ratio, half_shaft_damping_ratio : float
        Damping ratio of each shaft's own mode [-] (per element).
    """

    drive_inertia: float
    propshaft_stiffness: float
    pinion_inertia: float
    gear_inertia: float
    half_shaft_stiffness: float
    vehicle_inertia: float
    propshaft_damping_ratio: float = 0.05
    half_shaft_damping_ratio: float = 0.05

    def __post_init__(self):
        for name, value in asdict(self).items():
            rule = "ratio" if name.endswith("damping_ratio") else "positive"
            test, why = _RULES[rule]
            if not (isinstance(value, (int, float)) and math.isfinite(value) and test(value)):
                raise ValueError(f"{name} = {value!r}: {why}")

    @classmethod
    def from_config(cls, section, pinion_solid, gear_solid) -> "Driveline":
        """The driveline of the ``driveline`` section on a design point's solids.

        Parameters
        ----------
        section : dict
            Keys of :data:`DRIVELINE_CONFIG_KEYS` (missing ones take the defaults).
        pinion_solid, gear_solid : float
            Axial inertias of the pinion's and the gear's solids [kg m^2]
            (``lsbg geometry``); the section's added inertias go on top.

        Raises
        ------
        ValueError
            Naming the key and its value (``driveline.tyre_radius_m = -1: ...``).
        """
        values = driveline_values(section)
        return cls(drive_inertia=values["drive_inertia_kg_m2"],
                   propshaft_stiffness=values["propshaft_stiffness_N_m_per_rad"],
                   pinion_inertia=pinion_solid + values["pinion_added_inertia_kg_m2"],
                   gear_inertia=gear_solid + values["carrier_inertia_kg_m2"],
                   half_shaft_stiffness=values["half_shaft_stiffness_N_m_per_rad"],
                   vehicle_inertia=values["vehicle_mass_kg"] * values["tyre_radius_m"] ** 2,
                   propshaft_damping_ratio=values["propshaft_damping_ratio"],
                   half_shaft_damping_ratio=values["half_shaft_damping_ratio"])

    # ------------------------------------------------------------ the linearised model
    def matrices(self, mesh_stiffness, ratio, held=True):
        """Mass and stiffness matrices of the driveline linearised about its mean mesh.

        Parameters
        ----------
        mesh_stiffness : float
            The gear's mean torsional mesh stiffness k_theta [N m/rad].
        ratio : float
            rho = e1 / e2 [-].
        held : bool
            True: the run's system, the drive end held (coordinates phi1,
            phi2, phi_v); False: the free driveline (phi_d first).

        Returns
        -------
        mass, stiffness : numpy.ndarray
            [kg m^2], [N m/rad].
        """
        kp, kh, km = self.propshaft_stiffness, self.half_shaft_stiffness, mesh_stiffness
        stiffness = np.array([[kp + km * ratio**2, -km * ratio, 0.0],
                              [-km * ratio, km + kh, -kh],
                              [0.0, -kh, kh]])
        inertias = [self.pinion_inertia, self.gear_inertia, self.vehicle_inertia]
        if not held:
            stiffness = np.pad(stiffness, ((1, 0), (1, 0)))
            stiffness[0, 0], stiffness[0, 1], stiffness[1, 0] = kp, -kp, -kp
            inertias = [self.drive_inertia] + inertias
        return np.diag(inertias), stiffness

    def modes(self, mesh_stiffness, ratio, held=True):
        """Natural frequencies and mode shapes of :meth:`matrices` (scipy.linalg.eigh).

        Returns
        -------
        frequencies : numpy.ndarray
            Ascending [Hz] (the free driveline's first is its rigid-body mode, 0).
        shapes : numpy.ndarray
            Mass-normalised shapes in the columns [rad / sqrt(kg m^2)].
        """
        from scipy.linalg import eigh

        mass, stiffness = self.matrices(mesh_stiffness, ratio, held)
        values, shapes = eigh(stiffness, mass)
        return np.sqrt(np.clip(values, 0.0, None)) / (2 * math.pi), shapes

    # ------------------------------------------------------------ closed forms
    def mesh_mode_inertia(self, ratio):
        """The two-inertia mesh mode's inertia at the gear, 1 / (1/J2 + rho^2/J1) [kg m^2]:
        the ``gear_inertia`` the line contact's damping ratio refers to."""
        return 1.0 / (1.0 / self.gear_inertia + ratio**2 / self.pinion_inertia)

    def mesh_mode_frequency(self, mesh_stiffness, ratio):
        """The two-inertia mesh mode, pinion and gear on the mesh alone [Hz].

        omega^2 = k_m (r1^2 / J1 + r2^2 / J2), k_m = k_theta / r2^2 the mesh
        stiffness along the line of action and r_i = R_m e_i the base radii;
        in torsional terms omega^2 = k_theta (1/J2 + rho^2/J1). The limit of
        shafts soft against the mesh.
        """
        return math.sqrt(mesh_stiffness / self.mesh_mode_inertia(ratio)) / (2 * math.pi)

    def _rigid_mesh_chain(self, ratio):
        """The chain referred to the pinion with the mesh rigid: inertias of drive,
        pinion + gear, vehicle, and the two shafts' stiffnesses."""
        r2 = ratio**2
        return (self.drive_inertia, self.pinion_inertia + r2 * self.gear_inertia,
                r2 * self.vehicle_inertia, self.propshaft_stiffness, r2 * self.half_shaft_stiffness)

    def propshaft_frequency(self, ratio):
        """The propeller shaft's mode with the mesh and the half-shafts rigid [Hz]:
        J_d against J1 + rho^2 (J2 + J_v), omega^2 = k_p (1/J_a + 1/J_b)."""
        jd, ja, jv, kp, _ = self._rigid_mesh_chain(ratio)
        return math.sqrt(kp * (1.0 / jd + 1.0 / (ja + jv))) / (2 * math.pi)

    def half_shaft_frequency(self, ratio):
        """The half-shafts' mode with the mesh and the propeller shaft rigid [Hz]:
        J2 + (J_d + J1) / rho^2 against J_v on k_h."""
        jd, ja, jv, _, kh = self._rigid_mesh_chain(ratio)
        return math.sqrt(kh * (1.0 / (jd + ja) + 1.0 / jv)) / (2 * math.pi)

    def rigid_mesh_frequencies(self, ratio, held=True):
        """Both shafts' modes with the mesh rigid, closed form [Hz].

        The chain J_d -k_p- J_a -k_h'- J_b (referred to the pinion): free,
        omega^4 - omega^2 [k_p (1/J_d + 1/J_a) + k_h' (1/J_a + 1/J_b)]
        + k_p k_h' (J_d + J_a + J_b) / (J_d J_a J_b) = 0; held at the drive end,
        omega^4 - omega^2 [(k_p + k_h') / J_a + k_h' / J_b] + k_p k_h' / (J_a J_b) = 0.

        Returns
        -------
        numpy.ndarray
            The two non-zero frequencies, ascending [Hz].
        """
        jd, ja, jb, kp, kh = self._rigid_mesh_chain(ratio)
        if held:
            b, c = (kp + kh) / ja + kh / jb, kp * kh / (ja * jb)
        else:
            b, c = kp * (1 / jd + 1 / ja) + kh * (1 / ja + 1 / jb), kp * kh * (jd + ja + jb) / (jd * ja * jb)
        root = math.sqrt(b * b - 4 * c)
        return np.sqrt(np.array([2 * c / (b + root), 0.5 * (b + root)])) / (2 * math.pi)

    def damping(self, ratio):
        """Viscous coefficients c_p, c_h = 2 zeta k / omega of the shafts [N m s/rad]."""
        omega_p = 2 * math.pi * self.propshaft_frequency(ratio)
        omega_h = 2 * math.pi * self.half_shaft_frequency(ratio)
        return (2 * self.propshaft_damping_ratio * self.propshaft_stiffness / omega_p,
                2 * self.half_shaft_damping_ratio * self.half_shaft_stiffness / omega_h)

    # ------------------------------------------------------------ a run
    def system(self, speed, drive_offset, ratio, load):
        """The compiled equations' parameters (:func:`driveline_rates`).

        Parameters
        ----------
        speed : float
            The drive end's speed W [rad/s].
        drive_offset : float
            The drive end's rotation at t = 0 [rad].
        ratio : float
            rho = e1 / e2 [-].
        load : float
            Load torque on the vehicle [N m].
        """
        cp, ch = self.damping(ratio)
        return np.array([speed, drive_offset, self.propshaft_stiffness, cp,
                         self.half_shaft_stiffness, ch, self.pinion_inertia, self.gear_inertia,
                         self.vehicle_inertia, load])

    def attrs(self, mesh_stiffness, ratio):
        """The driveline's parameters and modes as dataset attributes (units in the keys)."""
        cp, ch = self.damping(ratio)
        held, _ = self.modes(mesh_stiffness, ratio, held=True)
        free, _ = self.modes(mesh_stiffness, ratio, held=False)
        out = {
            "driveline_drive_inertia_kg_m2": self.drive_inertia,
            "driveline_propshaft_stiffness_N_m_per_rad": self.propshaft_stiffness,
            "driveline_pinion_inertia_kg_m2": self.pinion_inertia,
            "driveline_gear_inertia_kg_m2": self.gear_inertia,
            "driveline_half_shaft_stiffness_N_m_per_rad": self.half_shaft_stiffness,
            "driveline_vehicle_inertia_kg_m2": self.vehicle_inertia,
            "driveline_propshaft_damping_ratio": self.propshaft_damping_ratio,
            "driveline_half_shaft_damping_ratio": self.half_shaft_damping_ratio,
            "driveline_propshaft_damping_N_m_s_per_rad": cp,
            "driveline_half_shaft_damping_N_m_s_per_rad": ch,
            "driveline_mesh_stiffness_N_m_per_rad": mesh_stiffness,
            "driveline_mesh_mode_two_inertia_hz": self.mesh_mode_frequency(mesh_stiffness, ratio),
            "driveline_propshaft_mode_hz": self.propshaft_frequency(ratio),
            "driveline_half_shaft_mode_hz": self.half_shaft_frequency(ratio),
        }
        out.update({f"driveline_mode{i + 1}_hz": float(f) for i, f in enumerate(held)})
        out.update({f"driveline_free_mode{i + 1}_hz": float(f) for i, f in enumerate(free)})
        return out


def driveline_values(section):
    """The ``driveline`` section's values with the defaults filled in, each key checked.

    Parameters
    ----------
    section : dict
        Keys of :data:`DRIVELINE_CONFIG_KEYS`.

    Returns
    -------
    dict
        Every key, as float.

    Raises
    ------
    ValueError
        ``driveline.KEY = VALUE: rule`` for an unknown key or a value against its rule.
    """
    out = {}
    for key, value in section.items():
        if key not in DRIVELINE_CONFIG_KEYS:
            raise ValueError(f"driveline.{key} = {value!r}: unknown key "
                             f"(known: {sorted(DRIVELINE_CONFIG_KEYS)})")
    for key, (default, rule) in DRIVELINE_CONFIG_KEYS.items():
        value = section.get(key, default)
        test, why = _RULES[rule]
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or not test(value):
            raise ValueError(f"driveline.{key} = {value!r}: {why}")
        out[key] = float(value)
    return out


# ---------------------------------------------------------------- the equations
@njit(cache=True)
def driveline_rates(t, y, out, row, system, params, sides, table):
    """Time derivative of a driveline run's state (compiled; both engines' equations).

    J1 phi1'' = k_p (phi_d - phi1) + c_p (W - omega1) + T1_mesh,
    J2 phi2'' = T2_mesh - k_h (phi2 - phi_v) - c_h (omega2 - omega_v),
    J_v phi_v'' = k_h (phi2 - phi_v) + c_h (omega2 - omega_v) - T_load,
    with phi_d = phi_d0 + W t and the mesh torques of
    :func:`lsbg.contact.kernels.mesh_forces`.

    Parameters
    ----------
    t : float
        Time [s].
    y : numpy.ndarray, shape (6,)
        phi1, phi2, phi_v [rad], omega1, omega2, omega_v [rad/s].
    out : numpy.ndarray, shape (m, 6)
        Its row ``row`` filled with dy/dt.
    row : int
    system : numpy.ndarray
        :meth:`Driveline.system`.
    params, sides, table : numpy.ndarray
        The contact model (:class:`lsbg.contact.MeshContact`).

    Returns
    -------
    float
        Deepest normal approach of the mesh [m].
    """
    speed = system[Y_SPEED]
    drive = system[Y_DRIVE_OFFSET] + speed * t
    gear, pinion, deepest, _, _, _ = mesh_forces(y[0], y[1], y[3], y[4], params, sides, table)
    shaft = system[Y_KP] * (drive - y[0]) + system[Y_CP] * (speed - y[3])
    half = system[Y_KH] * (y[1] - y[2]) + system[Y_CH] * (y[4] - y[5])
    out[row, 0], out[row, 1], out[row, 2] = y[3], y[4], y[5]
    out[row, 3] = (shaft + pinion) / system[Y_J1]
    out[row, 4] = (gear - half) / system[Y_J2]
    out[row, 5] = (half - system[Y_LOAD]) / system[Y_JV]
    return deepest


def mean_mesh_torques(contact, mismatch, speed, phases=64):
    """Gear and pinion torques of the mesh at a rotation mismatch, averaged over a mesh cycle.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
    mismatch : float
        eps = e1 phi1 - e2 phi2 [rad].
    speed : float
        Pinion speed [rad/s] (the gear at the kinematic speed rho omega1).
    phases : int
        Pinion positions over one base pitch [-].

    Returns
    -------
    gear, pinion : float
        Mean torques about u2 and u1 [N m].
    """
    e1, e2 = contact.e1, contact.e2
    phi1 = np.arange(phases) * contact.pitch / (phases * e1)
    phi2 = (phi1 * e1 - mismatch) / e2
    w1 = np.full(phases, float(speed))
    out = mesh_series(phi1, phi2, w1, w1 * e1 / e2, *contact.arrays)
    return float(out[:, 0].mean()), float(out[:, 1].mean())


def initial_state(driveline, contact, speed, load):
    """A driveline run's start: in motion, the mean torques in balance.

    Every inertia at its kinematic speed (omega1 = W, omega2 = omega_v = rho W),
    the mesh at the mismatch whose mean gear torque over a mesh cycle is the
    load (:func:`mean_mesh_torques`, at speed: friction included), the
    half-shafts twisted by load / k_h and the propeller shaft by the mean
    pinion torque over k_p, so that the slow modes (the vehicle's, near 1 Hz)
    start at rest.

    Parameters
    ----------
    driveline : Driveline
    contact : lsbg.contact.MeshContact
    speed : float
        The drive end's speed W [rad/s].
    load : float
        Load torque on the vehicle [N m].

    Returns
    -------
    y0 : numpy.ndarray, shape (6,)
        The state (:func:`driveline_rates`).
    drive_offset : float
        phi_d at t = 0 [rad].
    """
    from scipy.optimize import brentq

    ratio = contact.e1 / contact.e2
    static = contact.static_gear_angle(load)  # phi1 = 0: eps = -e2 phi2
    guess = -contact.e2 * static
    excess = lambda eps: mean_mesh_torques(contact, eps, speed)[0] - load  # noqa: E731
    width = max(abs(guess), 1e-7)
    low, high = guess - width, guess + width
    for _ in range(60):  # the mean torque grows with the mismatch
        if excess(low) <= 0.0 <= excess(high):
            break
        low, high = low - width, high + width
    else:
        raise ValueError(f"load_torque = {load!r}: the mesh's mean torque at speed does not "
                         f"reach it within {high!r} rad of mismatch")
    mismatch = brentq(excess, low, high, xtol=1e-15, rtol=1e-12)
    _, pinion = mean_mesh_torques(contact, mismatch, speed)
    phi2 = -mismatch / contact.e2
    y0 = np.array([0.0, phi2, phi2 - load / driveline.half_shaft_stiffness,
                   speed, ratio * speed, ratio * speed])
    return y0, -pinion / driveline.propshaft_stiffness
