# At the paper's design point: the runs of the reference engines (one per trace,
# model and engine), the model-form sensitivity runs (one job per trace) and
# the convergence tables (one per trace and model). A convergence table reuses
# the reference engines' default runs and writes its sweep-engine run at the
# default tolerance as the design point's run of that engine (the same run
# `lsbg simulate` would make: one job fewer per trace and model).


rule simulate:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        sources=sources("simulate"),
    output:
        FILES["run"],
    params:
        # Rerun trigger: the settings this run depends on.
        settings=lambda wildcards: simulation_params(wildcards.engine, wildcards.model),
    wildcard_constraints:
        engine=STUDY.reference_engines,
    log:
        "logs/simulate/{trace}_beta{spiral}_{model}_{engine}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v simulate --geometry {input.geometry} --engine {wildcards.engine}"
        " --contact-model {wildcards.model} --config {input.config} --out {output} > {log} 2>&1"


if STUDY.sensitivity:

    rule sensitivity:
        input:
            geometry=template(FILES["geometry"], spiral=PAPER_SPIRAL),
            config=ancient(FILES["study_config"]),
            sources=sources("simulate"),
        output:
            [template(FILES["sensitivity_run"], spiral=PAPER_SPIRAL, case=case)
             for case in STUDY.sensitivity],
        params:
            cases=" ".join(f"--case {key}={factor!r}"
                           for key, factor in STUDY.sensitivity.values()),
            out=lambda w: template(FILES["sensitivity_run"], trace=w.trace, spiral=PAPER_SPIRAL),
            engine=SWEEP_ENGINE,
            settings=simulation_params(SWEEP_ENGINE, "line"),
        log:
            "logs/sensitivity/{trace}.log",
        threads: 1
        resources:
            mem_mb=1000,
            runtime=simulation_runtime(runs=len(STUDY.sensitivity)),
        conda:
            CONDA_ENV
        shell:
            "lsbg -v sensitivity --geometry {input.geometry} --engine {params.engine}"
            " --config {input.config} {params.cases} --out '{params.out}' > {log} 2>&1"


rule convergence:
    input:
        geometry=template(FILES["geometry"], spiral=PAPER_SPIRAL),
        known=lambda wildcards: STUDY.known_runs(wildcards.trace, wildcards.model),
        config=ancient(FILES["study_config"]),
        sources=sources("convergence"),
    output:
        table=report(
            FILES["convergence"],
            caption="../report/convergence.rst",
            category="Verification",
            labels={"trace": "{trace}", "table": "convergence {model}"},
        ),
        run=template(FILES["run"], spiral=PAPER_SPIRAL, engine=SWEEP_ENGINE),
    params:
        engine=SWEEP_ENGINE,
        engines=lambda wildcards: " ".join(STUDY.convergence_engines(wildcards.model)),
        settings=lambda wildcards: plan.canonical({
            engine: simulation_params(engine, wildcards.model)
            for engine in STUDY.convergence_engines(wildcards.model)}),
        steady_state_after=config["statistics"]["steady_state_after_s"],
    log:
        "logs/convergence/{trace}_{model}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(runs=6),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v convergence --geometry {input.geometry} --config {input.config}"
        " --contact-model {wildcards.model} --engines {params.engines} --known {input.known}"
        " --default-run {params.engine}={output.run}"
        " --steady-state-after {params.steady_state_after} --out {output.table} > {log} 2>&1"
