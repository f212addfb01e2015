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
