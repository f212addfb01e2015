"""Helpers of the lsbg workflow (no rules here).

* the configuration: validated against workflow/schemas/config.schema.yaml
  (snakemake.utils.validate, which also fills in the schema's defaults), then
  every design point and the simulation/contact settings by lsbg's own checks,
  all before any job runs; each problem is reported with its key;
* design points, wildcard formatting and the file names of every stage;
* the lsbg source files each stage runs (inputs of its rules, so that editing
  one reruns exactly the jobs that use it);
* resources for a cluster executor.

Paths are relative to the working directory (where results/, logs/ and
reports/ are written); the repository's own files (lsbg/*.py, the notebooks)
are found next to the top-level Snakefile, see :func:`repo_path`.
"""

import math
import os
from pathlib import Path

import yaml
from snakemake.exceptions import WorkflowError
from snakemake.logging import logger
from snakemake.utils import validate

#: The repository: the directory of the top-level Snakefile.
REPO = Path(workflow.basedir).resolve()
SCHEMA = REPO / "workflow" / "schemas" / "config.schema.yaml"
LSBG = REPO / "lsbg"

#: Both traces run at the paper's design point (the paper compares them).
PAPER_TRACES = ("logarithmic", "circular")
REPORT_NAMES = ("paper", "sweep", "verification")

#: Software of the shell rules (used with --software-deployment-method conda,
#: e.g. --profile workflow/profiles/conda); relative to the .smk files.
CONDA_ENV = "../envs/lsbg.yaml"


def repo_path(relative):
    """A file of the repository, relative to the working directory if it lies inside it.

    Run from the repository root (the documented way) this is just ``relative``;
    run elsewhere (``--directory``, ``--snakefile``) it is the absolute path.
    """
    path = REPO / relative
    inside = os.path.relpath(path)
    return path.as_posix() if inside.startswith("..") else Path(inside).as_posix()


def angle_label(value):
    """Wildcard text of an angle or a torque: 35 -> "35", 37.5 -> "37.5" (no exponent)."""
    return f"{float(value):.6f}".rstrip("0").rstrip(".")


def sensitivity_contact(contact, key, factor):
    """The line model's contact setting of a sensitivity case: ``key`` scaled by ``factor``."""
    value = contact[key] * factor
    return {key: int(round(value)) if key == "slices" else value}


def sensitivity_case(key, factor):
    """Name of a sensitivity case, e.g. ``mesh_damping_ratio_x0.5``."""
    return f"{key}_x{angle_label(factor)}"


def sensitivity_option(case):
    """``lsbg simulate`` options of a sensitivity case (its changed contact setting)."""
    changed = sensitivity_contact(config["contact"], *SENSITIVITY[case])
    return " ".join(f"--set-contact {key}={value!r}" for key, value in changed.items())


# ------------------------------------------------------------- configuration
def _key_path(parts):
    """``["sweep", "spiral_angles_deg", 2]`` -> ``"sweep.spiral_angles_deg[2]"``."""
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "(top level)"


def schema_problems(config):
    """Every violation of the schema, one line each, starting with the key path."""
    import jsonschema

    with open(SCHEMA, encoding="utf-8") as handle:
        schema = yaml.safe_load(handle)
    problems = []
    for error in jsonschema.Draft202012Validator(schema).iter_errors(config):
        where = list(error.absolute_path)
        if error.validator == "additionalProperties":
            known = sorted(error.schema.get("properties", {}))
            problems += [f"{_key_path(where + [key])}: unknown key (known: {', '.join(known)})"
                         for key in sorted(set(error.instance) - set(known))]
        else:
            problems.append(f"{_key_path(where)}: {error.message}")
    return sorted(problems)


def study_problems(config):
    """What the schema cannot check: each design point and the settings, by lsbg itself."""
    from lsbg.contact import ContactParameters
    from lsbg.design import DesignError, GearPairDesign
    from lsbg.dynamics import SimulationSettings

    problems = []
    points = {(t, angle_label(s)) for t in config["sweep"]["traces"]
              for s in config["sweep"]["spiral_angles_deg"]}
    points |= {(t, angle_label(config["paper_spiral_angle_deg"])) for t in PAPER_TRACES}
    failing = {}  # message -> design points
    for trace, spiral in sorted(points, key=lambda point: (point[0], float(point[1]))):
        try:
            GearPairDesign.from_config({**config["design"], "trace": trace,
                                        "spiral_angle_deg": float(spiral)})
        except DesignError as error:
            failing.setdefault(str(error), []).append(f"{trace} {spiral} deg")
    problems += [f"design at {', '.join(where)}: {message}" for message, where in failing.items()]
    sweep_engine, reference = config["engines"]["sweep"], config["engines"]["reference"]
    if not set(reference) - {sweep_engine}:
        problems.append(f"engines.reference = {reference!r}: needs an engine other than "
                        f"engines.sweep = {sweep_engine!r} (the paper report compares them)")
    if config["engines"]["paper"] not in {sweep_engine, *reference}:
        problems.append(f"engines.paper = {config['engines']['paper']!r}: must be engines.sweep "
                        f"or one of engines.reference {reference!r}")
    for engine in sorted({sweep_engine, *reference}):
        try:
            SimulationSettings.from_config(config["simulation"], engine=engine)
        except ValueError as error:
            problems.append(str(error))
    try:
        ContactParameters.from_config(config["contact"])
    except ValueError as error:
        problems.append(str(error))
    for key, factors in config["sensitivity"].items():
        for k, factor in enumerate(factors):
            try:
                ContactParameters.from_config({**config["contact"], "model": "line",
                                               **sensitivity_contact(config["contact"], key, factor)})
            except ValueError as error:
                problems.append(f"sensitivity.{key}[{k}] = {factor!r}: {error}")
    duration = config["simulation"]["duration_s"]
    steady = config["statistics"]["steady_state_after_s"]
    if steady >= duration:
        problems.append(f"statistics.steady_state_after_s = {steady!r}: "
                        f"must be below simulation.duration_s = {duration!r}")
    start, stop = config["statistics"]["control_chart_window_s"]
    if not start < stop <= duration * (1 + 1e-9):
        problems.append(f"statistics.control_chart_window_s = {[start, stop]!r}: needs "
                        f"start < stop <= simulation.duration_s = {duration!r}")
    return list(dict.fromkeys(problems))


def check_config(config):
    """Validate ``config`` in place (schema defaults filled in); raise naming every bad key."""
    try:
        validate(config, str(SCHEMA))
    except WorkflowError as error:
        problems = schema_problems(config) or [str(error)]
        raise WorkflowError("invalid configuration (workflow/schemas/config.schema.yaml):\n  "
                            + "\n  ".join(f"config key {p}" for p in problems)) from None
    problems = study_problems(config)
    if problems:
        raise WorkflowError("invalid configuration:\n  " + "\n  ".join(problems))


check_config(config)


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


def write_design_file(path, design, log):
    """Write the design section to ``path`` (rule design_file); say so in ``log``."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(yaml_text(design, "config['design'] of the study; the trace and the "
                                            "spiral angle are those of each design point"),
                          encoding="utf-8")
    Path(log).parent.mkdir(parents=True, exist_ok=True)
    Path(log).write_text(f"wrote {path}\n", encoding="utf-8")


#: Sections of the study configuration that lsbg's commands read from
#: results/config.yaml (--config).
STUDY_SECTIONS = ("simulation", "contact", "statistics")


def write_study_config(path, only_if_missing=False):
    """Write the validated settings lsbg reads to ``path`` if they changed.

    The rules take the file as ancient() input and rerun on a change of their
    own settings (params), not on the file's time stamp. It is written when the
    workflow is parsed only if it is missing (a dry run, or a second invocation
    refused by the lock, must not change it under a running workflow), and by
    the ``onstart`` handler (real runs, under Snakemake's lock) if it changed.
    Not by a rule: when a job upstream of an ancient() input runs, Snakemake
    9.27 skips the params check of the jobs below it, so they would not rerun.
    """
    path = Path(path)
    if only_if_missing and path.exists():
        return
    text = yaml_text({s: config[s] for s in STUDY_SECTIONS},
                     "the lsbg study settings as validated (written by the workflow; do not edit)")
    if path.exists() and path.read_text(encoding="utf-8") == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    part = path.with_name(f"{path.name}.part")
    part.write_text(text, encoding="utf-8")
    part.replace(path)


#: Simulation keys that only some engines read.
ENGINE_ONLY_KEYS = {"time_step_s": ("pybullet",), "method": ("scipy",),
                    "compiled_method": ("compiled",), "rtol": ("scipy", "compiled")}
#: Contact keys that only one model reads (model itself: the rules name it).
MODEL_ONLY_KEYS = {
    "point": ("stiffness_N_per_mm1_5", "exponent", "damping_N_s_per_mm", "penetration_depth_mm"),
    "line": ("line_stiffness_N_per_mm_um", "mesh_damping_ratio", "slices",
             "line_approach_limit_mm"),
}


def simulation_params(engine, model):
    """The simulation and contact settings that a run of ``engine`` and ``model`` depends on."""
    simulation = {k: v for k, v in config["simulation"].items()
                  if engine in ENGINE_ONLY_KEYS.get(k, (engine,))}
    others = {key for name, keys in MODEL_ONLY_KEYS.items() if name != model for key in keys}
    contact = {k: v for k, v in config["contact"].items() if k not in others and k != "model"}
    return canonical({"simulation": simulation, "contact": contact})



# ------------------------------------------------------ design points, files
TRACES = list(config["sweep"]["traces"])
SPIRALS = [angle_label(a) for a in config["sweep"]["spiral_angles_deg"]]
SWEEP_MODELS = list(config["sweep"]["contact_models"])
PAPER_SPIRAL = angle_label(config["paper_spiral_angle_deg"])
SWEEP_ENGINE = config["engines"]["sweep"]
REFERENCE_ENGINES = [e for e in config["engines"]["reference"] if e != SWEEP_ENGINE]
PAPER_ENGINES = [SWEEP_ENGINE, *REFERENCE_ENGINES]
PAPER_ENGINE = config["engines"]["paper"]
CONTACT_MODELS = ("point", "line")
#: Sensitivity case -> (contact key, factor).
SENSITIVITY = {sensitivity_case(key, factor): (key, factor)
               for key, factors in config["sensitivity"].items() for factor in factors}

WILDCARDS = {
    "trace": "|".join(PAPER_TRACES),
    "spiral": r"\d+(\.\d+)?",
    "engine": "pybullet|scipy|compiled",
    "model": "point|line",
    "case": "|".join(SENSITIVITY) or "none",
}


wildcard_constraints:
    **WILDCARDS,


DESIGN_FILE = "results/design.yaml"
STUDY_CONFIG = "results/config.yaml"
GEOMETRY = "results/geometry/{trace}_beta{spiral}"
MESH = "results/mesh/{trace}_beta{spiral}.nc"
RUN = "results/runs/{trace}_beta{spiral}_{model}_{engine}.nc"
SENSITIVITY_RUN = "results/sensitivity/{trace}_beta{spiral}_{case}.nc"
CONVERGENCE = "results/verification/convergence_{trace}_{model}.csv"
SWEEP_FILE = "results/sweep.nc"
SUMMARY_FILE = "results/summary.csv"
REPORT = "reports/{name}.html"

write_study_config(STUDY_CONFIG, only_if_missing=True)


def geometry_dir(trace, spiral):
    return GEOMETRY.format(trace=trace, spiral=spiral)


def mesh_file(trace, spiral):
    return MESH.format(trace=trace, spiral=spiral)


def run_file(trace, spiral, model, engine):
    return RUN.format(trace=trace, spiral=spiral, model=model, engine=engine)


def sensitivity_file(trace, spiral, case):
    return SENSITIVITY_RUN.format(trace=trace, spiral=spiral, case=case)


#: Runs of the sweep: every trace at every spiral angle, every sweep model, the sweep engine.
SWEEP_RUNS = [run_file(t, s, m, SWEEP_ENGINE) for m in SWEEP_MODELS for t in TRACES for s in SPIRALS]
#: Runs at the paper's design point: both traces, both models, every engine.
PAPER_RUNS = [run_file(t, PAPER_SPIRAL, m, e) for m in CONTACT_MODELS for e in PAPER_ENGINES
              for t in PAPER_TRACES]
ALL_RUNS = list(dict.fromkeys(SWEEP_RUNS + PAPER_RUNS))
#: Loaded TCAs: every design point of the sweep and the paper's.
MESHES = list(dict.fromkeys([mesh_file(t, s) for t in TRACES for s in SPIRALS]
                            + [mesh_file(t, PAPER_SPIRAL) for t in PAPER_TRACES]))
SENSITIVITY_RUNS = [sensitivity_file(t, PAPER_SPIRAL, case) for case in SENSITIVITY
                    for t in PAPER_TRACES]
PAPER_GEOMETRY = [geometry_dir(t, PAPER_SPIRAL) for t in PAPER_TRACES]
CONVERGENCE_FILES = [CONVERGENCE.format(trace=t, model=m) for m in CONTACT_MODELS
                     for t in PAPER_TRACES]
REPORTS = {name: REPORT.format(name=name) for name in REPORT_NAMES}

#: Targets of ``rule all``; an extension appends its own (see workflow/extensions).
STUDY_TARGETS = [*REPORTS.values(), SWEEP_FILE, SUMMARY_FILE]
EXTENSION_TARGETS = []


def yaml_list(items):
    """A list as one ``--param`` value, which lsbg reads with yaml.safe_load."""
    return "[" + ", ".join(items) + "]"


# ---------------------------------------------------------- lsbg per stage
def sources(stage):
    """Inputs of the rules of ``stage``: the lsbg files it runs (lsbg.stages.STAGE_MODULES)."""
    from lsbg.stages import stage_sources

    return stage_sources(stage, root=os.getcwd())


def notebook(name):
    return repo_path(f"workflow/notebooks/{name}.ipynb")


def check_installed_lsbg():
    """Warn if the ``lsbg`` that the rules run is not the one next to this Snakefile."""
    import lsbg

    installed = Path(lsbg.__file__).resolve().parent
    if installed != LSBG:
        logger.warning(f"lsbg is imported from {installed}, not from {LSBG}: the rules run "
                       f"and track the sources there.")


check_installed_lsbg()


# ------------------------------------------------------------------ resources
def simulation_runtime(runs=1):
    """Cluster time limit [min] of ``runs`` simulations (generous, at least 10 min).

    Measured (tests/benchmarks/bench_dynamics.py): 1 s simulated takes about
    9 s of wall time with PyBullet at 1 µs steps, 3-9 s with scipy at rtol
    1e-8 and about 1 s with the compiled engine. Budgeted: 100 s per
    simulated second and run.
    """
    return max(10, math.ceil(runs * config["simulation"]["duration_s"] * 100 / 60))
