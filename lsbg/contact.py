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

import math
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


def step_scalar(x, x0, h0, x1, h1):
    """STEP of Eq. (10) on plain floats, for hot Python loops.

    No validation (callers pass x1 > x0); NaN in ``x`` propagates, as in
    :func:`step`. Parameters and units as :func:`step`.
    """
    delta = (x - x0) / (x1 - x0)
    # if-chains rather than min/max: this runs millions of times per run.
    if delta <= 0.0:
        return h0
    if delta >= 1.0:
        return h1
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
    def from_config(cls, config):
        """Build parameters from the workflow's ``contact`` section (paper units).

        Parameters
        ----------
        config : dict
            Keys of :data:`CONTACT_CONFIG_KEYS` (``stiffness_N_per_mm1_5``,
            ``exponent``, ``damping_N_s_per_mm``, ``penetration_depth_mm``,
            ``static_friction``, ``dynamic_friction``,
            ``stiction_velocity_mm_s``, ``friction_velocity_mm_s``); missing
            keys take the paper's values.

        Returns
        -------
        ContactParameters

        Raises
        ------
        ValueError
            Naming the configuration key and value, for unknown keys and
            invalid values.
        """
        paper = cls()
        values = {
            "stiffness_N_per_mm1_5": paper.k * _MM**paper.e, "exponent": paper.e,
            "damping_N_s_per_mm": paper.c_max * _MM, "penetration_depth_mm": paper.d / _MM,
            "static_friction": paper.mu_s, "dynamic_friction": paper.mu_d,
            "stiction_velocity_mm_s": paper.v_s / _MM, "friction_velocity_mm_s": paper.v_d / _MM,
        }
        for key, value in config.items():
            if key not in values:
                raise ValueError(f"contact.{key} = {value!r}: unknown key "
                                 f"(known: {sorted(values)})")
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"contact.{key} = {value!r}: must be a number")
            values[key] = value
        try:
            return cls.from_paper_units(*values.values())
        except ValueError as err:
            field = str(err).split(".", 1)[1].split(" ", 1)[0]
            key = CONTACT_CONFIG_KEYS[field]
            raise ValueError(f"contact.{key} = {values[key]!r}: {err}") from None

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


#: Field of :class:`ContactParameters` -> key of the workflow's ``contact`` section.
CONTACT_CONFIG_KEYS = {
    "k": "stiffness_N_per_mm1_5", "e": "exponent", "c_max": "damping_N_s_per_mm",
    "d": "penetration_depth_mm", "mu_s": "static_friction", "mu_d": "dynamic_friction",
    "v_s": "stiction_velocity_mm_s", "v_d": "friction_velocity_mm_s",
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
        x, xdot, params, step_scalar(x, 0.0, 0.0, params.d, params.c_max))
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
    if speed >= params.v_d:  # the common case in a running mesh
        return params.mu_d
    if speed < params.v_s:
        return step_scalar(speed, 0.0, 0.0, params.v_s, params.mu_s)
    return step_scalar(speed, params.v_s, params.mu_s, params.v_d,
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

#: Samples of the mesh-phase table per base pitch. At the paper's speed the
#: contact lines turn one table step in about 0.26 µs, below the 1 µs time step.
PHASE_SAMPLES_PER_PITCH = 20000


@dataclass(frozen=True)
class PairContact:
    """Contact of one tooth pair (one IMPACT incident), for output and checks.

    Attributes
    ----------
    side : str
        "drive" or "coast".
    phase : float
        Turn Psi of the contact line in its plane of action [rad].
    lever : float
        l = rho cos(beta_p) at the deepest point: penetration per unit
        mismatch and torque arm per unit base-cone sine [m].
    penetration : float
        Deepest normal approach x on the contact line [m].
    penetration_rate : float
        dx/dt [m/s].
    normal_force : float
        IMPACT force [N].
    friction_coefficient : float
        mu at the sliding speed [-].
    sliding_speed : float
        Tangential sliding speed at the point of action [m/s].
    gear_torque, pinion_torque : float
        Torques of this pair's normal and friction forces about each member's
        forward axis [N m].
    tangential_force : float
        Contact force on the gear along its circumferential direction at the
        point of action [N].
    radius : float
        Distance of the point of action from the gear axis [m].
    cone_distance : float
        Distance rho of the point of action from the apex [m]; the point is
        ``pair.planes[side].point(rho, phase + curve.polar_angle(rho))``.
    """

    side: str
    phase: float
    lever: float
    penetration: float
    penetration_rate: float
    normal_force: float
    friction_coefficient: float
    sliding_speed: float
    gear_torque: float
    pinion_torque: float
    tangential_force: float
    radius: float
    cone_distance: float


class MeshContact:
    """Contact kernel of a gear pair: tooth-pair forces from the exact geometry.

    Both flank sides are swept by a plane of action (:mod:`lsbg.geometry`), so
    a rotation mismatch only moves the contact lines within that plane. With
    e_i = sin(delta_b,i), the mismatch on the drive side is
    ``eps = phi1 e1 - phi2 e2`` (wrapped to one base pitch), and the normal
    approach at a point of a contact line at distance rho from the apex is
    ``x = rho cos(beta_p(rho)) eps`` (DESIGN.md §2). Each tooth pair in contact
    is one IMPACT incident (as Adams treats a connected penetration region):
    its depth is the deepest approach along its line, and its force acts
    there along the contact normal. The torque arm of that force about
    gear i is ``rho cos(beta_p) e_i``, the same lever that sets the depth.

    Everything that depends only on where a contact line sits in the plane
    (its turn Psi) is tabulated once per side: the lever at the deepest point
    and the products of the two members' circumferential vectors there, which
    give sliding speed, friction torques and the tangential force cheaply.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    params : ContactParameters
    samples_per_pitch : int
        Resolution of the phase tables [-].
    """

    def __init__(self, pair, params=None, samples_per_pitch=PHASE_SAMPLES_PER_PITCH):
        from lsbg.geometry import MEMBERS  # local import: geometry does not need contact

        self.pair = pair
        self.params = params if params is not None else ContactParameters()
        design = pair.design
        self.e1 = math.sin(design.base_cone_angle(1))
        self.e2 = math.sin(design.base_cone_angle(2))
        self.pitch = design.base_pitch_angle
        # Sign of u_i . N (the same for both members and both sides).
        self.orientation = math.copysign(1.0, pair.axis_normal_component(1, "drive"))
        assert all(math.copysign(1.0, pair.axis_normal_component(m, s)) == self.orientation
                   for m in MEMBERS for s in ("drive", "coast"))
        # Mismatch offsets from the tooth thickness placement (zero on the drive
        # side; on the coast side the mismatch at drive contact is -c j / R_m).
        off = pair.flank_offset
        self.coast_offset = off[(2, "coast")] * self.e2 - off[(1, "coast")] * self.e1
        self.coast_pinion_offset = off[(1, "coast")]
        self.tables = {side: self._tabulate(side, samples_per_pitch) for side in ("drive", "coast")}

    def _tabulate(self, side, samples_per_pitch):
        pair = self.pair
        plane = pair.planes[side]
        psi_lo, psi_hi, r_in, r_out = plane.field
        theta = plane.curve.polar_angle(np.array([r_in, r_out]))
        first, last = psi_lo - theta.max(), psi_hi - theta.min()
        step_ = self.pitch / samples_per_pitch
        n = int(math.ceil((last - first) / step_)) + 2
        phases = first + step_ * np.arange(n)
        lo, hi = plane.line_segment(phases)
        inside = hi > lo
        # Deepest point: maximum of the lever rho cos(beta_p) on the segment.
        t = np.linspace(0.0, 1.0, 33)
        rho = lo[:, None] + (hi - lo)[:, None] * t
        rho = np.where(inside[:, None], rho, plane.field[3])
        lever_all = rho * np.cos(plane.curve.ray_angle(rho))
        k = np.argmax(lever_all, axis=1)
        rho_star = rho[np.arange(n), k]
        lever = np.where(inside, lever_all[np.arange(n), k], 0.0)
        point = plane.point(rho_star, phases + plane.curve.polar_angle(rho_star))
        a = np.cross(pair.rotation_axis[1], point)  # pinion circumferential x radius
        b = np.cross(pair.rotation_axis[2], point)  # gear circumferential x radius
        columns = np.stack([lever, np.sum(a * a, 1), np.sum(a * b, 1), np.sum(b * b, 1),
                            np.linalg.norm(b, axis=1), rho_star], axis=1)
        columns[~inside] = 0.0
        # (first, last, 1/step, n, rows): plain Python floats and lists, so the
        # hot loop indexes them without numpy overhead.
        return (float(first), float(last), 1.0 / step_, n,
                [tuple(map(float, row)) for row in columns])

    # ------------------------------------------------------------ evaluation
    def mismatch(self, pinion_angle, gear_angle):
        """Drive-side rotation mismatch eps = phi1 e1 - phi2 e2, wrapped [rad].

        Positive when the pinion leads (drive flanks penetrate).
        """
        half = 0.5 * self.pitch
        return (pinion_angle * self.e1 - gear_angle * self.e2 + half) % self.pitch - half

    def evaluate(self, pinion_angle, gear_angle, pinion_speed, gear_speed, details=None):
        """Contact torques on both members at one state (float-only hot path).

        Parameters
        ----------
        pinion_angle, gear_angle : float
            Forward rotations phi1, phi2 [rad] (0, 0: drive flanks of tooth 0
            touch at the mean point).
        pinion_speed, gear_speed : float
            Forward angular speeds [rad/s].
        details : list, optional
            If given, a :class:`PairContact` is appended per pair in contact.

        Returns
        -------
        gear_torque, pinion_torque : float
            Contact torques about the forward axes u2 and u1 [N m].
        max_penetration : float
            Deepest normal approach of all pairs [m] (<= 0: no contact).
        """
        pitch = self.pitch
        half = 0.5 * pitch
        e1 = self.e1
        drive = (pinion_angle * e1 - gear_angle * self.e2 + half) % pitch - half
        rate = pinion_speed * e1 - gear_speed * self.e2
        # The mismatch is the same for every line of a side, so a side whose
        # flanks are apart (eps <= 0) costs nothing more.
        if drive > 0.0:
            # Turn of the mean of pinion tooth 0's line and the gear's line.
            phase = self.orientation * (pinion_angle * e1 - 0.5 * drive)
            gear_torque, pinion_torque, deepest = self._side(
                "drive", drive, rate, 1.0, phase, pinion_speed, gear_speed, details)
        else:
            gear_torque = pinion_torque = 0.0
            deepest = drive
        coast = (self.coast_offset - drive + half) % pitch - half
        if coast > 0.0:
            phase = self.orientation * ((pinion_angle + self.coast_pinion_offset) * e1 + 0.5 * coast)
            t2, t1, x = self._side("coast", coast, -rate, -1.0, phase, pinion_speed, gear_speed, details)
            gear_torque += t2
            pinion_torque += t1
            deepest = max(deepest, x)
        elif deepest <= 0.0:
            deepest = max(deepest, coast)
        return gear_torque, pinion_torque, deepest

    def _side(self, side, eps, eps_rate, sign, phase, pinion_speed, gear_speed, details):
        """Sum over the contact lines of one side: (gear torque, pinion torque, depth)."""
        params = self.params
        e1, e2, pitch = self.e1, self.e2, self.pitch
        first, last, inv_step, n, rows = self.tables[side]
        phase += math.ceil((first - phase) / pitch) * pitch
        gear_torque = pinion_torque = 0.0
        deepest = -math.inf
        while phase <= last:
            pos = (phase - first) * inv_step
            i = int(pos)
            phase_here = phase
            phase += pitch
            if i + 1 >= n:
                continue
            f = pos - i
            r0, r1 = rows[i], rows[i + 1]
            lever = r0[0] + f * (r1[0] - r0[0])
            if lever <= 0.0:
                continue
            x = lever * eps
            xdot = lever * eps_rate
            force = impact_force_scalar(x, xdot, params)
            aa = r0[1] + f * (r1[1] - r0[1])
            ab = r0[2] + f * (r1[2] - r0[2])
            bb = r0[3] + f * (r1[3] - r0[3])
            # Sliding of pinion on gear: v = w1 (u1 x X) - w2 (u2 x X); its
            # normal part is lever * (w1 e1 - w2 e2) and n.(u_i x X) = lever e_i.
            v_normal = lever * (pinion_speed * e1 - gear_speed * e2)
            slide2 = (pinion_speed * pinion_speed * aa - 2.0 * pinion_speed * gear_speed * ab
                      + gear_speed * gear_speed * bb - v_normal * v_normal)
            t2 = sign * force * lever * e2
            t1 = -sign * force * lever * e1
            mu = 0.0
            slide = 0.0
            if slide2 > 0.0:
                slide = math.sqrt(slide2)
                mu = friction_coefficient_scalar(slide, params)
                # Friction drags the gear along the pinion's sliding velocity.
                fric = mu * force / slide
                t2 += fric * (pinion_speed * ab - gear_speed * bb - v_normal * lever * e2)
                t1 -= fric * (pinion_speed * aa - gear_speed * ab - v_normal * lever * e1)
            gear_torque += t2
            pinion_torque += t1
            if x > deepest:
                deepest = x
            if details is not None:
                radius = r0[4] + f * (r1[4] - r0[4])
                rho = r0[5] + f * (r1[5] - r0[5])
                details.append(PairContact(side, phase_here, lever, x, xdot, force, mu, slide,
                                           t2, t1, t2 / radius, radius, rho))
        return gear_torque, pinion_torque, deepest

    def static_gear_angle(self, load_torque, pinion_angle=0.0):
        """Gear rotation at which the contact carries ``load_torque`` at rest.

        Parameters
        ----------
        load_torque : float
            Resisting torque on the gear [N m], >= 0.
        pinion_angle : float
            Pinion rotation [rad].

        Returns
        -------
        float
            Gear rotation phi2 [rad] (the drive flanks are pressed together by
            the elastic approach that carries the load).
        """
        from scipy.optimize import brentq

        base = pinion_angle * self.e1 / self.e2
        if load_torque <= 0.0:
            return base

        def residual(eps):
            return self.evaluate(pinion_angle, base - eps / self.e2, 0.0, 0.0)[0] - load_torque

        upper = 1e-6
        while residual(upper) < 0.0:
            upper *= 2.0
            if upper > 0.1 * self.pitch:
                raise ValueError(f"load_torque = {load_torque!r}: the contact cannot carry it "
                                 f"within a tenth of a base pitch of approach")
        eps = brentq(residual, 0.0, upper, xtol=1e-18, rtol=1e-14)
        return base - eps / self.e2
