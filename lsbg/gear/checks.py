"""The design points' physics, checked before any job, in the user's keys and units.

:func:`design_problems` builds the :class:`lsbg.gear.geometry.GearPair` of each
design point of a study, which runs lsbg's own checks (:mod:`lsbg.gear.design`:
proportions, backlash, bores, cutter radius; :mod:`lsbg.gear.geometry`:
pointed teeth, contact ratio >= 1 under interference). Their
:class:`~lsbg.gear.design.DesignError` names lsbg's field in SI
(``face_width = 0.5: ...``, lengths in metres); the problem line names the
user's key in the configuration's units (``design.face_width_mm = 500``), the
keys the rule compared it with, and the design points where it fails. Part
of :func:`lsbg.study.checks.check_config`, which adds the resource guard of
each point (:func:`lsbg.study.resources.geometry_problem`).
"""

from __future__ import annotations

import re
import warnings

import numpy as np

from lsbg.config import section_values
from lsbg.gear.depth import TAPER_DEFAULTS
from lsbg.gear.design import CONFIG_KEYS, DesignError, GearPairDesign

__all__ = ["user_message", "design_value", "points_named", "design_problems"]

#: lsbg's SI name of each design key (``face_width`` -> ``face_width_mm``).
_DESIGN_KEYS = {re.sub(r"_(mm|deg|kg_m3)$", "", key): key
                for key in (*CONFIG_KEYS, *TAPER_DEFAULTS)}


#: The design keys each of lsbg's design rules compares a key with (its
#: message names only the key at fault; the others may be the user's mistake,
#: e.g. ``module_mm: 0.01`` leaves the face width too wide).
_DESIGN_DEPENDS = {
    "pinion_teeth": ("gear_teeth",),
    "face_width": ("module_mm", "pinion_teeth", "gear_teeth", "shaft_angle_deg"),
    "addendum": ("module_mm", "normal_pressure_angle_deg", "base_cone_rule"),
    "dedendum": ("addendum_mm", "module_mm"),
    "backlash": ("module_mm", "face_width_mm"),
    "pinion_bore": ("module_mm", "pinion_teeth", "gear_teeth", "face_width_mm", "dedendum_mm"),
    "gear_bore": ("module_mm", "pinion_teeth", "gear_teeth", "face_width_mm", "dedendum_mm"),
    "cutter_radius": ("face_width_mm", "module_mm"),
    "base_cone_rule": ("addendum_mm", "module_mm"),
}


#: A DesignError's message: ``name = value: why``.
_DESIGN_ERROR = re.compile(r"^(\w+) = (.*?): (.*)$", re.DOTALL)


#: A length in metres inside a DesignError's message.
_METRES = re.compile(r"(?<![\w.])([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?) m\b")


def design_value(config, key):
    """``design.KEY = value`` as the user wrote it (or its default, so marked).

    Parameters
    ----------
    config : dict
        The configuration.
    key : str
        A key of the ``design`` section (:data:`lsbg.gear.design.CONFIG_KEYS`).

    Returns
    -------
    str
    """
    design = config["design"]
    if key in design:
        return f"design.{key} = {design[key]!r}"
    defaults = {**TAPER_DEFAULTS, **GearPairDesign().to_config()}
    return f"design.{key} = {defaults[key]!r} (default)"


def _value_at(config, path):
    """The value at a key path such as ``sweep.spiral_angles_deg[2]``."""
    value = config
    for name, index in re.findall(r"([^.\[\]]+)|\[(\d+)\]", path):
        value = value[int(index)] if index else value[name]
    return value


def user_message(error, config, point_keys):
    """A DesignError's message under the user's key and units: (key part, why).

    lsbg.gear.design names the dataclass field (``face_width = 0.5``) and writes
    lengths in metres; the user wrote ``design.face_width_mm: 500``.
    """
    match = _DESIGN_ERROR.match(str(error))
    if not match:
        return "design", str(error)
    name, why = match.group(1), match.group(3)
    why = _METRES.sub(lambda m: f"{float(m.group(1)) * 1e3:.6g} mm", why)
    if name == "spiral_angle":
        return f"{point_keys[0]} = {_value_at(config, point_keys[0])!r}", why
    key = _DESIGN_KEYS.get(name)
    if name in _DESIGN_DEPENDS:
        others = ", ".join(design_value(config, other) for other in _DESIGN_DEPENDS[name])
        why = f"{why} (with {others})"
    return (design_value(config, key) if key else f"design ({name} = {match.group(2)})"), why


def points_named(where, points):
    """The design points ``where`` as a problem line names them.

    Parameters
    ----------
    where : list of str
        The failing points' names (``"circular 35 deg"``), in order.
    points : collection
        Every design point of the study.

    Returns
    -------
    str
        ``every design point``, or the first four names and how many more.
    """
    more = f" and {len(where) - 4} more" if len(where) > 4 else ""
    return "every design point" if len(where) == len(points) else ", ".join(where[:4]) + more


def design_problems(config, points, pairs=None, guard=None):
    """lsbg's physics checks at every design point: one line per key at fault,
    naming the design points where it fails.

    Parameters
    ----------
    config : dict
        The configuration, defaults filled in.
    points : dict
        ``(trace, spiral label) -> key paths that ask for the point``
        (:func:`lsbg.study.points.design_points`).
    pairs : dict, optional
        Filled in with ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of
        each point that passes.
    guard : callable, optional
        ``guard(pair) -> (key part, why) or None``: a further check of a pair
        that passed (the study's resource guard); its problem fails the point
        as lsbg's own would.

    Returns
    -------
    list of str
        ``key = value: why (at points)``.
    """
    from lsbg.gear.geometry import GearPair

    failing = {}  # key part -> [why, points]
    for (trace, spiral), keys in points.items():
        where = f"{trace} {spiral} deg"
        try:
            # numpy's warnings of a hopeless design would print around the message
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                pair = GearPair(GearPairDesign.from_config(
                    {**config["design"], "trace": trace, "spiral_angle_deg": float(spiral)}))
                beyond = guard(pair) if guard is not None else None
        except DesignError as error:
            head, why = user_message(error, config, keys)
            failing.setdefault(head, [why, []])[1].append(where)
            continue
        except (ValueError, ArithmeticError) as error:
            # numbers beyond what the formulas survive (e.g. module_mm: 1e300)
            failing.setdefault(section_values(config, "design"), [
                f"lsbg cannot compute this design ({type(error).__name__}: {error})", []
            ])[1].append(where)
            continue
        if beyond:
            failing.setdefault(beyond[0], [beyond[1], []])[1].append(where)
        elif pairs is not None:
            pairs[(trace, spiral)] = pair
    return [f"{head}: {why} (at {points_named(where, points)})"
            for head, (why, where) in failing.items()]
