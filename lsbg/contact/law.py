"""Contact laws: the paper's IMPACT law (§3.1, Eq. 8–11), friction, and the line-slice law.

This module holds the force *laws*: given a penetration, its rate and a sliding
speed, they return a normal force and a friction coefficient. Everything is in
SI units (m, N, s); their parameters, and the paper's units (N/mm^1.5, N·s/mm,
mm, mm/s) at the edge, are in :mod:`lsbg.contact.parameters`.

Two contact models use these laws (:mod:`lsbg.contact.mesh`):

* ``"point"``, the paper's: one IMPACT incident per tooth pair, Eq. (8);
* ``"line"``: each contact line cut into slices, each slice a linear spring
  per unit length with viscous damping, clipped so that it never pulls
  (:func:`line_load`). Its stiffness is calibrated to the standard mesh
  stiffness of steel gears and its damping is a damping ratio of the mesh
  mode (docs/model.md, "The line model").

Every law comes twice: a vectorised function (numpy arrays or scalars) and a
``*_scalar`` twin on floats, compiled with numba so that the contact kernels
(:mod:`lsbg.contact.kernels`) call it without Python overhead. Both twins
evaluate the same private formulas (:func:`_step_from_delta`,
:func:`_impact_terms`); they differ only in how regimes are selected
(``np.where``/``np.clip`` versus ``if``).

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3.1, Eq. (8)–(11).
.. [2] MSC Adams Solver reference: IMPACT function, STEP function and the
   CONTACT statement's friction model.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = [
    "step", "step_scalar", "impact_force", "impact_force_scalar", "friction_coefficient",
    "friction_coefficient_scalar", "friction_integral_scalar", "line_load", "line_load_scalar"
]


def _jit(function):
    """The compiled twin of a float formula (compiled once per machine, cached on disk)."""
    return njit(cache=True, inline="always")(function)


# ---------------------------------------------------------------------------
# Eq. 10: Adams' cubic STEP
# ---------------------------------------------------------------------------

def _step_from_delta(delta, h0, h1):
    """Cubic of Eq. 10 for a normalised abscissa ``delta`` already in [0, 1].

    Works on floats and arrays alike, so the vectorised and the scalar STEP
    share this single formula. (3 - 2Δ)Δ² has zero slope at Δ = 0 and Δ = 1,
    which makes STEP continuous with its derivative (C¹).
    """
    return h0 + (h1 - h0) * (delta * delta * (3.0 - 2.0 * delta))


_step_from_delta_jit = _jit(_step_from_delta)


def step(x, x0, h0, x1, h1):
    """Adams' cubic STEP function, paper Eq. (10).

    ``h0`` for ``x <= x0``, ``h1`` for ``x >= x1`` and, in between,
    ``h0 + (h1 - h0) (3 - 2Δ) Δ²`` with ``Δ = (x - x0) / (x1 - x0)``.

    Parameters
    ----------
    x : array_like
        Independent variable [any unit].
    x0 : array_like
        Abscissa where the transition starts [unit of ``x``].
    h0 : array_like
        Value at and below ``x0`` [any unit].
    x1 : array_like
        Abscissa where the transition ends; must exceed ``x0`` [unit of ``x``].
    h1 : array_like
        Value at and above ``x1`` [unit of ``h0``].

    Returns
    -------
    numpy.ndarray or numpy.float64
        STEP value, broadcast over the inputs [unit of ``h0``].

    Raises
    ------
    ValueError
        If any ``x1 <= x0``.
    """
    x0 = np.asarray(x0, dtype=float)
    x1 = np.asarray(x1, dtype=float)
    if np.any(x1 <= x0):
        raise ValueError(f"step needs x1 > x0, got x0={x0}, x1={x1}")
    delta = np.clip((np.asarray(x, dtype=float) - x0) / (x1 - x0), 0.0, 1.0)
    return _step_from_delta(delta, h0, h1)


@njit(cache=True)
def step_scalar(x, x0, h0, x1, h1):
    """STEP of Eq. (10) on floats, compiled (for the contact kernels and hot loops).

    No validation (callers pass x1 > x0); NaN in ``x`` propagates, as in
    :func:`step`. Parameters and units as :func:`step`.
    """
    delta = (x - x0) / (x1 - x0)
    # if-chains rather than min/max: this runs millions of times per run.
    if delta <= 0.0:
        return h0
    if delta >= 1.0:
        return h1
    return _step_from_delta_jit(delta, h0, h1)


# ---------------------------------------------------------------------------
# Eq. 8: normal force (IMPACT)
# ---------------------------------------------------------------------------

def _impact_terms(x, xdot, k, e, damping_weight):
    """Unclipped Eq. (8) for x > 0: elastic term plus ramped damping."""
    return k * x**e + damping_weight * xdot


_impact_terms_jit = _jit(_impact_terms)


def impact_force(penetration, penetration_rate, params):
    """Normal contact force of Adams' IMPACT law, paper Eq. (8).

    ``F = k x^e + STEP(x, 0, 0, d, c_max) ẋ`` for ``x > 0``, else 0, and
    never negative.

    Parameters
    ----------
    penetration : array_like
        Normal approach x of the two flanks; positive means penetration [m].
    penetration_rate : array_like
        Time derivative ẋ of ``penetration``; positive while the flanks
        approach [m/s].
    params : ContactParameters
        Contact law.

    Returns
    -------
    numpy.ndarray or numpy.float64
        Normal force pushing the flanks apart, >= 0 [N]. NaN inputs give NaN
        where the flanks might be in contact.

    Notes
    -----
    Sign convention: the paper writes Eq. (8) with x < 0 meaning contact;
    here x > 0 means penetration, so that x is the penetration depth.

    The damping weight rises smoothly from 0 at first touch to ``c_max`` at
    ``x = d``, which avoids a force jump at impact. While the flanks separate
    quickly (ẋ < 0) the damping term can exceed the elastic one; the force is
    then clipped at 0, as Adams' IMPACT does, because flanks cannot pull.
    """
    x = np.asarray(penetration, dtype=float)
    weight = step(x, 0.0, 0.0, params.d, params.c_max)
    rate = np.asarray(penetration_rate, dtype=float)
    # max(x, 0) keeps x**e real where the result is discarded anyway.
    force = _impact_terms(np.maximum(x, 0.0), rate, params.k, params.e, weight)
    # [()] turns a 0-d result into a numpy scalar and leaves arrays alone.
    return np.where(x <= 0.0, 0.0, np.maximum(force, 0.0))[()]


@njit(cache=True)
def impact_force_scalar(x, xdot, k, e, c_max, d):
    """Compiled float twin of :func:`impact_force` (the contact kernels call it).

    Parameters
    ----------
    x : float
        Normal approach of the two flanks; positive means penetration [m].
    xdot : float
        Penetration rate; positive while the flanks approach [m/s].
    k, e, c_max, d : float
        The law's stiffness [N/m^e], exponent [-], maximum damping [N·s/m]
        and full-damping depth [m] (:class:`ContactParameters` fields).

    Returns
    -------
    float
        Normal force, >= 0 (NaN propagates) [N].
    """
    if x <= 0.0:
        return 0.0
    force = _impact_terms_jit(x, xdot, k, e, step_scalar(x, 0.0, 0.0, d, c_max))
    # Written so that NaN passes through, as np.maximum does.
    return 0.0 if force < 0.0 else force


# ---------------------------------------------------------------------------
# Friction coefficient
# ---------------------------------------------------------------------------

def friction_coefficient(sliding_speed, params):
    """Friction coefficient as a function of the sliding speed (Adams style).

    ``STEP(|v|, 0, 0, v_s, mu_s)`` for ``|v| < v_s``,
    ``STEP(|v|, v_s, mu_s, v_d, mu_d)`` for ``v_s <= |v| < v_d`` and ``mu_d``
    above.

    Parameters
    ----------
    sliding_speed : array_like
        Relative sliding velocity at the contact point; only its magnitude
        matters [m/s].
    params : ContactParameters
        Contact law.

    Returns
    -------
    numpy.ndarray or numpy.float64
        Friction coefficient, >= 0 [-]. The friction force is this times
        the normal force and opposes the sliding velocity.

    Notes
    -----
    The coefficient is 0 at zero sliding speed (there is no true stiction,
    which keeps the force a smooth function of the state) and C¹ in |v|.
    Adams' CONTACT statement blends the signed coefficient across
    [-v_s, v_s] with a single STEP instead; that curve has the same end
    values but is steeper near v = 0 (0.69 μ_s rather than 0.5 μ_s at
    v_s / 2).
    """
    speed = np.abs(np.asarray(sliding_speed, dtype=float))
    return np.where(
        speed < params.v_s,
        step(speed, 0.0, 0.0, params.v_s, params.mu_s),
        step(speed, params.v_s, params.mu_s, params.v_d, params.mu_d))[()]


@njit(cache=True)
def friction_coefficient_scalar(v, mu_s, mu_d, v_s, v_d):
    """Compiled float twin of :func:`friction_coefficient` (the kernels call it).

    Parameters
    ----------
    v : float
        Sliding velocity; only its magnitude matters [m/s].
    mu_s, mu_d : float
        Static and dynamic friction coefficients [-].
    v_s, v_d : float
        Stiction and friction transition velocities [m/s].

    Returns
    -------
    float
        Friction coefficient, >= 0 [-].
    """
    speed = abs(v)
    if speed >= v_d:  # the common case in a running mesh
        return mu_d
    if speed < v_s:
        return step_scalar(speed, 0.0, 0.0, v_s, mu_s)
    return step_scalar(speed, v_s, mu_s, v_d, mu_d)


@njit(cache=True)
def friction_integral_scalar(x, rate, mu_s, mu_d, v_s, v_d):
    """Integral of the friction coefficient where the sliding speed grows linearly.

    ``G(x) = int_0^x mu(rate u) du`` for a sliding speed ``rate * u`` that
    grows linearly with a coordinate u from 0 (e.g. the distance from the
    pitch line along a contact line, where the sliding reverses). Closed form
    of :func:`friction_coefficient` integrated piecewise (the STEP cubic
    integrates to D^3 - D^4/2). The line model averages friction over a slice
    with it, so that the narrow stiction zone at the pitch line counts with
    its true width rather than through the slice's centre.

    Parameters
    ----------
    x : float
        Upper limit, >= 0 [unit of u].
    rate : float
        Sliding speed per unit u, > 0 [m/s per unit of u].
    mu_s, mu_d, v_s, v_d : float
        The friction law of :func:`friction_coefficient_scalar`: static and
        dynamic coefficients [-], stiction and transition velocities [m/s].

    Returns
    -------
    float
        G(x) [unit of u].
    """
    xs = v_s / rate
    xd = v_d / rate
    if x <= xs:
        d = x / xs
        return xs * mu_s * (d * d * d - 0.5 * d * d * d * d)
    if x <= xd:
        d = (x - xs) / (xd - xs)
        return 0.5 * xs * mu_s + (xd - xs) * (mu_s * d + (mu_d - mu_s) * (d * d * d - 0.5 * d * d * d * d))
    return 0.5 * xs * mu_s + 0.5 * (xd - xs) * (mu_s + mu_d) + mu_d * (x - xd)


# ---------------------------------------------------------------------------
# The line model's slice law
# ---------------------------------------------------------------------------

def line_load(approach, approach_rate, stiffness, damping):
    """Normal load per unit length of a contact-line slice (line model).

    ``w = k_l x + c_l ẋ`` for ``x > 0``, else 0, and never negative: a linear
    spring per unit length with viscous damping, clipped because flanks
    cannot pull (the damping term would while they separate quickly).

    Parameters
    ----------
    approach : array_like
        Normal approach x of the flanks at the slice; positive means
        penetration [m].
    approach_rate : array_like
        dx/dt [m/s].
    stiffness : float
        k_l, load per unit length per unit approach [N/m^2].
    damping : float
        c_l, load per unit length per unit approach rate [N·s/m^2].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Load per unit length, >= 0 [N/m].
    """
    x = np.asarray(approach, dtype=float)
    w = stiffness * x + damping * np.asarray(approach_rate, dtype=float)
    return np.where(x <= 0.0, 0.0, np.maximum(w, 0.0))[()]


@njit(cache=True)
def line_load_scalar(x, xdot, stiffness, damping):
    """Compiled float twin of :func:`line_load` (the line kernel calls it).

    Parameters and units as :func:`line_load`; returns the load per unit
    length [N/m], >= 0 (NaN propagates).
    """
    if x <= 0.0:
        return 0.0
    w = stiffness * x + damping * xdot
    return 0.0 if w < 0.0 else w
