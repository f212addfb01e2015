"""Service life from stress: the S-N (Basquin) lines behind ISO 6336's life factors.

Above the endurance limit a gear's life N and its stress sigma follow
N sigma^p = const, the slope p read off the life factor curves of ISO
6336-2 (pitting, Z_NT) and ISO 6336-3 (tooth root, Y_NT): between the
static and the endurance points, Z_NT (or Y_NT) falls from its static value
to 1 while the cycles grow from N_static to N_endurance, so
p = ln(N_endurance / N_static) / ln(factor_static). Two members (or two gear
types) at stresses sigma_a and sigma_b then live N_a / N_b =
(sigma_b / sigma_a)^p: the stress ratio decides, the exponent magnifies it.

The exponent is uncertain: whether some pitting is permitted, and the
material class, give different slopes (:data:`EXPONENTS`), so
:func:`life_ratio` reports the ratio over the range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["BasquinLine", "EXPONENTS", "basquin_exponent", "life_ratio"]


@dataclass(frozen=True)
class BasquinLine:
    """Two points of a life factor curve.

    Parameters
    ----------
    static_cycles : float
        N at and below which the static factor applies [-].
    static_factor : float
        Z_NT or Y_NT there [-], > 1.
    endurance_cycles : float
        N at which the factor reaches 1 [-].
    source : str
        Where the points come from.
    """

    static_cycles: float
    static_factor: float
    endurance_cycles: float
    source: str

    @property
    def exponent(self):
        """p = ln(N_endurance / N_static) / ln(factor_static) [-]."""
        return basquin_exponent(self.static_cycles, self.static_factor, self.endurance_cycles)


#: Life factor lines: the stated exponent is the first of each tuple
#: (case-hardened steel, Eh), the others give its range.
EXPONENTS = {
    "contact": (
        BasquinLine(1e5, 1.6, 5e7, "ISO 6336-2, Table 2: Eh, no pitting permitted"),
        BasquinLine(6e5, 1.6, 1e9, "ISO 6336-2, Table 2: Eh, some pitting permitted"),
    ),
    "bending": (
        BasquinLine(1e3, 2.5, 3e6, "ISO 6336-3, Table 4: Eh, IF (root)"),
        BasquinLine(1e4, 2.5, 3e6, "ISO 6336-3, Table 4: St, V (through-hardened)"),
    ),
}


def basquin_exponent(static_cycles, static_factor, endurance_cycles):
    """Slope p of N sigma^p = const through a life factor curve's two points [-].

    Parameters
    ----------
    static_cycles, endurance_cycles : float
        Load cycles [-], 0 < static < endurance.
    static_factor : float
        The life factor at ``static_cycles`` [-], > 1 (1 at the endurance point).
    """
    if not (0 < static_cycles < endurance_cycles and static_factor > 1):
        raise ValueError(f"a life factor line needs 0 < N_static ({static_cycles!r}) < "
                         f"N_endurance ({endurance_cycles!r}) and a static factor > 1 "
                         f"({static_factor!r})")
    return math.log(endurance_cycles / static_cycles) / math.log(static_factor)


def life_ratio(stress, reference_stress, kind):
    """Life at ``stress`` over life at ``reference_stress`` on the Basquin line.

    Parameters
    ----------
    stress, reference_stress : float
        The two stresses [Pa], > 0, both above the endurance limit.
    kind : {"contact", "bending"}

    Returns
    -------
    dict
        ``ratio`` at the stated exponent, ``low`` and ``high`` over the
        range of :data:`EXPONENTS`, and ``exponent``, ``exponents`` [-].
    """
    if not (stress > 0 and reference_stress > 0):
        raise ValueError(f"stresses must be positive: {stress!r}, {reference_stress!r} Pa")
    lines = EXPONENTS[kind]
    exponents = np.array([line.exponent for line in lines])
    ratios = (reference_stress / stress) ** exponents
    return {"ratio": float(ratios[0]), "low": float(ratios.min()), "high": float(ratios.max()),
            "exponent": float(exponents[0]), "exponents": exponents.tolist()}
