# At the paper's design point: the model-form sensitivity runs (one job per
# trace) and the convergence tables (one job per trace and contact model).
# A convergence table runs every engine of its model over its time steps or
# tolerances and writes each engine's run at the default settings as the
# design point's run of that engine (the run `lsbg simulate` would make: no
# job, no process start-up and no SLURM submission of its own). `simulate`
# makes any other single run asked for by file name.


ruleorder: convergence_point > simulate
ruleorder: convergence_line > simulate


rule simulate:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        fe_ltca=fe_ltca_input(lambda w: STUDY.own_compliance and w.model == "line"),
        sources=sources("simulate"),
    output:
        FILES["run"],
    params:
        # Rerun trigger: the settings this run depends on.
        settings=lambda wildcards: simulation_params(wildcards.engine, wildcards.model),
        fe_ltca=fe_ltca_option,
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
        " --contact-model {wildcards.model} --config {input.config} {params.fe_ltca}"
        " --out {output} > {log} 2>&1"


if STUDY.sensitivity:

    rule sensitivity:
        input:
            geometry=template(FILES["geometry"], spiral=PAPER_SPIRAL),
            config=ancient(FILES["study_config"]),
            # the slice stiffness of the cases (or the base) under compliance fe
            fe_ltca=fe_ltca_input(lambda w: STUDY.needs_fe_ltca),
            sources=sources("simulate"),
        output:
            [template(FILES["sensitivity_run"], spiral=PAPER_SPIRAL, case=case)
             for case in STUDY.sensitivity],
        params:
            fe_ltca=fe_ltca_option,
            cases=STUDY.case_options("dynamics"),
            out=lambda w: template(FILES["sensitivity_run"], trace=w.trace, spiral=PAPER_SPIRAL),
            engine=SWEEP_ENGINE,
            settings=simulation_params(SWEEP_ENGINE, "line"),
        priority: plan.job_priority("sensitivity")
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
            " --config {input.config} {params.fe_ltca} {params.cases} --out '{params.out}'"
            " > {log} 2>&1"


for model in plan.CONTACT_MODELS:

    rule:
        name:
            f"convergence_{model}"
        input:
            geometry=template(FILES["geometry"], spiral=PAPER_SPIRAL),
            config=ancient(FILES["study_config"]),
            fe_ltca=fe_ltca_input(lambda w, rule=model: STUDY.own_compliance and rule == "line"),
            sources=sources("convergence"),
        output:
            table=report(
                template(FILES["convergence"], model=model),
                caption="../report/convergence.rst",
                category="Verification",
                labels={"trace": "{trace}", "table": f"convergence {model}"},
            ),
            runs=[template(FILES["run"], spiral=PAPER_SPIRAL, model=model, engine=engine)
                  for engine in STUDY.convergence_engines(model)],
        params:
            model=model,
            engines=" ".join(STUDY.convergence_engines(model)),
            # (the default binds this rule's model: the loop variable moves on)
            default_runs=lambda wildcards, rule=model: STUDY.convergence_default_runs(
                wildcards.trace, rule),
            # Rerun trigger: the settings of the table's engines.
            settings=plan.canonical({engine: simulation_params(engine, model)
                                     for engine in STUDY.convergence_engines(model)}),
            steady_state_after=config["statistics"]["steady_state_after_s"],
            fe_ltca=fe_ltca_option,
        priority: plan.job_priority(f"convergence_{model}")
        log:
            f"logs/convergence/{{trace}}_{model}.log",
        threads: 1
        resources:
            mem_mb=1000,
            runtime=simulation_runtime(runs=6),
        conda:
            CONDA_ENV
        shell:
            "lsbg -v convergence --geometry {input.geometry} --config {input.config}"
            " --contact-model {params.model} --engines {params.engines} {params.default_runs}"
            " --steady-state-after {params.steady_state_after} {params.fe_ltca}"
            " --out {output.table}"
            " > {log} 2>&1"
