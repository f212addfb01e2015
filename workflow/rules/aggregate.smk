# The stage after the runs: the sweep dataset and the summary table (with the
# contact state of every design point: workflow/rules/contact_state.smk).
# update(): Snakemake keeps the previous file until the new one is complete (by
# default it deletes a job's outputs before the job runs).


rule combine:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        runs=STUDY.sweep_runs,
        meshes=STUDY.meshes,
        tca=STUDY.tca_files,
        vh=STUDY.vh_maps,
        sources=sources("combine"),
    output:
        out=update(FILES["sweep"]),
    params:
        **command("combine"),
    log:
        "logs/combine/sweep.log",
    shell:
        LSBG


rule summary:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        runs=STUDY.all_runs + STUDY.sensitivity_runs(),
        meshes=STUDY.meshes,
        tca=STUDY.tca_files,
        vh=STUDY.vh_maps,
        config=ancient(FILES["study_config"]),
        sources=sources("summary"),
    output:
        out=report(update(FILES["summary"]), caption="../report/summary.rst", category="Summary"),
    params:
        **command("summary"),
        statistics=plan.canonical(config["statistics"]),  # rerun trigger
    log:
        "logs/summary/summary.log",
    shell:
        LSBG
