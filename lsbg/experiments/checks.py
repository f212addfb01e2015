"""The ``sensitivity`` section checked before any job: its case names and settings
(and ``practice.sensitivity``, the keys of it the practice and best pairs run).

Each function takes the workflow configuration (the schema's defaults filled
in) and returns one line per problem, starting with ``sensitivity.<key>[k]``
and the factor the user wrote. Part of :func:`lsbg.study.checks.check_config`.
"""

from __future__ import annotations

from lsbg.experiments.sensitivity import case_name, pair_case_keys, scaled_contact
from lsbg.files import label_clashes

__all__ = ["case_name_problems", "sensitivity_problems", "operating_problems"]


def case_name_problems(config):
    """Factors of one sensitivity key that differ but give the same case (file) name.

    Parameters
    ----------
    config : dict
        The configuration: its ``sensitivity`` section (key -> factors, or
        the values a switch takes).

    Returns
    -------
    list of str
    """
    problems = []
    for key, factors in config["sensitivity"].items():
        problems += label_clashes(factors, f"sensitivity.{key}",
                                  label=lambda factor, key=key: case_name(key, factor))
    return problems


def sensitivity_problems(config):
    """Each sensitivity case's contact law, as its line-model run will read it.

    A case scales or switches one contact setting
    (:func:`lsbg.experiments.sensitivity.scaled_contact`); the scaled section
    must still be a valid :class:`lsbg.contact.ContactParameters`.

    Parameters
    ----------
    config : dict
        The configuration: its ``sensitivity`` and ``contact`` sections.

    Returns
    -------
    list of str
        ``sensitivity.KEY[k] = factor: gives <the contact setting's problem>``; and
        ``practice.sensitivity[k]`` where it names no key of the section.
    """
    from lsbg.contact import ContactParameters
    from lsbg.dynamics.checks import settings_message

    problems = []
    for key, factors in config["sensitivity"].items():
        for k, factor in enumerate(factors):
            scaled = {**config["contact"], "model": "line",
                      **scaled_contact(config["contact"], key, factor)}
            try:
                ContactParameters.from_config(scaled)
            except ValueError as error:
                problems.append(f"sensitivity.{key}[{k}] = {factor!r}: gives "
                                f"{settings_message(error, {**config, 'contact': scaled})}")
    try:
        pair_case_keys(config)
    except ValueError as error:
        problems.append(str(error))
    return problems


def operating_problems(config):
    """Each operating or boundary case's simulation settings, as its run will read them.

    A ``pinion_speed`` case scales, a ``boundary`` case switches the ``simulation``
    section (:func:`lsbg.experiments.sensitivity.case_simulation`); the case runs on the
    sweep's engine (``engines.sweep``), and its section must differ from the study's.

    Parameters
    ----------
    config : dict
        The configuration: its ``sensitivity``, ``simulation`` and ``engines`` sections.

    Returns
    -------
    list of str
        ``sensitivity.KEY[k] = value: <the problem>``.
    """
    from lsbg.dynamics import SimulationSettings
    from lsbg.dynamics.checks import settings_message
    from lsbg.experiments.sensitivity import OPERATING_KEYS, SIMULATION_SWITCHES, case_simulation

    problems = []
    engine = config["engines"]["sweep"]
    for key in (*OPERATING_KEYS, *SIMULATION_SWITCHES):
        for k, value in enumerate(config["sensitivity"].get(key, [])):
            where = f"sensitivity.{key}[{k}] = {value!r}"
            try:
                simulation = case_simulation(key, value, config["simulation"])
            except ValueError as error:
                problems.append(f"{where}: {error}")
                continue
            if simulation == config["simulation"]:
                problems.append(f"{where}: the study's own setting (simulation.{key}); a "
                                f"case must change it")
                continue
            try:
                SimulationSettings.from_config(simulation, engine=engine)
            except ValueError as error:
                message = settings_message(error, {**config, "simulation": simulation})
                problems.append(f"{where}: gives {message} (engines.sweep {engine!r})")
    return problems
