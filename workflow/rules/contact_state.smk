# The contact state of every design point (each trace at each spiral angle of the
# sweep, and the paper's point): `lsbg misalignment-map` writes the V-H
# map (unloaded and loaded TCA on a grid of two assembly displacements, with the
# pattern's and the transmission error's change per 0.1 mm) and, in the same
# process, the unloaded TCA of the undisplaced pair at the tca section's
# resolution. The flanks, the map and the TCA settings come from the study
# config (flank_modification, misalignment, tca, misalignment_map); the map has
# misalignment_map.steps values per axis at the paper's point, sweep_steps at
# the others. The geometry comes from the study's point rules (points.smk). The
# paper's point of each trace is a job of its own, which also maps the
# sensitivity cases that reach the contact state (crowning, line stiffness;
# lsbg.experiments.sensitivity) at sweep_steps; the other angles of a trace are one job (one
# start-up, about 2 s, instead of one per angle), as in points.smk.


rule contact_state:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        # a topography file: its content is part of the flanks
        topography=[config["flank_modification"]["topography_file"]]
        if config["flank_modification"]["topography_file"]
        else [],
        sources=sources("contact_state"),
    output:
        tca=FILES["tca"],
        vh=FILES["vh_map"],
        # the contact-state sensitivity cases (crowning, line stiffness)
        cases=[template(FILES["vh_case"], case=case)
               for case in STUDY.stage_cases("contact_state")],
    params:
        steps=lambda wildcards: STUDY.map_steps(wildcards.spiral),
        cases=STUDY.case_options("contact_state"),
        case_out=lambda w: template(FILES["vh_case"], trace=w.trace, spiral=w.spiral),
        case_steps=config["misalignment_map"]["sweep_steps"],
        # Rerun trigger: the contact-state sections, the steps, the line model's
        # settings and the load of the loaded TCAs.
        settings=lambda wildcards: plan.contact_state_params(config, wildcards.spiral,
                                                             SWEEP_ENGINE),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("contact_state")
    log:
        "logs/contact_state/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v misalignment-map --geometry {input.geometry} --config {input.config}"
        " --steps {params.steps} --out {output.vh} --tca-out {output.tca}"
        " {params.cases} --case-steps {params.case_steps} --case-out '{params.case_out}'"
        " > {log} 2>&1"


CONTACT_BATCH = STUDY.batch_spirals(STUDY.traces[0])

if CONTACT_BATCH:

    rule sweep_contact_state:
        input:
            geometry=[template(FILES["geometry"], spiral=s) for s in CONTACT_BATCH],
            config=ancient(FILES["study_config"]),
            topography=[config["flank_modification"]["topography_file"]]
            if config["flank_modification"]["topography_file"]
            else [],
            sources=sources("contact_state"),
        output:
            tca=[template(FILES["tca"], spiral=s) for s in CONTACT_BATCH],
            vh=[template(FILES["vh_map"], spiral=s) for s in CONTACT_BATCH],
        params:
            spirals=" ".join(CONTACT_BATCH),
            steps=STUDY.map_steps(CONTACT_BATCH[0]),
            # lsbg fills in {spiral} (quoted: the shell must not touch the braces)
            geometry=lambda w: template(FILES["geometry"], trace=w.trace),
            tca=lambda w: template(FILES["tca"], trace=w.trace),
            vh=lambda w: template(FILES["vh_map"], trace=w.trace),
            # Rerun trigger: as contact_state's, at the sweep's steps.
            settings=plan.contact_state_params(config, CONTACT_BATCH[0], SWEEP_ENGINE),
        priority: plan.job_priority("sweep_contact_state")
        log:
            "logs/sweep_contact_state/{trace}.log",
        threads: 1
        resources:
            mem_mb=1000,
            runtime=10 + len(CONTACT_BATCH),
        conda:
            CONDA_ENV
        shell:
            "lsbg -v misalignment-map --geometry '{params.geometry}'"
            " --spiral-angles {params.spirals} --config {input.config}"
            " --steps {params.steps} --out '{params.vh}' --tca-out '{params.tca}' > {log} 2>&1"
