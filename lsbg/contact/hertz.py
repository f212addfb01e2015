"""Hertz contact stiffness: the k of the IMPACT law (paper Eq. 9), and what a given k implies.

The paper's Eq. (9) gives the stiffness k of ``F = k x^1.5`` from the radii of
curvature and the elastic constants of the two bodies, times a correction
coefficient it does not state; :func:`implied_correction_coefficient` finds
the coefficient behind its k, :func:`hertz_approach` the approach under a
force. SI units (m, N, Pa).

References
----------
.. [1] K. L. Johnson, Contact Mechanics, Cambridge University Press, 1985, §4.2.
"""

from __future__ import annotations

import numpy as np

__all__ = ["hertz_stiffness", "implied_correction_coefficient", "hertz_approach"]


# ---------------------------------------------------------------------------
# Eq. 9 and 11: Hertz stiffness and approach of two cylinders
# ---------------------------------------------------------------------------

def _hertz_stiffness_unit_correction(r1, r2, e1, e2, nu1, nu2):
    """Eq. (9) with ρ = 1: (4/3) sqrt(R*) E* [N/m^1.5]."""
    r1, r2, e1, e2, nu1, nu2 = (np.asarray(a, dtype=float)
                                for a in (r1, r2, e1, e2, nu1, nu2))
    reduced_radius = r1 * r2 / (r1 + r2)
    reduced_modulus = e1 * e2 / (e1 * (1.0 - nu2**2) + e2 * (1.0 - nu1**2))
    return 4.0 / 3.0 * np.sqrt(reduced_radius) * reduced_modulus


def hertz_stiffness(r1, r2, e1, e2, nu1, nu2, correction=1.0):
    """Hertz contact stiffness, paper Eq. (9).

    ``k = 4/3 sqrt(R1 R2 / (R1 + R2)) ρ E1 E2 / (E1 (1-ν2²) + E2 (1-ν1²))``

    Parameters
    ----------
    r1, r2 : array_like
        Radii of curvature of the two bodies at the contact point; the paper
        uses the outer pitch radii, 20.25 mm and 83.25 mm [m].
    e1, e2 : array_like
        Young's moduli [Pa].
    nu1, nu2 : array_like
        Poisson's ratios [-].
    correction : array_like, default 1.0
        Correction coefficient ρ of Eq. (9) [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Stiffness k of ``F = k x^1.5`` [N/m^1.5].

    Notes
    -----
    ``sqrt(m) · Pa = N/m^1.5``, so SI inputs give SI output; the paper's
    mm and N/mm² give N/mm^1.5 (factor 1000^1.5 smaller). The paper gives no
    ρ. With its data (E = 2.07e5 N/mm², ν = 0.285) Eq. (9) yields
    k / ρ = 6.06e5 N/mm^1.5, so its k = 6.65e7 N/mm^1.5 implies ρ ≈ 110
    (see :func:`implied_correction_coefficient`).
    """
    return correction * _hertz_stiffness_unit_correction(
        r1, r2, e1, e2, nu1, nu2)


def implied_correction_coefficient(k, r1, r2, e1, e2, nu1, nu2):
    """Correction coefficient ρ that makes Eq. (9) return a given stiffness.

    Parameters
    ----------
    k : array_like
        Contact stiffness for exponent 1.5 [N/m^1.5].
    r1, r2, e1, e2, nu1, nu2 : array_like
        Radii of curvature at the contact point [m], Young's moduli [Pa] and
        Poisson's ratios [-] of the two bodies, as in :func:`hertz_stiffness`.

    Returns
    -------
    numpy.ndarray or numpy.float64
        ρ [-]; about 110 for the paper's k and data.
    """
    return np.asarray(k, dtype=float) / _hertz_stiffness_unit_correction(
        r1, r2, e1, e2, nu1, nu2)


def hertz_approach(force, r1, r2, e1, e2, nu1, nu2, correction=1.0):
    """Hertz normal approach under a normal load, paper Eq. (11).

    Eq. (11) is ``F = k x^1.5`` solved for x with k from Eq. (9), so it is
    evaluated as ``x = (F / k)^(2/3)``.

    Parameters
    ----------
    force : array_like
        Normal contact force P, >= 0 [N].
    r1, r2, e1, e2, nu1, nu2, correction : array_like
        Radii of curvature at the contact point [m], Young's moduli [Pa],
        Poisson's ratios [-] and the correction coefficient ρ (default 1.0)
        [-], as in :func:`hertz_stiffness`.

    Returns
    -------
    numpy.ndarray or numpy.float64
        Normal approach x [m].

    Raises
    ------
    ValueError
        If any force is negative (Eq. 11 contains P² and would return the
        approach for a pull).
    """
    force = np.asarray(force, dtype=float)
    if np.any(force < 0.0):
        raise ValueError(f"hertz_approach needs force >= 0 [N], got {force}")
    k = hertz_stiffness(r1, r2, e1, e2, nu1, nu2, correction)
    return (force / k) ** (2.0 / 3.0)
