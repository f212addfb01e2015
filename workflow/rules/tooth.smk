# The tooth's own compliance (docs/model.md, "The tooth itself"): `lsbg compliance`
# meshes a seven-tooth segment of each member and writes its finite-element
# influence coefficients and fillet stresses (results/tooth/*_compliance.nc);
# `lsbg ltca` under contact.compliance: fe solves the loaded TCA with them and
# Hertz's local contact as a complementarity problem, and writes the transmission
# error, mesh stiffness, contact pressure, root stresses and the slice stiffness
# that line-model runs under compliance fe take (--fe-ltca).
#
# Which design points: under contact.compliance: uniform (the default) the
# paper's point of each trace, for the comparison uniform / FE in the paper
# report and the sensitivity case compliance_fe (results/tooth/*_ltca.nc).
# Under contact.compliance: fe every design point: the paper's compliance here,
# the other angles' inside their `lsbg points` batch (points.smk), and each
# design point's loaded TCA (results/mesh/) is the FE one.

import re

#: The rerun triggers of an FE loaded TCA: the load, the line model's settings (its
#: bands and flanks) and the tooth's.
FE_TRIGGERS = dict(load=config["simulation"]["load_torque_N_m"],
                   contact=simulation_params(SWEEP_ENGINE, "line")["contact"],
                   tooth=plan.canonical(config["tooth"]))


rule tooth_compliance:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        sources=sources("compliance"),
    output:
        out=FILES["compliance"],
    params:
        **command("compliance"),
        tooth=plan.canonical(config["tooth"]),  # rerun trigger (the design: the geometry's)
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
        **PAPER_PAIR,
    log:
        "logs/tooth_compliance/{trace}_beta{spiral}.log",
    resources:
        runtime=config["limits"]["tooth_minutes"],
    shell:
        LSBG


if not STUDY.own_compliance:

    rule fe_ltca:
        # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
        localrule: True
        input:
            geometry=FILES["geometry"],
            config=ancient(FILES["study_config"]),
            compliance_file=FILES["compliance"],
            sources=sources("ltca"),
        output:
            out=FILES["fe_ltca"],
        params:
            **command("ltca", set=["contact.compliance=fe"]),
            **FE_TRIGGERS,
        wildcard_constraints:
            spiral=re.escape(PAPER_SPIRAL),
        log:
            "logs/fe_ltca/{trace}_beta{spiral}.log",
        shell:
            LSBG


# The FE loaded TCA at the corners of the assembly's displacement envelope
# (misalignment_map.axes at +-misalignment_map.range, on the misalignment section):
# the largest contact pressure and root stresses at each corner and position, for
# the rating's "with displacement" (results/tooth/*_envelope.nc); and, in the same
# process on the same compliance, the FE loaded TCA of each sensitivity case that
# reaches it (crowning; results/tooth/*_{case}_ltca.nc), for the service-life
# claim's sensitivity table. In both modes: the paper's compliance is computed here.
rule fe_sensitivity:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        compliance_file=FILES["compliance"],
        sources=sources("ltca"),
    output:
        out=FILES["fe_envelope"],
        cases=[template(FILES["fe_case"], case=case) for case in STUDY.stage_cases("fe_ltca")],
    params:
        **command("ltca", set=["contact.compliance=fe"], envelope=True,
                  case=case_values("fe_ltca"),
                  case_out=lambda w: template(FILES["fe_case"], trace=w.trace, spiral=w.spiral)),
        **FE_TRIGGERS,
        envelope=plan.canonical({k: config[k] for k in ("misalignment", "flank_modification")}
                                | {k: config["misalignment_map"][k] for k in ("axes", "range")}),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/fe_sensitivity/{trace}_beta{spiral}.log",
    shell:
        LSBG
