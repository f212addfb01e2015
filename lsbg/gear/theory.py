"""Rigid-gear predictions the simulations are compared with (paper Eq. 12–13).

Table 3 of the paper compares the simulated mean gear speed and tangential
contact force with these values: Eq. (12) gives 1873.703 deg/s for a pinion
speed of 7703 deg/s and 9:37 teeth, Eq. (13) gives 23603.48 N for 1964.99 N·m
on the outer pitch diameter 166.5 mm.

The paper states that 7703 deg/s is "4500 revolutions per minute"; it is
1283.8 rpm (:func:`rpm_from_deg_per_s`). The simulations use 7703 deg/s.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3.1–3.2, Eq. (12),
   (13) and Table 3.
"""

import numpy as np


# 1 rpm = 360 deg per 60 s.
_DEG_PER_S_PER_RPM = 360.0 / 60.0


def gear_speed(pinion_speed, z1, z2):
    """Gear speed of an ideal (rigid, conjugate) pair, paper Eq. (12).

    ``n2 = n1 z1 / z2``

    Parameters
    ----------
    pinion_speed : array_like
        Pinion angular speed n1 [any angular speed unit, e.g. deg/s or
        rad/s].
    z1 : array_like
        Number of pinion teeth [-].
    z2 : array_like
        Number of gear teeth [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Gear angular speed n2 [unit of ``pinion_speed``].

    Raises
    ------
    ValueError
        If a tooth number is not positive.
    """
    z1 = np.asarray(z1, dtype=float)
    z2 = np.asarray(z2, dtype=float)
    if np.any(z1 <= 0) or np.any(z2 <= 0):
        raise ValueError(f"tooth numbers must be > 0, got z1={z1}, z2={z2}")
    return np.asarray(pinion_speed, dtype=float) * z1 / z2


def tangential_force(torque, pitch_diameter):
    """Tangential force at the pitch circle for a torque, paper Eq. (13).

    ``F = 2 T / d``

    Parameters
    ----------
    torque : array_like
        Transmitted torque T [N·m].
    pitch_diameter : array_like
        Pitch diameter d at which the force acts; the paper uses the outer
        (exterior transverse) pitch diameter [m].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Tangential force [N].

    Raises
    ------
    ValueError
        If a pitch diameter is not positive.
    """
    pitch_diameter = np.asarray(pitch_diameter, dtype=float)
    if np.any(pitch_diameter <= 0):
        raise ValueError(
            f"pitch_diameter must be > 0 [m], got {pitch_diameter}")
    return 2.0 * np.asarray(torque, dtype=float) / pitch_diameter


def rpm_from_deg_per_s(speed):
    """Convert an angular speed from deg/s to revolutions per minute.

    Parameters
    ----------
    speed : array_like
        Angular speed [deg/s].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Angular speed [rpm]. 7703 deg/s gives 1283.8 rpm, not the paper's
        "4500 rpm".
    """
    return np.asarray(speed, dtype=float) / _DEG_PER_S_PER_RPM


def deg_per_s_from_rpm(speed):
    """Convert an angular speed from revolutions per minute to deg/s.

    Parameters
    ----------
    speed : array_like
        Angular speed [rpm].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Angular speed [deg/s].
    """
    return np.asarray(speed, dtype=float) * _DEG_PER_S_PER_RPM
