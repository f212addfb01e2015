# Each gear type at its best ease-off (docs/optimise.md): `lsbg optimise` searches
# the pinion's ease-off of one trace at the paper's spiral angle with NSGA-II (the
# `optimise` section: objectives, bounds, budget, seed, choice rule), evaluated on
# the uniform-bed line model's loaded TCA over the load range and the unloaded TCA
# at the corners of the misalignment_map envelope, and writes the final population,
# its front, the chosen design, the hypervolume by generation and the shared
# design's figures (the flank_modification section). The default budget is about
# 15 s per trace; workflow/config-optimise.yaml runs the full one. Not included in
# the Snakefile yet: the lead engineer integrates it.


rule optimise:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        sources=sources("optimise"),
    output:
        out="results/optimise/{trace}_beta{spiral}_front.nc",
    params:
        **command("optimise"),
        # rerun triggers: the sections the command reads
        settings=plan.canonical({k: config[k] for k in (
            "optimise", "flank_modification", "misalignment", "misalignment_map", "tca",
            "contact", "simulation", "rating", "tooth")}),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/optimise/{trace}_beta{spiral}.log",
    resources:
        runtime=lambda w: 5 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG
