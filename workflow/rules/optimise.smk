# Each gear type at its best ease-off (docs/optimise.md): `lsbg optimise` searches the
# pinion's ease-off of one trace on the practice design at its load (the practice
# overlay as a second --config) with NSGA-II (the `optimise` section: objectives,
# bounds, budget, seed, choice rule), evaluated on the uniform-bed line model's loaded
# TCA over the load range and the unloaded TCA at the corners of the misalignment_map
# envelope, and writes the final population, its front, the chosen design, the
# hypervolume by generation and the shared design's figures, for the study's seed and
# the next. `lsbg release` then re-evaluates both fronts' candidates at converged mesh
# positions, on the uniform bed and with the FE loaded TCA (the practice compliance),
# releases one only if under FE it is no worse than the shared design (optimise.release)
# and writes the released ease-off, or the shared one, as an overlay
# (results/optimise/*_best.yaml), which the "best" design point's rules take
# (rules/practice.smk).

#: What `lsbg optimise` reads, its rerun trigger: its section, the envelope, the line
#: model, the marking compound, the pinion's speed, the rating and the tooth (the flanks
#: and the load: the practice overlay's, an input).
OPTIMISE_SETTINGS = plan.canonical({
    **{k: config[k] for k in ("misalignment", "misalignment_map", "rating", "tooth", "limits")},
    # the processes do not change the front: more of them rerun nothing
    "optimise": {k: v for k, v in config["optimise"].items() if k != "workers"},
    "contact": simulation_params(SWEEP_ENGINE, "line")["contact"],
    "marking_compound_um": config["tca"]["marking_compound_um"],
    "pinion_speed_deg_s": config["simulation"]["pinion_speed_deg_s"]})


for name, seed in zip(("optimise", "optimise_second_seed"), STUDY.optimise_seeds):

    rule:
        name:
            name
        input:
            geometry=FILES["practice_geometry"],
            config=PRACTICE_CONFIG,
            sources=sources("optimise"),
        output:
            out=template(FILES["optimise_front"], seed=seed),
        params:
            **command("optimise", set=[f"optimise.seed={seed}"]),
            settings=OPTIMISE_SETTINGS,
        wildcard_constraints:
            spiral=re.escape(PAPER_SPIRAL),
        log:
            f"logs/{name}/{{trace}}_beta{{spiral}}.log",
        # optimise.workers processes evaluate each generation; a SLURM job gets as
        # many CPUs (workflow/profiles/slurm), a local run at most --cores
        threads: config["optimise"]["workers"]
        resources:
            runtime=5 + int(config["limits"]["optimise_minutes"]),
            mem_mb=1500 + 500 * (config["optimise"]["workers"] - 1),
        shell:
            lsbg_shell("optimise.workers={threads}")


#: What `lsbg release` reads beyond the fronts: its section, the envelope, the line
#: model, the rating and the FE model (the compliance an input).
RELEASE_SETTINGS = plan.canonical({**OPTIMISE_SETTINGS, "tooth": config["tooth"]})


rule optimise_release:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        front=[template(FILES["optimise_front"], seed=seed) for seed in STUDY.optimise_seeds],
        compliance_file=FILES["practice_compliance"],
        sources=sources("release"),
    output:
        out=FILES["optimise_release"],
        overlay_out=FILES["best_overlay"],
    params:
        **command("release"),
        settings=RELEASE_SETTINGS,
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/optimise_release/{trace}_beta{spiral}.log",
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG
