# Meshing simulations (one NetCDF per design point and engine) and the
# convergence study at the paper's design point.


rule simulate:
    input:
        geometry=GEOMETRY,
        config=ancient(STUDY_CONFIG),
        sources=sources("simulate"),
    output:
        RUN,
    params:
        # Rerun trigger: the settings this run depends on.
        settings=lambda wildcards: simulation_params(wildcards.engine),
    log:
        "logs/simulate/{trace}_beta{spiral}_{engine}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v simulate --geometry {input.geometry} --engine {wildcards.engine}"
        " --config {input.config} --out {output} > {log} 2>&1"


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
        settings=canonical({"simulation": config["simulation"], "contact": config["contact"]}),
        steady_state_after=config["statistics"]["steady_state_after_s"],
    log:
        "logs/convergence/{trace}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(runs=6),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v convergence --geometry {input.geometry} --config {input.config}"
        " --steady-state-after {params.steady_state_after} --out {output} > {log} 2>&1"
