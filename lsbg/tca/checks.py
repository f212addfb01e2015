"""Checks of a contact state before any job: modification, displacements, V-H map.

:func:`contact_state_problems` is what :mod:`lsbg.study.checks` runs on the
``flank_modification:``, ``misalignment:`` and ``misalignment_map:`` sections
at a design point (through :func:`point_problems`, its answers kept by the
study): one line per key at fault, naming the key and its value;
:func:`user_lines` writes them in the user's values, and
:func:`map_steps_problems` checks the map's steps before any point.

* A relief larger than the normal backlash would leave the pinion's tooth
  thinner than the gap it was cut for: rejected.
* A displacement (alone, or at any corner of the V-H map) at which the drive
  flanks lose contact at some mesh position, or the coast flanks close the
  backlash (:func:`lsbg.tca.analysis.backlash`): the members interfere.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np

from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.misalignment import DISPLACEMENTS, Misalignment
from lsbg.tca.modification import FlankModification
from lsbg.tca.vh_map import DEFAULT_AXES, DEFAULT_RANGE, DEFAULT_STEPS, axis_values

__all__ = ["CHECK_POSITIONS", "CHECK_GRID", "normal_backlash", "modification_problems",
           "displacement_problems", "map_corners", "contact_state_problems",
           "map_steps_problems", "point_problems", "user_lines"]

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
    key = max((k for k in config if k.endswith("_um")), key=lambda k: abs(config[k]))
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



def map_steps_problems(section):
    """The V-H map's steps, which must be odd, before any design point is asked.

    Parameters
    ----------
    section : dict
        The ``misalignment_map`` section, defaults filled in.

    Returns
    -------
    list of str
    """
    return [f"misalignment_map.{key} = {section[key]!r}: must be odd (the map's values run "
            f"evenly from -range to +range through the aligned pair, 0 included)"
            for key in ("steps", "sweep_steps") if section[key] % 2 == 0]


def point_problems(pair, config, map_config):
    """:func:`contact_state_problems` of a configuration at one design point, quietly.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    config : dict
        The configuration: its ``flank_modification`` and ``misalignment`` sections.
    map_config : dict
        The V-H map at this point: ``axes``, ``range`` and the point's ``steps``.

    Returns
    -------
    list of str
        As lsbg writes them (:func:`user_lines` turns them into the user's values).
    """
    # numpy's warnings of a hopeless contact state would print around the message
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        return contact_state_problems(pair, config["flank_modification"],
                                      config["misalignment"], map_config)


def user_lines(lines, config):
    """A design point's problem lines as the configuration's check names them.

    The map is taken about the misalignment: where the misalignment itself
    fails, it is the key at fault and the map's corners are not named. A
    ``flank_modification`` key's value is given as the user wrote it (lsbg
    writes it as read: ``500.0`` for ``500``).

    Parameters
    ----------
    lines : list of str
        :func:`point_problems` at one design point.
    config : dict
        The configuration.

    Returns
    -------
    list of str
    """
    if any(line.startswith("misalignment.") for line in lines):
        lines = [line for line in lines if not line.startswith("misalignment_map.")]
    return [_user_value(line, config) for line in lines]


def _user_value(line, config):
    """The line with its flank_modification key's value as the user wrote it."""
    match = re.match(r"^flank_modification\.(\w+) = (.*?): (.*)$", line, re.DOTALL)
    if not (match and match.group(1) in config["flank_modification"]):
        return line
    return (f"flank_modification.{match.group(1)} = "
            f"{config['flank_modification'][match.group(1)]!r}: {match.group(3)}")
