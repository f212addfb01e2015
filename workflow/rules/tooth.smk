# The tooth's own compliance (docs/model.md, "The tooth itself"): `lsbg compliance`
# meshes a seven-tooth segment of each member and writes its finite-element
# influence coefficients and fillet stresses (results/tooth/*_compliance.nc);
# `lsbg ltca --compliance fe` solves the loaded TCA with them and Hertz's local
# contact as a complementarity problem, and writes the transmission error,
# mesh stiffness, contact pressure, root stresses and the slice stiffness that
# line-model runs under compliance fe take (--fe-ltca).
#
# Which design points: under contact.compliance: uniform (the default) the
# paper's point of each trace, for the comparison uniform / FE in the paper
# report and the sensitivity case compliance_fe (results/tooth/*_ltca.nc).
# Under contact.compliance: fe every design point: the paper's compliance here,
# the other angles' inside their `lsbg points` batch (points.smk), and each
# design point's loaded TCA (results/mesh/) is the FE one.

import re


rule tooth_compliance:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        sources=sources("tooth"),
    output:
        FILES["compliance"],
    params:
        # Rerun trigger: the material and the mesh (the design: the geometry's).
        tooth=plan.canonical(config["tooth"]),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("tooth_compliance")
    log:
        "logs/tooth_compliance/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=4000,
        runtime=config["limits"]["tooth_minutes"],
    conda:
        CONDA_ENV
    shell:
        "lsbg -v compliance --geometry {input.geometry} --config {input.config}"
        " --out {output} > {log} 2>&1"


if not STUDY.own_compliance:

    rule fe_ltca:
        input:
            geometry=FILES["geometry"],
            config=ancient(FILES["study_config"]),
            compliance=FILES["compliance"],
            sources=sources("ltca"),
        output:
            FILES["fe_ltca"],
        params:
            # Rerun trigger: the load, the line model's settings (its bands and
            # flanks) and the tooth's.
            load=config["simulation"]["load_torque_N_m"],
            contact=simulation_params(SWEEP_ENGINE, "line")["contact"],
            tooth=plan.canonical(config["tooth"]),
        wildcard_constraints:
            spiral=re.escape(PAPER_SPIRAL),
        priority: plan.job_priority("fe_ltca")
        log:
            "logs/fe_ltca/{trace}_beta{spiral}.log",
        threads: 1
        resources:
            mem_mb=2000,
            runtime=10,
        conda:
            CONDA_ENV
        shell:
            "lsbg -v ltca --geometry {input.geometry} --config {input.config} --compliance fe"
            " --compliance-file {input.compliance} --out {output} > {log} 2>&1"


# The FE loaded TCA at the corners of the assembly's displacement envelope
# (misalignment_map.axes at +-misalignment_map.range, on the misalignment section):
# the largest contact pressure and root stresses at each corner and position, for
# the rating's "with displacement" (results/tooth/*_envelope.nc); and, in the same
# process on the same compliance, the FE loaded TCA of each sensitivity case that
# reaches it (crowning; results/tooth/*_{case}_ltca.nc), for the service-life
# claim's sensitivity table. In both modes: the paper's compliance is computed here.
rule fe_sensitivity:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        compliance=FILES["compliance"],
        sources=sources("ltca"),
    output:
        envelope=FILES["fe_envelope"],
        cases=[template(FILES["fe_case"], case=case) for case in STUDY.stage_cases("fe_ltca")],
    params:
        # Rerun trigger: the load, the line model's bands, the flanks, the envelope and
        # the tooth's settings (the cases: their options).
        load=config["simulation"]["load_torque_N_m"],
        contact=simulation_params(SWEEP_ENGINE, "line")["contact"],
        flanks=plan.canonical({"misalignment": config["misalignment"],
                               "flank_modification": config["flank_modification"]}),
        envelope=plan.canonical({k: config["misalignment_map"][k] for k in ("axes", "range")}),
        tooth=plan.canonical(config["tooth"]),
        phases=plan.envelope_positions(config),
        cases=STUDY.case_options("fe_ltca"),
        case_out=lambda w: template(FILES["fe_case"], trace=w.trace, spiral=w.spiral),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    priority: plan.job_priority("fe_sensitivity")
    log:
        "logs/fe_sensitivity/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v ltca --geometry {input.geometry} --config {input.config} --compliance fe"
        " --compliance-file {input.compliance} --envelope --phases {params.phases}"
        " {params.cases} --case-out '{params.case_out}' --out {output.envelope} > {log} 2>&1"
