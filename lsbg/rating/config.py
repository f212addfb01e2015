"""The ``rating`` section of the study configuration.

The section states what ISO 10300 leaves to the user (paper-style units at
the edge: MPa, mm^2/s, um); it becomes a :class:`RatingMaterial` (with the
``tooth`` section's Young's modulus and Poisson ratio: one steel) and a
:class:`RatingConditions`. ``dynamic_factor: lsbg`` (the default) takes
K_v from the study's own run at the design point (the line model's largest
contact torque over its static value); a number >= 1 sets it. A bad value
raises an error naming ``rating.<key>`` and its value.
"""

from __future__ import annotations

import dataclasses
import math

__all__ = ["RATING_CONFIG_KEYS", "rating_from_config", "rate_design", "rating_problems"]

#: Key of the ``rating`` section -> (object, field, SI value of one unit of the key).
RATING_CONFIG_KEYS = {
    "application_factor": ("conditions", "application_factor", 1.0),
    "dynamic_factor": ("conditions", "dynamic_factor", 1.0),
    "mounting": ("conditions", "mounting", None),
    "contact_pattern": ("conditions", "contact_pattern", None),
    "accuracy_grade": ("conditions", "accuracy_grade", 1.0),
    "profile_crowning": ("conditions", "profile_crowning", None),
    "effective_face_width": ("conditions", "effective_face_width", 1.0),
    "oil_viscosity_mm2_s": ("conditions", "oil_viscosity", 1e-6),
    "flank_roughness_um": ("conditions", "flank_roughness", 1e-6),
    "root_roughness_um": ("conditions", "root_roughness", 1e-6),
    "contact_endurance_MPa": ("material", "contact_endurance", 1e6),
    "bending_endurance_MPa": ("material", "bending_endurance", 1e6),
}


def rating_from_config(section, tooth_section=None, dynamic_factor=None):
    """Material and conditions of a ``rating`` section.

    Parameters
    ----------
    section : dict
        Keys of :data:`RATING_CONFIG_KEYS`; missing keys take the defaults of
        :class:`lsbg.rating.iso10300.RatingMaterial` and
        :class:`~lsbg.rating.iso10300.RatingConditions`.
    tooth_section : dict, optional
        The ``tooth`` section: ``young_modulus_GPa`` and ``poisson_ratio``.
    dynamic_factor : float, optional
        K_v measured by lsbg [-]: used where the section says ``lsbg`` (or
        nothing); without it K_v = 1 there (the static rating).

    Returns
    -------
    material : lsbg.rating.iso10300.RatingMaterial
    conditions : lsbg.rating.iso10300.RatingConditions

    Raises
    ------
    ValueError
        Naming ``rating.<key>`` (or ``tooth.<key>``) and its value.
    """
    from lsbg.rating.iso10300 import RatingConditions, RatingMaterial
    from lsbg.config import config_key, section_objects

    section = dict(section or {})
    values = {"material": {}, "conditions": {}}
    for key, value in section.items():
        if key not in RATING_CONFIG_KEYS:
            raise ValueError(f"rating.{key} = {value!r}: unknown key (known: "
                             f"{sorted(RATING_CONFIG_KEYS)})")
        target, field, unit = RATING_CONFIG_KEYS[key]
        if value is None or (key == "dynamic_factor" and value == "lsbg"):
            continue
        if unit is None:
            values[target][field] = value
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise ValueError(f"rating.{key} = {value!r}: must be a finite number"
                             + (" or 'lsbg'" if key == "dynamic_factor" else ""))
        values[target][field] = value * unit
    if "dynamic_factor" not in values["conditions"] and dynamic_factor is not None:
        values["conditions"]["dynamic_factor"] = max(float(dynamic_factor), 1.0)
    tooth = dict(tooth_section or {})
    for key, field, unit in (("young_modulus_GPa", "young_modulus", 1e9),
                             ("poisson_ratio", "poisson_ratio", 1.0)):
        if tooth.get(key) is not None:
            values["material"][field] = tooth[key] * unit
    def named(target, field):
        key = config_key(RATING_CONFIG_KEYS, target, field)
        if key is not None:
            return f"rating.{key}", section.get(key, values[target].get(field))
        key = {"young_modulus": "young_modulus_GPa"}.get(field, field)
        return f"tooth.{key}", tooth.get(key)

    built = section_objects(values, {"material": RatingMaterial, "conditions": RatingConditions},
                            named, "rating")
    return built["material"], built["conditions"]


def rate_design(design, section, tooth_section, gear_torque, pinion_speed,
                dynamic_factor=None):
    """A design point rated with a study's ``rating`` and ``tooth`` sections.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    section, tooth_section : dict
        The ``rating`` and ``tooth`` sections (:func:`rating_from_config`;
        the tooth's fillet radius is the tool's edge radius).
    gear_torque : float
        The load on the gear [N m].
    pinion_speed : float
        [rad/s].
    dynamic_factor : float, optional
        K_v measured by lsbg [-] (:func:`rating_from_config`).

    Returns
    -------
    rating : lsbg.rating.iso10300.BevelRating
    material : lsbg.rating.iso10300.RatingMaterial
    conditions : lsbg.rating.iso10300.RatingConditions

    Raises
    ------
    ValueError
        A bad key (named), or a design the standard cannot rate.
    """
    from lsbg.rating.iso10300 import rate
    from lsbg.rating.virtual import rating_geometry

    tooth_section = tooth_section or {}
    material, conditions = rating_from_config(section, tooth_section, dynamic_factor)
    radius = tooth_section.get("fillet_radius_module")
    geometry = rating_geometry(design, effective_face_width=conditions.effective_face_width,
                               **({"tool_edge_radius": radius} if radius else {}))
    pinion_torque = gear_torque * design.pinion_teeth / design.gear_teeth
    return rate(geometry, pinion_torque, pinion_speed, material, conditions), material, conditions


def rating_fields(material, conditions):
    """Both objects' fields as one flat dict (SI), for a dataset's attributes."""
    return {**{f"material_{k}": v for k, v in dataclasses.asdict(material).items()},
            **{f"conditions_{k}": ("" if v is None else v)
               for k, v in dataclasses.asdict(conditions).items()}}


def rating_problems(config, pairs):
    """The ``rating`` section and the rated design points, checked before any job.

    Parameters
    ----------
    config, pairs : dict
        The study configuration (defaults filled in) and the design points
        that passed their own checks, as in
        :func:`lsbg.tooth.config.tooth_problems`; the paper's spiral angle is
        rated.

    Returns
    -------
    list of str
        One line per problem, starting with the key and its value.
    """
    from lsbg.files import number_label
    from lsbg.rating.iso10300 import rate
    from lsbg.rating.virtual import rating_geometry

    try:
        material, conditions = rating_from_config(config.get("rating", {}),
                                                  config.get("tooth", {}))
    except ValueError as error:
        return [str(error)]
    problems = []
    paper = number_label(config["paper_spiral_angle_deg"])
    radius = config.get("tooth", {}).get("fillet_radius_module", 0.25)
    for (trace, spiral), pair in pairs.items():
        if spiral != paper:
            continue
        geometry = rating_geometry(pair.design, radius, conditions.effective_face_width)
        try:
            rate(geometry, 1.0, 1.0, material, conditions)
        except ValueError as error:
            problems.append(f"paper_spiral_angle_deg = {config['paper_spiral_angle_deg']!r}: "
                            f"the ISO 10300 rating of the {trace} pair: {error}")
    return problems
