# Each gear type at its best ease-off (docs/optimise.md): `lsbg optimise` searches the
# pinion's ease-off of one trace on the practice design at its load (the practice
# overlay as a second --config) with NSGA-II (the `optimise` section: objectives,
# bounds, budget, seed, choice rule), evaluated on the uniform-bed line model's loaded
# TCA over the load range and the unloaded TCA at the corners of the misalignment_map
# envelope, and writes the final population, its front, the chosen design, the
# hypervolume by generation and the shared design's figures, for optimise.seeds seeds
# (a job per trace and seed). `lsbg release` then re-evaluates the fronts' candidates at converged mesh
# positions, on the uniform bed and with the FE loaded TCA (the practice compliance),
# releases one only if under FE it is no worse than the shared design (optimise.release)
# and writes the released ease-off, or the shared one, as an overlay
# (results/optimise/*_best.yaml), which the "best" design point's rules take
# (rules/practice.smk). `lsbg converge-front` evaluates every front member again at the
# release's converged positions and `lsbg trace-fronts` compares the traces' fronts
# (results/optimise/trace_fronts.nc; docs/optimise.md, "Trace against trace").

#: What `lsbg optimise` reads, its rerun trigger: its section, the envelope, the line
#: model, the marking compound, the pinion's speed, the rating and the tooth (the flanks
#: and the load: the practice overlay's, an input).
OPTIMISE_SETTINGS = plan.canonical({
    **{k: config[k] for k in ("misalignment", "misalignment_map", "rating", "tooth", "limits")},
    # the processes do not change a front, nor do more seeds the others': neither
    # reruns a search
    # (nor the matched designs' settings: lsbg matched-pairs reads them, rules/matched.smk)
    "optimise": {k: v for k, v in config["optimise"].items()
                 if k not in ("workers", "seeds", "matched")},
    "contact": simulation_params(SWEEP_ENGINE, "line")["contact"],
    "marking_compound_um": config["tca"]["marking_compound_um"],
    "pinion_speed_deg_s": config["simulation"]["pinion_speed_deg_s"]})


rule optimise:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        sources=sources("optimise"),
    output:
        out=FILES["optimise_front"],
    params:
        **command("optimise", set=lambda w: [f"optimise.seed={w.seed}"]),
        settings=OPTIMISE_SETTINGS,
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
        seed="|".join(map(str, STUDY.optimise_seeds)),
    log:
        "logs/optimise/{trace}_beta{spiral}_seed{seed}.log",
    # optimise.workers processes evaluate each generation; a SLURM job gets as
    # many CPUs (workflow/profiles/slurm), a local run at most --cores
    threads: config["optimise"]["workers"]
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
        mem_mb=1500 + 500 * (config["optimise"]["workers"] - 1),
    shell:
        lsbg_shell("optimise.workers={threads}")


#: A trace's fronts, every seed's (the release's and lsbg converge-front's input).
OPTIMISE_FRONTS = [template(FILES["optimise_front"], seed=seed) for seed in STUDY.optimise_seeds]


#: What `lsbg release` reads beyond the fronts: its section, the envelope, the line
#: model, the rating and the FE model (the compliance an input).
RELEASE_SETTINGS = plan.canonical({**OPTIMISE_SETTINGS, "tooth": config["tooth"]})


rule optimise_release:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        front=OPTIMISE_FRONTS,
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


rule optimise_converged_front:
    input:
        geometry=FILES["practice_geometry"],
        config=PRACTICE_CONFIG,
        front=OPTIMISE_FRONTS,
        release=FILES["optimise_release"],
        sources=sources("converge-front"),
    output:
        out=FILES["optimise_converged_front"],
    params:
        **command("converge-front"),
        settings=OPTIMISE_SETTINGS,
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/optimise_converged_front/{trace}_beta{spiral}.log",
    resources:
        runtime=5 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG


rule trace_fronts:
    input:
        converged=STUDY.optimise_converged_fronts,
        sources=sources("trace-fronts"),
    output:
        out=FILES["trace_fronts"],
    params:
        **command("trace-fronts"),
    log:
        "logs/trace_fronts/trace_fronts.log",
    localrule: True
    resources:
        runtime=10,
    shell:
        LSBG
