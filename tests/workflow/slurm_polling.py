"""``python -m tests.workflow.slurm_polling ARGS``: Snakemake's command line, with the
SLURM executor's status checks at most :data:`MAX_SECONDS` apart, for the test cluster.

The executor plugin (snakemake-executor-plugin-slurm 2.8) adds 10 s to its interval at
every status check that sees no job end, up to 180 s, and no setting caps that growth
(docs/scaling.md). On the one-node test cluster, whose jobs take seconds, a job that
ended was noticed up to about 20 s late. Capping
the interval changes only when Snakemake asks SLURM, not what it submits or how it
reads the answer: the profile, sbatch, squeue and the jobs are the README's.
"""

import sys

#: The longest interval [s] between two status checks here.
MAX_SECONDS = 2


def cap_status_interval(max_seconds=MAX_SECONDS):
    """Make the SLURM executor's next status check at most ``max_seconds`` [s] away."""
    from snakemake_executor_plugin_slurm import Executor

    interval = Executor.next_seconds_between_status_checks   # the interface's property

    def capped(self, value):
        interval.fset(self, value if value is None else min(value, max_seconds))

    Executor.next_seconds_between_status_checks = property(interval.fget, capped)


if __name__ == "__main__":
    cap_status_interval()
    from snakemake.cli import main

    sys.argv[0] = "snakemake"
    main()
