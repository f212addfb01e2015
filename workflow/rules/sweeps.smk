# Parameter sweeps of any setting (the `sweeps` section; lsbg.experiments.sweeps, docs/usage.md
# "Sweeping any setting"). Per sweep: its points (a Paramspace: one row per
# point, a column per swept key, the instance patterns name the files) run in
# batches of `batch_size` points per job and design point (`lsbg sweep-run`: one
# start-up per batch, which is what a cluster pays per job), then one job stacks
# them into results/sweeps/{name}.nc and .csv (`lsbg sweep-combine`). Resources
# are derived here from the runs a job carries: no profile entry is needed. The
# combine is a local rule: a few seconds of reading, which as a SLURM job would
# cost two Snakemake start-ups and a polling latency more (docs/scaling.md).

import re

from lsbg.files import number_label


def sweep_points(sweep, batch):
    """``--point RUN.nc KEY=VALUE ...`` values of a batch's points (the wildcards filled in)."""
    patterns = sweep.patterns()

    def points(wildcards):
        return [[FILES["sweep_run"].format(name=sweep.name, trace=wildcards.trace,
                                           spiral=wildcards.spiral, point=patterns[i]),
                 *(f"{key}={value!r}" for key, value in sweep.points[i].items())] for i in batch]
    return points


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
                sources=sources("sweep-run"),
            output:
                [FILES["sweep_run"].format(name=_sweep.name, trace="{trace}", spiral="{spiral}",
                                           point=_patterns[i]) for i in _batch],
            params:
                **command("sweep-run", engine=_sweep.engine, sweep=_sweep.name, kind=_sweep.kind,
                          set=[f"contact.model={_sweep.contact_model}"],
                          point=sweep_points(_sweep, _batch)),
                settings=simulation_params(_sweep.engine, _sweep.contact_model),  # rerun trigger
            wildcard_constraints:
                trace="|".join(_sweep.traces),
                spiral="|".join(map(re.escape, _labels)),
            log:
                f"logs/sweeps/{_sweep.name}/{{trace}}_beta{{spiral}}_batch{_k}.log",
            resources:
                **runtime(runs=len(_batch)),
            shell:
                LSBG

    rule:
        name:
            f"sweep_{_sweep.name}_combine"
        localrule: True
        input:
            runs=STUDY.parameter_sweep_runs(_sweep),
            config=ancient(FILES["study_config"]),
            sources=sources("sweep-combine"),
        output:
            out=FILES["sweep_dataset"].format(name=_sweep.name),
            csv=FILES["sweep_table"].format(name=_sweep.name),
        params:
            **command("sweep-combine"),
            statistics=plan.canonical(config["statistics"]),  # rerun trigger
        log:
            f"logs/sweeps/{_sweep.name}/combine.log",
        shell:
            LSBG
