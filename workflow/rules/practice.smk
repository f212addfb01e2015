# The pair as a designer would make it (docs/model.md, "The pair as a designer
# would make it"): `lsbg practice` writes the practice design as a configuration
# overlay (results/practice/design.yaml: ISO 23509 shift by practice.addendum_rule,
# thickness balancing the root stresses, undercut refused, both tips relieved by the mesh's
# deflection, its rated torque as the load). Its design point of each trace then
# runs the paper point's commands with the overlay as a second --config: the
# geometry, the FE compliance, the FE loaded TCA aligned and at the envelope's
# corners, the V-H map, the line-model run and the ISO rating, the three claims'
# inputs at the practice load (results/practice/); and the claims' model-form cells, the
# sensitivity cases of the keys of practice.sensitivity (lsbg.experiments.sensitivity)
# with the commands of the published pair's: the cases' line-model runs (`lsbg
# sensitivity`), their V-H maps in the contact state's process, their FE loaded TCAs in the
# envelope's, their K_v in the rating. The load curves of both designs
# (`lsbg load-curve`, results/load_curves/) put the FE loaded TCA and ISO 10300
# side by side from 10 % to 150 % of each design's rated torque and at the paper's
# load.

import re

from lsbg.experiments.sensitivity import pair_case_keys

#: The practice design point's configuration: the study's, the overlay over it.
PRACTICE_CONFIG = [ancient(FILES["study_config"]), FILES["practice_design"]]
PRACTICE_SPIRAL = dict(spiral=re.escape(PAPER_SPIRAL))
#: The sensitivity keys whose cases also run on the practice and best pairs.
PAIR_KEYS = pair_case_keys(config)


rule practice_design:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
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
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
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


# The practice design point's claims' files, once with the study's ease-off (and the
# overlay's tip reliefs: "practice") and, under the optimise section, once with each
# type's chosen ease-off ("best", rules/optimise.smk): the same commands on the same
# geometry and compliance, the chosen ease-off a third --config.
FLANK_SETS = {"practice": lambda w: PRACTICE_CONFIG}
if STUDY.optimise:
    FLANK_SETS["best"] = lambda w: [*PRACTICE_CONFIG, STUDY.best_file("overlay", w.trace)]




for flanks, flank_config in FLANK_SETS.items():

    # the FE loaded TCA at the practice load, aligned and (--envelope) at the corners, with
    # the FE loaded TCAs of the cases that reach it in the envelope's process
    for step, envelope in (("fe_ltca", False), ("fe_envelope", True)):
        fe_cases = STUDY.pair_stage_cases("fe_ltca") if envelope else []

        rule:
            name:
                f"{flanks}_{step}"
            # seconds of work: run by the submitting Snakemake, not as a cluster job
            # (docs/scaling.md)
            localrule: True
            input:
                geometry=FILES["practice_geometry"],
                config=flank_config,
                compliance_file=FILES["practice_compliance"],
                sources=sources("ltca"),
            output:
                out=FILES[f"{flanks}_{step}"],
                cases=[template(FILES[f"{flanks}_fe_case"], case=case) for case in fe_cases],
            params:
                **command("ltca", set=["contact.compliance=fe"], envelope=envelope,
                          case=case_values("fe_ltca", PAIR_KEYS) if fe_cases else [],
                          case_out=case_template(flanks, "fe_case") if fe_cases else None),
                # rerun triggers: the line model's settings and the tooth's (the load and
                # the flanks: the overlays')
                contact=FE_TRIGGERS["contact"],
                tooth=FE_TRIGGERS["tooth"],
                envelope=plan.canonical({k: config["misalignment_map"][k]
                                         for k in ("axes", "range")}),
            wildcard_constraints:
                **PRACTICE_SPIRAL,
            log:
                f"logs/{flanks}_{step}/{{trace}}_beta{{spiral}}.log",
            shell:
                LSBG

    rule:
        name:
            f"{flanks}_contact_state"
        input:
            geometry=FILES["practice_geometry"],
            config=flank_config,
            topography=TOPOGRAPHY,
            sources=sources("misalignment-map"),
        output:
            tca_out=FILES[f"{flanks}_tca"],
            out=FILES[f"{flanks}_vh_map"],
            cases=[template(FILES[f"{flanks}_vh_case"], case=case)
                   for case in STUDY.pair_stage_cases("contact_state")],
        params:
            **command("misalignment-map", case=case_values("contact_state", PAIR_KEYS),
                      case_out=case_template(flanks, "vh_case")),
            settings=plan.contact_state_params(config, PAPER_SPIRAL, SWEEP_ENGINE),
        wildcard_constraints:
            **PRACTICE_SPIRAL,
        log:
            f"logs/{flanks}_contact_state/{{trace}}_beta{{spiral}}.log",
        shell:
            LSBG

    rule:
        name:
            f"{flanks}_run"
        input:
            geometry=FILES["practice_geometry"],
            config=flank_config,
            sources=sources("simulate"),
        output:
            out=FILES[f"{flanks}_run"],
        params:
            **command("simulate", set=["contact.model=line"]),
            settings=lambda w: simulation_params(w.engine, "line"),  # rerun trigger
        wildcard_constraints:
            **PRACTICE_SPIRAL,
        log:
            f"logs/{flanks}_run/{{trace}}_beta{{spiral}}_{{engine}}.log",
        resources:
            **runtime(),
        shell:
            LSBG

    # the cases' line-model runs, as the published pair's (rule sensitivity)
    if STUDY.pair_cases:

        rule:
            name:
                f"{flanks}_sensitivity"
            input:
                geometry=FILES["practice_geometry"],
                config=flank_config,
                # the slice stiffness of the compliance_fe case
                fe_ltca=flank_file(flanks, "fe_ltca") if "compliance_fe" in STUDY.pair_cases
                else [],
                sources=sources("sensitivity"),
            output:
                [template(FILES[f"{flanks}_sensitivity_run"], case=case)
                 for case in STUDY.pair_cases],
            params:
                **command("sensitivity", engine=SWEEP_ENGINE,
                          case=case_values("dynamics", PAIR_KEYS),
                          out=case_template(flanks, "sensitivity_run")),
                settings=simulation_params(SWEEP_ENGINE, "line"),  # rerun trigger
            wildcard_constraints:
                **PRACTICE_SPIRAL,
            log:
                f"logs/{flanks}_sensitivity/{{trace}}_beta{{spiral}}.log",
            resources:
                **runtime(runs=len(STUDY.pair_cases)),
            shell:
                LSBG

    rule:
        name:
            f"{flanks}_rating"
        # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
        localrule: True
        input:
            geometry=FILES["practice_geometry"],
            config=flank_config,
            run=flank_file(flanks, "run"),
            fe_ltca=FILES[f"{flanks}_fe_ltca"],
            fe_envelope=FILES[f"{flanks}_fe_envelope"],
            # K_v of each case's run: the standard's cells of the life claim
            case_runs=lambda w, flanks=flanks: [STUDY.pair_case_run(flanks, w.trace, case)
                                                for case in STUDY.pair_cases],
            sources=sources("rate"),
        output:
            out=FILES[f"{flanks}_rating"],
        params:
            **command("rate", case_run=lambda w, flanks=flanks: [
                f"{case}={STUDY.pair_case_run(flanks, w.trace, case)}"
                for case in STUDY.pair_cases]),
            rating=plan.canonical({k: config[k] for k in ("rating", "tooth")}),  # rerun trigger
            steady_state=config["statistics"]["steady_state_after_s"],
        wildcard_constraints:
            **PRACTICE_SPIRAL,
        log:
            f"logs/{flanks}_rating/{{trace}}_beta{{spiral}}.log",
        shell:
            LSBG


rule load_curve:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        geometry=design_set_input(lambda w: STUDY.geometry(w.trace, w.spiral),
                                  practice_input("geometry")),
        compliance_file=design_set_input(lambda w: STUDY.compliance(w.trace, w.spiral),
                                         practice_input("compliance")),
        config=design_set_input(lambda w: [ancient(FILES["study_config"])],
                                lambda w: PRACTICE_CONFIG),
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
