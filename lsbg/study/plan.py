"""The Snakemake workflow's plan in plain Python: design points, runs and file names.

``workflow/rules/common.smk`` is only glue: it checks the configuration with
:func:`lsbg.study.checks.check_config` (which also fills in the schema's
defaults) and builds a :class:`Study`, whose attributes the rules read.
The design points and the file-name table are :mod:`lsbg.study.points`, what
each rule depends on (its ``params``) :mod:`lsbg.study.params`, the rules'
priorities :mod:`lsbg.study.job_order`; the rules read them all through this
module (``plan.FILES``, ``plan.simulation_params``, ``plan.assign_priorities``,
``plan.lift_job_rate_limit``).
Everything here is tested by pytest without Snakemake
(tests/study/test_plan.py, tests/study/test_checks.py).

File names are relative to the working directory (the repository root when
run the documented way).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property

from lsbg.files import number_label
from lsbg.study.job_order import JOB_SECONDS, assign_priorities, lift_job_rate_limit
from lsbg.study.params import (CONTACT_STATE_SECTIONS, STUDY_SECTIONS, canonical,
                               contact_state_params, simulation_params,
                               simulation_runtime, write_study_config,
                               yaml_text)
from lsbg.gear.design import TRACES
from lsbg.practice.design import practice_traces
from lsbg.study.points import (CONTACT_MODELS, FILES, PAPER_TRACES, REPORT_NAMES,
                               design_points, map_steps, speed_labels, speed_sweep_of)
from lsbg.study.trace_cells import TraceStudyFiles

#: The matched designs' dataset (lsbg matched-pairs). Here, not in lsbg.study.points'
#: FILES: that module is among every command's sources, so a new entry would rerun every job.
MATCHED_PAIRS = "results/optimise/matched_pairs.nc"

__all__ = ["PAPER_TRACES", "CONTACT_MODELS", "REPORT_NAMES", "STUDY_SECTIONS", "FILES",
           "design_points", "speed_labels", "canonical", "yaml_text",
           "write_study_config", "simulation_params", "simulation_runtime", "map_steps",
           "CONTACT_STATE_SECTIONS", "contact_state_params", "JOB_SECONDS",
           "assign_priorities", "lift_job_rate_limit", "DESIGN_SETS", "Study"]


#: The designs of the load curves: the pair as published, and as practice makes it.
DESIGN_SETS = ("paper", "practice")


# ---------------------------------------------------------------- the study
def _format(pattern, **fields):
    return pattern.format(**fields)


@dataclass
class Study(TraceStudyFiles):
    """Design points, runs and files of a validated configuration.

    Parameters
    ----------
    config : dict
        Checked by :func:`lsbg.study.checks.check_config` (defaults filled in).
    """

    config: dict
    traces: list = field(init=False)
    spirals: list = field(init=False)
    paper_spiral: str = field(init=False)

    def __post_init__(self):
        c = self.config
        self.traces = list(c["sweep"]["traces"])
        self.spirals = [number_label(a) for a in c["sweep"]["spiral_angles_deg"]]
        self.sweep_models = list(c["sweep"]["contact_models"])
        self.paper_spiral = number_label(c["paper_spiral_angle_deg"])
        self.sweep_engine = c["engines"]["sweep"]
        self.reference = {m: [e for e in c["engines"]["reference"].get(m, [])
                              if e != self.sweep_engine] for m in CONTACT_MODELS}
        self.paper_engine = c["engines"]["paper"]
        from lsbg.experiments.sensitivity import study_cases
        from lsbg.experiments.sweeps import sweeps_from_config

        #: sensitivity case -> (key, factor, switch value or corner label)
        self.sensitivity = study_cases(c["sensitivity"], c["misalignment_map"])
        #: the parameter sweeps of the ``sweeps`` section (lsbg.experiments.sweeps.Sweep)
        self.sweeps = sweeps_from_config(c)

    # -------------------------------------------------------- design points
    def batch_spirals(self, trace):
        """The sweep's spiral angles of ``trace`` run in one job (all but the paper's
        angle of a paper trace, which is a job of its own)."""
        if trace not in self.traces:
            return []
        return [s for s in self.spirals if not (s == self.paper_spiral and trace in PAPER_TRACES)]

    def batch_groups(self):
        """The sweep's batch jobs, ``[(rule suffix, traces, spiral labels)]``: the traces of
        the paper's pair leave the paper's angle to its own jobs (suffix ``""``); any other
        trace (ISO 23509's SBG) runs every angle of the sweep in its batch (suffix
        ``"_all_angles"``). Groups without a trace or an angle are left out."""
        groups = [("", [t for t in self.traces if t in PAPER_TRACES]),
                  ("_all_angles", [t for t in self.traces if t not in PAPER_TRACES])]
        return [(suffix, traces, self.batch_spirals(traces[0]))
                for suffix, traces in groups if traces and self.batch_spirals(traces[0])]

    def geometry(self, trace, spiral):
        return _format(FILES["geometry"], trace=trace, spiral=spiral)

    def mesh(self, trace, spiral):
        return _format(FILES["mesh"], trace=trace, spiral=spiral)

    def run(self, trace, spiral, model, engine):
        return _format(FILES["run"], trace=trace, spiral=spiral, model=model, engine=engine)

    def batch_outputs(self, trace):
        """Geometry dirs, loaded TCAs and sweep-engine runs of a trace's batch job."""
        spirals = self.batch_spirals(trace)
        return ([self.geometry(trace, s) for s in spirals] + [self.mesh(trace, s) for s in spirals]
                + [self.run(trace, s, m, self.sweep_engine) for s in spirals
                   for m in self.sweep_models])

    # ---------------------------------------------------------------- runs
    @property
    def sweep_runs(self):
        """Every trace at every spiral angle, every sweep model, the sweep engine."""
        return [self.run(t, s, m, self.sweep_engine) for m in self.sweep_models
                for t in self.traces for s in self.spirals]

    def reference_runs(self, model=None):
        """Runs of the reference engines at the paper's design point."""
        models = CONTACT_MODELS if model is None else (model,)
        return [self.run(t, self.paper_spiral, m, e) for m in models for e in self.reference[m]
                for t in PAPER_TRACES]

    @property
    def paper_runs(self):
        """Both traces, both models at the paper's point: sweep and reference engines."""
        return ([self.run(t, self.paper_spiral, m, self.sweep_engine) for m in CONTACT_MODELS
                 for t in PAPER_TRACES] + self.reference_runs())

    @property
    def all_runs(self):
        return list(dict.fromkeys(self.sweep_runs + self.paper_runs))

    @property
    def meshes(self):
        """Loaded TCAs: every design point of the sweep and the paper's."""
        return list(dict.fromkeys([self.mesh(t, s) for t in self.traces for s in self.spirals]
                                  + self.paper_meshes))

    @property
    def paper_meshes(self):
        return [self.mesh(t, self.paper_spiral) for t in PAPER_TRACES]

    @property
    def paper_geometry(self):
        return [self.geometry(t, self.paper_spiral) for t in PAPER_TRACES]

    # ------------------------------------------------ the tooth's compliance
    @property
    def own_compliance(self):
        """True when every line-model analysis and run takes the tooth's FE compliance
        (``contact.compliance: fe``)."""
        return self.config["contact"].get("compliance", "uniform") == "fe"

    def compliance(self, trace, spiral):
        return _format(FILES["compliance"], trace=trace, spiral=spiral)

    def fe_ltca(self, trace, spiral):
        """The loaded TCA with the FE compliance at a design point: the design point's
        loaded TCA itself under ``compliance: fe``, else the paper point's of
        results/tooth/."""
        if self.own_compliance:
            return self.mesh(trace, spiral)
        return _format(FILES["fe_ltca"], trace=trace, spiral=spiral)

    @property
    def tooth_files(self):
        """FE compliances (and, under ``compliance: uniform``, the FE loaded TCAs) the
        study makes: the paper's point of each trace; every design point under ``fe``."""
        if self.own_compliance:
            return [self.compliance(t, s) for t, s in self.points]
        return [f(t, self.paper_spiral) for t in PAPER_TRACES
                for f in (self.compliance, self.fe_ltca)]

    @property
    def needs_fe_ltca(self):
        """Whether a paper-point line-model run reads the FE loaded TCA (``--fe-ltca``)."""
        return self.own_compliance or "fe" in self.config["sensitivity"].get("compliance", [])

    # ------------------------------------------------------------ rating
    def rating(self, trace, spiral):
        return _format(FILES["rating"], trace=trace, spiral=spiral)

    def fe_envelope(self, trace, spiral):
        return _format(FILES["fe_envelope"], trace=trace, spiral=spiral)

    @property
    def rating_files(self):
        """The ISO 10300 rating of the paper's point, both traces."""
        return [self.rating(t, self.paper_spiral) for t in PAPER_TRACES]

    def rating_run(self, trace):
        """The run whose dynamic factor is the rating's K_v: the paper point's line-model
        run with the sweep engine (none when the sweep runs the point model only)."""
        if "line" not in self.sweep_models:
            return []
        return [self.run(trace, self.paper_spiral, "line", self.sweep_engine)]

    # -------------------------------------------------------- contact state
    @property
    def points(self):
        """Every design point of the study, ``(trace, spiral label)``: each trace at each
        spiral angle of the sweep, then the paper's point of each paper trace."""
        return list(dict.fromkeys([(t, s) for t in self.traces for s in self.spirals]
                                  + [(t, self.paper_spiral) for t in PAPER_TRACES]))

    def map_steps(self, spiral):
        """Values per axis of the V-H map at ``spiral`` (:func:`map_steps`)."""
        return map_steps(self.config, spiral)

    def tca(self, trace, spiral):
        return _format(FILES["tca"], trace=trace, spiral=spiral)

    def vh_map(self, trace, spiral):
        return _format(FILES["vh_map"], trace=trace, spiral=spiral)

    @property
    def tca_files(self):
        """Unloaded TCAs: every design point (:attr:`points`)."""
        return [self.tca(t, s) for t, s in self.points]

    @property
    def vh_maps(self):
        """V-H maps: every design point (:attr:`points`)."""
        return [self.vh_map(t, s) for t, s in self.points]

    @property
    def paper_tca_files(self):
        return [self.tca(t, self.paper_spiral) for t in PAPER_TRACES]

    @property
    def paper_vh_maps(self):
        return [self.vh_map(t, self.paper_spiral) for t in PAPER_TRACES]


    def stage_cases(self, stage):
        """The sensitivity cases (names) that reach ``stage``."""
        from lsbg.experiments.sensitivity import stage_cases

        return list(stage_cases(self.sensitivity, stage))

    def vh_cases(self, trace=None):
        """The paper point's V-H maps of the contact-state sensitivity cases."""
        traces = PAPER_TRACES if trace is None else (trace,)
        return [_format(FILES["vh_case"], trace=t, spiral=self.paper_spiral, case=case)
                for case in self.stage_cases("contact_state") for t in traces]

    def fe_cases(self, trace=None):
        """The paper point's FE loaded TCAs of the crowning sensitivity cases."""
        traces = PAPER_TRACES if trace is None else (trace,)
        return [_format(FILES["fe_case"], trace=t, spiral=self.paper_spiral, case=case)
                for case in self.stage_cases("fe_ltca") for t in traces]

    @property
    def sweep_files(self):
        """Each parameter sweep's dataset and summary table."""
        return [_format(FILES[kind], name=sweep.name) for sweep in self.sweeps
                for kind in ("sweep_dataset", "sweep_table")]

    def parameter_sweep_runs(self, sweep, batch=None):
        """A parameter sweep's runs (of a batch of its points) at its design points."""
        patterns = sweep.patterns()
        chosen = range(len(patterns)) if batch is None else batch
        return [_format(FILES["sweep_run"], name=sweep.name, trace=t, spiral=number_label(a),
                        point=patterns[i])
                for t in sweep.traces for a in sweep.spiral_angles for i in chosen]

    def sensitivity_run(self, trace, case):
        """The run of one sensitivity case at the paper's point of ``trace``."""
        return _format(FILES["sensitivity_run"], trace=trace, spiral=self.paper_spiral, case=case)

    def sensitivity_runs(self, trace=None):
        traces = PAPER_TRACES if trace is None else (trace,)
        return [self.sensitivity_run(t, case) for case in self.sensitivity for t in traces]

    @property
    def rated_cases(self):
        """The sensitivity cases whose run's K_v the rating takes (not another speed's)."""
        from lsbg.experiments.sensitivity import rated_cases

        return rated_cases(self.sensitivity)

    # --------------------------------------------------------- verification
    def convergence_engines(self, model):
        """Engines of a model's convergence table: the sweep engine and the model's
        reference engines, each over its time steps or tolerances."""
        return [self.sweep_engine, *self.reference[model]]

    def convergence_runs(self, trace, model):
        """The runs a convergence table writes: each of its engines' at the default
        settings, at the paper's design point (no separate job makes them)."""
        return [self.run(trace, self.paper_spiral, model, e)
                for e in self.convergence_engines(model)]

    def default_runs(self, trace, model):
        """``ENGINE=RUN.nc`` values of a convergence table's ``--default-run``: every run
        it writes (:meth:`convergence_runs`)."""
        return [f"{e}={r}" for e, r in zip(self.convergence_engines(model),
                                           self.convergence_runs(trace, model))]

    @property
    def convergence_files(self):
        return [_format(FILES["convergence"], trace=t, model=m) for m in CONTACT_MODELS
                for t in PAPER_TRACES]

    # ---------------------------------------------------------- speed sweep
    @property
    def speed_sweep(self):
        """The ``speed_sweep`` section, or None (none, or not ``enabled``)."""
        return speed_sweep_of(self.config)

    @property
    def speed_spiral(self):
        return number_label(self.speed_sweep.get("spiral_angle_deg",
                                                 self.config["paper_spiral_angle_deg"]))

    @property
    def speed_traces(self):
        return list(self.speed_sweep.get("traces", PAPER_TRACES))

    @property
    def speeds(self):
        """Pinion speeds of the speed sweep as file-name labels [deg/s]."""
        return speed_labels(self.speed_sweep["pinion_speeds_deg_s"])[1]


    @property
    def speed_boundaries(self):
        """The boundaries of the speed sweep, a curve each."""
        return list(self.speed_sweep.get("boundaries", ["prescribed_pinion"]))

    def speed_runs(self, boundary=None):
        """The speed sweep's runs (of one boundary)."""
        if not self.speed_sweep:
            return []
        boundaries = self.speed_boundaries if boundary is None else [boundary]
        return [_format(FILES["speed_run"], trace=t, spiral=self.speed_spiral, speed=v,
                        boundary=b)
                for b in boundaries for t in self.speed_traces for v in self.speeds]

    @property
    def speed_curves(self):
        """The speed sweep's curves, one per boundary."""
        if not self.speed_sweep:
            return []
        return [_format(FILES["speed_curve"], boundary=b) for b in self.speed_boundaries]

    # ------------------------------------------------------ practice design
    @property
    def practice(self):
        """Whether the study makes the practice design and the load curves (the
        ``practice`` section's ``enabled``; its stability claim needs line-model runs)."""
        return bool(self.config["practice"]["enabled"]) and "line" in self.sweep_models

    @property
    def practice_traces(self):
        """The practice design's traces: the LSBG and the SBG of ``practice.sbg_trace``
        (ISO 23509's face-milled by default, or the paper's arc)."""
        return practice_traces(self.config)

    def practice_file(self, kind, trace):
        """A practice design point's file: ``kind`` one of geometry, compliance,
        fe_ltca, fe_envelope, tca, vh_map, run, rating (``FILES["practice_<kind>"]``)."""
        return _format(FILES[f"practice_{kind}"], trace=trace, spiral=self.paper_spiral,
                       engine=self.sweep_engine)

    def practice_files(self, kind):
        """:meth:`practice_file` of both traces (none without the practice design)."""
        return [self.practice_file(kind, t) for t in self.practice_traces] if self.practice else []

    @cached_property
    def pair_cases(self):
        """The sensitivity cases that also run on the practice and best pairs (the keys
        of ``practice.sensitivity``): ``{name: (key, value)}`` as :attr:`sensitivity`."""
        from lsbg.experiments.sensitivity import pair_case_keys, pair_cases

        return pair_cases(self.sensitivity, pair_case_keys(self.config))

    def pair_stage_cases(self, stage):
        """The practice and best pairs' cases (names) that reach ``stage``."""
        from lsbg.experiments.sensitivity import stage_cases

        return list(stage_cases(self.pair_cases, stage))

    def pair_case_files(self, flanks, kind, trace=None):
        """The model-form cells' files of the practice pair (``flanks`` "practice") or of
        the best pair ("best"): ``kind`` "sensitivity_run" (each case's line-model run),
        "vh_case" (the V-H map of each case that reaches the contact state) or "fe_case"
        (the FE loaded TCA of each case that reaches it); both traces, or ``trace``'s.
        None where the study makes no such pair."""
        if not (self.optimise if flanks == "best" else self.practice):
            return []
        stage = {"sensitivity_run": "dynamics", "vh_case": "contact_state",
                 "fe_case": "fe_ltca"}[kind]
        traces = self.practice_traces if trace is None else [trace]
        return [_format(FILES[f"{flanks}_{kind}"], trace=t, spiral=self.paper_spiral, case=case)
                for case in self.pair_stage_cases(stage) for t in traces]

    def pair_case_run(self, flanks, trace, case):
        """The line-model run of one case on the practice or best pair (``flanks``)."""
        return _format(FILES[f"{flanks}_sensitivity_run"], trace=trace, spiral=self.paper_spiral,
                       case=case)

    @property
    def optimise(self):
        """Whether the study optimises each type's ease-off (on the practice design:
        ``optimise.enabled`` and the practice design made)."""
        return self.practice and bool(self.config["optimise"]["enabled"])

    @property
    def optimise_seeds(self):
        """The seeds of each trace's searches: ``optimise.seeds`` of them from the study's
        ``optimise.seed`` on (the fronts compared trace against trace, the convergence
        evidence)."""
        seed = int(self.config["optimise"]["seed"])
        return list(range(seed, seed + int(self.config["optimise"].get("seeds", 3))))

    def optimise_front(self, trace, seed):
        return _format(FILES["optimise_front"], trace=trace, spiral=self.paper_spiral,
                       seed=seed)

    @property
    def optimise_fronts(self):
        """Every front: both traces, both seeds (none without the optimisation)."""
        if not self.optimise:
            return []
        return [self.optimise_front(t, s) for t in self.practice_traces
                for s in self.optimise_seeds]

    def optimise_release(self, trace):
        return _format(FILES["optimise_release"], trace=trace, spiral=self.paper_spiral)

    @property
    def optimise_releases(self):
        """Each trace's release (lsbg release; none without the optimisation)."""
        return [self.optimise_release(t) for t in self.practice_traces] if self.optimise else []

    @property
    def optimise_converged_fronts(self):
        """Each trace's fronts at converged positions (lsbg converge-front; none without
        the optimisation)."""
        return [_format(FILES["optimise_converged_front"], trace=t, spiral=self.paper_spiral)
                for t in self.practice_traces] if self.optimise else []

    @property
    def trace_fronts(self):
        """The traces' fronts compared (lsbg trace-fronts), the paper cell's first, then
        every other cell's of the trace study (none without the optimisation)."""
        return [self.cell_trace_fronts(c["label"]) for c in self.trace_cells]

    def both_traces(self, name):
        """``FILES[name]`` of each practice trace at the paper's angle, the logarithmic
        trace's first (none without the optimisation): lsbg matched-pairs' inputs."""
        traces = sorted(self.practice_traces, key=lambda t: t != "logarithmic")
        return [_format(FILES[name], trace=t, spiral=self.paper_spiral)
                for t in traces] if self.optimise else []

    @property
    def matched_pairs(self):
        """The traces' matched designs answered (lsbg matched-pairs; none without the
        optimisation)."""
        return [MATCHED_PAIRS] if self.optimise else []

    def best_file(self, kind, trace):
        """A file of the practice design point with each type's chosen ease-off: ``kind``
        one of overlay, fe_ltca, fe_envelope, tca, vh_map, run, rating."""
        return _format(FILES[f"best_{kind}"], trace=trace, spiral=self.paper_spiral,
                       engine=self.sweep_engine)

    def best_files(self, kind):
        """:meth:`best_file` of both traces (none without the optimisation)."""
        return [self.best_file(kind, t) for t in self.practice_traces] if self.optimise else []

    def load_curve(self, design_set, trace):
        return _format(FILES["load_curve"], design_set=design_set, trace=trace,
                       spiral=self.paper_spiral)

    @property
    def load_curves(self):
        """The load curves of both designs (``paper``, ``practice``) and both traces (each
        design's own: :data:`PAPER_TRACES`, :attr:`practice_traces`)."""
        if not self.practice:
            return []
        traces = {"paper": PAPER_TRACES, "practice": self.practice_traces}
        return [self.load_curve(d, t) for d in DESIGN_SETS for t in traces[d]]

    # -------------------------------------------------------------- targets
    @property
    def reports(self):
        return {name: _format(FILES["report"], name=name) for name in REPORT_NAMES}

    @property
    def targets(self):
        """What ``rule all`` asks for."""
        extra = self.speed_curves
        return [*self.reports.values(), FILES["sweep"], FILES["summary"], *self.tca_files,
                *self.vh_maps, *self.vh_cases(), *self.tooth_files, *self.fe_cases(),
                *self.rating_files, *self.sweep_files, *extra,
                *self.practice_files("rating"), *self.practice_files("vh_map"),
                *self.load_curves, *self.optimise_fronts, *self.matched_pairs,
                *self.best_files("rating"),
                *self.best_files("vh_map"), *(p["file"] for p in self.cutter_points),
                *(f for flanks in ("practice", "best") for kind in ("vh_case", "fe_case")
                  for f in self.pair_case_files(flanks, kind))]

    # ------------------------------------------------ the cutter-radius sweep
    @cached_property
    def cutter_points(self):
        """The cutter-radius sweep's points (:func:`lsbg.experiments.cutter.cutter_points`),
        each with its ``file``; none unless ``cutter_sweep.enabled``."""
        if not self.config["cutter_sweep"]["enabled"]:
            return []
        from lsbg.experiments.cutter import cutter_points

        return [{**p, "file": _format(FILES["cutter_point"], point=p["label"] if
                                      p["trace"] == "logarithmic" else
                                      f"{p['trace']}_{p['label']}")}
                for p in cutter_points(self.config)]

    # ------------------------------------------------------------ wildcards
    @property
    def sample_wildcards(self):
        """A design point's wildcards, for the input functions of the rule graph
        (:func:`lsbg.study.job_order.rule_graph`): the paper's point, the line model, the
        trace study's first cell beyond the paper's (if any)."""
        return {"trace": PAPER_TRACES[0], "spiral": self.paper_spiral, "model": "line",
                "engine": self.sweep_engine, "cell": next(iter(self.other_cells), "none")}

    @property
    def wildcards(self):
        """Constraints of the wildcards (regular expressions)."""
        return {
            "trace": "|".join(TRACES),
            "spiral": r"\d+(\.\d+)?",
            "engine": "pybullet|scipy|compiled",
            "model": "|".join(CONTACT_MODELS),
            "case": "|".join(map(re.escape, self.sensitivity)) or "none",
            "speed": r"\d+(\.\d+)?",
            "boundary": "prescribed_pinion|driveline",
            "design_set": "|".join(DESIGN_SETS),
            "seed": r"\d+",
        }

    @property
    def reference_engines(self):
        """Regular expression of the engines the ``simulate`` rule runs."""
        engines = sorted({e for m in CONTACT_MODELS for e in self.reference[m]})
        return "|".join(engines) or "none"
