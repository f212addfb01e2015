"""Service life under a load spectrum: Miner's rule on the Basquin lines.

A gear does not run at one torque. ISO 6336-6 rates it under a load
spectrum by the Palmgren-Miner rule: a share n_i / N of the load cycles at
the stress sigma_i uses up n_i / N_i(sigma_i) of the life, and the gear
fails when the shares add up to 1. On the Basquin line N sigma^p = C of
:mod:`lsbg.rating.life` the life under the spectrum is

    N = C / sum_i s_i sigma_i^p,

s_i the share of the cycles at level i, so two gear types of the same
spectrum live N_a / N_b = sum_i s_i sigma_b,i^p / sum_i s_i sigma_a,i^p, and
the damage-equivalent stress (sum_i s_i sigma_i^p)^(1/p) is the one constant
stress that does the same damage. This is Miner's *elementary* rule: the line
is extended below the endurance limit (no level is free of damage), the
conservative choice of ISO 6336-6 when the stresses are not compared with the
limit (the FE stresses here are compared between the types, not with the
material's endurance strength).
"""

from __future__ import annotations

import numpy as np

__all__ = ["check_spectrum", "damage_equivalent_stress", "spectrum_life_ratio",
           "spectrum_stresses"]


def check_spectrum(torque_fractions, cycle_shares):
    """The spectrum as two arrays, or a ValueError naming the key.

    Parameters
    ----------
    torque_fractions : sequence of float
        Levels as fractions of the design load [-], > 0.
    cycle_shares : sequence of float
        The share of the load cycles at each level [-], >= 0, adding up to 1
        (within 1e-6).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
    """
    levels = np.asarray(torque_fractions, float)
    shares = np.asarray(cycle_shares, float)
    where = "practice.load_spectrum"
    if levels.ndim != 1 or levels.size == 0 or shares.shape != levels.shape:
        raise ValueError(f"{where}.cycle_shares = {shares.tolist()}: needs one share per torque "
                         f"fraction ({levels.size})")
    if not np.all(np.isfinite(levels) & (levels > 0)):
        raise ValueError(f"{where}.torque_fractions = {levels.tolist()}: each must be > 0")
    if not (np.all(np.isfinite(shares) & (shares >= 0)) and abs(shares.sum() - 1) <= 1e-6):
        raise ValueError(f"{where}.cycle_shares = {shares.tolist()}: must be >= 0 and add up to 1 "
                         f"(they add up to {shares.sum():.6g})")
    return levels, shares


def damage_equivalent_stress(stresses, shares, exponent):
    """(sum_i s_i sigma_i^p)^(1/p): the constant stress of the same Miner damage.

    Parameters
    ----------
    stresses : array_like
        sigma_i at the spectrum's levels, > 0 [any stress unit: the result's].
    shares : array_like
        s_i [-], adding up to 1.
    exponent : float
        The Basquin exponent p [-].
    """
    stresses = np.asarray(stresses, float)
    # scaled by the largest so that sigma^p (p up to ~25) stays finite
    top = stresses.max()
    return float(top * np.sum(np.asarray(shares, float) * (stresses / top) ** exponent)
                 ** (1.0 / exponent))


def spectrum_life_ratio(stresses, reference_stresses, shares, kind):
    """Life under the spectrum at ``stresses`` over life at ``reference_stresses``.

    Parameters
    ----------
    stresses, reference_stresses : array_like
        The two designs' (or types') stresses at each level, > 0 [one stress unit].
    shares : array_like
        The share of the cycles at each level [-].
    kind : {"contact", "bending"}
        Which Basquin lines (:data:`lsbg.rating.life.EXPONENTS`).

    Returns
    -------
    dict
        ``ratio`` at the stated exponent, ``low`` and ``high`` over the
        exponents' range, ``exponent``, and the damage-equivalent stresses
        ``equivalent`` and ``reference_equivalent`` at the stated exponent [the
        stresses' unit].
    """
    from lsbg.rating.life import EXPONENTS

    exponents = [line.exponent for line in EXPONENTS[kind]]
    ratios = [(damage_equivalent_stress(reference_stresses, shares, p)
               / damage_equivalent_stress(stresses, shares, p)) ** p for p in exponents]
    return {"ratio": ratios[0], "low": min(ratios), "high": max(ratios),
            "exponent": exponents[0],
            "equivalent": damage_equivalent_stress(stresses, shares, exponents[0]),
            "reference_equivalent": damage_equivalent_stress(reference_stresses, shares,
                                                             exponents[0])}


def spectrum_stresses(curve, variable, torques):
    """A load curve's cycle maximum of ``variable`` at gear torques, interpolated [its units].

    Parameters
    ----------
    curve : xarray.Dataset
        :func:`lsbg.practice.load_curve.load_curve`.
    variable : str
        E.g. ``max_contact_pressure`` (on torque and mesh phase: its largest
        over the cycle).
    torques : array_like
        [N m], within the curve's torques.

    Raises
    ------
    ValueError
        If a torque lies outside the curve (no extrapolation).
    """
    values = curve[variable]
    if "mesh_phase" in values.dims:
        values = values.max("mesh_phase")
    axis = curve["torque"].values
    torques = np.asarray(torques, float)
    # (the curve's torques are written to 1 mN m, a design load perhaps not)
    if torques.min() < axis.min() - 1e-3 or torques.max() > axis.max() + 1e-3:
        raise ValueError(f"load spectrum torques {torques.min():.4g}-{torques.max():.4g} N m lie "
                         f"outside the load curve's {axis.min():.4g}-{axis.max():.4g} N m "
                         f"(practice.load_range)")
    return np.interp(torques, axis, values.values)
