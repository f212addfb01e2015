# Meshing simulations (one NetCDF per design point, contact model and engine),
# the sensitivity runs and the convergence studies at the paper's design point.


rule simulate:
    input:
        geometry=GEOMETRY,
        config=ancient(STUDY_CONFIG),
        sources=sources("simulate"),
    output:
        RUN,
    params:
        # Rerun trigger: the settings this run depends on.
        settings=lambda wildcards: simulation_params(wildcards.engine, wildcards.model),
    log:
        "logs/simulate/{trace}_beta{spiral}_{model}_{engine}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v simulate --geometry {input.geometry} --engine {wildcards.engine}"
        " --contact-model {wildcards.model} --config {input.config} --out {output} > {log} 2>&1"


rule sensitivity:
    input:
        geometry=GEOMETRY,
        config=ancient(STUDY_CONFIG),
        sources=sources("simulate"),
    output:
        SENSITIVITY_RUN,
    params:
        engine=SWEEP_ENGINE,
        option=lambda wildcards: sensitivity_option(wildcards.case),
        settings=lambda wildcards: simulation_params(SWEEP_ENGINE, "line"),
    log:
        "logs/sensitivity/{trace}_beta{spiral}_{case}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v simulate --geometry {input.geometry} --engine {params.engine}"
        " --contact-model line {params.option} --config {input.config} --out {output}"
        " > {log} 2>&1"


rule convergence:
    input:
        geometry=geometry_dir("{trace}", PAPER_SPIRAL),
        config=ancient(STUDY_CONFIG),
        sources=sources("convergence"),
    output:
        report(
            CONVERGENCE,
            caption="../report/convergence.rst",
            category="Verification",
            labels={"trace": "{trace}", "table": "convergence"},
        ),
    params:
        settings=lambda wildcards: canonical({
            "simulation": config["simulation"],
            "contact": simulation_params("compiled", wildcards.model)["contact"],
        }),
        steady_state_after=config["statistics"]["steady_state_after_s"],
    log:
        "logs/convergence/{trace}_{model}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(runs=9),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v convergence --geometry {input.geometry} --config {input.config}"
        " --contact-model {wildcards.model} --steady-state-after {params.steady_state_after}"
        " --out {output} > {log} 2>&1"
