"""The workflow's configuration, checked completely before any job runs.

:func:`check_config` is the one check ``workflow/rules/common.smk`` calls
while Snakemake reads the workflow (``snakemake -n`` included), before the
DAG is built, with ``analyses=False``: steps 8 to 10 and 12 below run an
analysis at the design points (a TCA, an FE section, an ISO 10300 rating,
the practice design's root finding) and are :func:`analysis_problems` and
:func:`practice_analysis_problems`, which the Snakefile's ``onstart`` runs in
the submitting Snakemake before the first job. Nothing is kept between runs.
It returns every problem as one line that starts with the
user's key path and value, in the configuration's units (``design.face_width_mm
= 500``, never lsbg's SI name ``face_width = 0.5``). In order (each step
assumes the ones before it passed):

1. every number is finite: JSON Schema's range keywords let NaN through
   (every comparison with NaN is false) and inf through any lower bound;
2. the schema (lsbg/schemas/config.schema.yaml): types, ranges, enums,
   list lengths, duplicates, required and unknown keys; then the study's spiral
   angle in one key (:func:`one_spiral_angle`: ``design.spiral_angle_deg``);

then, with the schema's defaults filled in (:func:`fill_defaults`, as
``snakemake.utils.validate`` does), all of these (each a function of the
configuration that returns its problem lines):

3. file names: sweep values that differ but give the same file name
   (:func:`lsbg.files.label_clashes`: file names keep 6 decimals), the
   spiral angles here (and the paper's among them), the sensitivity factors in
   :func:`lsbg.experiments.checks.case_name_problems`;
4. the settings as lsbg's commands will read them: the paper engine and each
   engine's simulation settings (:func:`lsbg.dynamics.checks.engine_problems`),
   the driveline (:func:`lsbg.dynamics.checks.driveline_problems`), the
   contact law (:func:`lsbg.dynamics.checks.contact_problems`), the
   sensitivity cases (:func:`lsbg.experiments.checks.sensitivity_problems`, their
   speeds and boundaries :func:`lsbg.experiments.checks.operating_problems`)
   and the speed sweep (:func:`lsbg.study.resources.speed_sweep_problems`);
5. the statistics (:func:`lsbg.stats.checks.statistics_problems`): steady
   state <= chart window start < window end <= duration, and enough samples
   for the Anderson-Darling test, the Xbar-R subgroups and the sampling-phase
   spread of the summary;
6. every design point (:func:`lsbg.gear.checks.design_problems`):
   :class:`lsbg.gear.geometry.GearPair` runs lsbg's own checks
   (:mod:`lsbg.gear.design`: proportions, backlash, bores, cutter radius;
   :mod:`lsbg.gear.geometry`: pointed teeth, contact ratio >= 1 under
   interference), their messages mapped back to the design key in mm;
7. the resource guard (:mod:`lsbg.study.resources`): each design point's
   geometry memory and time, estimated from its mesh size
   (:func:`~lsbg.study.resources.geometry_problem`), against
   ``limits.memory_gb`` and ``limits.geometry_minutes``; each run's record
   against ``limits.memory_gb`` and the line model's slices against the
   runtime the simulation rules request
   (:func:`~lsbg.study.resources.run_cost_problems`); the load and the pinion
   speed against what the teeth of each contact model can carry and the
   full-rate record can resolve (:func:`~lsbg.study.resources.load_problems`);
8. the contact state: odd map steps and flanks lsbg can build (a topography
   file that is there) while parsing; at each design point that passed 6 and 7
   (:func:`~lsbg.tca.checks.contact_state_problems`, in the analyses): the relief
   within the backlash, the misalignment and the V-H map's corners neither
   losing contact nor closing the backlash;
9. the tooth section, the compliance case and each FE compliance's estimated
   cost and fillets (:func:`lsbg.tooth.config.tooth_problems`, in the analyses);
10. the rating section and the paper point's ISO 10300 rating
    (:func:`lsbg.rating.config.rating_problems`, in the analyses), and the ease-off
    optimisation's section and its budget (:func:`lsbg.optimise.checks.optimise_problems`);
11. the sweeps (:func:`lsbg.study.sweep_checks.sweep_problems`): every point of every
    sweep through the schema and steps 4, 6 and 7 as if its values were set in
    their own sections, at the sweep's own design points; points that give one
    file name; the number of runs against the resource guard.
12. the practice design (:func:`lsbg.practice.checks.practice_problems`): the
    design its rules make, its pairs and relieved flanks, its load spectrum.
13. the cutter-radius sweep (:func:`lsbg.experiments.cutter.cutter_sweep_problems`):
    its trace, and each listed cutter radius fitting the pair at the paper's spiral
    angle, while parsing.
14. the trace study's cells (:func:`lsbg.optimise.cells.trace_study_problems`): each
    listed spiral angle the paper's or the sweep's, each listed cutter radius fitting the
    pair at every angle of the section, while parsing.

A ``load_sweep`` section (the former extension) gets one line naming the
``sweeps`` entry that replaces it (:func:`lsbg.study.sweep_checks.load_sweep_moved`).
Each stage's checks live in its own package (a function of the configuration
that returns its problem lines); this module only calls them and shares the
design points that passed between them.

A YAML syntax error in a ``--configfile`` never reaches this module:
Snakemake 9 reads that file before the Snakefile and stops with
"Config file is not valid JSON or YAML" (without the file or the line;
``--verbose`` adds the YAML parser's message, which names both).
``lsbg check-config FILE`` (:mod:`lsbg.cli.config`) reads the files as
Snakemake does, names the file and line of such an error, and runs
:func:`check_config`.
"""

from __future__ import annotations

from lsbg.config import fill_defaults, key_path, nonfinite_problems, schema_problems
from lsbg.files import label_clashes, number_label
from lsbg.gear.checks import design_problems, points_named
from lsbg.stats.checks import AD_MIN_SAMPLES, statistics_problems
from lsbg.study.points import design_points, map_steps, speed_sweep_of
from lsbg.study.resources import (engines_run, geometry_problem, load_problems,
                                  memory_limit_gb, run_cost_problems, run_memory_gb,
                                  speed_sweep_problems)

__all__ = [
    "key_path", "check_config", "analysis_problems", "practice_analysis_problems",
    "one_spiral_angle", "nonfinite_problems", "schema_problems", "fill_defaults",
    "AD_MIN_SAMPLES"
]


def check_config(config, schema, analyses=True, given=None):
    """Every problem of a workflow configuration; fills in the schema's defaults.

    Parameters
    ----------
    config : dict
        The merged configuration, as Snakemake loaded it; changed in place:
        the schema's defaults are filled in once it passes the schema.
    schema : dict
        lsbg/schemas/config.schema.yaml, loaded.
    analyses : bool, optional
        Also run :func:`analysis_problems` (steps 8 to 10: a TCA and an ISO
        10300 rating at the design points) on the points that pass the others.
        The workflow checks without them while it is parsed (``snakemake -n``)
        and runs them in its ``onstart`` handler, before any job.
    given : dict, optional
        What the study's own files set over workflow/config.yaml (Snakemake's
        ``overwrite_config``: the ``--configfile`` files and ``--config``), for
        :func:`one_spiral_angle`; default: unknown.

    Returns
    -------
    list of str
        One line per problem, each starting with the key path and its value
        in the configuration's units; empty if the configuration is valid.
    """
    if "load_sweep" in config:  # the extension became an instance of the sweeps section
        from lsbg.study.sweep_checks import load_sweep_moved

        return [load_sweep_moved(config["load_sweep"])]
    nonfinite = nonfinite_problems(config)
    flagged = {line.split(" = ", 1)[0] for line in nonfinite}
    problems = nonfinite + [line for line in schema_problems(config, schema)
                            if line.split(":", 1)[0] not in flagged]
    problems += _design_point_keys(config)
    if problems:
        return problems
    problems = one_spiral_angle(config, given)
    if problems:
        return problems
    fill_defaults(config, schema)
    pairs = {}  # the design points that pass the physics and the resource guard
    problems = (_name_problems(config) + _settings_problems(config) + run_cost_problems(config)
                + _statistics_problems(config) + _design_problems(config, pairs))
    from lsbg.optimise.checks import optimise_problems  # (imports numba's kernels)

    problems += load_problems(config, pairs) + _flank_problems(config) + optimise_problems(config)
    from lsbg.matched.checks import matched_problems

    problems += matched_problems(config)
    if not problems:  # (at the paper's design point, which passed)
        from lsbg.experiments.cutter import cutter_sweep_problems

        problems += cutter_sweep_problems(config)
    if not problems:
        from lsbg.optimise.cells import trace_study_problems

        problems += trace_study_problems(config)
    if analyses:
        problems += analysis_problems(config, pairs)
    if not problems and config.get("sweeps"):
        problems += _sweeps_problems(config, schema, pairs)
    if analyses and not problems:
        problems += practice_analysis_problems(config)
    return list(dict.fromkeys(problems))


def analysis_problems(config, pairs=None):
    """Steps 8 to 10: the checks that run an analysis at the design points.

    Parameters
    ----------
    config : dict
        A configuration that passed :func:`check_config` with ``analyses=False``
        (defaults filled in).
    pairs : dict, optional
        ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of the design
        points that passed step 6 and 7; default: built here.

    Returns
    -------
    list of str
        One line per problem, as :func:`check_config`'s.
    """
    # these import numba's kernels and scipy: imported where they run
    from lsbg.rating.config import rating_problems
    from lsbg.tooth.config import tooth_problems

    if pairs is None:
        pairs = {}
        _design_problems(config, pairs)
    problems = _contact_state_problems(config, pairs)
    problems += tooth_problems(config, pairs, *memory_limit_gb(config))
    problems += rating_problems(config, pairs)
    return list(dict.fromkeys(problems))


def practice_analysis_problems(config):
    """Step 12: the practice design (:func:`lsbg.practice.checks.practice_problems`), made
    by its rules (scipy's root finding) when the study runs the line model; [] otherwise."""
    if "line" not in config["sweep"]["contact_models"]:
        return []
    from lsbg.practice.checks import practice_problems

    return practice_problems(config)


def _design_point_keys(config):
    """The trace given in the ``design`` section: the study's come from ``sweep.traces``
    (``lsbg geometry`` and the rules set it per point)."""
    design = config.get("design") if isinstance(config.get("design"), dict) else {}
    return [f"design.trace = {design['trace']!r}: the study's design points are set by "
            f"sweep.traces; remove it here"] if "trace" in design else []


#: The keys that set the study's spiral angles when design.spiral_angle_deg does not.
_ANGLE_KEYS = ("paper_spiral_angle_deg", "sweep.spiral_angles_deg")


def one_spiral_angle(config, given=None):
    """A study's spiral angle, set in one place (a schema-valid ``config``; in place).

    ``design.spiral_angle_deg: 30`` is the study's design point: the paper's point
    (``paper_spiral_angle_deg`` set to it) and, unless the study's own files list
    the sweep's angles in ``sweep.spiral_angles_deg`` (30 among them), the sweep's
    only angle; the key is then removed from ``design`` (the rules set it per point).
    (Without it, the paper's angle must be one of the sweep's: :func:`check_config`'s
    file-name step.)

    Parameters
    ----------
    config : dict
        The merged configuration (workflow/config.yaml and the study's files).
    given : dict, optional
        What the study's own files set (:func:`check_config`'s ``given``); None
        (unknown, e.g. a merge done in Python): the sweep is the one angle.

    Returns
    -------
    list of str
        One line if the study's files set the angle twice apart, naming what to change.
    """
    design = config["design"]
    if "spiral_angle_deg" not in design:
        return []
    angle, given = design["spiral_angle_deg"], given or {}
    paper, swept = (_value_at(given, key) for key in _ANGLE_KEYS)
    if paper is not None and number_label(paper) != number_label(angle):
        return [f"design.spiral_angle_deg = {angle!r}: the study's design point, and "
                f"paper_spiral_angle_deg = {paper!r} another; remove paper_spiral_angle_deg"]
    if swept is not None and number_label(angle) not in {number_label(a) for a in swept}:
        return [f"design.spiral_angle_deg = {angle!r}: not one of sweep.spiral_angles_deg = "
                f"{swept!r}; add {angle!r} there, or remove sweep.spiral_angles_deg for a "
                f"study of that one angle"]
    config["design"] = {k: v for k, v in design.items() if k != "spiral_angle_deg"}
    config["paper_spiral_angle_deg"] = angle
    config["sweep"] = {**config["sweep"], "spiral_angles_deg": swept or [angle]}
    return []


def _paper_angle_problems(config):
    """The paper's spiral angle outside the sweep: one more design point, unasked."""
    paper, swept = config["paper_spiral_angle_deg"], config["sweep"]["spiral_angles_deg"]
    if number_label(paper) in {number_label(a) for a in swept}:
        return []
    return [f"paper_spiral_angle_deg = {paper!r}: not one of sweep.spiral_angles_deg = "
            f"{swept!r}; for a study of that one angle set design.spiral_angle_deg: {paper!r} "
            f"instead of both keys, or add {paper!r} to sweep.spiral_angles_deg"]


def _value_at(config, dotted):
    """``config``'s value at a dotted key path, or None."""
    for key in dotted.split("."):
        if not isinstance(config, dict) or key not in config:
            return None
        config = config[key]
    return config


def _sweeps_problems(config, schema, pairs):
    """The ``sweeps`` section (:func:`lsbg.study.sweep_checks.sweep_problems`): each point through
    the schema and steps 4, 6 and 7, at the sweep's own design points."""
    from lsbg.study.sweep_checks import sweep_problems
    from lsbg.tca.separation import RealFlanks

    def check(changed, sweep):
        problems = (schema_problems(changed, schema) or _settings_problems(changed)
                    + run_cost_problems(changed))
        labels = {number_label(a) for a in sweep.spiral_angles}
        points = {k: v for k, v in pairs.items() if k[0] in sweep.traces and k[1] in labels}
        if any(k.split(".", 1)[0] in ("design", "flank_modification", "misalignment")
               for k in sweep.keys):  # the point's own design and flanks at its points
            points = {}
            where = {**changed, "paper_spiral_angle_deg": sweep.spiral_angles[0],
                     "sweep": {**changed["sweep"], "traces": list(sweep.traces),
                               "spiral_angles_deg": list(sweep.spiral_angles)}}
            problems += _design_problems(where, points)
            try:
                RealFlanks.from_config(changed["flank_modification"], changed["misalignment"])
            except ValueError as error:
                problems.append(str(error))
        return problems + load_problems(changed, points)

    return sweep_problems(config, check)


def _name_problems(config):
    """Sweep values that differ but give the same file name (or case name)."""
    from lsbg.experiments.checks import case_name_problems

    return (label_clashes(config["sweep"]["spiral_angles_deg"], "sweep.spiral_angles_deg")
            + _paper_angle_problems(config) + case_name_problems(config))


def _settings_problems(config):
    """The engines, simulation, contact, sensitivity and speed sweep as lsbg reads them."""
    from lsbg.dynamics.checks import contact_problems, driveline_problems, engine_problems
    from lsbg.experiments.checks import operating_problems, sensitivity_problems

    problems = (engine_problems(config, engines_run(config)) + driveline_problems(config)
                + contact_problems(config) + sensitivity_problems(config)
                + operating_problems(config))
    if speed_sweep_of(config):
        problems += speed_sweep_problems(config)
    return problems


def _statistics_problems(config):
    """The statistics windows; their samples counted only on a record the memory
    limit admits (a larger one: named by run_cost_problems)."""
    simulation = config["simulation"]
    need = run_memory_gb(simulation["samples"], simulation["duration_s"],
                         simulation["full_rate_hz"])[1]
    return statistics_problems(config, record_fits=need <= memory_limit_gb(config)[0])


def _design_problems(config, pairs=None):
    """lsbg's physics checks and the resource guard at every design point
    (:func:`lsbg.gear.checks.design_problems`); ``pairs`` is filled in with
    ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of each point that passes."""
    problems = design_problems(config, design_points(config), pairs,
                               guard=lambda pair: geometry_problem(pair, config))
    return problems + _practice_trace_problems(config)


def _practice_trace_problems(config):
    """The practice design's SBG (``practice.sbg_trace``) on the design section's cutter:
    its design rules (:class:`lsbg.gear.design.GearPairDesign`, the cutter circle across
    the face), before the practice design itself is made (step 12)."""
    from lsbg.gear.checks import user_message
    from lsbg.gear.design import DesignError, GearPairDesign

    section, trace = config["practice"], config["practice"]["sbg_trace"]
    if not section["enabled"] or "line" not in config["sweep"]["contact_models"]:
        return []
    spiral = float(config["paper_spiral_angle_deg"])
    try:
        GearPairDesign.from_config({**config["design"], "trace": trace, "spiral_angle_deg": spiral})
    except DesignError as error:
        head, why = user_message(error, config, ["paper_spiral_angle_deg"])
        return [f"{head}: {why} (at the practice design's {trace} {spiral:g} deg)"]
    return []


# ------------------------------------------------------------ contact state
def _flank_problems(config):
    """What the contact state's sections say without a TCA: odd map steps
    (:func:`lsbg.tca.checks.map_steps_problems`) and flanks that lsbg can build
    (:meth:`lsbg.tca.separation.RealFlanks.from_config`: a topography file that is
    there, a relief of its own keys)."""
    from lsbg.tca.checks import map_steps_problems
    from lsbg.tca.separation import RealFlanks

    try:
        RealFlanks.from_config(config["flank_modification"], config["misalignment"])
    except ValueError as error:
        return map_steps_problems(config["misalignment_map"]) + [str(error)]
    return map_steps_problems(config["misalignment_map"])


def _contact_state_problems(config, pairs):
    """The flank modification, the misalignment and the V-H map's corners at each
    point of ``pairs`` (:mod:`lsbg.tca.checks`): one line per key at fault, naming
    the design points where it fails. Only for sections :func:`_flank_problems` passes."""
    from lsbg.tca.checks import point_problems, user_lines

    section = config["misalignment_map"]
    if _flank_problems(config) or not pairs:
        return []
    failing = {}  # key path -> [first line, design points]
    for (trace, spiral), pair in pairs.items():
        map_config = {"axes": list(section["axes"]), "range": section["range"],
                      "steps": map_steps(config, spiral)}
        lines = user_lines(point_problems(pair, config, map_config), config)
        for line in lines:
            key = line.split(" = ", 1)[0].split(":", 1)[0]
            where = failing.setdefault(key, [line, []])[1]
            if f"{trace} {spiral} deg" not in where:  # (one point: several map corners)
                where.append(f"{trace} {spiral} deg")
    points = design_points(config)
    return [f"{line} (at {points_named(where, points)})" for line, where in failing.values()]
