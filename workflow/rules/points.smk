# Design points: exact flanks, solids, URDF and picture (geometry), the loaded
# tooth contact analysis (line model) and the runs of the sweep engine.
#
# The paper's design point of each trace: its geometry is a job of its own,
# first in line (every run at the paper's point reads it, so it must not rerun
# when a contact or simulation setting changes), then its loaded TCA; its
# sweep-engine runs come from the convergence tables (rules/simulate.smk).
# The other spiral angles of a trace are one `lsbg points` job (geometry,
# loaded TCA and runs in one process: the start-up is paid once per job instead
# of once per file); adding an angle reruns that job only. A trace outside the
# paper's pair (ISO 23509's SBG) has no paper-point jobs: its batch holds the
# paper's angle too.

import re


rule paper_geometry:
    input:
        config=ancient(FILES["study_config"]),
        sources=sources("geometry"),
    output:
        out=geometry_output(),
    params:
        **command("geometry"),
        design=plan.canonical(config["design"]),  # rerun trigger
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
        **PAPER_PAIR,
    log:
        "logs/paper_geometry/{trace}_beta{spiral}.log",
    shell:
        LSBG


rule paper_ltca:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        compliance_file=[FILES["compliance"]] if STUDY.own_compliance else [],
        sources=sources("ltca"),
    output:
        out=FILES["mesh"],
    params:
        **command("ltca"),
        load=config["simulation"]["load_torque_N_m"],  # rerun triggers
        contact=simulation_params(SWEEP_ENGINE, "line")["contact"],
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
        **PAPER_PAIR,
    log:
        "logs/paper_ltca/{trace}_beta{spiral}.log",
    shell:
        LSBG


# The kernels of a design point, compiled into numba's cache by the first job (or
# loaded from it): from an empty cache both traces' sweeps compiled the same kernels
# at once; the FE compliance's factor too. Meanwhile the other core builds the paper
# point's geometry, which calls none. (ancient: a rerun of it reruns nothing else.)
rule kernels:
    input:
        config=ancient(FILES["study_config"]),
        sources=sources("kernels"),
    output:
        out=FILES["kernels"],
    params:
        **command("kernels"),
    log:
        "logs/kernels.log",
    shell:
        LSBG


# the runs of a batch, one template per contact model
RUNS = {m: template(FILES["run"], model=m, engine=SWEEP_ENGINE) for m in STUDY.sweep_models}

# One rule per group of traces with the same angles (plan.Study.batch_groups): the
# paper's pair (every angle but the paper's), and a trace outside it (ISO 23509's SBG,
# face_milled), which runs every angle of the sweep, the paper's too, in its one job.
for _suffix, _traces, _batch in STUDY.batch_groups():

    rule:
        name:
            f"sweep_points{_suffix}"
        input:
            config=ancient(FILES["study_config"]),
            kernels=ancient(FILES["kernels"]),
            sources=sources("points"),
        output:
            geometry=[geometry_output(s) for s in _batch],
            meshes=[template(FILES["mesh"], spiral=s) for s in _batch],
            runs=[template(r, spiral=s) for s in _batch for r in RUNS.values()],
            compliances=[template(FILES["compliance"], spiral=s) for s in _batch]
            if STUDY.own_compliance else [],
        params:
            **command("points", spiral_angles=_batch, engine=SWEEP_ENGINE,
                      run=lambda w: [f"{m}={template(r, trace=w.trace)}" for m, r in RUNS.items()],
                      **point_templates(geometry_out=FILES["geometry"], mesh_out=FILES["mesh"],
                                        **({"compliance_out": FILES["compliance"]}
                                           if STUDY.own_compliance else {}))),
            design=plan.canonical(config["design"]),  # rerun triggers
            settings={m: simulation_params(SWEEP_ENGINE, m) for m in STUDY.sweep_models},
        wildcard_constraints:
            trace="|".join(_traces),
        log:
            "logs/sweep_points/{trace}.log",
        resources:
            **points_resources(len(_batch)),
        shell:
            LSBG
