"""The engines', simulation and contact settings, checked as lsbg's commands will read them.

Each function takes the workflow configuration (the schema's defaults filled
in) and returns one line per problem, starting with the user's key and value
(``contact.stiction_velocity_mm_s = 0.1``), never lsbg's SI field
(``v_s=0.0001 [m/s]``): :func:`settings_message` rewrites lsbg's messages.
Part of :func:`lsbg.study.checks.check_config`.
"""

from __future__ import annotations

import re

from lsbg.config import section_values

__all__ = ["settings_message", "engine_problems", "driveline_problems", "contact_problems"]

#: lsbg's message of a ``simulation`` or ``contact`` setting: the user's key
#: and value, then lsbg's field name, SI value and rule
#: (``contact.slices = 1: ContactParameters.slices must be ..., got slices=1``,
#: ``simulation.ramp_time_s = 2.0: ramp_time = 2.0: exceeds ...``).
_SETTINGS_ERROR = re.compile(r"^((?:simulation|contact)\.\w+ = .*?): "
                             r"(?:ContactParameters\.\w+ (.*?), got .*|\w+ = .*?: (.*))$",
                             re.DOTALL)


def settings_message(error, config):
    """lsbg's message of a setting without its SI field names and units: the rule
    in the user's keys (``v_s=0.0001 [m/s]`` -> ``contact.stiction_velocity_mm_s = 0.1``).

    Parameters
    ----------
    error : ValueError
        Raised by :meth:`lsbg.dynamics.SimulationSettings.from_config` or
        :meth:`lsbg.contact.ContactParameters.from_config`.
    config : dict
        The configuration whose ``contact`` section was read.

    Returns
    -------
    str
    """
    from lsbg.contact import CONTACT_CONFIG_KEYS

    match = _SETTINGS_ERROR.match(str(error))
    if not match:
        return str(error)
    rule = match.group(3)
    if rule is None:  # a contact rule: its unit is the SI field's, the user's value is not
        rule = re.sub(r" \[[^\]]*\]$", "", match.group(2))
        rule = re.sub(r"\b(\w+)=\S+", lambda m: (
            f"contact.{CONTACT_CONFIG_KEYS[m.group(1)]} = "
            f"{config['contact'].get(CONTACT_CONFIG_KEYS[m.group(1)])!r}"
            if m.group(1) in CONTACT_CONFIG_KEYS else m.group(0)), rule)
    return f"{match.group(1)}: {rule}"


def engine_problems(config, engines):
    """The paper's engine, and the ``simulation`` section as each engine reads it.

    Parameters
    ----------
    config : dict
        The configuration, defaults filled in: its ``engines`` and ``simulation``.
    engines : collection of str
        Every engine some run of the study uses
        (:func:`lsbg.study.resources.engines_run`).

    Returns
    -------
    list of str
        One line per problem; a setting that fails for several engines is one
        line naming them.
    """
    from lsbg.dynamics import SimulationSettings

    problems = []
    engines_section = config["engines"]
    sweep_engine, reference = engines_section["sweep"], engines_section["reference"]
    if engines_section["paper"] not in {sweep_engine, *reference.get("point", [])}:
        problems.append(f"engines.paper = {engines_section['paper']!r}: must be engines.sweep "
                        f"or one of engines.reference.point {reference.get('point', [])!r} "
                        f"(the paper report reproduces the paper with the point model)")
    engines_failing = {}  # message -> engines
    for engine in sorted(engines):
        try:
            SimulationSettings.from_config(config["simulation"], engine=engine)
        except ValueError as error:
            engines_failing.setdefault(settings_message(error, config), []).append(engine)
    problems += [f"{message} (engine {', '.join(names)})"
                 for message, names in engines_failing.items()]
    return problems


def contact_problems(config):
    """The ``contact`` section as :class:`lsbg.contact.ContactParameters` reads it: the
    contact law of every run.

    Parameters
    ----------
    config : dict
        The configuration: its ``contact`` section.

    Returns
    -------
    list of str
        At most one line.
    """
    from lsbg.contact import ContactParameters

    try:
        ContactParameters.from_config(config["contact"])
    except ValueError as error:
        return [settings_message(error, config)]
    except ArithmeticError as error:  # numbers beyond what the unit conversions survive
        return [f"{section_values(config, 'contact')}: lsbg cannot compute this "
                f"contact law ({type(error).__name__}: {error})"]
    return []


def driveline_problems(config):
    """The ``driveline`` section as :func:`lsbg.dynamics.driveline.driveline_values` reads it.

    Parameters
    ----------
    config : dict
        The configuration: its ``driveline`` section (checked whatever the boundary,
        so that switching to it later does not find a bad key).

    Returns
    -------
    list of str
        At most one line (``driveline.tyre_radius_m = 0: must be a positive number``).
    """
    from lsbg.dynamics.driveline import driveline_values

    try:
        driveline_values(config.get("driveline", {}))
    except ValueError as error:
        return [str(error)]
    return []
