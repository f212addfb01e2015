# Matched designs (docs/optimise.md, "Matched designs"): `lsbg matched-pairs` pairs the
# LSBG's converged front members with the SBG's on pattern movement and contact pressure
# (normalised by lsbg trace-fronts' common box, a caliper), answers each pair's designs
# (the stability proxy at both boundaries, full runs for the closest optimise.matched.full_runs
# pairs, the FE figures) and writes the paired statistics
# (results/optimise/matched_pairs.nc). The default study's answer is the proxy's, with a
# few full runs (indicative); workflow/config-trace.yaml asks for 30 pairs.

#: What `lsbg matched-pairs` reads beyond its inputs: its section (optimise.matched), the
#: searches', the compiled engine's runs' (not PyBullet's or scipy's keys) and the steady
#: state's start.
MATCHED_SETTINGS = plan.canonical({
    **OPTIMISE_SETTINGS,
    "matched": config["optimise"]["matched"],
    "simulation": engine_simulation(config, "compiled"),
    "statistics": {"steady_state_after_s": config["statistics"]["steady_state_after_s"]},
    **{k: config[k] for k in ("driveline", "tooth")}})


rule matched_pairs:
    input:
        converged=STUDY.both_traces("optimise_converged_front"),
        geometry=STUDY.both_traces("practice_geometry"),
        release=STUDY.both_traces("optimise_release"),
        compliance_file=STUDY.both_traces("practice_compliance"),
        rating=STUDY.both_traces("practice_rating"),
        front=STUDY.optimise_fronts,
        trace_fronts=FILES["trace_fronts"],
        config=PRACTICE_CONFIG,
        sources=sources("matched-pairs"),
    output:
        out=plan.MATCHED_PAIRS,
    params:
        **command("matched-pairs"),
        settings=MATCHED_SETTINGS,
    log:
        "logs/matched_pairs/matched_pairs.log",
    resources:
        runtime=10 + int(config["limits"]["optimise_minutes"]),
    shell:
        LSBG
