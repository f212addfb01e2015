"""Glue between Snakemake and lsbg (no rules here).

The configuration is checked completely by lsbg.study.checks.check_config
(finite numbers, lsbg/schemas/config.schema.yaml, file names, lsbg's own
checks of the settings and the statistics, the physics and the resource
guard of every design point), which also fills in the schema's defaults,
before any job runs; each problem is one line naming the user's key.
lsbg.study.plan.Study then names every design point, run and file; the rules
read it as STUDY (docs/architecture.md lists what an extension may read).

Each rule is its inputs, outputs, log and rerun triggers; each runs one
`lsbg` command (shell: LSBG) whose options are the rule's named inputs and
outputs (`params: **command("ltca")`, :func:`command`), its wildcards set the
design point (`--set design.trace=...`), and its source inputs are the lsbg
files the command's handler reaches (:func:`sources`, from the imports).
Priorities come from the rule graph and the conda environment from CONDA_ENV
once all rules are defined (the end of the Snakefile, :func:`finish_rules`);
memory and time from the profile (workflow/profiles/slurm) or :func:`runtime`.
"""

import os
import shlex
import sys
from functools import lru_cache
from pathlib import Path

from snakemake.logging import logger

from lsbg.config import SCHEMA_PATH, load_schema
from lsbg.files import duplicate_key_problems
from lsbg.study import checks as config_check
from lsbg.study import plan
from lsbg.study.params import engine_simulation

#: The repository: the directory of the top-level Snakefile.
REPO = Path(workflow.basedir).resolve()
SCHEMA = SCHEMA_PATH  # package data, as the report notebooks (NOTEBOOKS)
#: The report notebooks: lsbg.reports.NOTEBOOK_DIR (lsbg.reports imports pandas; not here).
NOTEBOOKS = SCHEMA_PATH.parents[1] / "notebooks"
#: Software of every rule (with --software-deployment-method conda).
CONDA_ENV = (REPO / "workflow" / "envs" / "lsbg.yaml").as_posix()
#: Extensions: the repository's, then the study folder's own (docs/usage.md, "A study of your own").
EXTENSION_DIRS = (REPO / "workflow" / "extensions", Path("workflow") / "extensions")


def extension_file(name):
    """The file of an extension named in the ``extensions`` list (the study's own first)."""
    for folder in reversed(EXTENSION_DIRS):
        if (folder / f"{name}.smk").is_file():
            return (folder / f"{name}.smk").resolve().as_posix()
    return None


def check_config(config):
    """Check ``config`` (schema defaults filled in, in place); stop naming every bad key.

    The checks that need no analysis, while the workflow is parsed (``snakemake -n``
    too); those that run one at the design points (a TCA, an FE section, an ISO
    10300 rating) by :func:`check_analyses`, before the first job. Printed and exited
    rather than raised: Snakemake prints a raised error with the stack lines of this
    file around the message. Inside a job (a SLURM job's Snakemake and its job step)
    the submitting Snakemake has checked the same configuration: only the defaults
    are filled in there.
    """
    schema = load_schema(SCHEMA)   # libyaml's loader: read by every Snakemake of a job too
    if workflow.remote_exec or workflow.subprocess_exec:
        config_check.fill_defaults(config, schema)
        return
    duplicated = duplicate_key_problems(workflow.configfiles)
    if duplicated:
        logger.error("invalid configuration file:\n" + "\n".join(f"  {p}" for p in duplicated))
        sys.exit(1)
    # (given: what the study's --configfile files and --config set over workflow/config.yaml)
    problems = config_check.check_config(config, schema, analyses=False,
                                         given=workflow.config_settings.overwrite_config)
    known = sorted({p.stem for folder in EXTENSION_DIRS for p in folder.glob("*.smk")})
    problems += [f"extensions[{k}] = {name!r}: no workflow/extensions/{name}.smk here or in "
                 f"the repository (known: {', '.join(known)})"
                 for k, name in enumerate(config.get("extensions", []))
                 if extension_file(name) is None]
    stop_if(problems)


def check_analyses():
    """The checks that run an analysis at each design point
    (lsbg.study.checks.analysis_problems): called by the Snakefile's ``onstart``,
    in the submitting Snakemake, after the plan and before any job runs. The settings
    file this parse wrote for the plan is removed if they fail (it says "as validated")."""
    problems = (config_check.analysis_problems(config)
                + config_check.practice_analysis_problems(config))
    if problems and not STUDY_CONFIG_KEPT:
        Path(FILES["study_config"]).unlink(missing_ok=True)
    stop_if(problems)


def report_search_estimate():
    """Print the ease-off searches' cells, job count and estimated CPU-hours (the
    Snakefile's ``onstart``, before any job; lsbg.optimise.checks.search_estimate)."""
    if not STUDY.optimise:
        return
    from lsbg.optimise.checks import search_estimate

    jobs, hours = search_estimate(config)
    cells = STUDY.trace_cells
    o = config["optimise"]
    logger.info(f"ease-off searches: {jobs} jobs in {len(cells)} cell(s) of the trace study "
                f"(the SBG per cell, the LSBG per spiral angle, {o['seeds']} seeds each, "
                f"{o['population']} x {o['generations']} designs each), about {hours:.3g} "
                f"CPU-hours estimated, {o['workers']} CPUs per job; then per trace and cell a "
                f"release and a converge-front job, and per cell a trace-fronts job")
    cell_jobs = STUDY.trace_study_jobs
    if len(cells) > 1:
        logger.info(f"the trace study's {len(cells) - 1} cell(s) beyond the paper's: "
                    f"{sum(cell_jobs.values())} jobs ("
                    + ", ".join(f"{rule} {n}" for rule, n in cell_jobs.items()) + ")")


def stop_if(problems):
    """Print ``problems`` (lines naming a configuration key) and exit 1, if any."""
    if problems:
        logger.error("invalid configuration (keys as in lsbg/schemas/config.schema.yaml):\n"
                     + "\n".join(f"  config key {p}" for p in problems))
        sys.exit(1)


check_config(config)
STUDY = plan.Study(config)
FILES = plan.FILES
SWEEP_ENGINE = STUDY.sweep_engine
PAPER_SPIRAL = STUDY.paper_spiral
#: The paper point's own jobs are the paper pair's (a wildcard constraint): another trace of
#: the sweep (face_milled) has its paper angle in its batch jobs (points.smk).
PAPER_PAIR = {"trace": "|".join(plan.PAPER_TRACES)}


wildcard_constraints:
    **STUDY.wildcards,


STUDY_CONFIG_KEPT = Path(FILES["study_config"]).exists()  # (check_analyses)
plan.write_study_config(FILES["study_config"], config, only_if_missing=True)
#: Targets of ``rule all``; an extension appends its own (see workflow/extensions).
EXTENSION_TARGETS = []


def check_installed_lsbg():
    """Warn if the ``lsbg`` that the rules run is not the one next to this Snakefile."""
    import lsbg

    installed = Path(lsbg.__file__).resolve().parent
    if installed != REPO / "lsbg":
        logger.warning(f"lsbg is imported from {installed}, not from {REPO / 'lsbg'}: the "
                       f"rules run and track the sources there.")


check_installed_lsbg()


# ---------------------------------------------------------------- the job server
#: The running job server (lsbg.cli.job_server), if this run started one.
JOB_SERVER = []


def start_job_server():
    """Under local execution: a server that forks the jobs' lsbg processes from one
    that has done their imports (about 1.2 s a job; LSBG_JOB_SERVER=0 turns it off).
    Not under SLURM or another executor: a job runs where its executor puts it."""
    if workflow.local_exec and not (workflow.remote_exec or workflow.touch or workflow.dryrun):
        from lsbg.cli import job_server

        server = job_server.start()
        if server is not None:  # (the jobs inherit the variable that names it)
            os.environ[job_server.SERVER_ENV] = job_server.socket_path(server)
            JOB_SERVER.append(server)


def stop_job_server():
    from lsbg.cli import job_server

    while JOB_SERVER:
        job_server.stop(JOB_SERVER.pop())


# ---------------------------------------------------------------- commands
#: The shell command of every rule: ``lsbg <params.command> <params.args>``.
def lsbg_shell(*settings):
    """A rule's shell: lsbg with the ``params`` of :func:`command`, into the log;
    ``settings`` are further ``--set`` values, which may name the job's ``{threads}``."""
    extra = "".join(f" --set {setting}" for setting in settings)
    return f"lsbg -v {{params.command}} {{params.args}}{extra} > {{log}} 2>&1"


LSBG = lsbg_shell()
#: Wildcards that name a setting of the command: ``--set KEY=VALUE``.
WILDCARD_SETTINGS = {"trace": "design.trace", "spiral": "design.spiral_angle_deg",
                     "model": "contact.model"}


def _subparser(name):
    from lsbg.cli import command_parsers

    return command_parsers()[name]


def _actions(name):
    """{name: argparse action} of an lsbg subcommand's options, each by its long option's
    name (``--compliance-file`` -> ``compliance_file``, ``--config`` -> ``config``)."""
    return {action.option_strings[-1].lstrip("-").replace("-", "_"): action
            for action in _subparser(name)._actions if action.option_strings}


def _words(action, value):
    """The words that give ``action`` the value ``value`` (a repeatable option once per
    item, a flag for True, nothing for None, False or an empty list)."""
    option = action.option_strings[-1]
    items = [value] if isinstance(value, (str, int, float)) else list(value or ())
    if value is True:
        return [option]
    if value is False or not items:
        return []
    if type(action).__name__ == "_AppendAction":  # (an item may be several words: --point)
        return [word for item in items for word in
                (option, *map(str, item if isinstance(item, (list, tuple)) else [item]))]
    return [option, *map(str, items)]


def case_values(stage, keys=None):
    """The ``--case KEY=VALUE`` values of the sensitivity cases that reach ``stage`` (of
    the sensitivity keys ``keys`` only, if given: the practice and best pairs')."""
    from lsbg.experiments.sensitivity import CASE_STAGES

    return [f"{key}={value!r}" for key, values in config["sensitivity"].items()
            if stage in CASE_STAGES[key] and (keys is None or key in keys) for value in values]


def command(name, **extra):
    """The ``params`` that run ``lsbg <name>`` in a rule, whose shell is LSBG.

    The rule's named inputs and outputs whose names are options of the command
    (``geometry`` -> ``--geometry``, ``compliance_file`` -> ``--compliance-file``)
    become those options; the others (``sources``) only rerun it. Its wildcards
    ``trace``, ``spiral`` and ``model`` set the design point and the contact model
    (:data:`WILDCARD_SETTINGS`) where the command reads those sections, ``engine``
    is ``--engine``. ``extra`` adds options by their names in lsbg (a value, a
    list, True for a flag, or a function of the wildcards); ``set`` adds
    ``--set`` values.
    """
    actions = _actions(name)
    reads = _subparser(name).get_default("sections") or ()

    def args(wildcards, input, output):
        words = []
        for files in (input, output):
            for key, value in files.items():
                if key in actions:
                    words += _words(actions[key], value)
        settings = [f"{setting}={wildcards[key]}" for key, setting in WILDCARD_SETTINGS.items()
                    if key in wildcards.keys() and setting.split(".")[0] in reads]
        if "engine" in wildcards.keys() and "engine" in actions:
            words += ["--engine", wildcards.engine]
        for key, value in extra.items():
            value = value(wildcards) if callable(value) else value
            if key == "set":
                settings += list(value)
            else:
                words += _words(actions[key], value)
        words += _words(actions["set"], settings) if settings else []
        return shlex.join(words)

    return {"command": name, "args": args}


def notebook_report(name, **values):
    """``params`` of a rule that renders ``reports/<name>.html`` (``lsbg report``, with
    ``shell: LSBG``): each named input but ``notebook`` and ``sources`` is the notebook
    parameter of its name (a list of files, or one file for ``*_file``), ``values`` the
    others; the notebook runs from its own folder."""
    def args(wildcards, input, output):
        params = {key: (value if key.endswith("_file") else list(value))
                  for key, value in input.items() if key not in ("notebook", "sources")}
        params.update(values)
        words = ["--out", output[0], "--notebook-dir", os.path.dirname(input.notebook)]
        for key, value in params.items():
            text = f"[{', '.join(map(str, value))}]" if isinstance(value, list) else str(value)
            words += ["--param", f"{key}={text}"]
        return shlex.join(words)

    return {"command": f"report {name}", "args": args}


def finish_rules(rules):
    """Once all rules are defined: each rule's priority from the rule graph
    (lsbg.study.job_order) and, for a rule that runs a command, the workflow's conda
    environment (CONDA_ENV) unless it names its own."""
    defined = list(rules)
    plan.assign_priorities(defined, STUDY.sample_wildcards)
    for each in defined:
        if each.shellcmd and each.conda_env is None:
            each.conda_env = CONDA_ENV


def repo_path(relative):
    """A file of the repository (a path relative to it, or lsbg's package data), relative
    to the working directory if inside it: a copy of the study finds its inputs as recorded."""
    path = REPO / relative
    inside = os.path.relpath(path)
    return path.as_posix() if inside.startswith("..") else Path(inside).as_posix()


#: Where each command's sources are listed with their digests (one input per rule).
SOURCES = Path(".snakemake") / "lsbg-sources"


@lru_cache(maxsize=None)
def sources(name, notebook=None):
    """The input that reruns a rule when a source that ``lsbg <name>`` runs changes.

    Every lsbg file its handler reaches by its imports (and, for a report, the
    notebook's code; lsbg.study.stages), listed with its SHA-256 in one file,
    ``.snakemake/lsbg-sources/<name>.sha256``, rewritten only when a digest
    changes: one input per job instead of the files themselves (``snakemake -n``
    stays readable), and ``sha256sum -c`` on it names the changed file.
    """
    path = SOURCES / (f"{name}-{notebook}.sha256" if notebook else f"{name}.sha256")
    if workflow.remote_exec or workflow.subprocess_exec:
        # the submitting Snakemake wrote it: a job's two Snakemakes (a SLURM job's and
        # its job step's) spare following the imports, 1-2 CPU-s each
        return path.as_posix()
    from lsbg.study.stages import sources_listing, write_if_changed

    notebook_file = NOTEBOOKS / f"{notebook}.ipynb" if notebook else None
    listing = sources_listing(command_closure(name, notebook_file))
    return write_if_changed(path, listing).as_posix()


def command_closure(name, notebook_file=None):
    """The lsbg modules that ``lsbg <name>`` runs (and a report's notebook), sorted."""
    from lsbg.cli import handler_of
    from lsbg.study.stages import function_closure, notebook_closure

    handler = handler_of(name)
    modules = function_closure(handler.__module__.removeprefix("lsbg."), handler.__name__)
    if notebook_file is not None:
        modules |= notebook_closure(notebook_file)
    return sorted(modules)


def runtime(runs=1):
    """``resources`` of a simulation rule: its time limit [min] for ``runs`` runs."""
    return {"runtime": plan.simulation_runtime(config, runs)}


def points_resources(points):
    """``resources`` of a job of ``points`` design points (``lsbg points``): 2 min each, and
    under ``contact.compliance: fe`` the FE compliance's memory and time too."""
    own = STUDY.own_compliance
    return {"mem_mb": 4000 if own else 1000,
            "runtime": 10 + (2 + own * config["limits"]["tooth_minutes"]) * points}


def geometry_output(spiral="{spiral}"):
    """A design point's geometry directory as a rule's output, its picture in the report."""
    return report(directory(template(FILES["geometry"], spiral=spiral)), patterns=["{name}.png"],
                  caption="../report/geometry.rst", category="Geometry", subcategory="{trace}",
                  labels={"trace": "{trace}", "spiral angle [deg]": spiral})


def point_templates(**patterns):
    """Extra options of a command that writes several design points of a trace: file-name
    templates with ``{spiral}`` (filled in by lsbg), the trace from the wildcards."""
    return {option: (lambda w, p=pattern: template(p, trace=w.trace))
            for option, pattern in patterns.items()}


def template(pattern, **fields):
    """A file-name template of ``lsbg points``/``sensitivity``: some fields filled in,
    the others left as ``{field}`` for lsbg."""
    keep = {name: f"{{{name}}}" for name in ("trace", "spiral", "model", "engine", "case")}
    return pattern.format(**{**keep, **fields})


def fe_ltca_input(needed):
    """Input ``fe_ltca`` of line-model runs: the loaded TCA with the FE compliance of their
    design point (the paper's, where the wildcards name no angle), where ``needed(wildcards)``."""
    return lambda w: ([STUDY.fe_ltca(w.trace, getattr(w, "spiral", PAPER_SPIRAL))]
                      if needed(w) else [])


def simulation_params(engine, model):
    return plan.simulation_params(config, engine, model)


def practice_input(kind):
    """A practice design point's file as a rule's input (its trace from the wildcards)."""
    return lambda w: STUDY.practice_file(kind, w.trace)


def flank_file(flanks, kind):
    """A file of the practice design point with the ``flanks`` set's ease-off ("practice",
    "best"), as a rule's input (its trace from the wildcards)."""
    if flanks == "practice":
        return practice_input(kind)
    return lambda w: STUDY.best_file(kind, w.trace)


def case_template(flanks, kind):
    """The ``{case}`` template of a flank set's case files (``kind``: sensitivity_run,
    vh_case, fe_case) for ``--out``/``--case-out``, the design point from the wildcards."""
    return lambda w: template(FILES[f"{flanks}_{kind}"], trace=w.trace, spiral=w.spiral)


def design_set_input(paper, practice):
    """An input of a load curve: ``paper(wildcards)`` for the published pair, else
    ``practice(wildcards)`` (rules/practice.smk)."""
    return lambda w: paper(w) if w.design_set == "paper" else practice(w)


# ---------------------------------------------------------------- the trace study
def cell_config(w):
    """A cell's configuration: the study's, the practice overlay at the cell's angle."""
    return [ancient(FILES["study_config"]),
            STUDY.cell_file("practice_design", w.trace, w.cell)]


def cell_set(w):
    """The ``--set`` values of a cell's design point (its angle, an SBG's cutter): the
    geometry's (the later commands read the design from the geometry)."""
    return STUDY.cell_settings(w.cell, w.trace)


def cell_input(kind):
    """A file of the cell's own chain as a rule's input (from the wildcards)."""
    return lambda w: STUDY.cell_file(kind, w.trace, w.cell)


def cell_fronts(w):
    """A cell's trace's fronts, every seed's."""
    return [STUDY.cell_file("front", w.trace, w.cell, seed) for seed in STUDY.optimise_seeds]
