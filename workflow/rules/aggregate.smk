# The stage after the runs: the sweep dataset and the summary table.


rule combine:
    input:
        runs=SWEEP_RUNS,
        meshes=MESHES,
        sources=sources("aggregate"),
    output:
        SWEEP_FILE,
    log:
        "logs/combine/sweep.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v combine --runs {input.runs} --meshes {input.meshes} --out {output} > {log} 2>&1"


rule summary:
    input:
        runs=ALL_RUNS + SENSITIVITY_RUNS,
        meshes=MESHES,
        config=ancient(STUDY_CONFIG),
        sources=sources("aggregate"),
    output:
        report(SUMMARY_FILE, caption="../report/summary.rst", category="Summary"),
    params:
        # Rerun trigger: the statistics settings the table depends on.
        statistics=canonical(config["statistics"]),
    log:
        "logs/summary/summary.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v summary --runs {input.runs} --meshes {input.meshes} --config {input.config}"
        " --out {output} > {log} 2>&1"
