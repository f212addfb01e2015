"""The Snakemake workflow: config validation, lint, the tiny study end to end, incrementality.

Every test runs ``python -m snakemake`` in a subprocess, in a temporary
directory, so that nothing is written into the repository:

* configuration and lint tests use the repository's Snakefile (``--snakefile``)
  from an empty working directory;
* the end-to-end tests copy the repository's files (``git ls-files``) into a
  temporary directory and run there with ``PYTHONPATH`` pointing at the copy,
  so that the jobs run the copy's lsbg and a changed file of the copy reruns
  what uses it, without touching the repository.
"""

import os
import re
import shutil
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

from lsbg.study import job_order
from tests.workflow.helpers import (REPO, SNAKEFILE, TEST_CONFIG, _JOB, copy_of_study,
                                    dry_run, job_inputs, planned_jobs, report_text, rules_of,
                                    snakemake, write_yaml, dataset_label_problems)


# ------------------------------------------------------------ configuration
# Invalid configurations: tests/study/test_checks.py (the fuzz suite, and a few
# end to end through snakemake -n).


def test_default_and_test_configs_are_valid_and_plan_the_study(tmp_path):
    proc = snakemake("-n", "--snakefile", SNAKEFILE, cwd=tmp_path, check=True)
    jobs = planned_jobs(proc.output)
    config = yaml.safe_load((REPO / "workflow" / "config.yaml").read_text(encoding="utf-8"))
    traces = config["sweep"]["traces"]
    # the paper's point of each trace (geometry, loaded TCA), then the other angles of
    # each trace in one job
    assert rules_of(jobs).count("paper_geometry") == rules_of(jobs).count("paper_ltca") == 2
    assert rules_of(jobs).count("sweep_points") == len(traces)
    points = [f for rule, out in jobs if rule in ("paper_geometry", "sweep_points")
              for f in out.split(", ") if f.startswith("results/geometry/")]
    assert len(points) == len(set(points)) == len(traces) * len(config["sweep"]["spiral_angles_deg"])
    # the reference engines' runs at the paper's point come from the convergence tables
    # (one per trace and model), which write every engine's run at the default settings
    assert "simulate" not in rules_of(jobs)
    assert rules_of(jobs).count("sensitivity") == 2  # one job per trace, every case
    assert rules_of(jobs).count("convergence_point") == rules_of(jobs).count("convergence_line") == 2
    written = {f for rule, out in jobs if rule.startswith("convergence_") for f in out.split(", ")}
    for model, engines in config["engines"]["reference"].items():
        for engine in engines:
            assert {f"results/runs/{t}_beta35_{model}_{engine}.nc" for t in traces} <= written
    for rule in ("combine", "summary", "report_paper", "report_sweep", "report_verification",
                 "all"):
        assert rule in rules_of(jobs)
    # the contact state: the paper's point of each trace a job of its own, the other
    # angles of a trace one job; an unloaded TCA and a V-H map per design point
    # (at the paper's point also the maps of the sensitivity cases that reach it)
    cases = ("line_stiffness_N_per_mm_um_x0.5", "line_stiffness_N_per_mm_um_x2",
             "crowning_x0", "crowning_x0.5", "crowning_x2")
    state = {out for rule, out in jobs if rule == "contact_state"}
    assert state == {", ".join([f"results/tca/{t}_beta35.nc", f"results/vh/{t}_beta35.nc",
                                *(f"results/vh/{t}_beta35_{c}.nc" for c in cases)])
                     for t in traces}
    assert rules_of(jobs).count("sweep_contact_state") == len(traces)
    maps = [f for rule, out in jobs if rule in ("contact_state", "sweep_contact_state")
            for f in out.split(", ") if f.startswith("results/vh/") and "_x" not in f]
    assert len(maps) == len(set(maps)) == len(points)
    # The settings lsbg reads, as validated (schema defaults filled in).
    written = yaml.safe_load((tmp_path / "results" / "config.yaml").read_text(encoding="utf-8"))
    assert set(written) == {"design", "simulation", "driveline", "contact",
                            "flank_modification", "misalignment", "tca", "misalignment_map",
                            "statistics", "tooth", "rating", "practice", "optimise", "limits",
                            "speed_sweep"}
    assert written["simulation"]["duration_s"] == config["simulation"]["duration_s"]
    # the search's budget as configured (lsbg optimise reads it from this file)
    assert written["optimise"]["population"] * written["optimise"]["generations"] == 360
    assert written["flank_modification"]["lengthwise_crowning_um"] == 25
    assert written["misalignment_map"]["sweep_steps"] == config["misalignment_map"]["sweep_steps"]


def test_the_sweep_with_iso_23509s_sbg_plans_one_more_job_per_stage(tmp_path):
    """workflow/config-sweep-face-milled.yaml: the face-milled SBG at every angle, the paper's
    too, in one points job and one contact-state job; the paper point's jobs stay the pair's."""
    proc = snakemake("-n", "--snakefile", SNAKEFILE, "--configfile",
                     str(REPO / "workflow" / "config-sweep-face-milled.yaml"), cwd=tmp_path,
                     check=True)
    jobs = planned_jobs(proc.output)
    config = yaml.safe_load((REPO / "workflow" / "config.yaml").read_text(encoding="utf-8"))
    angles = config["sweep"]["spiral_angles_deg"]
    assert rules_of(jobs).count("sweep_points") == rules_of(jobs).count("sweep_contact_state") == 2
    assert rules_of(jobs).count("sweep_points_all_angles") == 1
    assert rules_of(jobs).count("sweep_contact_state_all_angles") == 1
    points = [f for rule, out in jobs if rule == "sweep_points_all_angles"
              for f in out.split(", ") if f.startswith("results/geometry/")]
    assert points == [f"results/geometry/face_milled_beta{a:g}" for a in angles]
    for rule in ("paper_geometry", "paper_ltca", "contact_state", "convergence_point",
                 "convergence_line", "sensitivity"):
        assert rules_of(jobs).count(rule) == 2, rule
        assert not [out for r, out in jobs if r == rule and "face_milled_beta" in out], rule


def test_priorities_follow_the_studys_rule_graph(tmp_path):
    """Each rule's priority (lsbg.study.job_order, from the rules once defined) is its own
    measured seconds plus the longest chain of the rules that wait for it, in Snakemake's
    own rule graph."""
    proc = snakemake("--rulegraph", "--snakefile", SNAKEFILE, cwd=tmp_path, check=True)
    labels = dict(re.findall(r"^\s*(\d+)\[label = \"(\w+)\"", proc.stdout, re.M))
    edges = {(labels[a], labels[b]) for a, b in re.findall(r"^\s*(\d+) -> (\d+)$",
                                                            proc.stdout, re.M)}
    priorities = {rule: int(p) for rule, p in re.findall(
        r"^(?:local)?rule (\w+):\n(?:    .*\n)*?    priority: (\d+)", snakemake(
            "-n", "--snakefile", SNAKEFILE, cwd=tmp_path, check=True).output, re.M)}
    assert set(priorities) == set(labels.values()) - {"all"}
    for rule, priority in priorities.items():
        waiting = [priorities[b] for a, b in edges if a == rule and b != "all"]
        own = round(10 * job_order.JOB_SECONDS.get(rule, 0.0))
        assert abs(priority - own - max(waiting, default=0)) <= 1, (rule, priority, waiting)
    # the longest chain starts first: the highest priority is a rule that waits for none
    # (the practice design's, since its chain holds the searches and their release; the
    # paper point's geometry opens the paper jobs' chain, before any of them);
    # the kernels' job opens the sweep's, before the sweep's jobs
    first = max(priorities, key=priorities.get)
    assert not any(b == first for _, b in edges), (first, priorities)
    assert priorities["paper_geometry"] > max(
        priorities[b] for a, b in edges if a == "paper_geometry" and b != "all")
    assert priorities["kernels"] > priorities["sweep_points"]


_COMMAND = re.compile(r"lsbg -v (report \w+|[\w-]+) ")


def test_rules_list_the_lsbg_files_they_run(tmp_path):
    """A rule's sources are the files its command's handler reaches (and a report's
    notebook's imports): derived from the imports (lsbg.study.stages), listed with their
    digests in one input per job (.snakemake/lsbg-sources/), checked here against the
    command each job runs."""
    from lsbg.cli import handler_of
    from lsbg.study.stages import function_closure, notebook_closure, sources_listing

    proc = snakemake("-n", "-p", "--snakefile", SNAKEFILE, cwd=tmp_path, check=True)
    inputs = job_inputs(proc.output)
    commands = {}
    for block in re.split(r"\n(?=\[|localrule |rule )", proc.output):
        rule = re.match(r"(?:local)?rule (\w+):", block)
        command = _COMMAND.search(block)
        if rule and command:
            commands.setdefault(rule.group(1), command.group(1))
    assert set(commands) == set(inputs) - {"all"}
    listed = {}
    for rule, command in commands.items():
        name, _, notebook = command.partition(" ")
        listing = [f for f in inputs[rule] if f.startswith(".snakemake/lsbg-sources/")]
        assert listing == [f".snakemake/lsbg-sources/{name}{'-' + notebook if notebook else ''}"
                           f".sha256"], rule
        assert not any(f.startswith("lsbg/") for f in inputs[rule]), rule   # one input only
        handler = handler_of(name)
        modules = function_closure(handler.__module__.removeprefix("lsbg."), handler.__name__)
        if notebook:
            modules |= notebook_closure(REPO / "lsbg" / "notebooks" / f"{notebook}.ipynb")
        text = (tmp_path / listing[0]).read_text(encoding="utf-8")
        assert text == sources_listing(modules), rule
        listed[rule] = {line.split("  ", 1)[1] for line in text.splitlines()}
    # precise: the geometry does not rerun for the dynamics or the statistics
    assert not any(f.endswith(("verification.py", "summary.py", "pybullet_engine.py"))
                   for f in listed["paper_geometry"])
    assert "lsbg/tca/vh_map.py" in listed["contact_state"]
    assert "lsbg/tca/vh_map.py" not in listed["convergence_line"]
    for name in ("paper", "sweep", "verification"):
        assert any(f.endswith(f"lsbg/notebooks/{name}.ipynb")
                   for f in inputs[f"report_{name}"])


def test_lint_passes(tmp_path):
    proc = snakemake("--lint", "--snakefile", SNAKEFILE, cwd=tmp_path)
    assert proc.returncode == 0, proc.output
    assert "good condition" in proc.output


def test_slurm_profile_schedules_with_resources(tmp_path):
    """The SLURM profile alone selects the executor and gives every job its memory, time
    and one CPU, the searches as many as their threads, optimise.workers (dry run, no
    sbatch; tests/workflow/test_slurm.py runs it on a real cluster)."""
    profile = REPO / "workflow" / "profiles" / "slurm"
    assert yaml.safe_load((profile / "config.yaml").read_text())["executor"] == "slurm"
    proc = snakemake("-n", "--snakefile", SNAKEFILE, "--configfile", REPO / TEST_CONFIG,
                     "--profile", profile, cwd=tmp_path, check=True)
    jobs = [(rule, body) for rule, body in _JOB.findall(proc.output) if rule != "all"]
    assert jobs
    for rule, body in jobs:
        assert re.search(r"mem_mb=\d+", body) and re.search(r"runtime=\d+", body), body
        if rule.startswith("optimise"):  # the plugin asks for the rule's threads
            assert "cpus_per_task" not in body and "threads:" not in body, body
        else:
            assert "cpus_per_task=1" in body, body
    assert any(rule.startswith("optimise") for rule, _ in jobs)


# ---------------------------------------------------------------- end to end


@pytest.fixture(scope="module")
def swept_study(study, tmp_path_factory):
    """Both ways of extending the study, run once together in a copy of the session's study
    (:func:`copy_of_study`, so that the session's study stays as it was, with nothing to
    undo): the sweeps of workflow/config-sweep-example.yaml, a load sweep written in config
    and a new stage written as a rule file (workflow/extensions/mesh_mode.smk). What each
    would run on top of the finished study alone is planned first (``plans``)."""
    folder = tmp_path_factory.mktemp("swept")
    copy = copy_of_study(study, folder / "study")
    example = copy[0] / "workflow" / "config-sweep-example.yaml"
    load = write_yaml(folder / "load.yaml", {"sweeps": {"load": {
        "simulation.load_torque_N_m": [1000, 1500], "contact_model": "point"}},
        "extensions": ["mesh_mode"]})
    plans = {"example": dry_run(copy, example), "load": dry_run(copy, load)}
    snakemake("-j2", "--configfile", TEST_CONFIG, example, load, cwd=copy[0], env=copy[1],
              check=True)
    return SimpleNamespace(copy=copy, configs=(example, load), plans=plans, folder=folder)


@pytest.mark.slow
def test_sweeps_written_in_config_only_give_one_dataset_each(swept_study):
    """workflow/config-sweep-example.yaml on top of the test study: a friction sweep (one
    key, 5 values) and a two-key product sweep, one dataset each with its coordinates,
    only the sweeps' jobs run (the study is done), a batch job per batch_size points."""
    root = swept_study.copy[0]
    jobs, _ = swept_study.plans["example"]
    batches = [rule for rule in rules_of(jobs) if rule.startswith("sweep_")]
    assert batches == sorted(["sweep_damping_and_stiffness_batch0"] * 2
                             + ["sweep_damping_and_stiffness_batch1"] * 2
                             + ["sweep_damping_and_stiffness_combine",
                                "sweep_friction_batch0", "sweep_friction_batch0",
                                "sweep_friction_combine"])
    # (and the sweep report, which plots each sweep)
    # (and the paper report, which states the loads the sweeps ran)
    assert set(rules_of(jobs)) - set(batches) == {"report_sweep", "report_paper", "all"}
    html = (root / "reports" / "sweep.html").read_text(encoding="utf-8")
    assert "8. Parameter sweeps" in html and "Sweep 'friction' at 35°" in html
    assert "one line per mesh damping ratio" in html
    # the values themselves under "values of", the quasi-static contact beside the dynamics
    assert "values of dynamic friction" in html and "0, 0.05, 0.1, 0.15, 0.2" in html
    assert "bearing pattern length [mm]" in html
    assert not dataset_label_problems(root / "results" / "sweeps")
    with xr.open_dataset(root / "results" / "sweeps" / "friction.nc") as ds:
        assert ds["contact.dynamic_friction"].values.tolist() == [0, 0.05, 0.1, 0.15, 0.2]
        assert ds["gear_speed_full_rate_std"].dims == ("trace", "spiral_angle",
                                                       "contact.dynamic_friction")
        assert np.isfinite(ds["gear_speed_full_rate_std"]).all()
        assert ds["contact.dynamic_friction"].attrs["long_name"] == "dynamic friction"
        # friction leaves the quasi-static contact as it is: the same at every point
        for figure in ("loaded_te_peak_to_peak", "pattern_length"):
            assert (ds[figure] > 0).all() and (ds[figure].std("contact.dynamic_friction")
                                               < 1e-9 * ds[figure].mean()).all()
    with xr.open_dataset(root / "results" / "sweeps" / "damping_and_stiffness.nc") as ds:
        assert ds["gear_speed_full_rate_std"].sizes == {
            "trace": 2, "spiral_angle": 1, "contact.mesh_damping_ratio": 3,
            "contact.line_stiffness_N_per_mm_um": 3}
        assert ds["contact.line_stiffness_N_per_mm_um"].attrs["units"] == "N/(mm um)"
        # a stiffer bed, a stiffer mesh: the gear speed's fluctuation falls with it
        speed = ds["gear_speed_full_rate_std"].sel(trace="logarithmic", spiral_angle=35.0)
        assert (speed.diff("contact.line_stiffness_N_per_mm_um") < 0).all()
    table = pd.read_csv(root / "results" / "sweeps" / "friction.csv")
    assert {"contact.dynamic_friction", "quantity", "full_rate_std"} <= set(table.columns)


@pytest.mark.slow
def test_study_writes_the_sweep_dataset_with_units(study):
    root, _ = study
    with xr.open_dataset(root / "results" / "sweep.nc") as ds:
        assert set(ds.dims) == {"contact_model", "trace", "spiral_angle", "time", "time_full",
                                "mesh_phase", "E", "P"}
        assert list(ds.contact_model.values) == ["point", "line"]
        assert list(ds.trace.values) == ["logarithmic", "circular"]
        assert list(ds.spiral_angle.values) == [35.0]
        assert ds["gear_speed"].attrs["units"] == "deg/s"
        assert ds["pinion_speed"].attrs["units"] == "deg/s"
        assert ds["tangential_force"].attrs["units"] == "N"
        assert ds["tangential_force_outer"].attrs["units"] == "N"
        assert ds.attrs["Conventions"].startswith("CF-")
        assert ds.attrs["solver_engine"] == "compiled"
        assert ds.sizes["time"] == 26  # samples 25 -> 26 instants
        assert ds.sizes["time_full"] == 2001  # 50 kHz from 0.01 s to 0.05 s
        assert ds["static_transmission_error_peak_to_peak"].attrs["units"] == "urad"
        assert ds.sizes["mesh_phase"] >= 200
        # the contact state: the crowned pair's unloaded TCA and its 3 x 3 V-H maps
        te = ds["unloaded_transmission_error_peak_to_peak"]
        assert te.attrs["units"] == "urad" and (te > 0).all()
        assert ((ds["pattern_length_per_face_width"] > 0.3)
                & (ds["pattern_length_per_face_width"] < 0.9)).all()
        assert ds.sizes["E"] == ds.sizes["P"] == 3
        assert ds["vh_transmission_error_loaded_pp"].dims == ("trace", "spiral_angle", "E", "P")
        assert np.isfinite(ds["vh_pattern_shift_lengthwise"]).all()
        assert ds["pattern_shift_lengthwise_per_0_1_P"].attrs["units"] == "mm/(0.1 mm)"


@pytest.mark.slow
def test_outputs_do_not_name_the_study_directory(study):
    """Reports, tables, provenance and the summary's log name files relative to the study."""
    root, _ = study
    checked = 0
    for folder in ("results", "reports", "logs/summary", "logs/combine"):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix == ".nc":
                with xr.open_dataset(path) as ds:
                    text = repr(ds.attrs) + "".join(repr(v.attrs) for v in ds.variables.values())
            elif path.suffix in (".html", ".csv", ".json", ".yaml", ".urdf", ".log", ".txt"):
                text = path.read_text(encoding="utf-8")
            else:
                continue
            checked += 1
            assert str(root) not in text, path.relative_to(root)
    assert checked > 20


@pytest.mark.slow
def test_study_writes_the_summary_table(study):
    root, _ = study
    table = pd.read_csv(root / "results" / "summary.csv")
    from lsbg.aggregate.summary import SUMMARY_COLUMNS

    assert list(table.columns) == list(SUMMARY_COLUMNS)
    runs = table[~table.engine.isin(["ltca", "tca"])].groupby("run").size()
    # two traces x (point, line) x compiled, the point model on pybullet, the line model
    # on scipy, five sensitivity cases (damping x2, the tooth's FE compliance, crowning
    # x0.5, the pinion at 1.5 times its speed, the torsional driveline) x two traces
    assert len(runs) == 18
    speed = table[table.quantity == "gear_speed"]
    # the gear at the pinion's speed over the ratio: 1873.703 deg/s, 1.5 times that in the
    # case of the faster pinion
    faster = speed.run.str.contains("pinion_speed_x1.5")
    assert faster.sum() == 2
    assert (abs(speed["mean"] - 1873.703 * np.where(faster, 1.5, 1.0)) / 1873.703 < 0.02).all()
    mesh = table[table.engine == "ltca"]
    assert sorted(mesh.quantity) == ["mesh_stiffness"] * 2 + ["static_transmission_error"] * 2
    assert mesh[mesh.quantity == "static_transmission_error"].harmonic_1.notna().all()
    state = table[table.engine == "tca"]
    # per design point: the unloaded TE, and four sensitivities per axis (E, P)
    assert len(state) == 2 * (1 + 2 * 4)
    assert set(state.run) == {"logarithmic_beta35", "circular_beta35"}
    assert state[state.quantity == "unloaded_transmission_error"].peak_to_peak.gt(0).all()
    assert state[state.quantity.str.endswith("_per_0_1_P")]["mean"].notna().all()


@pytest.mark.slow
@pytest.mark.parametrize("name", ["paper", "sweep", "verification"])
def test_study_renders_the_reports(study, name):
    root, _ = study
    html = (root / "reports" / f"{name}.html").read_text(encoding="utf-8")
    headings = re.findall(r"<h([12])[^>]*>(.*?)</h\1>", html, re.DOTALL)
    assert [level for level, _ in headings].count("1") >= 1
    assert [level for level, _ in headings].count("2") >= 3, headings
    assert html.count("data:image/png;base64,") >= 1
    assert "Traceback" not in html
    # numbers read as in a paper (lsbg.stats.format_number): no e-notation in the text
    text = report_text(root / "reports" / f"{name}.html")
    e_notation = [text[max(m.start() - 60, 0):m.end()]
                  for m in re.finditer(r"\b\d+(?:\.\d+)?e[+-]\d+\b", text)]
    assert not e_notation, e_notation


@pytest.mark.slow
def test_study_keeps_the_logs_and_the_validated_settings(study):
    root, _ = study
    assert "lsbg.solid.export" in (root / "logs" / "paper_geometry"
                             / "logarithmic_beta35.log").read_text()
    assert "tangential_force_std_N" in (root / "logs" / "convergence"
                                        / "circular_line.log").read_text()
    settings = yaml.safe_load((root / "results" / "config.yaml").read_text(encoding="utf-8"))
    assert settings["simulation"]["duration_s"] == 0.05
    assert settings["design"]["module_mm"] == 4.5
    assert settings["statistics"]["subgroup_size"] == 5
    # every search ran the test config's budget, not the default's 360 designs
    test_config = yaml.safe_load((root / TEST_CONFIG).read_text(encoding="utf-8"))
    budget = test_config["optimise"]["population"] * test_config["optimise"]["generations"]
    for front in sorted((root / "results" / "optimise").glob("*_seed*_front.nc")):
        with xr.open_dataset(front) as ds:
            assert int(ds.attrs["evaluations"]) == budget == 24, front.name


@pytest.mark.slow
def test_after_the_run_there_is_nothing_to_do(study):
    jobs, output = dry_run(study)
    assert not jobs, output
    assert "Nothing to be done" in output


@pytest.mark.slow
def test_a_new_spiral_angle_runs_only_its_points_and_the_aggregates(study, tmp_path):
    extra = write_yaml(tmp_path / "more.yaml", {"sweep": {"spiral_angles_deg": [35, 40]}})
    jobs, output = dry_run(study, extra)
    # (the paper report's conclusion says what the sweep finds at the other angles, so it
    # reads the combined sweep and is rendered again; the verification report is not)
    # (the first sweep point: the kernels' job first, lsbg.study.kernels)
    assert rules_of(jobs) == sorted(["kernels"] + ["sweep_points"] * 2
                                    + ["sweep_contact_state"] * 2
                                    + ["combine", "summary", "rating_sweep", "report_sweep",
                                       "report_paper", "all"]), output
    assert {out for rule, out in jobs if rule == "sweep_contact_state"} == {
        f"results/tca/{t}_beta40.nc, results/vh/{t}_beta40.nc"
        for t in ("logarithmic", "circular")}
    new = {f for rule, out in jobs if rule == "sweep_points" for f in out.split(", ")}
    assert new == {"results/geometry/logarithmic_beta40", "results/geometry/circular_beta40",
                   "results/mesh/logarithmic_beta40.nc", "results/mesh/circular_beta40.nc",
                   *(f"results/runs/{t}_beta40_{m}_compiled.nc" for t in ("logarithmic", "circular")
                     for m in ("point", "line"))}


@pytest.mark.slow
def test_a_changed_setting_reruns_only_the_runs_that_use_it(study, tmp_path):
    """The params trigger: the time step concerns the pybullet runs and convergence only, a
    line-model setting the line-model runs and loaded TCAs only."""
    extra = write_yaml(tmp_path / "dt.yaml", {"simulation": {"time_step_s": 2e-6}})
    jobs, output = dry_run(study, extra)
    # (the point model's convergence tables write its compiled runs too: combine follows,
    # and the design point's checks read the point-model run)
    assert rules_of(jobs) == sorted(["convergence_point"] * 2 + _CHECKS + _AGGREGATES), output
    assert {f for rule, out in jobs if rule == "convergence_point" for f in out.split(", ")} == {
        f"results/{name}" for t in ("logarithmic", "circular")
        for name in (f"verification/convergence_{t}_point.csv",
                     f"runs/{t}_beta35_point_compiled.nc", f"runs/{t}_beta35_point_pybullet.nc")}
    extra = write_yaml(tmp_path / "line.yaml", {"contact": {"mesh_damping_ratio": 0.07}})
    jobs, output = dry_run(study, extra)
    # (the FE loaded TCA too: its bands and flanks are the line model's; not the FE
    # compliance, which depends on the design and the tooth section only)
    # (and the rating: its FE loaded TCA and its K_v's line run)
    # (the practice design point's line-model jobs and the load curves likewise)
    _paper_line = (["paper_ltca"] * 2 + ["fe_ltca"] * 2 + ["sensitivity"] * 2
                   + ["convergence_line"] * 2 + ["contact_state"] * 2 + ["rating"] * 2
                   + ["fe_sensitivity"] * 2 + _CHECKS + _AGGREGATES)
    assert rules_of(jobs) == sorted(_paper_line + _PRACTICE_LINE + _CUTTER), output
    # The flanks: every line-model job and the contact state, not the point model; the
    # practice design (its overlay carries the flanks with its tip reliefs) anew.
    extra = write_yaml(tmp_path / "flanks.yaml", {"flank_modification": {"bias_um": 2}})
    jobs, output = dry_run(study, extra)
    assert rules_of(jobs) == sorted(_paper_line + _PRACTICE_ALL + ["load_curve"] * 2 + _CUTTER), \
        output
    # The contact state's own settings: its jobs and what reads them.
    extra = write_yaml(tmp_path / "tca.yaml", {"tca": {"positions": 50}})
    jobs, output = dry_run(study, extra)
    # (the search's settings hold the marking compound only: its choice stays)
    assert rules_of(jobs) == sorted(["contact_state"] * 2 + ["practice_contact_state"] * 2
                                    + ["best_contact_state"] * 2
                                    + ["combine", "summary", "rating_sweep", "report_paper",
                                       "report_sweep", "all"] + _CUTTER), output
    # Statistics settings rerun the statistics, not the simulations; the steady state
    # the convergence tables and the rating's K_v too
    extra = write_yaml(tmp_path / "stats.yaml", {"statistics": {"subgroup_size": 4}})
    jobs, output = dry_run(study, extra)
    assert rules_of(jobs) == sorted(["summary", "rating_sweep", "report_sweep", "all"]), output
    extra = write_yaml(tmp_path / "steady.yaml", {"statistics": {"steady_state_after_s": 0.008}})
    jobs, output = dry_run(study, extra)
    # (and the matched designs' runs: their steady state starts there)
    assert rules_of(jobs) == sorted(_CONVERGENCE + ["rating"] * 2 + ["practice_rating"] * 2
                                    + ["best_rating"] * 2 + ["matched_pairs"] + _CHECKS
                                    + _AGGREGATES), output
    # The rating's own settings: its jobs and the reports that show them
    extra = write_yaml(tmp_path / "rating.yaml", {"rating": {"application_factor": 1.25}})
    jobs, output = dry_run(study, extra)
    # (the sweep report rates every design point by the standard: lsbg rate-sweep; the
    # practice design is made by the rating's rules: made anew, and its load curves)
    assert rules_of(jobs) == sorted(["rating", "rating", "rating_sweep", "report_paper",
                                     "report_sweep", "all"] + _PRACTICE_ALL
                                    + ["load_curve"] * 2), output


_CONVERGENCE = ["convergence_point"] * 2 + ["convergence_line"] * 2
#: The design point's checks (lsbg checks): they read its loaded TCA and point-model run.
_CHECKS = ["checks"] * 2
_AGGREGATES = ["combine", "summary", "rating_sweep", "report_paper", "report_sweep",
               "report_verification", "all"]
#: The practice design point's jobs of both traces, and the load curves of both designs.
_PRACTICE_POINT = [f"practice_{step}" for step in (
    "geometry", "compliance", "fe_ltca", "fe_envelope", "contact_state", "run", "sensitivity",
    "rating")] * 2
_LOAD_CURVES = ["load_curve"] * 4
#: Each type's ease-off searched (three seeds) and released, its fronts at converged
#: positions, the traces' fronts compared and their matched designs, and its design point's jobs.
_OPTIMISE = (["optimise"] * 6 + ["optimise_release"] * 2 + ["optimise_converged_front"] * 2
             + ["trace_fronts", "matched_pairs"])
_BEST = [f"best_{step}" for step in (
    "fe_ltca", "fe_envelope", "contact_state", "run", "sensitivity", "rating")] * 2
#: What the overlay's change reruns: the practice design and everything made from it.
_PRACTICE_ALL = ["practice_design"] + _PRACTICE_POINT + ["load_curve"] * 2 + _OPTIMISE + _BEST
#: What a line-model setting reruns of it: the jobs that read the line model or its runs,
#: the searches (on the line model) and so the chosen designs.
_PRACTICE_LINE = [f"practice_{step}" for step in (
    "fe_ltca", "fe_envelope", "contact_state", "run", "sensitivity", "rating")] * 2 \
    + _LOAD_CURVES \
    + _OPTIMISE + _BEST
#: Every job of the test study.
_EVERYTHING = (["paper_geometry"] * 2 + ["paper_ltca"] * 2 + ["sensitivity"] * 2
               + _CONVERGENCE + ["contact_state"] * 2 + ["tooth_compliance"] * 2
               + ["fe_ltca"] * 2 + ["fe_sensitivity"] * 2 + ["rating"] * 2 + _CHECKS
               + _AGGREGATES + _PRACTICE_POINT + _LOAD_CURVES + _OPTIMISE + _BEST)
#: The cutter-radius sweep's points of the test study: the LSBG (reading the FE loaded TCA
#: of the tooth stage) and the SBG at its three cutters (each pair built in memory).
_CUTTER_SBG = [f"cutter_face_milled_r{r}" for r in ("76_2", "95_25", "127_581")]
_CUTTER = ["cutter_lsbg"] + _CUTTER_SBG
#: The loaded TCA's jobs: the commands that reach lsbg.tca.loaded and what reads them.
#: The practice and best points' jobs that the sensitivity cases do not reach: the runs
#: and the searches (the chosen design is unchanged, so its runs are too).
_NO_CASES = ("practice_run", "best_run", "optimise", "optimise_release",
             "optimise_converged_front", "trace_fronts", "load_curve")
_LOADED_TCA = (["paper_ltca"] * 2 + ["fe_ltca"] * 2 + ["fe_sensitivity"] * 2
               + ["contact_state"] * 2 + ["sensitivity"] * 2 + ["rating"] * 2 + _CHECKS
               + _AGGREGATES)
CODE_CHANGES = {
    # (the rating reads the line run that the convergence table writes, and its K_v
    # comes through lsbg.aggregate.summary, which reads lsbg.stats)
    "lsbg/experiments/verification.py": _CONVERGENCE + ["rating"] * 2 + _CHECKS + _AGGREGATES,
    # (the matched designs read lsbg.stats through lsbg.aggregate.runs, and the practice
    # ratings)
    "lsbg/stats/samples.py": ["rating"] * 2 + ["practice_rating"] * 2 + ["best_rating"] * 2
                             + ["matched_pairs"] + _AGGREGATES,
    # a command depends on its stage only (lsbg.study.stages): the loaded TCA reruns the
    # loaded TCAs (the line model's, the FE one, the V-H maps'), not the runs or the FE
    # compliance; the sensitivity runs and the rating read the FE loaded TCA
    # (the search reads the loaded TCA's stage, so it and its choice's jobs rerun)
    "lsbg/tca/loaded.py": _LOADED_TCA + [r for r in _PRACTICE_LINE if r != "practice_run"]
                          + _CUTTER,
    # the V-H map: the contact state's jobs alone, and the aggregates that read them
    "lsbg/tca/vh_map.py": ["contact_state"] * 2 + ["practice_contact_state"] * 2
                          + _OPTIMISE + _BEST + _CUTTER  # (the search imports lsbg.tca)
                          + ["combine", "summary", "rating_sweep", "report_paper",
                             "report_sweep", "all"],
    # (the cases reach the contact state's and the loaded TCA's commands, lsbg ltca
    # --case, and the rating reads the cases' runs)
    "lsbg/experiments/sensitivity.py": _LOADED_TCA + [
        r for r in _PRACTICE_LINE if r not in _NO_CASES] + ["cutter_lsbg"],
    # every run at the paper's point reads its geometry; the convergence tables write
    # every engine's run there; the FE segment is lofted through the STEP solid's
    # sections (lsbg.solid.step, lsbg.solid.solids)
    # (the cutter sweep's SBG points build their pairs in memory, without lsbg.solid)
    "lsbg/solid/solids.py": _EVERYTHING + ["cutter_lsbg"],
    "lsbg/notebooks/sweep.ipynb": ["report_sweep", "all"],
}


@pytest.mark.slow
@pytest.mark.parametrize("changed", CODE_CHANGES)
def test_a_changed_source_reruns_what_uses_it(study, changed):
    root, _ = study
    path = root / changed
    backup = path.with_name(path.name + ".orig")
    shutil.copy2(path, backup)
    try:
        text = path.read_text(encoding="utf-8")
        if path.suffix == ".ipynb":
            text = text.replace('"cells": [', '"cells": [ ', 1)  # same notebook, other bytes
        else:
            text += "\n# a change\n"
        path.write_text(text, encoding="utf-8")
        jobs, output = dry_run(study)
        assert rules_of(jobs) == sorted(CODE_CHANGES[changed]), output
    finally:
        shutil.copy2(backup, path)  # content and time stamp back
        backup.unlink()
    assert not dry_run(study)[0]


@pytest.mark.slow
def test_report_of_the_provenance(study):
    root, env = study
    proc = snakemake("--report", "provenance.html", "--configfile", TEST_CONFIG, cwd=root,
                     env=env, check=True)
    html = (root / "provenance.html").read_text(encoding="utf-8")
    for item in ("summary.csv", "paper.html", "convergence_circular_line.csv", "pair.png"):
        assert item in html, item
    assert "Report created" in proc.output


# -------------------------------------------------------------- extension
@pytest.mark.slow
def test_the_load_sweep_is_a_sweep_and_mesh_mode_a_new_stage(swept_study, study):
    """Both ways of extending the study, each run: the former load-sweep extension as a
    sweep written in config only (Eq. 13 at each swept torque), and a new stage written
    as a rule file (workflow/extensions/mesh_mode.smk), each adding only its own jobs."""
    copy = swept_study.copy
    root, env = copy
    jobs, output = swept_study.plans["load"]
    assert rules_of(jobs) == sorted(["sweep_load_batch0"] * 2 + ["sweep_load_combine",
                                                                 "mesh_mode", "report_sweep",
                                                                 "report_paper", "all"]), output
    table = pd.read_csv(root / "results" / "sweeps" / "load.csv")
    force = table[table.quantity == "tangential_force_outer"]
    # Eq. 13 with the swept torque: F = 2 T / d2, d2 = 37 * 4.5 mm.
    for torque in (1000, 1500):
        rows = force[force["simulation.load_torque_N_m"] == torque]
        assert len(rows) == 2 and rows["theory"].tolist() == pytest.approx([2 * torque / 0.1665] * 2)
        assert (rows["error_rate_percent"] < 5).all()
    with xr.open_dataset(root / "results" / "sweeps" / "load"
                         / "circular_beta35_load_torque_N_m~1500.nc") as ds:
        assert float(ds.attrs["solver_load_torque_N_m"]) == pytest.approx(1500)
        assert ds.attrs["contact_model"] == "point"
    # the paper report names the loads that ran; the session's study ran one load
    paper = report_text(root / "reports" / "paper.html")
    assert "No other load was run" not in paper
    assert "Other loads ran in the parameter sweep 'load' (1000, 1500 N·m" in paper
    assert "No other load was run" in report_text(study[0] / "reports" / "paper.html")
    modes = pd.read_csv(root / "results" / "extensions" / "mesh_mode.csv")
    assert sorted(modes.trace) == ["circular", "logarithmic"]
    # the mesh frequency z1 n meets f_n at the first resonance speed
    assert (modes["resonance_speed_order_1_deg_s"] / 360 * 9).tolist() == pytest.approx(
        modes["natural_frequency_hz"].tolist(), rel=1e-12)
    assert not dry_run(copy, *swept_study.configs)[0]
    # Without them only the reports that read the sweeps change back; the former section
    # names its replacement.
    jobs, output = dry_run(copy)
    assert rules_of(jobs) == ["all", "report_paper", "report_sweep"], output
    old = write_yaml(swept_study.folder / "old.yaml",
                     {"load_sweep": {"torques_N_m": [1000, 1500]}})
    proc = snakemake("-n", "--configfile", TEST_CONFIG, old, cwd=root, env=env)
    assert proc.returncode != 0
    assert "load_sweep: replaced by the sweeps section" in proc.output
    assert "sweeps: {load: {simulation.load_torque_N_m: [1000, 1500], contact_model: point}}" \
        in proc.output


def test_conda_environment_pins_match_environment_pip():
    """workflow/envs/lsbg.yaml (for --software-deployment-method conda) must not drift."""
    import yaml

    env = yaml.safe_load((REPO / "workflow" / "envs" / "lsbg.yaml").read_text())
    pip_section = next(d["pip"] for d in env["dependencies"] if isinstance(d, dict))
    conda_pins = {line for line in pip_section if "==" in line}
    requirements = {line.strip() for line in (REPO / "environment-pip.txt").read_text().splitlines()
                    if "==" in line and not line.startswith("#")}
    assert conda_pins and conda_pins <= requirements


@pytest.mark.slow
def test_reports_show_well_in_a_browser(study, tmp_path):
    """Each report, opened in headless Chromium 1400 px wide, fits the page, loads nothing
    but itself, has readable tables and opens with its finding
    (workflow/scripts/check_reports.py); screenshots go to tmp_path. Without Chromium the
    test skips, except on CI (CI=true), where it fails."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "check_reports", REPO / "workflow" / "scripts" / "check_reports.py")
    check_reports = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(check_reports)
    reason = check_reports.browser_unavailable()
    if reason:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI needs Chromium for the report checks: {reason}")
        pytest.skip(reason)
    root, _ = study
    problems = []
    with check_reports.open_browser() as browser:
        for name in ("paper", "sweep", "verification"):
            problems += check_reports.check_report(root / "reports" / f"{name}.html",
                                                   screenshot_dir=tmp_path, browser=browser)
    assert not problems, f"{len(problems)} problem(s) (screenshots in {tmp_path}):\n" + \
        "\n".join(problems)
