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
        out=FILES["run"],
    params:
        **command("simulate"),
        settings=lambda w: simulation_params(w.engine, w.model),  # rerun trigger
    wildcard_constraints:
        engine=STUDY.reference_engines,
    log:
        "logs/simulate/{trace}_beta{spiral}_{model}_{engine}.log",
    resources:
        **runtime(),
    shell:
        LSBG


if STUDY.sensitivity:

    rule sensitivity:
        input:
            geometry=template(FILES["geometry"], spiral=PAPER_SPIRAL),
            config=ancient(FILES["study_config"]),
            # the slice stiffness of the cases (or the base) under compliance fe
            fe_ltca=fe_ltca_input(lambda w: STUDY.needs_fe_ltca),
            sources=sources("sensitivity"),
        output:
            [template(FILES["sensitivity_run"], spiral=PAPER_SPIRAL, case=case)
             for case in STUDY.sensitivity],
        params:
            **command("sensitivity", engine=SWEEP_ENGINE, case=case_values("dynamics"),
                      out=lambda w: template(FILES["sensitivity_run"], trace=w.trace,
                                             spiral=PAPER_SPIRAL)),
            settings=simulation_params(SWEEP_ENGINE, "line"),  # rerun trigger
        log:
            "logs/sensitivity/{trace}.log",
        resources:
            **runtime(runs=len(STUDY.sensitivity)),
        shell:
            LSBG


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
            out=report(template(FILES["convergence"], model=model),
                       caption="../report/convergence.rst", category="Verification",
                       labels={"trace": "{trace}", "table": f"convergence {model}"}),
            runs=STUDY.convergence_runs("{trace}", model),
        params:
            # (the defaults bind this rule's model: the loop variable moves on)
            **command("convergence", set=[f"contact.model={model}"],
                      engines=STUDY.convergence_engines(model),
                      default_run=lambda w, rule=model: STUDY.default_runs(w.trace, rule)),
            settings=plan.canonical({engine: simulation_params(engine, model)  # rerun triggers
                                     for engine in STUDY.convergence_engines(model)}),
            steady_state_after=config["statistics"]["steady_state_after_s"],
        wildcard_constraints:
            **PAPER_PAIR,
        log:
            f"logs/convergence/{{trace}}_{model}.log",
        resources:
            **runtime(runs=6),
        shell:
            LSBG
