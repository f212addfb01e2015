"""The Snakemake workflow's plan in plain Python: design points, file names and
what each rule depends on.

``workflow/rules/common.smk`` is only glue: it checks the configuration with
:func:`lsbg.study.checks.check_config` (which also fills in the schema's
defaults) and builds a :class:`Study`, whose attributes the rules read.
Everything here is tested by pytest without Snakemake
(tests/test_workflow_plan.py, tests/test_config_checks.py).

File names are relative to the working directory (the repository root when
run the documented way).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from lsbg.files import number_label
from lsbg.study.job_order import GATE_RULES, JOB_SECONDS, job_priority

__all__ = ["PAPER_TRACES", "CONTACT_MODELS", "REPORT_NAMES", "STUDY_SECTIONS", "FILES",
           "design_points", "speed_labels", "speed_keywords", "canonical", "yaml_text",
           "write_study_config", "simulation_params", "simulation_runtime", "map_steps",
           "CONTACT_STATE_SECTIONS", "contact_state_params", "JOB_SECONDS", "GATE_RULES",
           "job_priority", "envelope_positions", "Study"]

#: Both traces run at the paper's design point (the paper compares them).
PAPER_TRACES = ("logarithmic", "circular")
CONTACT_MODELS = ("point", "line")
REPORT_NAMES = ("paper", "sweep", "verification")
#: The contact state: the flanks every line-model analysis and run reads
#: (lsbg.cli.options.flanks_from_args), and the settings of `lsbg misalignment-map`.
FLANK_SECTIONS = ("flank_modification", "misalignment")
CONTACT_STATE_SECTIONS = (*FLANK_SECTIONS, "tca", "misalignment_map")
#: Sections of the configuration that lsbg's commands read from results/config.yaml.
STUDY_SECTIONS = ("design", "simulation", "contact", *CONTACT_STATE_SECTIONS, "statistics",
                  "tooth", "rating")

#: File name patterns of every stage (Snakemake wildcards in braces).
FILES = {
    "study_config": "results/config.yaml",
    "geometry": "results/geometry/{trace}_beta{spiral}",
    "mesh": "results/mesh/{trace}_beta{spiral}.nc",
    "run": "results/runs/{trace}_beta{spiral}_{model}_{engine}.nc",
    "sensitivity_run": "results/sensitivity/{trace}_beta{spiral}_{case}.nc",
    "convergence": "results/verification/convergence_{trace}_{model}.csv",
    "sweep": "results/sweep.nc",
    "summary": "results/summary.csv",
    "speed_run": "results/speed/{trace}_beta{spiral}_w{speed}.nc",
    "speed_curve": "results/speed_curve.nc",
    "tca": "results/tca/{trace}_beta{spiral}.nc",
    "vh_map": "results/vh/{trace}_beta{spiral}.nc",
    "compliance": "results/tooth/{trace}_beta{spiral}_compliance.nc",
    "fe_ltca": "results/tooth/{trace}_beta{spiral}_ltca.nc",
    "fe_envelope": "results/tooth/{trace}_beta{spiral}_envelope.nc",
    "fe_case": "results/tooth/{trace}_beta{spiral}_{case}_ltca.nc",
    "vh_case": "results/vh/{trace}_beta{spiral}_{case}.nc",
    "rating": "results/rating/{trace}_beta{spiral}.nc",
    "sweep_run": "results/sweeps/{name}/{trace}_beta{spiral}_{point}.nc",
    "sweep_dataset": "results/sweeps/{name}.nc",
    "sweep_table": "results/sweeps/{name}.csv",
    "report": "reports/{name}.html",
}

#: Simulation keys that only some engines read.
ENGINE_ONLY_KEYS = {"time_step_s": ("pybullet",), "method": ("scipy",),
                    "compiled_method": ("compiled",), "rtol": ("scipy", "compiled")}
#: Contact keys that only one model reads (``model`` itself: the rules name it).
MODEL_ONLY_KEYS = {
    "point": ("stiffness_N_per_mm1_5", "exponent", "damping_N_s_per_mm", "penetration_depth_mm"),
    "line": ("line_stiffness_N_per_mm_um", "mesh_damping_ratio", "slices",
             "line_approach_limit_mm", "compliance"),
}


# ------------------------------------------------------------ design points
def design_points(config):
    """Every design point of a study and the keys of the configuration that ask for it.

    Parameters
    ----------
    config : dict
        Validated by the schema, its defaults filled in.

    Returns
    -------
    dict
        ``(trace, spiral label)`` -> key paths of the spiral angles that give the
        point, e.g. ``("circular", "35") -> ["paper_spiral_angle_deg",
        "sweep.spiral_angles_deg[1]"]``; sorted by trace, then angle. The label
        is the angle [deg] as file names and the jobs have it
        (:func:`lsbg.files.number_label`).
    """
    asked = [(trace, number_label(angle), f"sweep.spiral_angles_deg[{k}]")
             for trace in config["sweep"]["traces"]
             for k, angle in enumerate(config["sweep"]["spiral_angles_deg"])]
    asked += [(trace, number_label(config["paper_spiral_angle_deg"]), "paper_spiral_angle_deg")
              for trace in PAPER_TRACES]
    speed = config.get("speed_sweep")
    if speed:
        key = "speed_sweep.spiral_angle_deg" if "spiral_angle_deg" in speed \
            else "paper_spiral_angle_deg"
        angle = speed.get("spiral_angle_deg", config["paper_spiral_angle_deg"])
        asked += [(trace, number_label(angle), key)
                  for trace in speed.get("traces", PAPER_TRACES)]
    points = {}
    for trace, spiral, key in sorted(asked, key=lambda a: (a[0], float(a[1]), a[2])):
        keys = points.setdefault((trace, spiral), [])
        if key not in keys:
            keys.append(key)
    return points


def speed_labels(grid):
    """The speed sweep's pinion speeds [rad/s] and their file-name labels [deg/s, to 1e-3].

    Parameters
    ----------
    grid : dict
        ``speed_sweep.pinion_speeds_deg_s``: ``start``, ``stop`` [deg/s], ``count``.
    """
    from lsbg.experiments.speed import speed_grid

    speeds = speed_grid(math.radians(grid["start"]), math.radians(grid["stop"]), grid["count"])
    return speeds, [number_label(round(math.degrees(v), 3)) for v in speeds]


def speed_keywords(speed):
    """Keywords of :func:`lsbg.experiments.speed.speed_settings` from the ``speed_sweep`` section."""
    return {"mesh_cycles": speed["mesh_cycles"], "min_window": speed["min_window_s"],
            "settle_time": speed["settle_time_s"], "ramp_time": speed["ramp_time_s"],
            "samples_per_mesh": speed["samples_per_mesh"]}


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
    sections = {s: config[s] for s in STUDY_SECTIONS}
    text = yaml_text(sections,
                     "the lsbg study settings as validated (written by the workflow; do not edit)")
    if path.exists() and path.read_text(encoding="utf-8") == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    part = path.with_name(f"{path.name}.part")
    part.write_text(text, encoding="utf-8")
    part.replace(path)


def simulation_params(config, engine, model):
    """The simulation and contact settings a run of ``engine`` and ``model`` depends on
    (the rules' rerun trigger).

    The line model's contact settings include the flanks it runs on: the
    ``flank_modification`` and ``misalignment`` sections (every line-model
    command applies them; the point model keeps the conjugate flanks), so
    that every rule whose trigger holds them (the loaded TCA's too) reruns on
    a change of the contact state; under ``compliance: fe`` also the ``tooth``
    section (the FE compliance it runs on).
    """
    simulation = {k: v for k, v in config["simulation"].items()
                  if engine in ENGINE_ONLY_KEYS.get(k, (engine,))}
    others = {key for name, keys in MODEL_ONLY_KEYS.items() if name != model for key in keys}
    contact = {k: v for k, v in config["contact"].items() if k not in others and k != "model"}
    if model == "line":
        contact.update({section: config.get(section, {}) for section in FLANK_SECTIONS})
        if contact.get("compliance") == "fe":
            contact["tooth"] = config.get("tooth", {})
    return canonical({"simulation": simulation, "contact": contact})


def map_steps(config, spiral):
    """Values per axis of the V-H map at a design point's spiral angle (its file-name
    label): ``misalignment_map.steps`` at the paper's, else ``sweep_steps``."""
    section = config["misalignment_map"]
    paper = number_label(config["paper_spiral_angle_deg"])
    return section["steps"] if number_label(spiral) == paper else section["sweep_steps"]


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


#: Budgeted wall time per simulated second and run [s] (measured: PyBullet
#: about 8, scipy 3-14, compiled about 1; tests/benchmarks/bench_dynamics.py).
BUDGET_PER_SECOND = 100.0


def simulation_runtime(config, runs=1):
    """Cluster time limit [min] of ``runs`` simulations (generous, at least 10 min)."""
    return max(10, math.ceil(runs * config["simulation"]["duration_s"] * BUDGET_PER_SECOND / 60))


def envelope_positions(config):
    """Mesh positions of each FE loaded TCA of the displacement envelope (rule fe_sensitivity).

    Half the aligned LTCA's (``tooth.ltca_positions``, at least 8): measured on
    the paper's pair (35 deg, both members, four corners), 100 positions put
    the largest contact pressure and root stresses within 0.5 % (their medians
    over the cycle within 0.3 %) of 200 positions', in 5.7 s instead of 9.6 s.

    Parameters
    ----------
    config : dict
        The study configuration, defaults filled in.

    Returns
    -------
    int
    """
    return max(8, int(config["tooth"].get("ltca_positions", 200)) // 2)


# ---------------------------------------------------------------- the study
def _format(pattern, **fields):
    return pattern.format(**fields)


@dataclass
class Study:
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

    def case_options(self, stage):
        """``--case KEY=VALUE`` options of the ``sensitivity`` section's entries that
        reach ``stage`` (:data:`lsbg.experiments.sensitivity.CASE_STAGES`)."""
        from lsbg.experiments.sensitivity import CASE_STAGES

        return " ".join(f"--case {key}={value!r}" for key, values in
                        self.config["sensitivity"].items() if stage in CASE_STAGES[key]
                        for value in values)

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

    def convergence_default_runs(self, trace, model):
        """``--default-run ENGINE=RUN.nc`` options of a convergence table: every run it
        writes (:meth:`convergence_runs`)."""
        return " ".join(f"--default-run {e}={r}" for e, r in
                        zip(self.convergence_engines(model), self.convergence_runs(trace, model)))

    @property
    def convergence_files(self):
        return [_format(FILES["convergence"], trace=t, model=m) for m in CONTACT_MODELS
                for t in PAPER_TRACES]

    # ---------------------------------------------------------- speed sweep
    @property
    def speed_sweep(self):
        """The ``speed_sweep`` section, or None."""
        return self.config.get("speed_sweep") or None

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
    def speed_options(self):
        """``lsbg speed-run`` options of the speed sweep."""
        speed = self.speed_sweep
        return (f"--mesh-cycles {speed['mesh_cycles']} --min-window {speed['min_window_s']} "
                f"--settle-time {speed['settle_time_s']} --ramp-time {speed['ramp_time_s']} "
                f"--samples-per-mesh {speed['samples_per_mesh']}")

    @property
    def speed_runs(self):
        if not self.speed_sweep:
            return []
        return [_format(FILES["speed_run"], trace=t, spiral=self.speed_spiral, speed=v)
                for t in self.speed_traces for v in self.speeds]

    # -------------------------------------------------------------- targets
    @property
    def reports(self):
        return {name: _format(FILES["report"], name=name) for name in REPORT_NAMES}

    @property
    def targets(self):
        """What ``rule all`` asks for."""
        extra = [FILES["speed_curve"]] if self.speed_sweep else []
        return [*self.reports.values(), FILES["sweep"], FILES["summary"], *self.tca_files,
                *self.vh_maps, *self.vh_cases(), *self.tooth_files, *self.fe_cases(),
                *self.rating_files, *self.sweep_files, *extra]

    # ------------------------------------------------------------ wildcards
    @property
    def wildcards(self):
        """Constraints of the wildcards (regular expressions)."""
        return {
            "trace": "|".join(PAPER_TRACES),
            "spiral": r"\d+(\.\d+)?",
            "engine": "pybullet|scipy|compiled",
            "model": "|".join(CONTACT_MODELS),
            "case": "|".join(map(re.escape, self.sensitivity)) or "none",
            "speed": r"\d+(\.\d+)?",
        }

    @property
    def reference_engines(self):
        """Regular expression of the engines the ``simulate`` rule runs."""
        engines = sorted({e for m in CONTACT_MODELS for e in self.reference[m]})
        return "|".join(engines) or "none"
