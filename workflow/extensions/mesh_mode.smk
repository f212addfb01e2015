# Extension example: a new stage written as a rule (the study's rules untouched).
# Included by the Snakefile when the config lists it:
#
#   extensions: [mesh_mode]
#
# The mesh mode of every design point of the study (`lsbg mesh-mode`): the line
# model's mean mesh stiffness, the gear's inertia, the natural frequency f_n of
# the mesh mode and the pinion speeds at which the mesh frequency meets f_n,
# f_n/2 and f_n/3, one row per design point, in one job (one start-up):
#   results/extensions/mesh_mode.csv
# What such a rule declares: its inputs (the study's files by STUDY's names, the
# config, and the sources of the lsbg stage it runs, so that editing them reruns
# it), a log, its resources (the SLURM profile's default resources apply to any
# rule it does not name), and its output among EXTENSION_TARGETS so that `rule
# all` asks for it. Its settings are checked with the study's (contact section).

MESH_MODE_TABLE = "results/extensions/mesh_mode.csv"
EXTENSION_TARGETS.append(MESH_MODE_TABLE)


rule mesh_mode:
    input:
        geometry=[STUDY.geometry(trace, spiral) for trace, spiral in STUDY.points],
        config=ancient(FILES["study_config"]),
        sources=sources("speed"),
    output:
        MESH_MODE_TABLE,
    params:
        # Rerun trigger: the line model's settings and the flanks it reads.
        settings=simulation_params(SWEEP_ENGINE, "line"),
    log:
        "logs/extensions/mesh_mode.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v mesh-mode --geometry {input.geometry} --config {input.config}"
        " --out {output} > {log} 2>&1"
