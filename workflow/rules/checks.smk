# What the reports show that lsbg computes for them (the reports only read files):
# `lsbg checks` checks at the paper's point of each trace what nobody tuned (the
# flanks' conjugacy, the line model's loaded TCA without load, at twice the load and
# with more slices, the surface TCA on the conjugate, crowned and displaced pair) and
# computes the gear's contact resonance on the point model that the paper report
# explains its fluctuations with (results/verification/*_checks.nc: the verification
# and paper reports); `lsbg rate-sweep` rates every design point of the summary table
# by ISO 10300 with its own K_v (results/rating_sweep.nc: the sweep report's service
# life).

import re

#: The checks of a design point, and the rating of every design point.
CHECKS = "results/verification/{trace}_beta{spiral}_checks.nc"
RATING_SWEEP = "results/rating_sweep.nc"
#: The checks the paper and verification reports read: the paper's point of each trace.
PAPER_CHECKS = [CHECKS.format(trace=t, spiral=PAPER_SPIRAL) for t in plan.PAPER_TRACES]


rule checks:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        geometry=FILES["geometry"],
        mesh=FILES["mesh"],
        # the contact law and load of the resonance: the paper engine's point-model run
        run=lambda w: STUDY.run(w.trace, w.spiral, "point", STUDY.paper_engine),
        sources=sources("checks"),
    output:
        out=CHECKS,
    params:
        **command("checks"),
    wildcard_constraints:
        spiral=re.escape(PAPER_SPIRAL),
    log:
        "logs/checks/{trace}_beta{spiral}.log",
    shell:
        LSBG


rule rating_sweep:
    # seconds of work: run by the submitting Snakemake, not as a cluster job (docs/scaling.md)
    localrule: True
    input:
        summary=FILES["summary"],
        config=ancient(FILES["study_config"]),
        sources=sources("rate-sweep"),
    output:
        out=RATING_SWEEP,
    params:
        **command("rate-sweep", engine=SWEEP_ENGINE),
        # rerun triggers (the config file is ancient): the sections it reads
        rating=plan.canonical({k: config[k] for k in ("design", "rating", "tooth")}),
        load=[config["simulation"][k] for k in ("load_torque_N_m", "pinion_speed_deg_s")],
    log:
        "logs/rating_sweep/rating_sweep.log",
    shell:
        LSBG
