# The rating by the standard (docs/model.md, "Service life"): `lsbg rate` rates
# the paper's point of each trace by ISO 10300:2023 method B1 with the factors of
# the `rating` section (K_v: the dynamic factor of the point's line-model run),
# and writes the stresses, safety factors and rated torques of both members beside
# the largest contact pressure and root stresses of the FE loaded TCA, aligned and
# at each corner of the assembly's displacement envelope (rule fe_sensitivity,
# tooth.smk), and rated again with the K_v of each sensitivity case's run at the
# study's speed
# (results/rating/*.nc).
# The paper report compares them (its service-life section).


rule rating:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        run=lambda w: STUDY.rating_run(w.trace),
        fe_ltca=lambda w: [STUDY.fe_ltca(w.trace, w.spiral)],
        fe_envelope=FILES["fe_envelope"],
        # K_v of each sensitivity case's run: the standard's cells of the life claim
        # (the cases at another pinion speed are not rated: the rating holds at the study's)
        case_runs=lambda w: [STUDY.sensitivity_run(w.trace, case) for case in STUDY.rated_cases]
        if STUDY.rating_run(w.trace) else [],
        sources=sources("rate"),
    output:
        out=FILES["rating"],
    params:
        **command("rate", case_run=lambda w: [
            f"{case}={STUDY.sensitivity_run(w.trace, case)}" for case in STUDY.rated_cases]
            if STUDY.rating_run(w.trace) else []),
        rating=plan.canonical({k: config[k] for k in ("rating", "tooth")}),  # rerun triggers
        load=[config["simulation"][k] for k in ("load_torque_N_m", "pinion_speed_deg_s")],
        steady_state=config["statistics"]["steady_state_after_s"],
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/rating/{trace}_beta{spiral}.log",
    shell:
        LSBG
