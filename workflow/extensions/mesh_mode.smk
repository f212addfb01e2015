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
# What such a rule declares: its inputs named as the command's options (the
# study's files by STUDY's names, the config) and the sources its command runs
# (so that editing them reruns it), its output (`out`, among EXTENSION_TARGETS so
# that `rule all` asks for it), a log, and the command: `params: **command(...)`,
# `shell: LSBG`. Its settings are checked with the study's (contact section); its
# priority comes from the rule graph and its resources from the profile's defaults.

MESH_MODE_TABLE = "results/extensions/mesh_mode.csv"
EXTENSION_TARGETS.append(MESH_MODE_TABLE)


rule mesh_mode:
    input:
        geometry=[STUDY.geometry(trace, spiral) for trace, spiral in STUDY.points],
        config=ancient(FILES["study_config"]),
        sources=sources("mesh-mode"),
    output:
        out=MESH_MODE_TABLE,
    params:
        **command("mesh-mode"),
        settings=simulation_params(SWEEP_ENGINE, "line"),  # rerun trigger
    log:
        "logs/extensions/mesh_mode.log",
    shell:
        LSBG
