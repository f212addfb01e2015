# The three reports: papermill-parameterised notebooks rendered to HTML by
# `lsbg report` (the notebook is an input and is run from its own folder, so
# editing it reruns the report). Each named input is the notebook parameter of
# its name (notebook_report); lsbg reads each --param value as YAML.

STATISTICS = config["statistics"]


rule report_paper:
    input:
        notebook=repo_path(NOTEBOOKS / "paper.ipynb"),
        runs=STUDY.paper_runs,
        sensitivity_runs=STUDY.sensitivity_runs(),
        mesh_files=STUDY.paper_meshes,
        geometry_dirs=STUDY.paper_geometry,
        sweep_file=FILES["sweep"],
        tca_files=STUDY.paper_tca_files,
        vh_files=STUDY.paper_vh_maps,
        vh_case_files=STUDY.vh_cases(),
        fe_ltca_files=[STUDY.fe_ltca(t, PAPER_SPIRAL) for t in plan.PAPER_TRACES],
        fe_case_files=STUDY.fe_cases(),
        rating_files=STUDY.rating_files,
        checks_files=PAPER_CHECKS,
        parameter_sweep_files=[FILES["sweep_dataset"].format(name=s.name) for s in STUDY.sweeps],
        # the pair as a designer would make it (rules/practice.smk)
        practice_run_files=STUDY.practice_files("run"),
        practice_vh_files=STUDY.practice_files("vh_map"),
        practice_rating_files=STUDY.practice_files("rating"),
        practice_fe_ltca_files=STUDY.practice_files("fe_ltca"),
        practice_geometry_dirs=STUDY.practice_files("geometry"),
        # its model-form cells (practice.sensitivity)
        practice_sensitivity_runs=STUDY.pair_case_files("practice", "sensitivity_run"),
        practice_vh_case_files=STUDY.pair_case_files("practice", "vh_case"),
        practice_fe_case_files=STUDY.pair_case_files("practice", "fe_case"),
        load_curve_files=STUDY.load_curves,
        # each type at its best ease-off (rules/optimise.smk)
        optimise_front_files=STUDY.optimise_fronts,
        optimise_release_files=STUDY.optimise_releases,
        trace_fronts_files=STUDY.trace_fronts,
        # the matched designs (rules/matched.smk)
        matched_pairs_files=STUDY.matched_pairs,
        best_run_files=STUDY.best_files("run"),
        best_vh_files=STUDY.best_files("vh_map"),
        best_rating_files=STUDY.best_files("rating"),
        best_fe_ltca_files=STUDY.best_files("fe_ltca"),
        best_sensitivity_runs=STUDY.pair_case_files("best", "sensitivity_run"),
        best_vh_case_files=STUDY.pair_case_files("best", "vh_case"),
        best_fe_case_files=STUDY.pair_case_files("best", "fe_case"),
        sources=sources("report", "paper"),
    output:
        report(STUDY.reports["paper"], caption="../report/reports.rst", category="Reports",
               labels={"report": "paper"}),
    params:
        **notebook_report("paper", paper_engine=STUDY.paper_engine, line_engine=SWEEP_ENGINE,
                          steady_state_after_s=STATISTICS["steady_state_after_s"],
                          chart_window_start_s=STATISTICS["control_chart_window_s"][0],
                          chart_window_stop_s=STATISTICS["control_chart_window_s"][1],
                          subgroup_size=STATISTICS["subgroup_size"],
                          load_spectrum_fractions=config["practice"]["load_spectrum"][
                              "torque_fractions"],
                          load_spectrum_shares=config["practice"]["load_spectrum"]["cycle_shares"],
                          practice_profile_shift=config["practice"]["profile_shift"],
                          practice_addendum_rule=config["practice"]["addendum_rule"]),
    log:
        "logs/report_paper/paper.log",
    shell:
        LSBG


rule report_sweep:
    input:
        notebook=repo_path(NOTEBOOKS / "sweep.ipynb"),
        sweep_file=FILES["sweep"],
        summary_file=FILES["summary"],
        speed_curve_file=STUDY.speed_curves,
        vh_files=STUDY.vh_maps,
        rating_sweep_file=RATING_SWEEP,
        parameter_sweep_files=[FILES["sweep_dataset"].format(name=s.name) for s in STUDY.sweeps],
        cutter_files=[p["file"] for p in STUDY.cutter_points],
        sources=sources("report", "sweep"),
    output:
        report(STUDY.reports["sweep"], caption="../report/reports.rst", category="Reports",
               labels={"report": "sweep"}),
    params:
        **notebook_report("sweep", steady_state_after_s=STATISTICS["steady_state_after_s"]),
        # Rerun trigger: the ISO 10300 rating's settings (the config file is ancient)
        rating=plan.canonical({k: config[k] for k in ("rating", "tooth")}),
    log:
        "logs/report_sweep/sweep.log",
    shell:
        LSBG


rule report_verification:
    input:
        notebook=repo_path(NOTEBOOKS / "verification.ipynb"),
        convergence_files=STUDY.convergence_files,
        geometry_dirs=STUDY.paper_geometry,
        runs=STUDY.paper_runs,
        mesh_files=STUDY.paper_meshes,
        checks_files=PAPER_CHECKS,
        sources=sources("report", "verification"),
    output:
        report(STUDY.reports["verification"], caption="../report/reports.rst",
               category="Reports", labels={"report": "verification"}),
    params:
        **notebook_report("verification",
                          steady_state_after_s=STATISTICS["steady_state_after_s"]),
    log:
        "logs/report_verification/verification.log",
    shell:
        LSBG
