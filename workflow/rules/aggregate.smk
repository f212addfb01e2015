# The stage after the runs: the sweep dataset and the summary table (with the
# contact state of every design point: workflow/rules/contact_state.smk).


rule combine:
    input:
        runs=STUDY.sweep_runs,
        meshes=STUDY.meshes,
        tca=STUDY.tca_files,
        vh=STUDY.vh_maps,
        sources=sources("aggregate"),
    output:
        # update(): Snakemake keeps the previous file until the new one is complete
        # (by default it deletes a job's outputs before the job runs).
        update(FILES["sweep"]),
    priority: plan.job_priority("combine")
    log:
        "logs/combine/sweep.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v combine --runs {input.runs} --meshes {input.meshes} --tca {input.tca}"
        " --vh {input.vh} --out {output} > {log} 2>&1"


rule summary:
    input:
        runs=STUDY.all_runs + STUDY.sensitivity_runs(),
        meshes=STUDY.meshes,
        tca=STUDY.tca_files,
        vh=STUDY.vh_maps,
        config=ancient(FILES["study_config"]),
        sources=sources("aggregate"),
    output:
        report(update(FILES["summary"]), caption="../report/summary.rst", category="Summary"),
    params:
        # Rerun trigger: the statistics settings the table depends on.
        statistics=plan.canonical(config["statistics"]),
    priority: plan.job_priority("summary")
    log:
        "logs/summary/summary.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v summary --runs {input.runs} --meshes {input.meshes} --tca {input.tca}"
        " --vh {input.vh} --config {input.config} --out {output} > {log} 2>&1"
