"""The ``optimise`` section: read into lsbg's objects, checked before any evaluation.

:func:`optimise_problems` is the study's check of the section (called by
:func:`lsbg.study.checks.check_config`), one line per problem naming the key
and its value, in the configuration's units; :func:`run_settings` reads the
section with the sections it borrows from (``rating`` and ``tooth`` for the
rated torque, the lubricant and the steel; ``simulation`` for the pinion's
speed; ``contact`` for the line model; ``misalignment`` and
``misalignment_map`` for the envelope; ``tca`` for the marking compound) and
raises the first problem as a ValueError before anything is evaluated:

* a bound that is reversed, below what the coefficient allows, or a space
  with every variable fixed (:func:`lsbg.optimise.space.bounds_problems`);
* an objective that is not one of :data:`lsbg.optimise.objectives.OBJECTIVES`
  (or named twice), a choice rule that needs an objective not optimised;
* a budget, population x generations evaluations of each trace, whose
  estimated time (:func:`evaluation_seconds`) exceeds ``limits.optimise_minutes``.

The section's keys and defaults are the schema's
(``lsbg/schemas/config.schema.yaml``, section ``optimise``).
"""

from __future__ import annotations

import math

from lsbg.optimise.choice import CHOICE_RULES
from lsbg.optimise.friction import FRICTION_LAWS, RZ_PER_RA, Lubricant
from lsbg.optimise.objectives import OBJECTIVES, EvaluationSettings
from lsbg.optimise.release import release_problems
from lsbg.optimise.search import ALGORITHMS
from lsbg.optimise.space import DesignSpace, bounds_problems

__all__ = ["EVALUATION_COST", "evaluation_seconds", "optimise_problems", "rated_torque",
           "run_settings", "envelope_corners_of", "search_estimate"]

#: The cost of one evaluation on one core of the 2-core machine lsbg is developed
#: on [s]: a base (the curvature-free work of each state: its separation table and
#: quick unloaded TCA) per state of the envelope, and a cost per static solve
#: (a phase at a torque). Measured on the paper's pair: 40 ms at 24 phases,
#: 3 torques and 4 corners (5 states, 168 solves).
EVALUATION_COST = {"per_state": 0.0055, "per_solve": 0.00008}


def envelope_corners_of(config):
    """The envelope's corners, ``(label, {letter: SI value})``, of ``misalignment_map``'s
    axes and range (:func:`lsbg.tca.misalignment.envelope_corners`)."""
    from lsbg.tca.misalignment import DISPLACEMENTS, envelope_corners

    section = config.get("misalignment_map", {})
    axes = tuple(section.get("axes", ("E", "P")))
    half = section.get("range", 0.1)
    return tuple((label, {a: v * DISPLACEMENTS[a][2] for a, v in values.items()})
                 for label, values in envelope_corners(axes, half).items())


def evaluation_seconds(config):
    """Estimated seconds of one evaluation under a configuration [s]."""
    section = config.get("optimise", {})
    torques = len(set(section.get("load_factors", [0.5, 1.0, 1.5])) | {1.0})
    corners = len(envelope_corners_of(config))
    phases = section.get("phases", 24)
    return (EVALUATION_COST["per_state"] * (1 + corners)
            + EVALUATION_COST["per_solve"] * phases * (torques + corners))


def optimise_problems(config):
    """Every problem of the ``optimise`` section, one line each (no evaluation).

    Parameters
    ----------
    config : dict
        The configuration, the schema's defaults filled in.

    Returns
    -------
    list of str
    """
    section = config.get("optimise", {})
    problems = bounds_problems(section.get("bounds", {}))
    objectives = list(section.get("objectives", []))
    unknown = [name for name in objectives if name not in OBJECTIVES]
    if unknown:
        problems.append(f"optimise.objectives = {objectives!r}: {unknown[0]!r} is not an "
                        f"objective (known: {', '.join(OBJECTIVES)})")
    elif not objectives or len(set(objectives)) < len(objectives):
        problems.append(f"optimise.objectives = {objectives!r}: name at least one objective, "
                        f"each once")
    rule = section.get("choice", "knee")
    if rule not in CHOICE_RULES:
        problems.append(f"optimise.choice = {rule!r}: one of {', '.join(CHOICE_RULES)}")
    elif rule == "least_transmission_error" and not {"transmission_error",
                                                     "contact_pressure"} <= set(objectives):
        problems.append(f"optimise.choice = {rule!r}: needs the objectives transmission_error "
                        f"and contact_pressure (optimise.objectives = {objectives!r})")
    if section.get("algorithm", "nsga2") not in ALGORITHMS:
        problems.append(f"optimise.algorithm = {section.get('algorithm')!r}: one of "
                        f"{', '.join(ALGORITHMS)}")
    if section.get("friction_law", "iso_tr_14179_2") not in FRICTION_LAWS:
        problems.append(f"optimise.friction_law = {section.get('friction_law')!r}: one of "
                        f"{', '.join(FRICTION_LAWS)}")
    try:
        lubricant = lubricant_of(config)
    except ValueError as error:
        problems.append(str(error))
    else:
        if section.get("friction_law") == "benedict_kelley" and lubricant.roughness >= 1.27e-6:
            key, value = _roughness_key(config)
            problems.append(f"{key} = {value!r}: Benedict & Kelley's roughness factor needs "
                            f"Ra < 1.27 um (50 microinches); this is Ra "
                            f"{lubricant.roughness * 1e6:.3g} um")
    problems += release_problems(section.get("release", {}), section.get("phases", 24))
    problems += budget_problems(config)
    return problems


def budget_problems(config):
    """A budget beyond ``limits.optimise_minutes``: one line naming population and generations."""
    section = config.get("optimise", {})
    population, generations = section.get("population", 20), section.get("generations", 20)
    minutes = config.get("limits", {}).get("optimise_minutes", 10)
    workers = max(int(section.get("workers", 1)), 1)
    each = evaluation_seconds(config)
    needed = population * generations * each / 60 / workers
    if needed <= minutes:
        return []
    cores = "one core" if workers == 1 else f"{workers} cores (optimise.workers)"
    return [f"optimise.population = {population!r}, optimise.generations = {generations!r}: "
            f"{population * generations} evaluations of each trace, about {needed:.3g} min on "
            f"{cores} ({each * 1e3:.2g} ms each), more than limits.optimise_minutes = "
            f"{minutes!r}"]


def search_estimate(config):
    """The study's ease-off searches: their cells, job count and estimated CPU-hours.

    Every cell of the trace study (:func:`lsbg.optimise.cells.trace_cells`) searches the
    SBG ``optimise.seeds`` times; the LSBG, which has no cutter, is searched once per
    spiral angle (its fronts serve every cutter of the angle).

    Parameters
    ----------
    config : dict
        The configuration, the schema's defaults filled in.

    Returns
    -------
    jobs : int
        Searches [-].
    cpu_hours : float
        Their estimated CPU time, :func:`evaluation_seconds` per design [h].
    """
    from lsbg.optimise.cells import trace_cells

    section = config.get("optimise", {})
    cells = trace_cells(config)
    searched = len(cells) + len({c["lsbg_cell"] for c in cells})
    jobs = searched * int(section.get("seeds", 3))
    designs = section.get("population", 20) * section.get("generations", 18)
    return jobs, jobs * designs * evaluation_seconds(config) / 3600


def _roughness_key(config):
    section = config.get("optimise", {})
    if section.get("flank_roughness_Ra_um") is not None:
        return "optimise.flank_roughness_Ra_um", section["flank_roughness_Ra_um"]
    return "rating.flank_roughness_um", config.get("rating", {}).get("flank_roughness_um", 8)


def lubricant_of(config):
    """The lubricant of the ``optimise`` section, its unset keys the ``rating`` section's.

    Returns
    -------
    lsbg.optimise.friction.Lubricant

    Raises
    ------
    ValueError
        Naming the key at fault.
    """
    section, rating = config.get("optimise", {}), config.get("rating", {})
    nu = section.get("oil_viscosity_mm2_s")
    nu_key = "optimise.oil_viscosity_mm2_s"
    if nu is None:
        nu, nu_key = rating.get("oil_viscosity_mm2_s", 150), "rating.oil_viscosity_mm2_s"
    ra = section.get("flank_roughness_Ra_um")
    roughness = ra * 1e-6 if ra is not None else \
        rating.get("flank_roughness_um", 8) * 1e-6 / RZ_PER_RA
    density = section.get("oil_density_kg_m3", 880)
    try:
        return Lubricant(kinematic_viscosity=nu * 1e-6, density=density, roughness=roughness)
    except (TypeError, ValueError) as error:
        key = {"kinematic_viscosity": nu_key, "density": "optimise.oil_density_kg_m3",
               "roughness": _roughness_key(config)[0]}[str(error).split(" ", 1)[0]]
        raise ValueError(f"{key}: {error}") from None


def rated_torque(design, config):
    """The design's rated gear torque [N m]: ``optimise.rated_torque_N_m``, or the
    gear torque at which ISO 10300's contact stress reaches its permissible value
    (:func:`lsbg.rating.config.rate_design` with the ``rating`` and ``tooth``
    sections at the simulation's pinion speed; 485 N m for the paper's pair)."""
    value = config.get("optimise", {}).get("rated_torque_N_m")
    if value is not None:
        return float(value)
    from lsbg.rating.config import rate_design

    simulation = config.get("simulation", {})
    speed = math.radians(simulation.get("pinion_speed_deg_s", 7703))
    load = simulation.get("load_torque_N_m", 1964.99)
    rating = rate_design(design, config.get("rating", {}), config.get("tooth", {}), load,
                         speed)[0]
    z1, z2 = design.teeth
    return float(rating.rated_pinion_torque_contact * z2 / z1)


def run_settings(config, design):
    """The space, the evaluation's settings and the search's of a configuration.

    Parameters
    ----------
    config : dict
        The configuration (:func:`lsbg.config.resolve_config`), defaults filled in.
    design : lsbg.gear.design.GearPairDesign

    Returns
    -------
    dict
        ``space`` (DesignSpace), ``evaluation`` (EvaluationSettings), ``objectives``,
        ``population``, ``generations``, ``seed``, ``algorithm``, ``choice``,
        ``choose_from``, ``start_from_shared``, ``workers``,
        ``permissible_pressure`` [MPa; None: the shared design's own] and
        ``reference`` (the configuration's ``flank_modification``, the shared design).

    Raises
    ------
    ValueError
        The first of :func:`optimise_problems`, before any evaluation.
    """
    from lsbg.contact import ContactParameters
    from lsbg.tca.misalignment import Misalignment
    from lsbg.tca.modification import FlankModification

    problems = optimise_problems(config)
    if problems:
        raise ValueError(problems[0])
    section = config["optimise"]
    tooth = config.get("tooth", {})
    edge_radius = (tooth.get("fillet_radius_module", 0.25) * design.mean_module
                   * math.cos(design.spiral_angle))
    evaluation = EvaluationSettings(
        rated_torque=rated_torque(design, config),
        load_factors=tuple(float(f) for f in section["load_factors"]),
        phases=int(section["phases"]),
        base=Misalignment.from_config(config.get("misalignment", {})),
        corners=envelope_corners_of(config),
        pinion_speed=math.radians(config.get("simulation", {}).get("pinion_speed_deg_s", 7703)),
        friction_law=section["friction_law"],
        lubricant=lubricant_of(config),
        young_modulus=tooth.get("young_modulus_GPa", 206) * 1e9,
        poisson_ratio=tooth.get("poisson_ratio", 0.3),
        pattern_margin=float(section["pattern_margin"]),
        edge_load_tolerance=float(section["edge_load_tolerance"]),
        marking=config.get("tca", {}).get("marking_compound_um", 6.35) * 1e-6,
        check_positions=int(config.get("misalignment_map", {}).get("positions", 100)),
        contact=ContactParameters.from_config(config.get("contact", {})),
        edge_radius=edge_radius)
    reference = FlankModification.from_config(config.get("flank_modification", {}))
    # None: the shared design's own largest pressure at the rated torque, set once
    # it is evaluated (lsbg.optimise.run.optimise_pair). At the rated torque ISO
    # 10300's sigma_H equals its permissible value by definition, while the line
    # model's Hertz p0 runs 15-30 % above sigma_Hlim for every design: against
    # sigma_Hlim no member qualifies and the rule falls back to the least pressure.
    permissible = section.get("permissible_pressure_MPa")
    return {"space": DesignSpace.from_config(section.get("bounds", {}), reference),
            "evaluation": evaluation, "objectives": tuple(section["objectives"]),
            "population": int(section["population"]),
            "generations": int(section["generations"]), "seed": int(section["seed"]),
            "algorithm": section["algorithm"], "choice": section["choice"],
            "choose_from": section["choose_from"], "workers": int(section["workers"]),
            "start_from_shared": bool(section["start_from_shared"]),
            "permissible_pressure": None if permissible is None else float(permissible),
            "reference": reference}
