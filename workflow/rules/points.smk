# Design points: exact flanks, solids, URDF and picture (geometry), the loaded
# tooth contact analysis (line model) and the runs of the sweep engine.
#
# The paper's design point of each trace: its geometry is a job of its own,
# first in line (every run at the paper's point reads it, so it must not rerun
# when a contact or simulation setting changes), then its loaded TCA; its
# sweep-engine runs come from the convergence tables (rules/simulate.smk).
# The other spiral angles of a trace are one `lsbg points` job (geometry,
# loaded TCA and runs in one process: the start-up, about 1.8 s, is paid once
# per job instead of once per file); adding an angle reruns that job only.

import re


rule paper_geometry:
    input:
        config=ancient(FILES["study_config"]),
        sources=sources("geometry"),
    output:
        report(
            directory(FILES["geometry"]),
            patterns=["{name}.png"],
            caption="../report/geometry.rst",
            category="Geometry",
            subcategory="{trace}",
            labels={"trace": "{trace}", "spiral angle [deg]": "{spiral}"},
        ),
    params:
        # Rerun trigger: the design.
        design=plan.canonical(config["design"]),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("paper_geometry")
    log:
        "logs/paper_geometry/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v geometry --trace {wildcards.trace} --spiral-angle {wildcards.spiral}"
        " --design {input.config} --out {output} > {log} 2>&1"


rule paper_ltca:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        # under contact.compliance: fe, the FE compliance (rules/tooth.smk)
        compliance=[FILES["compliance"]] if STUDY.own_compliance else [],
        sources=sources("ltca"),
    output:
        FILES["mesh"],
    params:
        # Rerun trigger: the load and the line model's settings (with fe: the tooth's).
        load=config["simulation"]["load_torque_N_m"],
        contact=simulation_params(SWEEP_ENGINE, "line")["contact"],
        compliance=lambda w, input: (f"--compliance-file {input.compliance}"
                                     if input.compliance else ""),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("paper_ltca")
    log:
        "logs/paper_ltca/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v ltca --geometry {input.geometry} --config {input.config}"
        " {params.compliance} --out {output} > {log} 2>&1"


BATCH = STUDY.batch_spirals(STUDY.traces[0])

if BATCH:

    rule sweep_points:
        input:
            config=ancient(FILES["study_config"]),
            sources=sources("points"),
        output:
            geometry=[
                report(
                    directory(template(FILES["geometry"], spiral=s)),
                    patterns=["{name}.png"],
                    caption="../report/geometry.rst",
                    category="Geometry",
                    subcategory="{trace}",
                    labels={"trace": "{trace}", "spiral angle [deg]": s},
                )
                for s in BATCH
            ],
            meshes=[template(FILES["mesh"], spiral=s) for s in BATCH],
            runs=[template(FILES["run"], spiral=s, model=m, engine=SWEEP_ENGINE)
                  for s in BATCH for m in STUDY.sweep_models],
            # under contact.compliance: fe, each point's FE compliance
            compliances=[template(FILES["compliance"], spiral=s) for s in BATCH]
            if STUDY.own_compliance
            else [],
        params:
            spirals=" ".join(BATCH),
            engine=SWEEP_ENGINE,
            # lsbg fills in {spiral} (quoted: the shell must not touch the braces)
            geometry=lambda w: template(FILES["geometry"], trace=w.trace),
            mesh=lambda w: template(FILES["mesh"], trace=w.trace),
            runs=lambda w: " ".join(
                "--run '{}={}'".format(m, template(FILES["run"], trace=w.trace, model=m,
                                                   engine=SWEEP_ENGINE))
                for m in STUDY.sweep_models),
            compliance=lambda w: ("--compliance-out '{}'".format(
                template(FILES["compliance"], trace=w.trace)) if STUDY.own_compliance else ""),
            design=plan.canonical(config["design"]),
            settings={m: simulation_params(SWEEP_ENGINE, m) for m in STUDY.sweep_models},
        priority: plan.job_priority("sweep_points")
        log:
            "logs/sweep_points/{trace}.log",
        threads: 1
        resources:
            mem_mb=4000 if STUDY.own_compliance else 1000,
            runtime=10 + (2 + STUDY.own_compliance * config["limits"]["tooth_minutes"])
            * len(BATCH),
        conda:
            CONDA_ENV
        shell:
            "lsbg -v points --trace {wildcards.trace} --spiral-angles {params.spirals}"
            " --design {input.config} --config {input.config} --engine {params.engine}"
            " --geometry-out '{params.geometry}' --mesh-out '{params.mesh}'"
            " {params.compliance} {params.runs} > {log} 2>&1"
