"""Sliding friction of the mesh: friction laws, the power loss and the mesh efficiency.

The mesh loses, at each contact point, its friction force times its sliding
speed: P = sum_i mu_i F_i V_s,i over the points of every loaded tooth pair
(F_i the band's normal force from the loaded TCA, V_s,i the sliding speed of
the exact kinematics, :func:`lsbg.optimise.kinematics.contact_speeds`),
averaged over the mesh cycle. The mesh efficiency is the power the gear
takes off over the power the pinion puts in, T_2 omega_2 / (T_2 omega_2 + P).
Two named laws give mu:

* ``benedict_kelley``: Benedict & Kelley, "Instantaneous coefficients of gear
  tooth friction", ASLE Transactions 4 (1961) 59-70, the local law of roller
  tests behind the gear-loss work of Anderson & Loewenthal (NASA, 1980) and
  compared by Xu, Kahraman, Anderson & Maddock (J. Mech. Des. 129, 2007):
  mu = 0.0127 C_R log10(3.17e8 w / (eta V_s V_sum^2)) in its units (w load
  per unit length [lb/in], eta [cP], speeds [in/s]), which in SI-based units
  is mu = 0.0127 C_R log10(29.66 w / (eta V_s V_sum^2)) with w [N/m], eta
  [mPa s] and V [m/s] (the same number: 3.17e8 (0.0254 m)^3 / (175.13 N/m per
  lb/in) = 2.966e-2 with eta in Pa s); C_R = 50 / (50 - S) with S the mean CLA
  (Ra) roughness of the flanks in microinches, defined for S < 50 uin (Ra <
  1.27 um). It grows without bound as V_s -> 0 (the pitch line, where the
  loss mu F V_s still goes to 0): the sliding speed in its logarithm is held at
  :data:`LEAST_SLIDING_SPEED` or more, and mu at 0 or more.
* ``iso_tr_14179_2``: ISO/TR 14179-2:2001 (the FZG regression of Schlenk,
  1994; Fernandes et al., Tribol. Int. 88, 2015), one mean coefficient for the
  mesh from its nominal values: mu_mz = 0.048 (F_bt/b / (V_sum,C rho_red,C))^0.2
  eta^-0.05 Ra^0.25 X_L, with F_bt/b [N/mm] the tangential load on the base
  circle per unit face width, V_sum,C [m/s] and rho_red,C [mm] the sum speed
  and the relative radius of curvature at the pitch point, eta [mPa s] the
  oil's dynamic viscosity, Ra [um] the flanks' mean arithmetic roughness and
  X_L the lubricant factor (1 for mineral oil). lsbg takes the pitch point at
  the mean cone distance of its own exact kinematics and curvature
  (:func:`nominal_values`), not a virtual cylindrical gear's.

The lubricant (:class:`Lubricant`) is the rating's: ISO 10300's nominal
kinematic viscosity at 40 degC (150 mm^2/s by default), taken as the
viscosity in the contact (a bulk temperature of 40 degC: a cool, conservative
oil, whose higher viscosity lowers mu in both laws), a mineral oil's density,
and the flanks' Ra from the rating's mean peak-to-valley Rz (Ra ~ Rz / 6, the
usual ratio of ground and lapped gear flanks).

SI units inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FRICTION_LAWS", "Lubricant", "benedict_kelley", "iso_tr_14179_2",
           "nominal_values", "friction_coefficients", "mesh_power_loss", "mesh_efficiency",
           "LEAST_SLIDING_SPEED", "RZ_PER_RA"]

#: The friction laws by name, with their source.
FRICTION_LAWS = {
    "benedict_kelley": "Benedict & Kelley, ASLE Trans. 4 (1961) 59-70, local",
    "iso_tr_14179_2": "ISO/TR 14179-2:2001 (Schlenk 1994), mean over the mesh",
}
#: Sliding speed Benedict & Kelley's logarithm is held at, at least [m/s].
LEAST_SLIDING_SPEED = 0.01
#: Mean peak-to-valley over arithmetic roughness of gear flanks, Rz / Ra [-].
RZ_PER_RA = 6.0
#: Benedict & Kelley's constant with w [N/m], eta [mPa s], speeds [m/s] [-].
_BK_CONSTANT = 3.17e8 * 0.0254**3 / (4.4482216152605 / 0.0254)
#: Benedict & Kelley's roughness factor's limit, S < 50 microinches [m].
_BK_ROUGHNESS_LIMIT = 50 * 0.0254e-6


@dataclass(frozen=True)
class Lubricant:
    """The oil and the flanks' roughness, in SI units.

    Parameters
    ----------
    kinematic_viscosity : float
        nu in the contact [m^2/s] (lsbg: the rating's nu_40).
    density : float
        rho [kg/m^3] (a mineral oil at 40 degC: 880).
    roughness : float
        Ra, the arithmetic mean roughness of the flanks, both members' mean [m].
    lubricant_factor : float
        X_L of ISO/TR 14179-2 [-] (1 for mineral oil).
    """

    kinematic_viscosity: float = 150e-6
    density: float = 880.0
    roughness: float = 8e-6 / RZ_PER_RA
    lubricant_factor: float = 1.0

    def __post_init__(self):
        for name in ("kinematic_viscosity", "density", "roughness", "lubricant_factor"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value) or value <= 0:
                raise ValueError(f"{name} = {value!r}: must be a number > 0")

    @property
    def dynamic_viscosity(self):
        """eta = nu rho [Pa s]."""
        return self.kinematic_viscosity * self.density


def benedict_kelley(line_load, sliding_speed, rolling_speed, lubricant):
    """Benedict & Kelley's (1961) coefficient of friction at contact points [-].

    Parameters
    ----------
    line_load : array_like
        w, normal load per unit length of contact line [N/m], > 0 where loaded.
    sliding_speed : array_like
        V_s [m/s] (held at :data:`LEAST_SLIDING_SPEED` or more in the logarithm).
    rolling_speed : array_like
        V_sum, the sum of the surfaces' speeds across the line [m/s], > 0.
    lubricant : Lubricant

    Returns
    -------
    numpy.ndarray
        mu >= 0 (0 where unloaded).

    Raises
    ------
    ValueError
        If the roughness is beyond the law's roughness factor (Ra >= 1.27 um).
    """
    if lubricant.roughness >= _BK_ROUGHNESS_LIMIT:
        raise ValueError(f"roughness = {lubricant.roughness!r}: Benedict & Kelley's roughness "
                         f"factor 50/(50 - S) needs S < 50 microinches (Ra < 1.27 um)")
    w = np.asarray(line_load, float)
    slide = np.maximum(np.asarray(sliding_speed, float), LEAST_SLIDING_SPEED)
    roll = np.asarray(rolling_speed, float)
    factor = 50.0 / (50.0 - lubricant.roughness / 0.0254e-6)
    eta = lubricant.dynamic_viscosity * 1e3  # mPa s
    out = np.zeros(np.broadcast(w, slide, roll).shape)
    loaded = np.broadcast_to(w > 0, out.shape)
    argument = _BK_CONSTANT * w / (eta * slide * roll**2)
    out[loaded] = 0.0127 * factor * np.log10(np.broadcast_to(argument, out.shape)[loaded])
    return np.maximum(out, 0.0)


def iso_tr_14179_2(tangential_load, face_width, rolling_speed, relative_radius, lubricant):
    """ISO/TR 14179-2's mean coefficient of friction of a mesh, mu_mz [-].

    Parameters
    ----------
    tangential_load : float
        F_bt, the tangential load on the base circle [N].
    face_width : float
        b [m].
    rolling_speed : float
        V_sum,C, the sum speed at the pitch point [m/s], > 0.
    relative_radius : float
        rho_red,C, the relative radius of curvature at the pitch point [m], > 0.
    lubricant : Lubricant

    Returns
    -------
    float
    """
    load = tangential_load / face_width * 1e-3                     # N/mm
    group = load / (rolling_speed * relative_radius * 1e3)         # (N/mm)/(m/s mm)
    eta = lubricant.dynamic_viscosity * 1e3                        # mPa s
    return float(0.048 * group**0.2 * eta**-0.05 * (lubricant.roughness * 1e6)**0.25
                 * lubricant.lubricant_factor)


def nominal_values(pair, gear_torque, pinion_speed, curvature):
    """ISO/TR 14179-2's nominal values of a pair from lsbg's own kinematics.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    gear_torque : float
        T_2 [N m].
    pinion_speed : float
        omega_1 [rad/s].
    curvature : callable
        ``curvature(rho, psi)`` -> relative curvature [1/m]
        (:class:`lsbg.optimise.kinematics.CurvatureTable`).

    Returns
    -------
    dict
        ``tangential_load`` T_2 / r_b2 [N] (r_b2 = R_m sin(delta_b2), the
        gear's base radius at the mean point), ``rolling_speed`` [m/s] and
        ``relative_radius`` [m] at the mean point of the pitch line.
    """
    from lsbg.optimise.kinematics import contact_speeds

    design = pair.design
    rho = design.mean_cone_distance
    _, rolling = contact_speeds(pair, rho, 0.0, pinion_speed)
    base_radius = rho * math.sin(design.base_cone_angle(2))
    return {"tangential_load": gear_torque / base_radius, "rolling_speed": float(rolling),
            "relative_radius": float(1.0 / curvature(rho, 0.0))}


def friction_coefficients(law, line_load, sliding_speed, rolling_speed, lubricant,
                          nominal=None, face_width=None):
    """The coefficient of friction of each contact point under a named law [-].

    Parameters
    ----------
    law : str
        A key of :data:`FRICTION_LAWS`.
    line_load, sliding_speed, rolling_speed : array_like
        At the points [N/m, m/s, m/s].
    lubricant : Lubricant
    nominal : dict, optional
        :func:`nominal_values` (``iso_tr_14179_2`` only).
    face_width : float, optional
        b [m] (``iso_tr_14179_2`` only).

    Returns
    -------
    numpy.ndarray
        mu at each point (the mesh's mean everywhere under ``iso_tr_14179_2``).
    """
    if law == "benedict_kelley":
        return benedict_kelley(line_load, sliding_speed, rolling_speed, lubricant)
    if law == "iso_tr_14179_2":
        mu = iso_tr_14179_2(nominal["tangential_load"], face_width, nominal["rolling_speed"],
                            nominal["relative_radius"], lubricant)
        return np.full(np.shape(line_load), mu)
    raise ValueError(f"friction law {law!r}: one of {sorted(FRICTION_LAWS)}")


def mesh_power_loss(force, sliding_speed, friction, axis=None):
    """Sliding power loss sum(mu F V_s) [W].

    Parameters
    ----------
    force : array_like
        Normal force of each point [N].
    sliding_speed : array_like
        [m/s].
    friction : array_like
        mu [-].
    axis : int or tuple, optional
        Axes summed over (default: all).

    Returns
    -------
    numpy.ndarray or float
    """
    return np.sum(np.asarray(friction) * np.asarray(force) * np.asarray(sliding_speed), axis=axis)


def mesh_efficiency(power_loss, gear_torque, gear_speed):
    """Mesh efficiency 1 - P / (T_2 omega_2 + P) [-].

    Parameters
    ----------
    power_loss : float
        Mean sliding loss over a mesh cycle [W].
    gear_torque : float
        T_2 [N m], > 0.
    gear_speed : float
        omega_2 [rad/s], > 0.
    """
    output = gear_torque * gear_speed
    return 1.0 - power_loss / (output + power_loss)
