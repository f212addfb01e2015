# The rating by the standard (docs/model.md, "Service life"): `lsbg rate` rates
# the paper's point of each trace by ISO 10300:2023 method B1 with the factors of
# the `rating` section (K_v: the dynamic factor of the point's line-model run),
# and writes the stresses, safety factors and rated torques of both members beside
# the largest contact pressure and root stresses of the FE loaded TCA, aligned and
# at each corner of the assembly's displacement envelope (rule fe_sensitivity,
# tooth.smk), and rated again with the K_v of each sensitivity case's run
# (results/rating/*.nc).
# The paper report compares them (its service-life section).

import re


rule rating:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        run=lambda w: STUDY.rating_run(w.trace),
        fe_ltca=lambda w: [STUDY.fe_ltca(w.trace, w.spiral)],
        envelope=FILES["fe_envelope"],
        # K_v of each sensitivity case's run: the standard's cells of the life claim
        case_runs=lambda w: STUDY.sensitivity_runs(w.trace) if STUDY.rating_run(w.trace) else [],
        sources=sources("rating"),
    output:
        FILES["rating"],
    params:
        # Rerun trigger: the rating's factors, the load and speed, the tool radius.
        rating=plan.canonical(config["rating"]),
        load=config["simulation"]["load_torque_N_m"],
        speed=config["simulation"]["pinion_speed_deg_s"],
        steady_state=config["statistics"]["steady_state_after_s"],
        tooth=plan.canonical(config["tooth"]),
        run=lambda wildcards, input: f"--run {input.run}" if input.run else "",
        case_runs=lambda wildcards, input: " ".join(
            f"--case-run '{case}={STUDY.sensitivity_run(wildcards.trace, case)}'"
            for case in STUDY.sensitivity) if input.case_runs else "",
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("rating")
    log:
        "logs/rating/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v rate --geometry {input.geometry} --config {input.config} {params.run}"
        " --fe-ltca {input.fe_ltca} --fe-envelope {input.envelope} {params.case_runs}"
        " --out {output} > {log} 2>&1"
