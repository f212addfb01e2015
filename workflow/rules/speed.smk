# The dynamic-factor curve (included when the config has a speed_sweep section,
# e.g. --configfile workflow/config-speed.yaml): the line model at each pinion
# speed of the sweep, for each trace at one spiral angle (`lsbg speed-run`),
# combined into results/speed_curve.nc (`lsbg speed-curve`), which
# reports/sweep.html plots. The geometry comes from the study's point rules.

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
                  set=lambda w: [f"simulation.pinion_speed_deg_s={w.speed}"]),
        settings=simulation_params(SPEED_ENGINE, "line"),  # rerun triggers
        speed=plan.canonical(STUDY.speed_sweep),
    log:
        "logs/speed_run/{trace}_beta{spiral}_w{speed}.log",
    shell:
        LSBG


rule speed_curve:
    input:
        runs=STUDY.speed_runs,
        sources=sources("speed-curve"),
    output:
        out=report(FILES["speed_curve"], caption="../report/speed.rst", category="Speed sweep"),
    params:
        **command("speed-curve"),
    log:
        "logs/speed_curve/speed_curve.log",
    shell:
        LSBG
