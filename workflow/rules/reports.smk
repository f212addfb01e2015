# The three reports: papermill-parameterised notebooks rendered to HTML by
# `lsbg report` (the notebook is an input and is run from its own folder, so
# editing it reruns the report). lsbg reads each --param value as YAML.


rule report_paper:
    input:
        notebook=notebook("paper"),
        runs=STUDY.paper_runs,
        sensitivity=STUDY.sensitivity_runs(),
        meshes=STUDY.paper_meshes,
        geometry=STUDY.paper_geometry,
        sweep=FILES["sweep"],
        tca=STUDY.paper_tca_files,
        vh=STUDY.paper_vh_maps,
        vh_cases=STUDY.vh_cases(),
        fe_ltca=[STUDY.fe_ltca(t, PAPER_SPIRAL) for t in plan.PAPER_TRACES],
        fe_cases=STUDY.fe_cases(),
        rating=STUDY.rating_files,
        sources=sources("report"),
    output:
        report(STUDY.reports["paper"], caption="../report/reports.rst", category="Reports",
               labels={"report": "paper"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        runs=lambda wildcards, input: yaml_list(input.runs),
        sensitivity=lambda wildcards, input: yaml_list(input.sensitivity),
        meshes=lambda wildcards, input: yaml_list(input.meshes),
        geometry=lambda wildcards, input: yaml_list(input.geometry),
        tca=lambda wildcards, input: yaml_list(input.tca),
        vh=lambda wildcards, input: yaml_list(input.vh),
        vh_cases=lambda wildcards, input: yaml_list(input.vh_cases),
        fe_ltca=lambda wildcards, input: yaml_list(input.fe_ltca),
        fe_cases=lambda wildcards, input: yaml_list(input.fe_cases),
        rating=lambda wildcards, input: yaml_list(input.rating),
        paper_engine=STUDY.paper_engine,
        line_engine=SWEEP_ENGINE,
        steady_state_after=config["statistics"]["steady_state_after_s"],
        window_start=config["statistics"]["control_chart_window_s"][0],
        window_stop=config["statistics"]["control_chart_window_s"][1],
        subgroup_size=config["statistics"]["subgroup_size"],
    priority: plan.job_priority("report_paper")
    log:
        "logs/report_paper/paper.log",
    threads: 1
    resources:
        mem_mb=4000,
        runtime=30,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v report paper --notebook-dir {params.notebook_dir} --out {output}"
        " --param 'runs={params.runs}' --param 'sensitivity_runs={params.sensitivity}'"
        " --param 'mesh_files={params.meshes}' --param 'geometry_dirs={params.geometry}'"
        " --param 'tca_files={params.tca}' --param 'vh_files={params.vh}'"
        " --param 'fe_ltca_files={params.fe_ltca}' --param 'rating_files={params.rating}'"
        " --param 'vh_case_files={params.vh_cases}' --param 'fe_case_files={params.fe_cases}'"
        " --param paper_engine={params.paper_engine}"
        " --param line_engine={params.line_engine}"
        " --param steady_state_after_s={params.steady_state_after}"
        " --param chart_window_start_s={params.window_start}"
        " --param chart_window_stop_s={params.window_stop}"
        " --param subgroup_size={params.subgroup_size}"
        " --param sweep_file={input.sweep} > {log} 2>&1"


rule report_sweep:
    input:
        notebook=notebook("sweep"),
        sweep=FILES["sweep"],
        summary=FILES["summary"],
        speed_curve=[FILES["speed_curve"]] if STUDY.speed_sweep else [],
        vh=STUDY.vh_maps,
        config=ancient(FILES["study_config"]),
        parameter_sweeps=[FILES["sweep_dataset"].format(name=s.name) for s in STUDY.sweeps],
        sources=sources("report"),
    output:
        report(STUDY.reports["sweep"], caption="../report/reports.rst", category="Reports",
               labels={"report": "sweep"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        vh=lambda wildcards, input: yaml_list(input.vh),
        parameter_sweeps=lambda wildcards, input: yaml_list(input.parameter_sweeps),
        steady_state_after=config["statistics"]["steady_state_after_s"],
        # Rerun trigger: the ISO 10300 rating's settings (the config file is ancient)
        rating=plan.canonical({k: config[k] for k in ("rating", "tooth")}),
    priority: plan.job_priority("report_sweep")
    log:
        "logs/report_sweep/sweep.log",
    threads: 1
    resources:
        mem_mb=4000,
        runtime=30,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v report sweep --notebook-dir {params.notebook_dir} --out {output}"
        " --param sweep_file={input.sweep} --param summary_file={input.summary}"
        " --param 'speed_curve_file={input.speed_curve}' --param 'vh_files={params.vh}'"
        " --param config_file={input.config}"
        " --param 'parameter_sweep_files={params.parameter_sweeps}'"
        " --param steady_state_after_s={params.steady_state_after} > {log} 2>&1"


rule report_verification:
    input:
        notebook=notebook("verification"),
        convergence=STUDY.convergence_files,
        geometry=STUDY.paper_geometry,
        runs=STUDY.paper_runs,
        meshes=STUDY.paper_meshes,
        sources=sources("report"),
    output:
        report(STUDY.reports["verification"], caption="../report/reports.rst", category="Reports",
               labels={"report": "verification"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        convergence=lambda wildcards, input: yaml_list(input.convergence),
        geometry=lambda wildcards, input: yaml_list(input.geometry),
        runs=lambda wildcards, input: yaml_list(input.runs),
        meshes=lambda wildcards, input: yaml_list(input.meshes),
        steady_state_after=config["statistics"]["steady_state_after_s"],
    priority: plan.job_priority("report_verification")
    log:
        "logs/report_verification/verification.log",
    threads: 1
    resources:
        mem_mb=4000,
        runtime=30,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v report verification --notebook-dir {params.notebook_dir} --out {output}"
        " --param 'convergence_files={params.convergence}'"
        " --param 'geometry_dirs={params.geometry}' --param 'runs={params.runs}'"
        " --param 'mesh_files={params.meshes}'"
        " --param steady_state_after_s={params.steady_state_after} > {log} 2>&1"
