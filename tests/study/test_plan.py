"""lsbg.study.plan, the workflow's plan without Snakemake: the design points, runs and
files of a study, the rerun triggers and the study config (the configuration checks:
tests/study/test_checks.py)."""

import copy
import os
import re
from pathlib import Path

import pytest
import yaml
from snakemake.utils import validate

from lsbg.study import job_order
from lsbg.study import plan

REPO = Path(__file__).resolve().parents[2]
SCHEMA = REPO / "lsbg" / "schemas" / "config.schema.yaml"


def load(*names, **overrides):
    """workflow/config.yaml with other config files merged over it, validated by the schema
    (which fills in its defaults), then ``overrides`` ({section: {key: value}})."""
    config = {}
    for name in ("config.yaml", *names):
        data = yaml.safe_load((REPO / "workflow" / name).read_text(encoding="utf-8"))
        for key, value in data.items():
            config[key] = value
    for section, values in overrides.items():
        if isinstance(values, dict) and isinstance(config.get(section), dict):
            config[section] = {**config[section], **values}
        else:
            config[section] = values
    validate(config, str(SCHEMA))
    return config


@pytest.fixture(scope="module")
def default():
    return load()


def test_every_run_and_file_of_the_default_study_is_planned_once(default):
    study = plan.Study(default)
    traces, spirals = default["sweep"]["traces"], default["sweep"]["spiral_angles_deg"]
    models = default["sweep"]["contact_models"]
    assert len(study.sweep_runs) == len(set(study.sweep_runs)) == (
        len(traces) * len(spirals) * len(models))
    # the batch job of each trace, the paper's geometry and loaded TCA of each paper trace,
    # and the sweep engine's run of each paper trace and model (by its convergence table)
    produced = []
    for trace in traces:
        produced += study.batch_outputs(trace)
    produced += study.paper_geometry + study.paper_meshes
    produced += [study.run(t, study.paper_spiral, m, study.sweep_engine)
                 for t in plan.PAPER_TRACES for m in plan.CONTACT_MODELS]
    assert len(produced) == len(set(produced))
    sweep_engine = {run for run in study.all_runs if run.endswith(f"_{study.sweep_engine}.nc")}
    assert sweep_engine == {f for f in produced if f.startswith("results/runs/")}
    assert set(study.meshes) == {f for f in produced if f.startswith("results/mesh/")}
    # reference engines only at the paper's point, where the convergence tables write
    # every engine's default run: each reference run once, the sweep engine's too
    for run in study.reference_runs():
        assert f"_beta{study.paper_spiral}_" in run and run not in produced
    by_tables = [run for trace in plan.PAPER_TRACES for model in plan.CONTACT_MODELS
                 for run in study.convergence_runs(trace, model)]
    assert len(by_tables) == len(set(by_tables))
    assert set(by_tables) == set(study.paper_runs)
    assert set(study.reference_runs()) < set(by_tables)
    assert study.default_runs("circular", "point") == [
        "compiled=results/runs/circular_beta35_point_compiled.nc",
        "pybullet=results/runs/circular_beta35_point_pybullet.nc"]
    assert study.targets == [*study.reports.values(), plan.FILES["sweep"],
                             plan.FILES["summary"], *study.tca_files, *study.vh_maps,
                             *study.vh_cases(), *study.tooth_files, *study.fe_cases(),
                             *study.rating_files, *study.speed_curves,
                             *study.practice_files("rating"),
                             *study.practice_files("vh_map"), *study.load_curves,
                             *study.optimise_fronts, *study.matched_pairs,
                             *study.best_files("rating"),
                             *study.best_files("vh_map"),
                             *(p["file"] for p in study.cutter_points),
                             *study.pair_case_files("practice", "vh_case"),
                             *study.pair_case_files("practice", "fe_case"),
                             *study.pair_case_files("best", "vh_case"),
                             *study.pair_case_files("best", "fe_case")]
    # the cutter-radius sweep: the LSBG, then ISO 23509's SBG at each nominal cutter radius
    # that fits and at the LSBG's lengthwise curvature radius R_m / sin(beta_m)
    assert [p["file"] for p in study.cutter_points] == [
        "results/cutter/lsbg.nc", *(f"results/cutter/face_milled_r{r}.nc" for r in (
            "44.45", "63.5", "76.2", "95.25", "114.3", "127.581"))]
    # each trace's search at optimise.seeds = 3 seeds, and the chosen ease-off's rating and
    # V-H map: the practice pair's traces, its SBG ISO 23509's face-milled one; each trace's
    # converged fronts and the traces' comparison
    assert study.practice_traces == ("logarithmic", "face_milled")
    assert study.optimise_fronts == [f"results/optimise/{t}_beta35_seed{s}_front.nc"
                                     for t in ("logarithmic", "face_milled") for s in (1, 2, 3)]
    assert study.optimise_converged_fronts == [
        f"results/optimise/{t}_beta35_converged_front.nc" for t in ("logarithmic", "face_milled")]
    assert study.trace_fronts == ["results/optimise/trace_fronts.nc"]
    assert study.matched_pairs == ["results/optimise/matched_pairs.nc"]
    assert "results/optimise/matched_pairs.nc" in study.targets
    assert study.both_traces("optimise_release") == [
        f"results/optimise/{t}_beta35_release.nc" for t in ("logarithmic", "face_milled")]
    assert study.best_files("rating") == ["results/best/rating/logarithmic_beta35.nc",
                                          "results/best/rating/face_milled_beta35.nc"]
    # the practice design point of each trace and the load curves of both designs (the
    # published pair's SBG the paper's arc)
    assert study.practice_files("rating") == ["results/practice/rating/logarithmic_beta35.nc",
                                              "results/practice/rating/face_milled_beta35.nc"]
    assert study.load_curves == [f"results/load_curves/{d}_{t}_beta35.nc"
                                 for d, sbg in (("paper", "circular"), ("practice", "face_milled"))
                                 for t in ("logarithmic", sbg)]
    assert study.practice_file("run", "face_milled") == \
        "results/practice/runs/face_milled_beta35_line_compiled.nc"
    # the paper's SBG for the practice pair too, when asked
    papers = plan.Study(load(practice={"sbg_trace": "circular"}))
    assert papers.practice_files("rating") == ["results/practice/rating/logarithmic_beta35.nc",
                                               "results/practice/rating/circular_beta35.nc"]
    assert re.fullmatch(study.wildcards["trace"], "face_milled")
    # the sensitivity cases: every case's run; the V-H maps and FE loaded TCAs of the
    # cases that reach them (crowning and line stiffness; crowning)
    assert len(study.sensitivity_runs()) == 2 * len(study.sensitivity) == 2 * 16
    # the rating takes every case's K_v but the two at other pinion speeds
    assert study.rated_cases == [c for c in study.sensitivity if "pinion_speed" not in c]
    assert len(study.rated_cases) == 14 and "boundary_driveline" in study.rated_cases
    assert {f.rsplit("_beta35_", 1)[1] for f in study.vh_cases()} == {
        f"{case}.nc" for case in ("crowning_x0", "crowning_x0.5", "crowning_x2",
                                  "line_stiffness_N_per_mm_um_x0.5",
                                  "line_stiffness_N_per_mm_um_x2")}
    assert {f.rsplit("_beta35_", 1)[1] for f in study.fe_cases()} == {
        f"{case}_ltca.nc" for case in ("crowning_x0", "crowning_x0.5", "crowning_x2")}
    # the practice and best pairs' cells: the default study's crowning cases on both
    # traces (practice.sensitivity), every case of the section under 'all'
    # the practice and best pairs' runs also at the other speeds and under the driveline
    crowning = ("crowning_x0", "crowning_x0.5", "crowning_x2")
    dynamics = (*crowning, "pinion_speed_x0.25", "pinion_speed_x1.5", "boundary_driveline")
    for flanks in ("practice", "best"):
        assert study.pair_case_files(flanks, "sensitivity_run") == [
            f"results/{flanks}/sensitivity/{t}_beta35_{case}.nc" for case in dynamics
            for t in ("logarithmic", "face_milled")]
        assert study.pair_case_files(flanks, "vh_case", "face_milled") == [
            f"results/{flanks}/vh/face_milled_beta35_{case}.nc" for case in crowning]
        assert study.pair_case_files(flanks, "fe_case", "logarithmic") == [
            f"results/{flanks}/tooth/logarithmic_beta35_{case}_ltca.nc" for case in crowning]
    every = plan.Study(load(practice={"sensitivity": ["all"]}))
    assert every.pair_cases == every.sensitivity and len(every.pair_cases) == 16
    assert every.pair_stage_cases("contact_state") == every.stage_cases("contact_state")
    assert every.pair_case_run("best", "face_milled", "slices_x2") == \
        "results/best/sensitivity/face_milled_beta35_slices_x2.nc"
    assert plan.Study(load(optimise={"enabled": False})).pair_case_files("best", "vh_case") == []
    # the ISO 10300 rating: the paper's point of each trace, K_v from its line run
    assert study.rating_files == ["results/rating/logarithmic_beta35.nc",
                                  "results/rating/circular_beta35.nc"]
    assert study.rating_run("circular") == ["results/runs/circular_beta35_line_compiled.nc"]
    # the displaced assemblies' FE loaded TCAs: half the aligned one's positions
    from lsbg.tooth.analysis import envelope_positions

    assert envelope_positions(default["tooth"]["ltca_positions"]) == 100


def test_the_fe_compliance_is_planned_at_the_paper_point_or_everywhere(default):
    """compliance uniform: the FE compliance and loaded TCA at the paper's point, both
    traces; fe: every design point's compliance, and its loaded TCA is the design point's."""
    study = plan.Study(default)
    assert not study.own_compliance and study.needs_fe_ltca
    assert study.tooth_files == [f"results/tooth/{t}_beta35_{what}.nc"
                                 for t in plan.PAPER_TRACES for what in ("compliance", "ltca")]
    assert study.fe_ltca("circular", "35") == "results/tooth/circular_beta35_ltca.nc"
    fe = plan.Study(load(contact={**default["contact"], "compliance": "fe"},
                         sensitivity={**default["sensitivity"], "compliance": ["uniform"]}))
    assert fe.own_compliance and fe.needs_fe_ltca
    assert fe.tooth_files == [fe.compliance(t, s) for t, s in fe.points]
    assert len(fe.tooth_files) == len(study.points)
    assert fe.fe_ltca("logarithmic", "22.5") == "results/mesh/logarithmic_beta22.5.nc"
    # the line model's runs then depend on the tooth section too
    assert "tooth" in plan.simulation_params(fe.config, "compiled", "line")["contact"]
    assert "tooth" not in plan.simulation_params(fe.config, "compiled", "point")["contact"]


def test_contact_state_files_cover_every_design_point(default):
    study = plan.Study(default)
    traces, spirals = default["sweep"]["traces"], default["sweep"]["spiral_angles_deg"]
    assert len(study.points) == len(set(study.points)) == len(traces) * len(spirals)
    assert set(study.points) == set(plan.design_points(default))
    assert len(study.tca_files) == len(set(study.tca_files)) == len(study.points)
    assert study.tca("circular", "35") == "results/tca/circular_beta35.nc"
    assert study.vh_map("logarithmic", "22.5") == "results/vh/logarithmic_beta22.5.nc"
    assert set(study.paper_tca_files) < set(study.tca_files)
    assert set(study.paper_vh_maps) == {f"results/vh/{t}_beta35.nc" for t in plan.PAPER_TRACES}
    # the paper's point gets the fine map, the other angles of the sweep the coarse one
    assert study.map_steps("35") == default["misalignment_map"]["steps"] == 9
    assert study.map_steps("30") == study.map_steps("22.5") == 5
    # a paper angle outside the sweep: its points are added (both traces)
    config = load(paper_spiral_angle_deg=33, sweep={"traces": ["logarithmic"],
                                                    "spiral_angles_deg": [30]})
    study = plan.Study(config)
    assert study.points == [("logarithmic", "30"), ("logarithmic", "33"), ("circular", "33")]
    assert set(study.points) == set(plan.design_points(config))


def test_contact_state_is_a_rerun_trigger_of_every_line_model_job(default):
    line = plan.simulation_params(default, "compiled", "line")
    point = plan.simulation_params(default, "pybullet", "point")
    assert line["contact"]["flank_modification"] == default["flank_modification"]
    assert line["contact"]["misalignment"] == default["misalignment"]
    assert "flank_modification" not in point["contact"]     # conjugate flanks
    crowned = copy.deepcopy(default)
    crowned["flank_modification"]["bias_um"] = 3
    assert plan.simulation_params(crowned, "compiled", "line") != line
    assert plan.simulation_params(crowned, "pybullet", "point") == point
    # the contact-state job: its sections, its point's steps, the line model, the load
    paper = plan.contact_state_params(default, "35", "compiled")
    sweep = plan.contact_state_params(default, "30", "compiled")
    assert paper["steps"] == 9 and sweep["steps"] == 5
    assert paper["load_torque_N_m"] == default["simulation"]["load_torque_N_m"]
    assert paper["contact"] == line["contact"]
    assert {k: v for k, v in paper.items() if k != "steps"} == \
        {k: v for k, v in sweep.items() if k != "steps"}
    for section, key, value in (("tca", "positions", 100), ("misalignment", "offset_E_mm", 0.05),
                                ("misalignment_map", "range", 0.05),
                                ("contact", "line_stiffness_N_per_mm_um", 20.0)):
        changed = copy.deepcopy(default)
        changed[section][key] = value
        assert plan.contact_state_params(changed, "35", "compiled") != paper, section
    changed = copy.deepcopy(default)
    changed["misalignment_map"]["load_torque_N_m"] = 1000
    assert plan.contact_state_params(changed, "35", "compiled")["load_torque_N_m"] == 1000


def test_the_paper_point_is_not_in_a_batch(default):
    study = plan.Study(default)
    for trace in plan.PAPER_TRACES:
        assert study.paper_spiral not in study.batch_spirals(trace)
        assert study.batch_spirals(trace)


def test_a_third_trace_runs_every_angle_in_its_batch():
    """ISO 23509's SBG in the sweep (workflow/config-sweep-face-milled.yaml): its batch holds
    the paper's angle too, the paper point's own jobs stay the pair's."""
    overlay = yaml.safe_load((REPO / "workflow" / "config-sweep-face-milled.yaml").read_text())
    study = plan.Study(load(sweep=overlay["sweep"]))  # (merged into the section, as Snakemake does)
    spirals = study.spirals
    assert study.traces == ["logarithmic", "circular", "face_milled"]
    assert study.batch_groups() == [
        ("", ["logarithmic", "circular"], [s for s in spirals if s != study.paper_spiral]),
        ("_all_angles", ["face_milled"], spirals)]
    # every design point once, the face-milled SBG's at every angle; no reference runs,
    # sensitivity cases or paper-point files of it
    assert [s for t, s in study.points if t == "face_milled"] == spirals
    assert len(study.points) == len(set(study.points)) == 3 * len(spirals)
    produced = [f for t in study.traces for f in study.batch_outputs(t)]
    produced += study.paper_geometry + study.paper_meshes
    assert len(produced) == len(set(produced))
    assert {r for r in study.sweep_runs if "face_milled" in r} <= set(produced)
    assert not [f for f in study.paper_runs + study.sensitivity_runs() + study.vh_cases()
                if "face_milled" in f]


def test_sensitivity_and_speed_sweep_runs_are_named_by_case_and_speed():
    config = load("config-speed.yaml")
    study = plan.Study(config)
    grid = config["speed_sweep"]["pinion_speeds_deg_s"]
    assert len(study.speeds) == len(set(study.speeds)) == grid["count"]
    assert float(study.speeds[0]) == pytest.approx(grid["start"])
    assert float(study.speeds[-1]) == pytest.approx(grid["stop"])
    # both traces under both boundaries, a curve per boundary
    assert study.speed_boundaries == ["prescribed_pinion", "driveline"]
    assert len(study.speed_runs()) == len(set(study.speed_runs())) == 2 * 2 * grid["count"]
    assert len(study.speed_runs("driveline")) == 2 * grid["count"]
    assert all("_driveline_w" in run for run in study.speed_runs("driveline"))
    assert study.speed_curves == ["results/speed_curve_prescribed_pinion.nc",
                                  "results/speed_curve_driveline.nc"]
    assert set(study.speed_curves) <= set(study.targets)
    cases = study.sensitivity_runs()
    # every entry one case, but an envelope: one case per corner of the V-H envelope
    corners = 2 ** len(config["misalignment_map"]["axes"])
    entries = sum(len(v) * (corners if k == "displacement" else 1)
                  for k, v in config["sensitivity"].items())
    assert len(cases) == len(set(cases)) == 2 * entries
    assert any("_displaced_E-0.1_P+0.1.nc" in case for case in cases)


def test_simulation_params_hold_only_what_the_run_reads(default):
    pybullet = plan.simulation_params(default, "pybullet", "point")
    assert "time_step_s" in pybullet["simulation"] and "rtol" not in pybullet["simulation"]
    assert "stiffness_N_per_mm1_5" in pybullet["contact"]
    assert "slices" not in pybullet["contact"]
    line = plan.simulation_params(default, "compiled", "line")
    assert "time_step_s" not in line["simulation"] and "slices" in line["contact"]
    changed = copy.deepcopy(default)
    changed["contact"]["slices"] = 40
    assert plan.simulation_params(changed, "pybullet", "point") == pybullet
    assert plan.simulation_params(changed, "compiled", "line") != line


def test_study_config_holds_every_section_a_command_reads(default, tmp_path):
    """A section that the study config lacks is read at its defaults by the command: the
    workflow's ``optimise`` section once ran every search at the default budget."""
    from lsbg.cli import command_parsers

    read = {section for parser in command_parsers().values()
            for section in parser.get_default("sections") or ()}
    assert "optimise" in read and "limits" in read
    assert read <= set(plan.STUDY_SECTIONS) | {"speed_sweep"}
    changed = copy.deepcopy(default)
    changed["optimise"]["population"] = 8
    path = tmp_path / "config.yaml"
    plan.write_study_config(path, changed)
    assert yaml.safe_load(path.read_text(encoding="utf-8"))["optimise"]["population"] == 8


def test_study_config_is_written_only_when_it_changes(default, tmp_path):
    path = tmp_path / "results" / "config.yaml"
    plan.write_study_config(path, default)
    written = yaml.safe_load(path.read_text(encoding="utf-8"))
    assert set(written) == {*plan.STUDY_SECTIONS, "speed_sweep"}  # (the default sweeps speeds)
    assert written["design"]["module_mm"] == default["design"]["module_mm"]
    # the contact state, as lsbg's commands read it
    assert written["flank_modification"] == default["flank_modification"]
    assert written["misalignment_map"] == default["misalignment_map"]
    os.utime(path, (1, 1))
    plan.write_study_config(path, default)
    assert path.stat().st_mtime == 1                      # same text: not touched
    changed = copy.deepcopy(default)
    changed["simulation"]["samples"] = 1000
    plan.write_study_config(path, changed, only_if_missing=True)
    assert path.stat().st_mtime == 1                      # exists: a dry run leaves it
    plan.write_study_config(path, changed)
    assert yaml.safe_load(path.read_text(encoding="utf-8"))["simulation"]["samples"] == 1000
    assert not list(path.parent.glob("*.part"))


class Rule:
    """A stand-in of a Snakemake rule: a name, input files (or functions) and outputs."""

    def __init__(self, name, input=(), output=()):
        self.name, self.input, self.output, self.priority = name, list(input), list(output), 0


def test_the_rule_graph_comes_from_the_rules_files():
    geometry = Rule("geometry", output=["results/geometry/{trace}_beta{spiral}"])
    ltca = Rule("ltca", input=["results/geometry/{trace}_beta{spiral}", "results/config.yaml"],
                output=["results/mesh/{trace}_beta{spiral}.nc"])
    run = Rule("run", input=[lambda w: [f"results/geometry/{w.trace}_beta{w.spiral}"]],
               output=["results/runs/{trace}_beta{spiral}_{model}.nc"])
    combine = Rule("combine", input=[["results/runs/circular_beta20_line.nc",
                                      "results/mesh/circular_beta20.nc"]],
                   output=["results/sweep.nc"])
    report = Rule("report", input=["results/sweep.nc", "results/mesh/circular_beta20.nc"],
                  output=["reports/paper.html"])
    graph = job_order.rule_graph([geometry, ltca, run, combine, report],
                                 samples={"trace": "circular", "spiral": "35"})
    assert graph == {"geometry": ["ltca", "run"], "ltca": ["combine", "report"],
                     "run": ["combine"], "combine": ["report"], "report": []}
    # a function that needs more than sample wildcards draws no edge (and raises nothing)
    broken = Rule("broken", input=[lambda w: 1 / 0])
    assert job_order.rule_graph([geometry, broken])["geometry"] == []


def test_jobs_run_highest_level_first():
    seconds = {"geometry": 5.0, "ltca": 1.0, "run": 10.0, "combine": 3.0, "report": 15.0}
    rules = [Rule("geometry", output=["g/{p}"]), Rule("ltca", ["g/{p}"], ["m/{p}"]),
             Rule("run", ["g/{p}"], ["r/{p}"]), Rule("combine", ["r/x", "m/x"], ["s"]),
             Rule("report", ["s", "m/x"], ["h"]), Rule("new_stage", ["s"], ["n"])]
    priorities = job_order.assign_priorities(rules, seconds=seconds)
    # its own seconds plus the longest chain of the rules that wait for it, in 0.1 s
    assert priorities == {"geometry": 330, "ltca": 190, "run": 280, "combine": 180,
                          "report": 150, "new_stage": 0}
    assert [r.priority for r in rules] == list(priorities.values())
    # a job starts before every job that waits for it; a rule not measured counts 0 s
    graph = job_order.rule_graph(rules)
    assert all(priorities[a] > priorities[b] for a, later in graph.items() for b in later
               if b != "new_stage")
    # the measured seconds are the default study's rules
    assert {"paper_geometry", "sweep_points", "report_paper"} <= set(job_order.JOB_SECONDS)


def _workflow(rate_limit, local=True):
    """A stand-in for the running Workflow: its scheduler's rate limiter as Snakemake makes
    it from ``--max-jobs-per-timespan``."""
    from types import SimpleNamespace

    from snakemake.scheduling.job_scheduler import JobRateLimiter
    from snakemake.settings.types import MaxJobsPerTimespan

    limiter = JobRateLimiter(MaxJobsPerTimespan.parse_choice(rate_limit))
    return SimpleNamespace(local_exec=local, remote_exec=not local,
                           scheduler=SimpleNamespace(job_rate_limiter=limiter))


def test_a_local_run_drops_only_snakemakes_default_job_rate_limit():
    from snakemake.cli import get_argument_parser

    # the limit taken off is Snakemake's own default (a new default fails here first)
    default = get_argument_parser().get_default("max_jobs_per_timespan")
    workflow = _workflow(default)
    assert (workflow.scheduler.job_rate_limiter.max_jobs,
            workflow.scheduler.job_rate_limiter.timespan) == job_order.DEFAULT_RATE_LIMIT
    assert job_order.lift_job_rate_limit(workflow) is True
    assert workflow.scheduler.job_rate_limiter is None
    assert job_order.lift_job_rate_limit(workflow) is False  # nothing left to take off
    # a limit the user chose, and one under SLURM, stay
    for chosen, local in (("50/1m", True), ("100/2s", True), (default, False)):
        workflow = _workflow(chosen, local)
        assert job_order.lift_job_rate_limit(workflow) is False
        assert workflow.scheduler.job_rate_limiter is not None


def test_the_default_study_compares_the_traces_in_the_paper_cell_only(default):
    study = plan.Study(default)
    assert [c["label"] for c in study.trace_cells] == ["beta35"]
    assert study.trace_fronts == ["results/optimise/trace_fronts.nc"]
    assert study.other_cells == {} and sum(study.trace_study_jobs.values()) == 0
    # the paper cell's chain is the optimise rules' files
    assert study.cell_converged_fronts("beta35") == study.optimise_converged_fronts


def test_every_other_cell_has_its_chain_and_shares_the_angles_lsbg():
    config = load(trace_study={"spiral_angles_deg": [35, 25], "cutter_radii_mm": [76.2, 95.25]})
    study = plan.Study(config)
    labels = [c["label"] for c in study.trace_cells]
    assert labels == ["beta35", "beta35_r95.25", "beta25", "beta25_r95.25"]
    assert study.trace_fronts == ["results/optimise/trace_fronts.nc",
                                  *(f"results/optimise/trace_fronts_{c}.nc" for c in labels[1:])]
    # the LSBG of a cutter cell: its angle's (the paper's files at the paper's angle)
    assert study.cell_converged_fronts("beta35_r95.25") == [
        "results/optimise/logarithmic_beta35_converged_front.nc",
        "results/trace_study/beta35_r95.25/face_milled_converged_front.nc"]
    assert study.cell_converged_fronts("beta25_r95.25")[0] == \
        "results/trace_study/beta25/logarithmic_converged_front.nc"
    # one practice design per angle, the paper's the practice rules'
    assert study.cell_file("practice_design", "face_milled", "beta35_r95.25") == \
        "results/practice/design.yaml"
    assert study.cell_file("practice_design", "logarithmic", "beta25_r95.25") == \
        "results/trace_study/beta25_design.yaml"
    assert study.cell_settings("beta25_r95.25", "face_milled") == [
        "design.spiral_angle_deg=25", "design.cutter_radius_mm=95.25"]
    assert study.cell_settings("beta25_r95.25", "logarithmic") == ["design.spiral_angle_deg=25"]
    seeds = len(study.optimise_seeds)
    # searched: the SBG in 3 other cells, the LSBG at 25 deg once
    assert study.trace_study_jobs == {
        "cell_practice_design": 1, "cell_geometry": 4, "cell_compliance": 4,
        "cell_optimise": 4 * seeds, "cell_release": 4, "cell_converged_front": 4,
        "cell_trace_fronts": 3}
