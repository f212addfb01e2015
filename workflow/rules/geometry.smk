# One design point = (trace, spiral angle): exact flanks, solids, URDF, picture.


rule geometry:
    input:
        design=DESIGN_FILE,
        sources=sources("geometry"),
    output:
        report(
            directory(GEOMETRY),
            patterns=["{name}.png"],
            caption="../report/geometry.rst",
            category="Geometry",
            subcategory="{trace}",
            labels={"trace": "{trace}", "spiral angle [deg]": "{spiral}"},
        ),
    log:
        "logs/geometry/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v geometry --trace {wildcards.trace} --spiral-angle {wildcards.spiral}"
        " --design {input.design} --out {output} > {log} 2>&1"


# Loaded tooth contact analysis (line model) of one design point: transmission
# error, mesh stiffness, tooth-pair loads and contact pattern over a mesh cycle.


rule ltca:
    input:
        geometry=GEOMETRY,
        config=ancient(STUDY_CONFIG),
        sources=sources("ltca"),
    output:
        MESH,
    params:
        # Rerun trigger: the settings the analysis depends on.
        settings=lambda wildcards: {
            "load_torque_N_m": config["simulation"]["load_torque_N_m"],
            **simulation_params("compiled", "line")["contact"],
        },
    log:
        "logs/ltca/{trace}_beta{spiral}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v ltca --geometry {input.geometry} --config {input.config} --out {output}"
        " > {log} 2>&1"
