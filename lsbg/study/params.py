"""What each rule's job depends on: its ``params`` (the rerun trigger), the study's
settings file and the time the rule requests.

Snakemake reruns a job when its ``params`` change: :func:`simulation_params`
and :func:`contact_state_params` hold exactly the settings a job reads
(keys sorted, :func:`canonical`), so editing a setting reruns the jobs that
read it and no other. :func:`write_study_config` writes the sections lsbg's
commands read (``results/config.yaml``).
"""

from __future__ import annotations

import math
from pathlib import Path

import yaml

from lsbg.study.points import map_steps

__all__ = ["FLANK_SECTIONS", "CONTACT_STATE_SECTIONS", "STUDY_SECTIONS", "ENGINE_ONLY_KEYS",
           "MODEL_ONLY_KEYS", "canonical", "yaml_text", "write_study_config",
           "engine_simulation", "simulation_params", "contact_state_params", "BUDGET_PER_SECOND",
           "simulation_runtime"]

#: The contact state: the flanks every line-model analysis and run reads
#: (lsbg.cli.options.flanks_from_args), and the settings of `lsbg misalignment-map`.
FLANK_SECTIONS = ("flank_modification", "misalignment")
CONTACT_STATE_SECTIONS = (*FLANK_SECTIONS, "tca", "misalignment_map")
#: Sections of the configuration that lsbg's commands read from results/config.yaml:
#: every section a command of the workflow names (tests/study/test_plan.py checks it
#: against the commands' parsers; a missing one runs that command on its defaults).
STUDY_SECTIONS = ("design", "simulation", "driveline", "contact", *CONTACT_STATE_SECTIONS,
                  "statistics", "tooth", "rating", "practice", "optimise", "limits")


#: Simulation keys that only some engines read.
ENGINE_ONLY_KEYS = {"time_step_s": ("pybullet",), "method": ("scipy",),
                    "compiled_method": ("compiled",), "rtol": ("scipy", "compiled")}
#: Contact keys that only one model reads (``model`` itself: the rules name it).
MODEL_ONLY_KEYS = {
    "point": ("stiffness_N_per_mm1_5", "exponent", "damping_N_s_per_mm", "penetration_depth_mm"),
    "line": ("line_stiffness_N_per_mm_um", "mesh_damping_ratio", "slices",
             "line_approach_limit_mm", "compliance"),
}


def canonical(value):
    """``value`` with every mapping's keys sorted: stable ``params`` for the rerun trigger."""
    if isinstance(value, dict):
        return {key: canonical(value[key]) for key in sorted(value)}
    if isinstance(value, list):
        return [canonical(item) for item in value]
    return value


def yaml_text(data, comment):
    """``data`` as YAML (keys sorted) under the comment line ``comment``."""
    body = yaml.safe_dump(canonical(dict(data)), sort_keys=False)
    return f"# {comment}\n{body}"


def write_study_config(path, config, only_if_missing=False):
    """Write the validated settings lsbg reads to ``path`` if they changed.

    The rules take the file as ancient() input and rerun on a change of their
    own settings (params), not on the file's time stamp. The workflow writes it
    when parsed only if it is missing (a dry run, or a second invocation
    refused by the lock, must not change it under a running workflow), and in
    its ``onstart`` handler (real runs, under Snakemake's lock) if it changed.
    Not by a rule: when a job upstream of an ancient() input runs, Snakemake
    9.27 skips the params check of the jobs below it, so they would not rerun.
    """
    path = Path(path)
    if only_if_missing and path.exists():
        return
    # (the speed sweep's section only where the study has one: its presence starts it)
    sections = {s: config[s] for s in (*STUDY_SECTIONS, "speed_sweep") if s in config}
    text = yaml_text(sections,
                     "the lsbg study settings as validated (written by the workflow; do not edit)")
    if path.exists() and path.read_text(encoding="utf-8") == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    part = path.with_name(f"{path.name}.part")
    part.write_text(text, encoding="utf-8")
    part.replace(path)


def engine_simulation(config, engine):
    """The ``simulation`` section without the keys only other engines read
    (:data:`ENGINE_ONLY_KEYS`).

    Parameters
    ----------
    config : dict
        A checked configuration.
    engine : str
        ``compiled``, ``scipy`` or ``pybullet``.

    Returns
    -------
    dict
    """
    return {k: v for k, v in config["simulation"].items()
            if engine in ENGINE_ONLY_KEYS.get(k, (engine,))}


def simulation_params(config, engine, model):
    """The simulation and contact settings a run of ``engine`` and ``model`` depends on
    (the rules' rerun trigger).

    The line model's contact settings include the flanks it runs on: the
    ``flank_modification`` and ``misalignment`` sections (every line-model
    command applies them; the point model keeps the conjugate flanks), so
    that every rule whose trigger holds them (the loaded TCA's too) reruns on
    a change of the contact state; under ``compliance: fe`` also the ``tooth``
    section (the FE compliance it runs on). The boundary only where it is the
    driveline, with the ``driveline`` section (the prescribed pinion's runs keep
    the trigger they had before the boundary was a setting).
    """
    simulation = engine_simulation(config, engine)
    if simulation.get("boundary", "prescribed_pinion") == "prescribed_pinion":
        simulation.pop("boundary", None)
    else:
        simulation["driveline"] = config.get("driveline", {})
    others = {key for name, keys in MODEL_ONLY_KEYS.items() if name != model for key in keys}
    contact = {k: v for k, v in config["contact"].items() if k not in others and k != "model"}
    if model == "line":
        contact.update({section: config.get(section, {}) for section in FLANK_SECTIONS})
        if contact.get("compliance") == "fe":
            contact["tooth"] = config.get("tooth", {})
    return canonical({"simulation": simulation, "contact": contact})


def contact_state_params(config, spiral, engine):
    """What a design point's contact-state job (``lsbg misalignment-map``) depends on
    (its rule's rerun trigger): the contact-state sections, the map's steps there,
    the line model's contact settings and the load of the loaded TCAs."""
    load = config["misalignment_map"].get("load_torque_N_m")
    return canonical({
        **{section: config[section] for section in CONTACT_STATE_SECTIONS},
        "steps": map_steps(config, spiral),
        "contact": simulation_params(config, engine, "line")["contact"],
        "load_torque_N_m": config["simulation"]["load_torque_N_m"] if load is None else load,
    })


#: Budgeted wall time per simulated second and run [s]: a bound well above every
#: engine's (tests/benchmarks/bench_dynamics.py measures them).
BUDGET_PER_SECOND = 100.0


def simulation_runtime(config, runs=1):
    """Cluster time limit [min] of ``runs`` simulations (generous, at least 10 min)."""
    return max(10, math.ceil(runs * config["simulation"]["duration_s"] * BUDGET_PER_SECOND / 60))


