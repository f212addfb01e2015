"""Assembly displacements of a bevel gear pair: E, P, G and the shaft-angle error.

The four standard displacements of a bevel pair (as in Gleason's V-H check
and ANSI/AGMA 2005), with one sign convention in every output
(docs/model.md, "Assembly displacements", has its figure). In lsbg's mesh
frame the apex (the crossing point of the axes) is the origin, the pitch line
is +x, the axes a1 (pinion) and a2 (gear) lie in the xy (axial) plane and
point from the apex into the members, and z = x x y:

* **P**, pinion axial: the pinion moves by P along a1, away from the apex
  for P > 0 (its mounting distance grows: out of mesh);
* **G**, gear axial: the gear moves by G along a2, away from the apex for
  G > 0 (out of mesh);
* **E**, offset: the pinion moves by E along +z, perpendicular to both axes
  (a hypoid offset);
* **Sigma**, shaft-angle error: the gear's axis turns by Sigma about +z
  through the apex, in the sense that opens the angle between a1 and a2 for
  Sigma > 0.

The pinion keeps its rotation axis's direction (it only translates); the
gear is turned and then translated. Lengths are metres and angles radians
inside; the configuration (``misalignment:``) speaks mm and degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Misalignment", "MISALIGNMENT_CONFIG_KEYS", "DISPLACEMENTS", "member_frames",
           "envelope_corners", "corner_displacements"]

_MM = 1e-3

#: The displacements by their letters: (field, configuration key, SI per config unit).
DISPLACEMENTS = {
    "E": ("offset", "offset_E_mm", _MM),
    "P": ("pinion_axial", "pinion_axial_P_mm", _MM),
    "G": ("gear_axial", "gear_axial_G_mm", _MM),
    "Sigma": ("shaft_angle_error", "shaft_angle_error_deg", math.pi / 180.0),
}

#: Configuration keys of ``misalignment:`` and the field each sets (of :data:`DISPLACEMENTS`).
MISALIGNMENT_CONFIG_KEYS = {key: name for name, key, _ in DISPLACEMENTS.values()}


@dataclass(frozen=True)
class Misalignment:
    """Assembly displacements of a gear pair, SI units.

    Parameters
    ----------
    offset : float
        E, the pinion's displacement along +z, normal to both axes [m].
    pinion_axial : float
        P, the pinion's displacement along its axis away from the apex [m].
    gear_axial : float
        G, the gear's displacement along its axis away from the apex [m].
    shaft_angle_error : float
        Sigma, the gear axis's turn about +z opening the shaft angle [rad].
    """

    offset: float = 0.0
    pinion_axial: float = 0.0
    gear_axial: float = 0.0
    shaft_angle_error: float = 0.0

    def __post_init__(self):
        for name, key, scale in DISPLACEMENTS.values():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                shown = value / scale if isinstance(value, (int, float)) else value
                raise ValueError(f"misalignment.{key} = {shown!r}: must be a finite number")

    @classmethod
    def from_config(cls, config):
        """Build from the ``misalignment:`` section (mm, degrees).

        Parameters
        ----------
        config : dict or None
            Keys of :data:`MISALIGNMENT_CONFIG_KEYS`; missing keys are 0.

        Raises
        ------
        ValueError
            Naming the key and value (``misalignment.<key>``).
        """
        kwargs = {}
        scales = {key: scale for _, key, scale in DISPLACEMENTS.values()}
        for key, value in (config or {}).items():
            if key not in MISALIGNMENT_CONFIG_KEYS:
                raise ValueError(f"misalignment.{key} = {value!r}: unknown key "
                                 f"(known: {sorted(MISALIGNMENT_CONFIG_KEYS)})")
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"misalignment.{key} = {value!r}: must be a finite number")
            kwargs[MISALIGNMENT_CONFIG_KEYS[key]] = float(value) * scales[key]
        return cls(**kwargs)

    def to_config(self):
        """The ``misalignment:`` keys in mm and degrees."""
        return {key: getattr(self, name) / scale for name, key, scale in DISPLACEMENTS.values()}

    def replace(self, **letters):
        """A copy with displacements set by letter, SI (``replace(P=1e-4)``)."""
        values = {name: getattr(self, name) for name, _, _ in DISPLACEMENTS.values()}
        for letter, value in letters.items():
            if letter not in DISPLACEMENTS:
                raise ValueError(f"displacement {letter!r}: one of {sorted(DISPLACEMENTS)}")
            values[DISPLACEMENTS[letter][0]] = float(value)
        return Misalignment(**values)

    def shifted(self, **letters):
        """A copy with displacements added by letter, SI (``shifted(P=1e-4)``)."""
        added = {letter: getattr(self, DISPLACEMENTS[letter][0]) + float(value)
                 for letter, value in letters.items() if letter in DISPLACEMENTS}
        return self.replace(**{**letters, **added})

    @property
    def is_zero(self):
        """True for the aligned pair."""
        return all(getattr(self, name) == 0.0 for name, _, _ in DISPLACEMENTS.values())


def member_frames(pair, misalignment):
    """Where the displaced members sit in the mesh frame.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    misalignment : Misalignment

    Returns
    -------
    pinion_shift : numpy.ndarray, shape (3,)
        Translation of the pinion [m].
    gear_turn : numpy.ndarray, shape (3, 3)
        Rotation of the gear about +z through the apex [-].
    gear_shift : numpy.ndarray, shape (3,)
        Translation of the gear after its turn [m].

    A point X of the gear's nominal (aligned) frame sits at
    ``gear_turn @ X + gear_shift``; a pinion point X at ``X + pinion_shift``.
    """
    a1, a2 = pair.axis[1], pair.axis[2]
    z = np.array([0.0, 0.0, 1.0])
    pinion_shift = misalignment.pinion_axial * a1 + misalignment.offset * z
    # Opening the shaft angle turns a2 away from a1 about z.
    sense = math.copysign(1.0, float(np.cross(a1, a2) @ z))
    angle = sense * misalignment.shaft_angle_error
    c, s = math.cos(angle), math.sin(angle)
    gear_turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    gear_shift = misalignment.gear_axial * (gear_turn @ a2)
    return pinion_shift, gear_turn, gear_shift


def envelope_corners(axes, half_range):
    """The corners of a V-H envelope: every sign of each displacement.

    Parameters
    ----------
    axes : sequence of str
        Displacement letters (``E``, ``P``, ``G``, ``Sigma``).
    half_range : float
        Largest displacement either way [mm; deg for Sigma].

    Returns
    -------
    dict
        ``{label: {letter: value}}``, e.g. ``"E+0.1 P-0.1": {"E": 0.1, "P": -0.1}``,
        in configuration units.
    """
    import itertools

    out = {}
    for signs in itertools.product((1, -1), repeat=len(axes)):
        values = {a: s * half_range for a, s in zip(axes, signs)}
        out[" ".join(f"{a}{v:+g}" for a, v in values.items())] = values
    return out


def corner_displacements(label):
    """The displacements of a corner's label, the inverse of :func:`envelope_corners`.

    Parameters
    ----------
    label : str
        E.g. ``"E+0.1 P-0.1"``.

    Returns
    -------
    dict
        ``{letter: value}`` [mm; deg for Sigma].

    Raises
    ------
    ValueError
        A part that is not LETTER+VALUE with a letter of :data:`DISPLACEMENTS`.
    """
    out = {}
    for part in str(label).split():
        letter = next((a for a in DISPLACEMENTS if part.startswith(a)
                       and part[len(a):len(a) + 1] in "+-"), None)
        if letter is None:
            raise ValueError(f"displacement corner {label!r}: {part!r} is not LETTER+VALUE "
                             f"with LETTER one of {', '.join(DISPLACEMENTS)}")
        out[letter] = float(part[len(letter):])
    return out
