# Extension example: a new sweep dimension, the load torque, through config and
# new rules only (the study's rules are untouched). Included by the Snakefile
# when the config has a `load_sweep` section, e.g. (--configfile):
#
#   load_sweep:
#     torques_N_m: [1000, 1964.99, 3000]
#     traces: [logarithmic, circular]     # default: both
#     engine: pybullet                    # default: engines.sweep
#     contact_model: line                 # default: point
#
# The paper's design point (its geometry comes from the study's `paper_geometry`
# rule) is simulated at every torque, each run by `lsbg simulate --load-torque`;
# one `lsbg summary` per torque tabulates its runs (the summary has no
# load-torque column, the file name carries it). Outputs:
#   results/extensions/load_sweep/runs/{trace}_beta{spiral}_{model}_{engine}_T{torque}.nc
#   results/extensions/load_sweep/summary_T{torque}.csv

from lsbg.files import number_label

LOAD_SWEEP = config["load_sweep"]
LOAD_ENGINE = LOAD_SWEEP.get("engine", SWEEP_ENGINE)
LOAD_MODEL = LOAD_SWEEP.get("contact_model", "point")
LOAD_TORQUES = [number_label(torque) for torque in LOAD_SWEEP["torques_N_m"]]
LOAD_RUN = "results/extensions/load_sweep/runs/{trace}_beta{spiral}_{model}_{engine}_T{torque}.nc"
LOAD_SUMMARY = "results/extensions/load_sweep/summary_T{torque}.csv"

EXTENSION_TARGETS.extend(LOAD_SUMMARY.format(torque=torque) for torque in LOAD_TORQUES)


rule load_sweep_simulate:
    input:
        geometry=FILES["geometry"],
        config=ancient(FILES["study_config"]),
        sources=sources("simulate"),
    output:
        LOAD_RUN,
    params:
        settings=lambda wildcards: simulation_params(wildcards.engine, wildcards.model),
    wildcard_constraints:
        torque=STUDY.wildcards["spiral"],
    log:
        "logs/load_sweep_simulate/{trace}_beta{spiral}_{model}_{engine}_T{torque}.log",
    threads: 1
    resources:
        mem_mb=1000,
        runtime=simulation_runtime(),
    conda:
        CONDA_ENV
    shell:
        "lsbg -v simulate --geometry {input.geometry} --engine {wildcards.engine}"
        " --contact-model {wildcards.model} --config {input.config}"
        " --load-torque {wildcards.torque} --out {output} > {log} 2>&1"


rule load_sweep_summary:
    input:
        runs=lambda wildcards: [
            LOAD_RUN.format(trace=trace, spiral=PAPER_SPIRAL, model=LOAD_MODEL,
                            engine=LOAD_ENGINE, torque=wildcards.torque)
            for trace in LOAD_SWEEP["traces"]
        ],
        config=ancient(FILES["study_config"]),
        sources=sources("aggregate"),
    output:
        LOAD_SUMMARY,
    params:
        statistics=plan.canonical(config["statistics"]),
    wildcard_constraints:
        torque=STUDY.wildcards["spiral"],
    log:
        "logs/load_sweep_summary/T{torque}.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    conda:
        CONDA_ENV
    shell:
        "lsbg -v summary --runs {input.runs} --config {input.config} --out {output} > {log} 2>&1"
