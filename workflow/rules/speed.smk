# The dynamic-factor curve (included when the config has a speed_sweep section, as
# workflow/config.yaml's 0.25-1.5 times the paper's speed; workflow/config-speed.yaml
# runs a wide one): the line model at each pinion speed of the sweep, for each trace
# at one spiral angle and each boundary (`lsbg speed-run`, simulation.boundary set
# per run), combined per boundary into results/speed_curve_{boundary}.nc (`lsbg
# speed-curve`), which reports/sweep.html plots. The geometry comes from the study's
# point rules.

SPEED_ENGINE = STUDY.speed_sweep["engine"]


rule speed_run:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        fe_ltca=fe_ltca_input(lambda w: STUDY.own_compliance),
        sources=sources("speed-run"),
    output:
        out=FILES["speed_run"],
    params:
        **command("speed-run", engine=SPEED_ENGINE,
                  set=lambda w: [f"simulation.pinion_speed_deg_s={w.speed}",
                                 f"simulation.boundary={w.boundary}"]),
        settings=simulation_params(SPEED_ENGINE, "line"),  # rerun triggers
        speed=plan.canonical(STUDY.speed_sweep),
    log:
        "logs/speed_run/{trace}_beta{spiral}_{boundary}_w{speed}.log",
    shell:
        LSBG


rule speed_curve:
    input:
        runs=lambda w: STUDY.speed_runs(w.boundary),
        sources=sources("speed-curve"),
    output:
        out=report(FILES["speed_curve"], caption="../report/speed.rst", category="Speed sweep"),
    params:
        **command("speed-curve", orders=STUDY.speed_sweep["resonance_orders"]),
    log:
        "logs/speed_curve/speed_curve_{boundary}.log",
    shell:
        LSBG
