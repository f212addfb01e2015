"""The design space: the pinion's ease-off coefficients within bounds.

A design is a :class:`lsbg.tca.modification.FlankModification` of the
pinion's drive flank (docs/model.md, "Flank modification"); the optimiser
turns its coefficients (:data:`VARIABLES`) within bounds stated in the
configuration's units, micrometres (``optimise.bounds.lengthwise_crowning_um:
[5, 60]``) and fractions of the active profile for the reliefs' lengths. A
variable whose two bounds are equal is fixed at that value; the others are
the optimiser's variables, scaled to 0..1 between their bounds.

Default bounds (:data:`VARIABLES`) and why:

* lengthwise crowning C_L 10-50 um: below about 10 um the bearing pattern at
  the marking-compound thickness (6.35 um) runs off the face at the
  envelope's corners; 50 um is about two thirds of the paper pair's normal
  backlash (77 um), which any relief must stay within (a constraint);
* profile crowning C_P 0-20 um: from none (the pattern localised lengthwise
  only) to about the loaded approach at the rated torque (15-30 um), beyond
  which the load gathers on the pitch line;
* bias B -10-10 um: the twist that tilts the path of contact, as large as
  the crownings' usual difference;
* spiral and pressure angle corrections C_beta, C_alpha -10-10 um: the
  first-order terms that move the pattern towards the heel or the toe, the
  tip or the root by a few millimetres (about one P or E step of 0.1 mm);
* tip reliefs C_a1, C_a2 0-30 um: none to about the loaded approach, the
  amounts that take the profile's ends out of loaded contact;
* the reliefs' lengths L_1, L_2 fixed at the shared design's own (the
  configuration's ``flank_modification``: the practice design's "long"
  relief, from the tip to the highest point of single contact, or the
  modification's default 0.25 of the active profile): the amount of a tip
  relief is tuned to its length, and a search that fixed another length
  could not reach the shared design (on the practice pair at 35 deg, 0.25
  against its 0.137 kept every feasible design's loaded TE above 57 urad at
  the rated torque, twice the shared design's 34 urad); give them two
  bounds to free them.

SI inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["VARIABLES", "DesignSpace", "bounds_problems"]

_UM = 1e-6

#: Configuration key -> (FlankModification field, SI value of one unit of the key,
#: default bounds in the key's unit (None: fixed at the shared design's value),
#: least value allowed, greatest value allowed).
VARIABLES = {
    "lengthwise_crowning_um": ("lengthwise_crowning", _UM, (10.0, 50.0), 0.0, math.inf),
    "profile_crowning_um": ("profile_crowning", _UM, (0.0, 20.0), 0.0, math.inf),
    "bias_um": ("bias", _UM, (-10.0, 10.0), -math.inf, math.inf),
    "spiral_angle_correction_um": ("spiral_angle_correction", _UM, (-10.0, 10.0), -math.inf,
                                   math.inf),
    "pressure_angle_correction_um": ("pressure_angle_correction", _UM, (-10.0, 10.0),
                                     -math.inf, math.inf),
    "pinion_tip_relief_um": ("pinion_tip_relief", _UM, (0.0, 30.0), 0.0, math.inf),
    "gear_tip_relief_um": ("gear_tip_relief", _UM, (0.0, 30.0), 0.0, math.inf),
    "pinion_tip_relief_length": ("pinion_tip_relief_length", 1.0, None, 0.0, 1.0),
    "gear_tip_relief_length": ("gear_tip_relief_length", 1.0, None, 0.0, 1.0),
}


def bounds_problems(bounds, reference=None):
    """Problems of an ``optimise.bounds`` section, one line each, naming the key and value.

    Parameters
    ----------
    bounds : dict
        ``{key: [low, high]}`` in the keys' units (keys of :data:`VARIABLES`;
        missing keys take their default bounds).
    reference : lsbg.tca.modification.FlankModification, optional
        The shared design, whose values fix the keys left out whose default
        bounds are None in :data:`VARIABLES` (default: the modification's defaults).

    Returns
    -------
    list of str
    """
    problems = []
    for key, value in (bounds or {}).items():
        where = f"optimise.bounds.{key} = {value!r}"
        if key not in VARIABLES:
            problems.append(f"{where}: unknown key (known: {', '.join(VARIABLES)})")
            continue
        if not (isinstance(value, (list, tuple)) and len(value) == 2 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                for v in value)):
            problems.append(f"{where}: must be [low, high], two finite numbers")
            continue
        low, high = value
        _, _, _, least, most = VARIABLES[key]
        fraction = key.endswith("_length")
        if low > high:
            problems.append(f"{where}: the lower bound is above the upper one (write "
                            f"[{high!r}, {low!r}]; equal bounds fix the variable)")
        elif fraction and not (least < low and high <= most):
            problems.append(f"{where}: a relief's length is a fraction of the active profile, "
                            f"0 < L <= 1")
        elif low < least:
            problems.append(f"{where}: must be >= {least:g} um (a crowning or a tip relief "
                            f"removes material)")
    space = dict(_defaults(reference),
                 **{k: v for k, v in (bounds or {}).items() if k in VARIABLES})
    if not problems and all(low == high for low, high in space.values()):
        problems.append(f"optimise.bounds = {dict(bounds or {})!r}: every variable is fixed "
                        f"(equal bounds): nothing to optimise; give at least one key two "
                        f"different bounds")
    return problems


def _defaults(reference=None):
    """Every key's default bounds; those None in :data:`VARIABLES` fixed at the reference's."""
    from lsbg.tca.modification import FlankModification

    reference = FlankModification() if reference is None else reference
    return {key: list(spec[2]) if spec[2] is not None else
            [getattr(reference, spec[0]) / spec[1]] * 2 for key, spec in VARIABLES.items()}


@dataclass(frozen=True)
class DesignSpace:
    """The free ease-off coefficients and their bounds, the fixed ones' values.

    Parameters
    ----------
    keys : tuple of str
        Configuration keys of the free variables, in :data:`VARIABLES`' order.
    lower, upper : numpy.ndarray
        Their bounds in SI [m; the lengths in fractions of the active profile].
    fixed : dict
        ``{field: SI value}`` of the fixed ones.
    """

    keys: tuple
    lower: np.ndarray
    upper: np.ndarray
    fixed: dict

    @classmethod
    def from_config(cls, bounds=None, reference=None):
        """The space of an ``optimise.bounds`` section (configuration units).

        Parameters
        ----------
        bounds : dict, optional
            ``{key: [low, high]}``; keys left out take their defaults.
        reference : lsbg.tca.modification.FlankModification, optional
            The shared design: the reliefs' lengths left out are fixed at its
            own (default: the modification's default, 0.25).

        Raises
        ------
        ValueError
            The first of :func:`bounds_problems`, naming the key and value.
        """
        problems = bounds_problems(bounds, reference)
        if problems:
            raise ValueError(problems[0])
        space = dict(_defaults(reference), **(bounds or {}))
        keys, lower, upper, fixed = [], [], [], {}
        for key, (field, unit, *_) in VARIABLES.items():
            low, high = (float(v) * unit for v in space[key])
            if low == high:
                fixed[field] = low
            else:
                keys.append(key)
                lower.append(low)
                upper.append(high)
        return cls(tuple(keys), np.array(lower), np.array(upper), fixed)

    @property
    def size(self):
        """Number of free variables [-]."""
        return len(self.keys)

    @property
    def fields(self):
        """The FlankModification fields of the free variables."""
        return tuple(VARIABLES[key][0] for key in self.keys)

    def modification(self, x):
        """The modification at scaled variables x in [0, 1] (one per free key).

        Parameters
        ----------
        x : array_like, shape (size,)

        Returns
        -------
        lsbg.tca.modification.FlankModification
        """
        from lsbg.tca.modification import FlankModification

        values = self.values(x)
        return FlankModification(**self.fixed, **{f: float(v) for f, v in
                                                  zip(self.fields, values)})

    def values(self, x):
        """SI values of the free variables at scaled x in [0, 1] [m or -]."""
        x = np.clip(np.asarray(x, float), 0.0, 1.0)
        return self.lower + x * (self.upper - self.lower)

    def scaled(self, modification):
        """The scaled variables of a modification (inverse of :meth:`modification`) [-]."""
        values = np.array([getattr(modification, f) for f in self.fields])
        return (values - self.lower) / (self.upper - self.lower)

    def config_values(self, x):
        """``{key: value}`` of every variable, free and fixed, in the keys' units."""
        modification = self.modification(x)
        return {key: getattr(modification, field) / unit
                for key, (field, unit, *_) in VARIABLES.items()}
