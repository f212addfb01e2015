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
# lsbg.experiments.sensitivity) at sweep_steps; the other angles of a trace are one
# job (one start-up instead of one per angle), as in points.smk.

#: A topography file's content is part of the flanks: it reruns the contact state.
TOPOGRAPHY = [config["flank_modification"]["topography_file"]] if config["flank_modification"][
    "topography_file"] else []


rule contact_state:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        topography=TOPOGRAPHY,
        sources=sources("misalignment-map"),
    output:
        tca_out=FILES["tca"],
        out=FILES["vh_map"],
        cases=[template(FILES["vh_case"], case=case) for case in STUDY.stage_cases("contact_state")],
    params:
        **command("misalignment-map", case=case_values("contact_state"),
                  case_out=lambda w: template(FILES["vh_case"], trace=w.trace, spiral=w.spiral)),
        # rerun trigger: the contact-state sections, the line model and the load
        settings=lambda w: plan.contact_state_params(config, w.spiral, SWEEP_ENGINE),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
        **PAPER_PAIR,
    log:
        "logs/contact_state/{trace}_beta{spiral}.log",
    shell:
        LSBG


# The batches as points.smk's (plan.Study.batch_groups). A trace outside the paper's pair
# is mapped at sweep_steps at every angle, the paper's too (its paper point has no job of
# its own, and no sensitivity cases).
for _suffix, _traces, _batch in STUDY.batch_groups():
    _steps = STUDY.map_steps(_batch[0]) if not _suffix else config["misalignment_map"]["sweep_steps"]

    rule:
        name:
            f"sweep_contact_state{_suffix}"
        input:
            geometries=[template(FILES["geometry"], spiral=s) for s in _batch],
            config=ancient(FILES["study_config"]),
            topography=TOPOGRAPHY,
            sources=sources("misalignment-map"),
        output:
            tca=[template(FILES["tca"], spiral=s) for s in _batch],
            vh=[template(FILES["vh_map"], spiral=s) for s in _batch],
        params:
            **command("misalignment-map", spiral_angles=_batch,
                      set=[f"misalignment_map.steps={_steps}"],
                      **point_templates(geometry=FILES["geometry"], out=FILES["vh_map"],
                                        tca_out=FILES["tca"])),
            settings={**plan.contact_state_params(config, _batch[0], SWEEP_ENGINE),
                      "steps": _steps},
        wildcard_constraints:
            trace="|".join(_traces),
        log:
            "logs/sweep_contact_state/{trace}.log",
        resources:
            runtime=10 + len(_batch),
        shell:
            LSBG
