"""Model-form sensitivity of the line model: cases that scale one contact setting.

The line model rests on settings nobody measured for this pair: the line
stiffness (calibrated to ISO 6336-1's c_gamma), the mesh-mode damping ratio
and the number of slices. A sensitivity case scales one of them by a factor
(the workflow's ``sensitivity`` section, e.g. ``mesh_damping_ratio: [0.5, 2]``)
and reruns both traces at the paper's design point; the paper report asks
whether the verdict survives every case.
"""

from __future__ import annotations

from lsbg.files import number_label

__all__ = ["SENSITIVITY_KEYS", "case_name", "parse_case", "scaled_contact"]

#: Contact keys (paper units) a case may scale.
SENSITIVITY_KEYS = ("mesh_damping_ratio", "line_stiffness_N_per_mm_um", "slices")


def case_name(key, factor):
    """Name of a case, e.g. ``mesh_damping_ratio_x0.5``.

    Parameters
    ----------
    key : str
        One of :data:`SENSITIVITY_KEYS`.
    factor : float
        [-]
    """
    return f"{key}_x{number_label(factor)}"


def parse_case(name):
    """``(key, factor)`` of a case name (:func:`case_name`).

    Raises
    ------
    ValueError
        If the name is not ``KEY_xFACTOR`` with a key of :data:`SENSITIVITY_KEYS`.
    """
    key, sep, factor = str(name).rpartition("_x")
    try:
        value = float(factor)
    except ValueError:
        value = None
    if not sep or key not in SENSITIVITY_KEYS or value is None:
        raise ValueError(f"case {name!r}: must be KEY_xFACTOR with KEY one of "
                         f"{', '.join(SENSITIVITY_KEYS)}")
    return key, value


def scaled_contact(contact, key, factor):
    """The contact setting of a case: ``{key: contact[key] * factor}``.

    Parameters
    ----------
    contact : dict
        The ``contact`` section (paper units).
    key : str
        One of :data:`SENSITIVITY_KEYS`.
    factor : float
        [-], > 0.

    Returns
    -------
    dict
        One key; ``slices`` rounded to a whole number.

    Raises
    ------
    ValueError
        Naming the key or the factor.
    """
    if key not in SENSITIVITY_KEYS:
        raise ValueError(f"sensitivity key {key!r}: must be one of {', '.join(SENSITIVITY_KEYS)}")
    if not (isinstance(factor, (int, float)) and not isinstance(factor, bool) and factor > 0):
        raise ValueError(f"sensitivity.{key} factor {factor!r}: must be a positive number")
    value = contact[key] * factor
    return {key: int(round(value)) if key == "slices" else value}
