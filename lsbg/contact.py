"""Contact law of the paper (§3.1, Eq. 8–11): Adams-style IMPACT and friction.

This module holds the force *law*: given a penetration, its rate and a sliding
speed, it returns a normal force and a friction coefficient. Everything is in
SI units (m, N, s, Pa); the paper's units (N/mm^1.5, N·s/mm, mm, mm/s) appear
only in :meth:`ContactParameters.from_paper_units`.

Every law comes twice: a vectorised function (numpy arrays or scalars) and a
``*_scalar`` twin that uses plain floats only. The twin exists because the
PyBullet engine evaluates the law about 1e6 times per simulated second from a
Python loop, where numpy costs about 1 µs per operation on a scalar. Both
twins evaluate the same private formulas (:func:`_step_from_delta`,
:func:`_impact_terms`); they differ only in how regimes are selected
(``np.where``/``np.clip`` versus ``if``/``min``/``max``).

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3.1, Eq. (8)–(11).
.. [2] MSC Adams Solver reference: IMPACT function, STEP function and the
   CONTACT statement's friction model.
"""

from dataclasses import dataclass

import numpy as np


# One millimetre in metres: the paper's units are N, mm and s.
_MM = 1e-3


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


def _step_scalar(x, x0, h0, x1, h1):
    """STEP of Eq. (10) on plain floats; no validation (callers pass valid
    parameters). NaN in ``x`` propagates, as in :func:`step`."""
    delta = min(max((x - x0) / (x1 - x0), 0.0), 1.0)
    return _step_from_delta(delta, h0, h1)


# ---------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------

@dataclass(frozen=True, slots=True)
class ContactParameters:
    """Parameters of the IMPACT contact law and its friction, in SI units.

    The defaults are the paper's values (§3.1), converted to SI. The paper
    gives no friction transition velocities; ``v_s`` = 0.1 mm/s and
    ``v_d`` = 10 mm/s are the values documented as Adams' defaults for the
    friction of IMPACT contacts (they also appear in the usual Adams table
    for dry steel on steel), so the paper's Adams model most likely used
    them. Keep them configurable.

    Parameters
    ----------
    k : float, default 6.65e7 N/mm^1.5 = 2.1029e12 N/m^1.5
        Contact stiffness [N/m^e]. Its unit depends on ``e``.
    e : float, default 1.5
        Force exponent [-]; 1.5 is Hertz's point contact.
    c_max : float, default 50 N·s/mm = 5e4 N·s/m
        Maximum damping coefficient, reached at penetration ``d`` [N·s/m].
    d : float, default 0.1 mm = 1e-4 m
        Penetration at which full damping is reached [m].
    mu_s : float, default 0.08
        Static friction coefficient [-].
    mu_d : float, default 0.05
        Dynamic friction coefficient [-].
    v_s : float, default 0.1 mm/s = 1e-4 m/s
        Stiction transition velocity: sliding speed at which ``mu_s`` is
        reached [m/s].
    v_d : float, default 10 mm/s = 1e-2 m/s
        Friction transition velocity: sliding speed from which ``mu_d``
        applies [m/s].

    Raises
    ------
    ValueError
        Naming the offending field and its value, if ``k <= 0``, ``e < 1``,
        ``c_max < 0``, ``d <= 0``, a friction coefficient is outside [0, 1],
        ``v_s <= 0`` or ``v_d <= v_s``.

    Notes
    -----
    All fields are stored as Python floats, which keeps the ``*_scalar``
    functions free of numpy scalar arithmetic.
    """

    k: float = 6.65e7 / _MM**1.5
    e: float = 1.5
    c_max: float = 50.0 / _MM
    d: float = 0.1 * _MM
    mu_s: float = 0.08
    mu_d: float = 0.05
    v_s: float = 0.1 * _MM
    v_d: float = 10.0 * _MM

    def __post_init__(self):
        for name in ("k", "e", "c_max", "d", "mu_s", "mu_d", "v_s", "v_d"):
            object.__setattr__(self, name, float(getattr(self, name)))
        # Written as "not (valid)" so that NaN is rejected too.
        checks = (
            ("k", self.k > 0.0, "must be > 0 [N/m^e]"),
            ("e", self.e >= 1.0, "must be >= 1 [-]"),
            ("c_max", self.c_max >= 0.0, "must be >= 0 [N*s/m]"),
            ("d", self.d > 0.0, "must be > 0 [m]"),
            ("mu_s", 0.0 <= self.mu_s <= 1.0, "must lie in [0, 1] [-]"),
            ("mu_d", 0.0 <= self.mu_d <= 1.0, "must lie in [0, 1] [-]"),
            ("v_s", self.v_s > 0.0, "must be > 0 [m/s]"),
            ("v_d", self.v_d > self.v_s, f"must be > v_s={self.v_s!r} [m/s]"),
        )
        for name, valid, rule in checks:
            if not valid:
                raise ValueError(
                    f"ContactParameters.{name} {rule}, got "
                    f"{name}={getattr(self, name)!r}")

    @classmethod
    def from_paper_units(cls, k, e, c_max, d, mu_s, mu_d, v_s, v_d):
        """Build parameters from values in the paper's units (N, mm, s).

        Parameters
        ----------
        k : float
            Contact stiffness [N/mm^e].
        e : float
            Force exponent [-].
        c_max : float
            Maximum damping coefficient [N·s/mm].
        d : float
            Penetration at which full damping is reached [mm].
        mu_s, mu_d : float
            Static and dynamic friction coefficients [-].
        v_s, v_d : float
            Stiction and friction transition velocities [mm/s].

        Returns
        -------
        ContactParameters
            The same law in SI units.

        Notes
        -----
        ``k x_mm^e = k (x_m / 1e-3)^e``, so k [N/m^e] = k [N/mm^e] · 1000^e;
        for e = 1.5 the factor is 31622.8.
        """
        return cls(k=k / _MM**e, e=e, c_max=c_max / _MM, d=d * _MM,
                   mu_s=mu_s, mu_d=mu_d, v_s=v_s * _MM, v_d=v_d * _MM)

    @classmethod
    def paper(cls):
        """The paper's contact law (§3.1), i.e. the defaults.

        Returns
        -------
        ContactParameters
            k = 6.65e7 N/mm^1.5, e = 1.5, C = 50 N·s/mm, d = 0.1 mm,
            μ_s = 0.08, μ_d = 0.05, v_s = 0.1 mm/s, v_d = 10 mm/s, in SI.
        """
        return cls()

    def to_dict(self):
        """Parameters keyed by names that carry their SI unit.

        Meant for output attributes (e.g. NetCDF global attributes).

        Returns
        -------
        dict of str to float
        """
        return {
            "contact_stiffness_N_per_m_e": self.k,
            "contact_force_exponent": self.e,
            "contact_damping_N_s_per_m": self.c_max,
            "penetration_depth_m": self.d,
            "static_friction_coefficient": self.mu_s,
            "dynamic_friction_coefficient": self.mu_d,
            "stiction_transition_velocity_m_per_s": self.v_s,
            "friction_transition_velocity_m_per_s": self.v_d,
        }


# ---------------------------------------------------------------------------
# Eq. 8: normal force (IMPACT)
# ---------------------------------------------------------------------------

def _impact_terms(x, xdot, params, damping_weight):
    """Unclipped Eq. (8) for x > 0: elastic term plus ramped damping."""
    return params.k * x**params.e + damping_weight * xdot


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
    force = _impact_terms(np.maximum(x, 0.0), rate, params, weight)
    # [()] turns a 0-d result into a numpy scalar and leaves arrays alone.
    return np.where(x <= 0.0, 0.0, np.maximum(force, 0.0))[()]


def impact_force_scalar(x, xdot, params):
    """Float-only twin of :func:`impact_force` for hot Python loops.

    Parameters
    ----------
    x : float
        Normal approach of the two flanks; positive means penetration [m].
    xdot : float
        Penetration rate; positive while the flanks approach [m/s].
    params : ContactParameters
        Contact law.

    Returns
    -------
    float
        Normal force, >= 0 (NaN propagates) [N].
    """
    if x <= 0.0:
        return 0.0
    force = _impact_terms(
        x, xdot, params, _step_scalar(x, 0.0, 0.0, params.d, params.c_max))
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


def friction_coefficient_scalar(v, params):
    """Float-only twin of :func:`friction_coefficient` for hot Python loops.

    Parameters
    ----------
    v : float
        Sliding velocity; only its magnitude matters [m/s].
    params : ContactParameters
        Contact law.

    Returns
    -------
    float
        Friction coefficient, >= 0 [-].
    """
    speed = abs(v)
    if speed < params.v_s:
        return _step_scalar(speed, 0.0, 0.0, params.v_s, params.mu_s)
    return _step_scalar(speed, params.v_s, params.mu_s, params.v_d,
                        params.mu_d)


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
    r1, r2 : array_like
        Radii of curvature at the contact point [m].
    e1, e2 : array_like
        Young's moduli [Pa].
    nu1, nu2 : array_like
        Poisson's ratios [-].

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
    r1, r2 : array_like
        Radii of curvature at the contact point [m].
    e1, e2 : array_like
        Young's moduli [Pa].
    nu1, nu2 : array_like
        Poisson's ratios [-].
    correction : array_like, default 1.0
        Correction coefficient ρ of Eq. (9) [-].

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


# ---------------------------------------------------------------------------
# Contact kernel: flank geometry -> penetration, rate and sliding speed
# ---------------------------------------------------------------------------
