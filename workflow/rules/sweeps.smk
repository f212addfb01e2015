# Parameter sweeps of any setting (the `sweeps` section; lsbg.experiments.sweeps, README
# "Sweeping any setting"). Per sweep: its points (a Paramspace: one row per
# point, a column per swept key, the instance patterns name the files) run in
# batches of `batch_size` points per job and design point (`lsbg sweep-run`: one
# start-up per batch, which is what a cluster pays per job), then one job stacks
# them into results/sweeps/{name}.nc and .csv (`lsbg sweep-combine`). Resources
# are derived here from the runs a job carries: no profile entry is needed. The
# combine is a local rule: a few seconds of reading, which as a SLURM job would
# cost two Snakemake start-ups and a polling latency more (docs/scaling.md).

import re
import shlex

from lsbg.files import number_label


def sweep_point_options(sweep, batch):
    """``--point RUN.nc KEY=VALUE ...`` of a batch's points (the wildcards filled in)."""
    def options(wildcards, output):
        return " ".join(
            f"--point {shlex.quote(out)} "
            + " ".join(shlex.quote(f"{key}={value!r}") for key, value in sweep.points[i].items())
            for out, i in zip(output, batch))
    return options


for _sweep in STUDY.sweeps:
    _patterns = _sweep.patterns()
    _labels = [number_label(a) for a in _sweep.spiral_angles]
    for _k, _batch in enumerate(_sweep.batches()):

        rule:
            name:
                f"sweep_{_sweep.name}_batch{_k}"
            input:
                geometry=FILES["geometry"],
                config=ancient(FILES["study_config"]),
                sources=sources("sweep"),
            output:
                [FILES["sweep_run"].format(name=_sweep.name, trace="{trace}", spiral="{spiral}",
                                           point=_patterns[i]) for i in _batch],
            params:
                points=sweep_point_options(_sweep, _batch),
                engine=_sweep.engine,
                model=_sweep.contact_model,
                kind=_sweep.kind,
                name=_sweep.name,
                # Rerun trigger: the settings the runs read besides their own values.
                settings=simulation_params(_sweep.engine, _sweep.contact_model),
            wildcard_constraints:
                trace="|".join(_sweep.traces),
                spiral="|".join(map(re.escape, _labels)),
            log:
                f"logs/sweeps/{_sweep.name}/{{trace}}_beta{{spiral}}_batch{_k}.log",
            threads: 1
            resources:
                mem_mb=1000,
                runtime=simulation_runtime(runs=len(_batch)),
            conda:
                CONDA_ENV
            shell:
                "lsbg -v sweep-run --geometry {input.geometry} --config {input.config}"
                " --engine {params.engine} --contact-model {params.model} --sweep {params.name}"
                " --kind {params.kind} {params.points} > {log} 2>&1"

    rule:
        name:
            f"sweep_{_sweep.name}_combine"
        localrule: True
        input:
            runs=STUDY.parameter_sweep_runs(_sweep),
            config=ancient(FILES["study_config"]),
            sources=sources("sweep"),
        output:
            dataset=FILES["sweep_dataset"].format(name=_sweep.name),
            table=FILES["sweep_table"].format(name=_sweep.name),
        params:
            statistics=plan.canonical(config["statistics"]),
        log:
            f"logs/sweeps/{_sweep.name}/combine.log",
        threads: 1
        resources:
            mem_mb=2000,
            runtime=10,
        conda:
            CONDA_ENV
        shell:
            "lsbg -v sweep-combine --runs {input.runs} --config {input.config}"
            " --out {output.dataset} --csv {output.table} > {log} 2>&1"
