"""Contact laws: the paper's IMPACT law (§3.1, Eq. 8–11), friction, and the line-slice law.

This module holds the force *laws*: given a penetration, its rate and a sliding
speed, they return a normal force and a friction coefficient. Everything is in
SI units (m, N, s, Pa); the paper's units (N/mm^1.5, N·s/mm, mm, mm/s) appear
only in :meth:`ContactParameters.from_paper_units` and
:meth:`ContactParameters.from_config`.

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

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

# One millimetre and one micrometre in metres: the paper's units are N, mm and s.
_MM = 1e-3
_UM = 1e-6

#: Contact models of :class:`ContactParameters`.
CONTACT_MODELS = ("point", "line")


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
# Parameters
# ---------------------------------------------------------------------------

@dataclass(frozen=True, slots=True)
class ContactParameters:
    """Parameters of the contact model and its friction, in SI units.

    The IMPACT defaults are the paper's values (§3.1), converted to SI. The
    paper gives no friction transition velocities; ``v_s`` = 0.1 mm/s and
    ``v_d`` = 10 mm/s are the values documented as Adams' defaults for the
    friction of IMPACT contacts (they also appear in the usual Adams table
    for dry steel on steel), so the paper's Adams model most likely used
    them. Keep them configurable.

    Parameters
    ----------
    k : float, default 6.65e7 N/mm^1.5 = 2.1029e12 N/m^1.5
        IMPACT contact stiffness [N/m^e]. Its unit depends on ``e``.
    e : float, default 1.5
        IMPACT force exponent [-]; 1.5 is Hertz's point contact.
    c_max : float, default 50 N·s/mm = 5e4 N·s/m
        IMPACT maximum damping coefficient, reached at penetration ``d`` [N·s/m].
    d : float, default 0.1 mm = 1e-4 m
        Penetration at which full IMPACT damping is reached [m]; a deeper
        penetration stops a point-model run (the law no longer holds).
    mu_s : float, default 0.08
        Static friction coefficient [-] (both models).
    mu_d : float, default 0.05
        Dynamic friction coefficient [-] (both models).
    v_s : float, default 0.1 mm/s = 1e-4 m/s
        Stiction transition velocity: sliding speed at which ``mu_s`` is
        reached [m/s].
    v_d : float, default 10 mm/s = 1e-2 m/s
        Friction transition velocity: sliding speed from which ``mu_d``
        applies [m/s].
    model : {"point", "line"}, default "point"
        Contact model: the paper's IMPACT incident per tooth pair, or the
        contact lines cut into slices.
    line_stiffness : float, default 19.4 N/(mm·µm) = 1.94e10 N/m^2
        Line model: normal load per unit contact-line length per unit normal
        approach [N/m^2]. The default makes the mean mesh stiffness per unit
        face width of the paper's LSBG (35°) equal ISO 6336-1's
        c_γ = 20 N/(mm·µm) for steel (:func:`lsbg.contact.mesh.calibrated_line_stiffness`).
    damping_ratio : float, default 0.05
        Line model: damping ratio of the mesh mode [-] (gear-dynamics
        literature: 0.02–0.1, docs/model.md).
    slices : int, default 20
        Line model: slices across the face width [-], chosen by the
        convergence test of tests/test_line_contact.py.
    approach_limit : float, default 0.5 mm = 5e-4 m
        Line model: a slice approach beyond this stops the run as a blow-up
        [m] (a linear slice law for steel teeth means nothing at half a
        millimetre; the static approach at the paper's load is about 60 µm).

    Raises
    ------
    ValueError
        Naming the offending field and its value, if ``k <= 0``, ``e < 1``,
        ``c_max < 0``, ``d <= 0``, a friction coefficient is outside [0, 1],
        ``v_s <= 0``, ``v_d <= v_s``, ``model`` is unknown,
        ``line_stiffness <= 0``, ``damping_ratio < 0``, ``slices < 2`` or
        not whole, or ``approach_limit <= 0``.

    Notes
    -----
    The float fields are stored as Python floats and ``slices`` as an int.
    """

    k: float = 6.65e7 / _MM**1.5
    e: float = 1.5
    c_max: float = 50.0 / _MM
    d: float = 0.1 * _MM
    mu_s: float = 0.08
    mu_d: float = 0.05
    v_s: float = 0.1 * _MM
    v_d: float = 10.0 * _MM
    model: str = "point"
    line_stiffness: float = 19.4e9  # 19.4 N/(mm·µm)
    damping_ratio: float = 0.05
    slices: int = 20
    approach_limit: float = 0.5 * _MM

    def __post_init__(self):
        for name in _FLOAT_FIELDS:
            object.__setattr__(self, name, float(getattr(self, name)))
        slices = self.slices
        whole = not isinstance(slices, bool) and float(slices).is_integer()
        if whole:
            object.__setattr__(self, "slices", int(slices))
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
            ("model", self.model in CONTACT_MODELS, f"must be one of {CONTACT_MODELS}"),
            ("line_stiffness", self.line_stiffness > 0.0, "must be > 0 [N/m^2]"),
            ("damping_ratio", 0.0 <= self.damping_ratio <= 1.0, "must lie in [0, 1] [-]"),
            ("slices", whole and self.slices >= 2, "must be a whole number >= 2"),
            ("approach_limit", self.approach_limit > 0.0, "must be > 0 [m]"),
        )
        for name, valid, rule in checks:
            if not valid:
                raise ValueError(
                    f"ContactParameters.{name} {rule}, got "
                    f"{name}={getattr(self, name)!r}")

    @classmethod
    def from_paper_units(cls, k, e, c_max, d, mu_s, mu_d, v_s, v_d, **line):
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
        **line
            Fields of the line model, in SI (``model``, ``line_stiffness``,
            ``damping_ratio``, ``slices``, ``approach_limit``).

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
                   mu_s=mu_s, mu_d=mu_d, v_s=v_s * _MM, v_d=v_d * _MM, **line)

    @classmethod
    def from_config(cls, config):
        """Build parameters from the workflow's ``contact`` section (paper units).

        Parameters
        ----------
        config : dict
            Keys of :data:`CONTACT_CONFIG_KEYS`: ``model``,
            ``stiffness_N_per_mm1_5``, ``exponent``, ``damping_N_s_per_mm``,
            ``penetration_depth_mm``, ``static_friction``, ``dynamic_friction``,
            ``stiction_velocity_mm_s``, ``friction_velocity_mm_s``,
            ``line_stiffness_N_per_mm_um``, ``mesh_damping_ratio``, ``slices``,
            ``line_approach_limit_mm``; missing keys take the defaults.

        Returns
        -------
        ContactParameters

        Raises
        ------
        ValueError
            Naming the configuration key (``contact.<key>``) and its value,
            for unknown keys and invalid values.
        """
        known = {key: field for field, key in CONTACT_CONFIG_KEYS.items()}
        kwargs = {}
        for key, value in config.items():
            if key not in known:
                raise ValueError(f"contact.{key} = {value!r}: unknown key "
                                 f"(known: {sorted(known)})")
            field = known[key]
            if field == "model":
                kwargs[field] = value
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"contact.{key} = {value!r}: must be a number")
            kwargs[field] = value if field == "slices" else value * _PAPER_UNITS[field]
        if "k" in kwargs:  # N/mm^e -> N/m^e: the factor depends on the exponent
            kwargs["k"] = kwargs["k"] / _MM**kwargs.get("e", cls.e)
        try:
            return cls(**kwargs)
        except ValueError as err:
            field = str(err).split(".", 1)[1].split(" ", 1)[0]
            key = CONTACT_CONFIG_KEYS[field]
            shown = config.get(key, getattr(cls, field))
            raise ValueError(f"contact.{key} = {shown!r}: {err}") from None

    def to_config(self):
        """The parameters as the workflow's ``contact`` keys (paper units).

        Returns
        -------
        dict
            Inverse of :meth:`from_config`.
        """
        out = {}
        for field, key in CONTACT_CONFIG_KEYS.items():
            value = getattr(self, field)
            if field == "k":
                value = value * _MM**self.e
            elif field not in ("model", "slices"):
                value = value / _PAPER_UNITS[field]
            out[key] = value
        return out

    @classmethod
    def paper(cls):
        """The paper's contact law (§3.1), i.e. the defaults.

        Returns
        -------
        ContactParameters
            k = 6.65e7 N/mm^1.5, e = 1.5, C = 50 N·s/mm, d = 0.1 mm,
            μ_s = 0.08, μ_d = 0.05, v_s = 0.1 mm/s, v_d = 10 mm/s, in SI,
            point model.
        """
        return cls()

    def replace(self, **changes):
        """A copy with some fields changed (SI units), validated again."""
        import dataclasses

        return dataclasses.replace(self, **changes)

    def to_dict(self):
        """Parameters keyed by names that carry their SI unit.

        Meant for output attributes (e.g. NetCDF global attributes); the
        inverse is :meth:`from_dict`.

        Returns
        -------
        dict of str to float, int or str
        """
        return {name: getattr(self, field) for field, name in _ATTRIBUTE_NAMES.items()}

    @classmethod
    def from_dict(cls, attributes, prefix=""):
        """Parameters from :meth:`to_dict` keys (each optionally prefixed).

        Parameters
        ----------
        attributes : mapping
            E.g. a run dataset's attributes with ``prefix="contact_"``; keys
            that are absent take the defaults.
        prefix : str

        Returns
        -------
        ContactParameters
        """
        values = {}
        for field, name in _ATTRIBUTE_NAMES.items():
            if prefix + name in attributes:
                value = attributes[prefix + name]
                values[field] = value if field == "model" else (
                    int(value) if field == "slices" else float(value))
        return cls(**values)


_FLOAT_FIELDS = ("k", "e", "c_max", "d", "mu_s", "mu_d", "v_s", "v_d", "line_stiffness",
                 "damping_ratio", "approach_limit")

#: Field of :class:`ContactParameters` -> key of the workflow's ``contact`` section.
CONTACT_CONFIG_KEYS = {
    "model": "model",
    "k": "stiffness_N_per_mm1_5", "e": "exponent", "c_max": "damping_N_s_per_mm",
    "d": "penetration_depth_mm", "mu_s": "static_friction", "mu_d": "dynamic_friction",
    "v_s": "stiction_velocity_mm_s", "v_d": "friction_velocity_mm_s",
    "line_stiffness": "line_stiffness_N_per_mm_um", "damping_ratio": "mesh_damping_ratio",
    "slices": "slices", "approach_limit": "line_approach_limit_mm",
}

# Field -> SI value of one unit of its configuration key (k handled apart: its
# unit depends on the exponent).
_PAPER_UNITS = {
    "k": 1.0, "e": 1.0, "c_max": 1.0 / _MM, "d": _MM, "mu_s": 1.0, "mu_d": 1.0,
    "v_s": _MM, "v_d": _MM, "line_stiffness": 1.0 / (_MM * _UM), "damping_ratio": 1.0,
    "approach_limit": _MM,
}

# Field -> output attribute name (SI unit in the name).
_ATTRIBUTE_NAMES = {
    "k": "contact_stiffness_N_per_m_e",
    "e": "contact_force_exponent",
    "c_max": "contact_damping_N_s_per_m",
    "d": "penetration_depth_m",
    "mu_s": "static_friction_coefficient",
    "mu_d": "dynamic_friction_coefficient",
    "v_s": "stiction_transition_velocity_m_per_s",
    "v_d": "friction_transition_velocity_m_per_s",
    "model": "model",
    "line_stiffness": "line_stiffness_N_per_m2",
    "damping_ratio": "mesh_damping_ratio",
    "slices": "slices",
    "approach_limit": "line_approach_limit_m",
}


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
    mu_s, mu_d : float
        Static and dynamic friction coefficients [-].
    v_s, v_d : float
        Stiction and friction transition velocities [m/s].

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
