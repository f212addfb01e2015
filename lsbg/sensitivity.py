"""Model-form sensitivity of the line model: cases that scale or switch one contact setting.

The line model rests on settings nobody measured for this pair: the line
stiffness (calibrated to ISO 6336-1's c_gamma), the mesh-mode damping ratio
and the number of slices. A sensitivity case scales one of them by a factor
(the workflow's ``sensitivity`` section, e.g. ``mesh_damping_ratio: [0.5, 2]``)
and reruns both traces at the paper's design point; the paper report asks
whether the verdict survives every case. A switch case sets a word-valued
setting instead: ``compliance: [fe]`` runs the line model on the tooth's own
stiffness from finite elements (or, from a study under ``compliance: fe``,
``[uniform]`` on the uniform bed).
"""

from __future__ import annotations

from lsbg.files import number_label

__all__ = ["SENSITIVITY_KEYS", "SENSITIVITY_SWITCHES", "case_name", "parse_case",
           "scaled_contact", "case_label"]

#: Contact keys (paper units) a case may scale.
SENSITIVITY_KEYS = ("mesh_damping_ratio", "line_stiffness_N_per_mm_um", "slices")

#: Word-valued contact keys a case may switch -> their values.
SENSITIVITY_SWITCHES = {"compliance": ("uniform", "fe")}

#: Words of the keys and values in the reports.
_LABELS = {"mesh_damping_ratio": "damping ratio", "line_stiffness_N_per_mm_um": "line stiffness",
           "slices": "slices", "compliance": "compliance", "fe": "FE", "uniform": "uniform"}


def case_name(key, factor):
    """Name of a case, e.g. ``mesh_damping_ratio_x0.5``, or ``compliance_fe`` for a switch.

    Parameters
    ----------
    key : str
        One of :data:`SENSITIVITY_KEYS` or :data:`SENSITIVITY_SWITCHES`.
    factor : float or str
        [-], or the switch's value.
    """
    if key in SENSITIVITY_SWITCHES:
        return f"{key}_{factor}"
    return f"{key}_x{number_label(factor)}"


def case_label(name):
    """A case name in words: ``damping ratio ×0.5``, ``compliance: FE``.

    Parameters
    ----------
    name : str
        As :func:`case_name` gives it.
    """
    key, value = parse_case(name)
    if key in SENSITIVITY_SWITCHES:
        return f"{_LABELS[key]}: {_LABELS.get(value, value)}"
    return f"{_LABELS.get(key, key)} ×{number_label(value)}"


def parse_case(name):
    """``(key, factor)`` of a case name (:func:`case_name`); ``(key, value)`` of a switch.

    Raises
    ------
    ValueError
        If the name is neither ``KEY_xFACTOR`` with a key of
        :data:`SENSITIVITY_KEYS` nor ``KEY_VALUE`` of a switch.
    """
    for key, values in SENSITIVITY_SWITCHES.items():
        head, _, value = str(name).rpartition("_")
        if head == key and value in values:
            return key, value
    key, sep, factor = str(name).rpartition("_x")
    try:
        value = float(factor)
    except ValueError:
        value = None
    if not sep or key not in SENSITIVITY_KEYS or value is None:
        raise ValueError(f"case {name!r}: must be KEY_xFACTOR with KEY one of "
                         f"{', '.join(SENSITIVITY_KEYS)}, or "
                         f"{', '.join(f'{k}_{v}' for k, vs in SENSITIVITY_SWITCHES.items() for v in vs)}")
    return key, value


def scaled_contact(contact, key, factor):
    """The contact setting of a case: ``{key: contact[key] * factor}``, or
    ``{key: value}`` for a switch.

    Parameters
    ----------
    contact : dict
        The ``contact`` section (paper units).
    key : str
        One of :data:`SENSITIVITY_KEYS` or :data:`SENSITIVITY_SWITCHES`.
    factor : float or str
        [-], > 0; a switch's value.

    Returns
    -------
    dict
        One key; ``slices`` rounded to a whole number.

    Raises
    ------
    ValueError
        Naming the key or the factor.
    """
    if key in SENSITIVITY_SWITCHES:
        values = SENSITIVITY_SWITCHES[key]
        if factor not in values:
            raise ValueError(f"sensitivity.{key} value {factor!r}: must be one of {values}")
        return {key: factor}
    if key not in SENSITIVITY_KEYS:
        raise ValueError(f"sensitivity key {key!r}: must be one of "
                         f"{', '.join(SENSITIVITY_KEYS + tuple(SENSITIVITY_SWITCHES))}")
    if not (isinstance(factor, (int, float)) and not isinstance(factor, bool) and factor > 0):
        raise ValueError(f"sensitivity.{key} factor {factor!r}: must be a positive number")
    value = contact[key] * factor
    return {key: int(round(value)) if key == "slices" else value}
