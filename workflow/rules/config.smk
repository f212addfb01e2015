# results/design.yaml: the design section of the configuration (after
# --configfile/--config overrides), rewritten only when it changes (params
# rerun trigger); every geometry depends on it. (results/config.yaml, the
# settings the runs read, is written when the workflow is parsed: see
# write_study_config in common.smk.)


rule design_file:
    output:
        DESIGN_FILE,
    params:
        design=canonical(config["design"]),
    log:
        "logs/design_file/design.log",
    threads: 1
    resources:
        mem_mb=100,
        runtime=1,
    localrule: True
    run:
        write_design_file(output[0], params.design, log[0])
