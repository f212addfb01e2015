"""Checks of a contact state before any job: modification, displacements, V-H map.

:func:`contact_state_problems` is what :mod:`lsbg.study.checks` runs on the
``flank_modification:``, ``misalignment:`` and ``misalignment_map:`` sections
at a design point: one line per key at fault, naming the key and its value.

* A relief larger than the normal backlash would leave the pinion's tooth
  thinner than the gap it was cut for: rejected.
* A displacement (alone, or at any corner of the V-H map) at which the drive
  flanks lose contact at some mesh position, or the coast flanks close the
  backlash (:func:`lsbg.tca.analysis.backlash`): the members interfere.
"""

from __future__ import annotations

import math

from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.misalignment import DISPLACEMENTS, Misalignment
from lsbg.tca.modification import FlankModification
from lsbg.tca.vh_map import DEFAULT_AXES, DEFAULT_RANGE, DEFAULT_STEPS, axis_values

#: A quick TCA: positions over the mesh cycle and the pinion grid [-].
CHECK_POSITIONS = 16
CHECK_GRID = (31, 61)


def normal_backlash(design):
    """Normal backlash at the mean point, j_n = j_t cos(alpha_n) cos(beta_m) [m]."""
    return design.backlash * math.cos(design.normal_pressure_angle) * math.cos(design.spiral_angle)


def modification_problems(pair, modification):
    """Problems of a modification on a pair (relief beyond the backlash)."""
    largest = modification.largest_relief()
    limit = normal_backlash(pair.design)
    if largest <= limit:
        return []
    config = modification.to_config()
    key = max(("lengthwise_crowning_um", "profile_crowning_um", "bias_um"),
              key=lambda k: abs(config[k]))
    if modification.topography_file is not None and abs(config[key]) * 1e-6 < limit:
        key = "topography_file"
    return [f"flank_modification.{key} = {config[key]!r}: the largest relief of the pinion flank, "
            f"{largest * 1e6:.4g} um, exceeds the normal backlash {limit * 1e6:.4g} um"]


def displacement_problems(pair, modification, misalignment, where):
    """Problems of one displaced assembly: contact lost, or backlash closed.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification
    misalignment : Misalignment
    where : str
        The key(s) and value(s) that set this displacement, for the message.

    Returns
    -------
    list of str
    """
    try:
        tooth_contact_analysis(pair, modification, misalignment, CHECK_POSITIONS,
                               grid=CHECK_GRID)
    except ValueError as err:
        return [f"{where}: {str(err).split(': ', 1)[-1]}"]
    return []


def map_corners(config):
    """Displacements at the corners of a V-H map section (SI), with their keys."""
    axes = tuple((config or {}).get("axes", DEFAULT_AXES))
    half = (config or {}).get("range", DEFAULT_RANGE)
    steps = (config or {}).get("steps", DEFAULT_STEPS)
    values = axis_values(half, steps)
    corners = []
    for a in (values[0], values[-1]):
        for b in (values[0], values[-1]):
            corners.append(({axes[0]: a * DISPLACEMENTS[axes[0]][2],
                             axes[1]: b * DISPLACEMENTS[axes[1]][2]},
                            f"misalignment_map.range = {half!r} ({axes[0]} = {a:g}, "
                            f"{axes[1]} = {b:g})"))
    return corners


def contact_state_problems(pair, modification_config, misalignment_config, map_config=None):
    """Every problem of the contact-state sections at one design point.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification_config, misalignment_config, map_config : dict or None
        The ``flank_modification:``, ``misalignment:`` and
        ``misalignment_map:`` sections (configuration units).

    Returns
    -------
    list of str
        One line per problem, starting with the key path.
    """
    try:
        modification = FlankModification.from_config(modification_config)
    except ValueError as err:
        return [str(err)]
    try:
        misalignment = Misalignment.from_config(misalignment_config)
    except ValueError as err:
        return [str(err)]
    problems = modification_problems(pair, modification)
    if problems:
        return problems
    if not misalignment.is_zero:
        keys = ", ".join(f"misalignment.{k} = {v!r}" for k, v in
                         (misalignment_config or {}).items() if v)
        problems += displacement_problems(pair, modification, misalignment, keys)
    if map_config is not None:
        try:
            corners = map_corners(map_config)
        except ValueError as err:
            return problems + [str(err)]
        for shift, where in corners:
            shifted = misalignment.shifted(**shift)
            problems += displacement_problems(pair, modification, shifted, where)
    return list(dict.fromkeys(problems))

