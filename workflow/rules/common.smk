"""Glue between Snakemake and lsbg.study.plan (no rules here).

The configuration is checked completely by lsbg.study.checks.check_config
(finite numbers, workflow/schemas/config.schema.yaml, file names, lsbg's own
checks of the settings and the statistics, the physics and the resource
guard of every design point), which also fills in the schema's defaults,
before any job runs; each problem is one line naming the user's key.
lsbg.study.plan.Study then names every design point, run and file; the rules
read it as STUDY. Paths are relative to the working directory; the
repository's own files (the notebooks) are found next to the Snakefile.
"""

import os
import sys
from pathlib import Path

import yaml
from snakemake.logging import logger

from lsbg.study import checks as config_check
from lsbg.study import plan
from lsbg.files import duplicate_key_problems

#: The repository: the directory of the top-level Snakefile.
REPO = Path(workflow.basedir).resolve()
SCHEMA = REPO / "workflow" / "schemas" / "config.schema.yaml"
#: Software of the shell rules (with --software-deployment-method conda).
CONDA_ENV = "../envs/lsbg.yaml"


def check_config(config):
    """Check ``config`` (schema defaults filled in, in place); stop naming every bad key.

    Printed and exited rather than raised: Snakemake prints a raised error with
    the stack lines of this file around the message. Inside a job (a SLURM job's
    Snakemake and its job step) the submitting Snakemake has checked the same
    configuration: only the defaults are filled in there, which spares every
    job about a CPU-second per Snakemake (the physics of every design point).
    """
    schema = yaml.safe_load(SCHEMA.read_text(encoding="utf-8"))
    if workflow.remote_exec or workflow.subprocess_exec:
        config_check.fill_defaults(config, schema)
        return
    duplicated = duplicate_key_problems(workflow.configfiles)
    if duplicated:
        logger.error("invalid configuration file:\n" + "\n".join(f"  {p}" for p in duplicated))
        sys.exit(1)
    problems = config_check.check_config(config, schema)
    known = sorted(p.stem for p in (REPO / "workflow" / "extensions").glob("*.smk"))
    problems += [f"extensions[{k}] = {name!r}: no workflow/extensions/{name}.smk (known: "
                 f"{', '.join(known)})" for k, name in enumerate(config.get("extensions", []))
                 if name not in known]
    if problems:
        logger.error("invalid configuration (keys as in workflow/schemas/config.schema.yaml):\n"
                     + "\n".join(f"  config key {p}" for p in problems))
        sys.exit(1)


check_config(config)
STUDY = plan.Study(config)
FILES = plan.FILES
SWEEP_ENGINE = STUDY.sweep_engine
PAPER_SPIRAL = STUDY.paper_spiral


wildcard_constraints:
    **STUDY.wildcards,


plan.write_study_config(FILES["study_config"], config, only_if_missing=True)
#: Targets of ``rule all``; an extension appends its own (see workflow/extensions).
EXTENSION_TARGETS = []


def repo_path(relative):
    """A file of the repository, relative to the working directory if inside it."""
    path = REPO / relative
    inside = os.path.relpath(path)
    return path.as_posix() if inside.startswith("..") else Path(inside).as_posix()


def sources(stage):
    """Inputs of the rules of ``stage``: the lsbg files it runs (lsbg.study.stages.STAGE_MODULES)."""
    from lsbg.study.stages import stage_sources

    return stage_sources(stage, root=os.getcwd())


def notebook(name):
    return repo_path(f"workflow/notebooks/{name}.ipynb")


def yaml_list(items):
    """A list as one ``--param`` value, which lsbg reads with yaml.safe_load."""
    return f"[{', '.join(items)}]"


def simulation_params(engine, model):
    return plan.simulation_params(config, engine, model)


def simulation_runtime(runs=1):
    return plan.simulation_runtime(config, runs)


def template(pattern, **fields):
    """A file-name template of ``lsbg points``/``sensitivity``: some fields filled in,
    the others left as ``{field}`` for lsbg."""
    keep = {name: f"{{{name}}}" for name in ("trace", "spiral", "model", "engine", "case")}
    return pattern.format(**{**keep, **fields})


def check_installed_lsbg():
    """Warn if the ``lsbg`` that the rules run is not the one next to this Snakefile."""
    import lsbg

    installed = Path(lsbg.__file__).resolve().parent
    if installed != REPO / "lsbg":
        logger.warning(f"lsbg is imported from {installed}, not from {REPO / 'lsbg'}: the "
                       f"rules run and track the sources there.")


check_installed_lsbg()


def fe_ltca_input(needed):
    """Input ``fe_ltca`` of line-model runs: the loaded TCA with the FE compliance of their
    design point (the paper's, where the wildcards name no angle), where ``needed(wildcards)``."""
    return lambda w: ([STUDY.fe_ltca(w.trace, getattr(w, "spiral", PAPER_SPIRAL))]
                      if needed(w) else [])


def fe_ltca_option(wildcards, input):
    """``--fe-ltca FILE`` of a run whose rule has the ``fe_ltca`` input, else nothing."""
    return f"--fe-ltca {input.fe_ltca}" if input.fe_ltca else ""
