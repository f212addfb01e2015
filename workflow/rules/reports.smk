# The three reports: papermill-parameterised notebooks rendered to HTML by
# `lsbg report` (the notebook is an input and is run from its own folder, so
# editing it reruns the report). lsbg reads each --param value as YAML.


rule report_paper:
    input:
        notebook=notebook("paper"),
        lsbg_run=run_file("logarithmic", PAPER_SPIRAL, SWEEP_ENGINE),
        sbg_run=run_file("circular", PAPER_SPIRAL, SWEEP_ENGINE),
        lsbg_reference_run=run_file("logarithmic", PAPER_SPIRAL, REFERENCE_ENGINES[0]),
        sbg_reference_run=run_file("circular", PAPER_SPIRAL, REFERENCE_ENGINES[0]),
        lsbg_geometry=geometry_dir("logarithmic", PAPER_SPIRAL),
        sbg_geometry=geometry_dir("circular", PAPER_SPIRAL),
        summary=SUMMARY_FILE,
        sources=report_sources("paper"),
    output:
        report(REPORTS["paper"], caption="../report/reports.rst", category="Reports",
               labels={"report": "paper"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        steady_state_after=config["statistics"]["steady_state_after_s"],
        window_start=config["statistics"]["control_chart_window_s"][0],
        window_stop=config["statistics"]["control_chart_window_s"][1],
        subgroup_size=config["statistics"]["subgroup_size"],
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
        " --param lsbg_run={input.lsbg_run} --param sbg_run={input.sbg_run}"
        " --param lsbg_reference_run={input.lsbg_reference_run}"
        " --param sbg_reference_run={input.sbg_reference_run}"
        " --param lsbg_geometry={input.lsbg_geometry} --param sbg_geometry={input.sbg_geometry}"
        " --param summary_file={input.summary}"
        " --param steady_state_after_s={params.steady_state_after}"
        " --param chart_window_start_s={params.window_start}"
        " --param chart_window_stop_s={params.window_stop}"
        " --param subgroup_size={params.subgroup_size} > {log} 2>&1"


rule report_sweep:
    input:
        notebook=notebook("sweep"),
        sweep=SWEEP_FILE,
        summary=SUMMARY_FILE,
        sources=report_sources("sweep"),
    output:
        report(REPORTS["sweep"], caption="../report/reports.rst", category="Reports",
               labels={"report": "sweep"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        steady_state_after=config["statistics"]["steady_state_after_s"],
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
        " --param steady_state_after_s={params.steady_state_after} > {log} 2>&1"


rule report_verification:
    input:
        notebook=notebook("verification"),
        convergence=CONVERGENCE_FILES,
        geometry=PAPER_GEOMETRY,
        runs=PAPER_RUNS,
        sources=report_sources("verification"),
    output:
        report(REPORTS["verification"], caption="../report/reports.rst", category="Reports",
               labels={"report": "verification"}),
    params:
        notebook_dir=lambda wildcards, input: os.path.dirname(input.notebook),
        convergence=lambda wildcards, input: yaml_list(input.convergence),
        geometry=lambda wildcards, input: yaml_list(input.geometry),
        runs=lambda wildcards, input: yaml_list(input.runs),
        steady_state_after=config["statistics"]["steady_state_after_s"],
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
        " --param steady_state_after_s={params.steady_state_after} > {log} 2>&1"
