# The pair as a designer would make it (docs/model.md, "The pair as a designer
# would make it"): `lsbg practice` writes the practice design as a configuration
# overlay (results/practice/design.yaml: ISO 23509 shift and thickness by the
# Gleason system's rules, undercut refused, both tips relieved by the mesh's
# deflection, its rated torque as the load). Its design point of each trace then
# runs the paper point's commands with the overlay as a second --config: the
# geometry, the FE compliance, the FE loaded TCA aligned and at the envelope's
# corners, the V-H map, the line-model run and the ISO rating, the three claims'
# inputs at the practice load (results/practice/). The load curves of both designs
# (`lsbg load-curve`, results/load_curves/) put the FE loaded TCA and ISO 10300
# side by side from 10 % to 150 % of each design's rated torque and at the paper's
# load.

import re

#: The practice design point's configuration: the study's, the overlay over it.
PRACTICE_CONFIG = [ancient(FILES["study_config"]), FILES["practice_design"]]
PRACTICE_SPIRAL = dict(spiral=re.escape(PAPER_SPIRAL))


rule practice_design:
    input:
        config=ancient(FILES["study_config"]),
        sources=sources("practice"),
    output:
        out=FILES["practice_design"],
    params:
        **command("practice", set=[f"design.spiral_angle_deg={PAPER_SPIRAL}"]),
        # rerun trigger: what the rules read (the rating's speed of the simulation section)
        settings=plan.canonical({k: config[k] for k in (
            "design", "practice", "rating", "tooth", "flank_modification")}),
        speed=config["simulation"]["pinion_speed_deg_s"],
    log:
        "logs/practice_design.log",
    shell:
        LSBG


rule practice_geometry:
    input:
        config=PRACTICE_CONFIG,
        sources=sources("geometry"),
    output:
        out=directory(FILES["practice_geometry"]),
    params:
        **command("geometry", no_step=True),
        design=plan.canonical(config["design"]),  # rerun trigger
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    log:
        "logs/practice_geometry/{trace}_beta{spiral}.log",
    shell:
        LSBG


rule practice_compliance:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        sources=sources("compliance"),
    output:
        out=FILES["practice_compliance"],
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    params:
        **command("compliance"),
        tooth=plan.canonical(config["tooth"]),  # rerun trigger
    log:
        "logs/practice_compliance/{trace}_beta{spiral}.log",
    resources:
        runtime=config["limits"]["tooth_minutes"],
    shell:
        LSBG


# the FE loaded TCA at the practice load, aligned and (--envelope) at the corners
for name, envelope in (("practice_fe_ltca", False), ("practice_fe_envelope", True)):

    rule:
        name:
            name
        input:
            geometry=FILES["practice_geometry"],
            config=PRACTICE_CONFIG,
            compliance_file=FILES["practice_compliance"],
            sources=sources("ltca"),
        output:
            out=FILES[name],
        params:
            **command("ltca", set=["contact.compliance=fe"], envelope=envelope),
            # rerun triggers: the line model's settings and the tooth's (the load: the overlay's)
            contact=FE_TRIGGERS["contact"],
            tooth=FE_TRIGGERS["tooth"],
            envelope=plan.canonical({k: config["misalignment_map"][k] for k in ("axes", "range")}),
        wildcard_constraints:
            **PRACTICE_SPIRAL,
        log:
            f"logs/{name}/{{trace}}_beta{{spiral}}.log",
        shell:
            LSBG


rule practice_contact_state:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        topography=TOPOGRAPHY,
        sources=sources("misalignment-map"),
    output:
        tca_out=FILES["practice_tca"],
        out=FILES["practice_vh_map"],
    params:
        **command("misalignment-map"),
        settings=plan.contact_state_params(config, PAPER_SPIRAL, SWEEP_ENGINE),
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    log:
        "logs/practice_contact_state/{trace}_beta{spiral}.log",
    shell:
        LSBG


rule practice_run:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        sources=sources("simulate"),
    output:
        out=FILES["practice_run"],
    params:
        **command("simulate", set=["contact.model=line"]),
        settings=lambda w: simulation_params(w.engine, "line"),  # rerun trigger
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    log:
        "logs/practice_run/{trace}_beta{spiral}_{engine}.log",
    resources:
        **runtime(),
    shell:
        LSBG


rule practice_rating:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        run=practice_input("run"),
        fe_ltca=FILES["practice_fe_ltca"],
        fe_envelope=FILES["practice_fe_envelope"],
        sources=sources("rate"),
    output:
        out=FILES["practice_rating"],
    params:
        **command("rate"),
        rating=plan.canonical({k: config[k] for k in ("rating", "tooth")}),  # rerun trigger
        steady_state=config["statistics"]["steady_state_after_s"],
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    log:
        "logs/practice_rating/{trace}_beta{spiral}.log",
    shell:
        LSBG


rule load_curve:
    input:
        geometry=design_set_input(lambda w: STUDY.geometry(w.trace, w.spiral),
                             practice_input("geometry")),
        compliance_file=design_set_input(lambda w: STUDY.compliance(w.trace, w.spiral),
                                    practice_input("compliance")),
        config=design_set_input(lambda w: [ancient(FILES["study_config"])], lambda w: PRACTICE_CONFIG),
        sources=sources("load-curve"),
    output:
        out=FILES["load_curve"],
    params:
        # the paper's load on every curve
        **command("load-curve", also_at=[config["simulation"]["load_torque_N_m"]],
                  design_set=lambda w: w.design_set),
        settings=plan.canonical({k: config[k] for k in (
            "practice", "rating", "tooth", "contact", "flank_modification", "misalignment")}),
    wildcard_constraints:
        **PRACTICE_SPIRAL,
    log:
        "logs/load_curve/{design_set}_{trace}_beta{spiral}.log",
    shell:
        LSBG
