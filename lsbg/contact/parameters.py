"""Parameters of the contact models, in SI inside and in the paper's units at the edges.

:class:`ContactParameters` holds the point model's IMPACT parameters (Eq. 8–11),
friction, and the line model's stiffness per unit length, mesh damping ratio
and slices. Inside everything is SI (m, N, s, Pa); the paper's units
(N/mm^1.5, N·s/mm, mm, mm/s) appear only in
:meth:`ContactParameters.from_paper_units`, :meth:`ContactParameters.from_config`
(keys :data:`CONTACT_CONFIG_KEYS`) and the dataset attributes.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3.1, Eq. (8)–(11).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["CONTACT_MODELS", "COMPLIANCES", "ContactParameters", "CONTACT_CONFIG_KEYS"]


# One millimetre and one micrometre in metres: the paper's units are N, mm and s.
_MM = 1e-3


_UM = 1e-6


#: Contact models of :class:`ContactParameters`.
CONTACT_MODELS = ("point", "line")

#: Line model's compliance of the teeth: the uniform bed of springs k_l, or the
#: tooth's own from finite elements (:mod:`lsbg.tooth`).
COMPLIANCES = ("uniform", "fe")


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
        convergence test of tests/contact/test_kernels.py.
    approach_limit : float, default 0.5 mm = 5e-4 m
        Line model: a slice approach beyond this stops the run as a blow-up
        [m] (a linear slice law for steel teeth means nothing at half a
        millimetre; the static approach at the paper's load is about 60 µm).
    compliance : {"uniform", "fe"}, default "uniform"
        Line model: every slice on the uniform bed ``line_stiffness``, or
        the drive side's slices on the tooth's own stiffness from the loaded
        TCA with the finite-element compliance (a
        :class:`lsbg.contact.slices.SliceStiffness` given to the contact).

    Raises
    ------
    ValueError
        Naming the offending field and its value, if ``k <= 0``, ``e < 1``,
        ``c_max < 0``, ``d <= 0``, a friction coefficient is outside [0, 1],
        ``v_s <= 0``, ``v_d <= v_s``, ``model`` or ``compliance`` is unknown,
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
    compliance: str = "uniform"

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
            ("compliance", self.compliance in COMPLIANCES, f"must be one of {COMPLIANCES}"),
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
            if field in _WORD_FIELDS:
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
            elif field not in (*_WORD_FIELDS, "slices"):
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
                values[field] = value if field in _WORD_FIELDS else (
                    int(value) if field == "slices" else float(value))
        return cls(**values)


#: Fields that are words, not numbers.
_WORD_FIELDS = ("model", "compliance")

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
    "compliance": "compliance",
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
    "compliance": "compliance",
}
