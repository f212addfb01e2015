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
        sources=sources("speed"),
    output:
        FILES["speed_run"],
    params:
        engine=SPEED_ENGINE,
        options=STUDY.speed_options,
        settings=simulation_params(SPEED_ENGINE, "line"),
        fe_ltca=fe_ltca_option,
    log:
        "logs/speed_run/{trace}_beta{spiral}_w{speed}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v speed-run --geometry {input.geometry} --config {input.config}"
        " --engine {params.engine} --pinion-speed {wildcards.speed} {params.options}"
        " {params.fe_ltca} --out {output} > {log} 2>&1"


rule speed_curve:
    input:
        runs=STUDY.speed_runs,
        sources=sources("speed"),
    output:
        report(FILES["speed_curve"], caption="../report/speed.rst", category="Speed sweep"),
    log:
        "logs/speed_curve/speed_curve.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v speed-curve --runs {input.runs} --out {output} > {log} 2>&1"
