"""The order in which Snakemake starts the study's ready jobs on a few cores.

Snakemake knows the DAG but not what a job costs, so the order in which it
starts the ready jobs decides how long the cores sit idle. Each rule of the
default study gets a ``priority:`` from :func:`job_priority`:

1. :data:`GATE_RULES`, the paper point's geometry and loaded TCA (1-5 s each),
   before everything: every report and aggregate waits for them (left to
   the end by their length, they held all of those back: 82 s with -j2).
2. Every other rule by its *level*: its own measured job seconds plus the
   longest chain of rules that wait for it, down to the last report (the
   "highest level first" list schedule; Adam, Chandy & Dickson, Commun. ACM
   17(12), 1974). The longest remaining chain starts first and short jobs
   are left for the end, where they fill the cores.

Ranking by a job's own length only (longest processing time first, until
2026-11-25) started the FE compliance's chain (its loaded TCA, the sensitivity
runs that read it, the rating, the paper report: 50 s end to end) after the
sweep batches and the convergence runs, and the paper report then ran alone
at the end (tests/benchmarks/bench_study.py prints the timeline).
:data:`WAITING` is the study's rule graph (``snakemake --rulegraph``; a test
keeps the two equal) and :data:`JOB_SECONDS` the job times measured by
bench_study.py.
"""

from __future__ import annotations

from functools import lru_cache

__all__ = ["JOB_SECONDS", "WAITING", "GATE_RULES", "level", "job_priority"]

#: Wall time [s] of one job of each rule of the default study, ``snakemake -j2``
#: on the 2-core reference machine (tests/benchmarks/bench_study.py, 2026-11-25).
JOB_SECONDS = {"paper_geometry": 5.4, "paper_ltca": 1.1, "tooth_compliance": 8.8,
               "fe_ltca": 3.0, "fe_sensitivity": 5.9, "sweep_points": 17.2,
               "sweep_contact_state": 13.7, "contact_state": 8.8, "convergence_point": 13.1,
               "convergence_line": 10.6, "sensitivity": 14.5, "rating": 0.8, "combine": 3.7,
               "summary": 3.5, "report_paper": 15.9, "report_sweep": 8.4,
               "report_verification": 7.7}

#: {rule: the rules whose jobs read its outputs} in the default study (without
#: the gates' edges, which :func:`job_priority` puts first anyway).
WAITING = {
    "tooth_compliance": ("fe_ltca", "fe_sensitivity"),
    "fe_ltca": ("sensitivity", "rating", "report_paper"),
    "fe_sensitivity": ("rating", "report_paper"),
    "sensitivity": ("rating", "summary", "report_paper"),
    "rating": ("report_paper",),
    "sweep_points": ("sweep_contact_state", "combine", "summary"),
    "sweep_contact_state": ("combine", "summary", "report_sweep"),
    "contact_state": ("combine", "summary", "report_paper", "report_sweep"),
    "convergence_point": ("combine", "summary", "report_paper", "report_verification"),
    "convergence_line": ("combine", "summary", "rating", "report_paper",
                         "report_verification"),
    "combine": ("report_paper", "report_sweep"),
    "summary": ("report_sweep",),
    "report_paper": (),
    "report_sweep": (),
    "report_verification": (),
}

#: Short jobs that every report and aggregate waits for: before all others, in this order.
GATE_RULES = ("paper_geometry", "paper_ltca")


@lru_cache(maxsize=None)
def level(rule):
    """Job seconds from the start of a job of ``rule`` to the end of the study [s].

    Its own :data:`JOB_SECONDS` plus the largest level of the rules in
    :data:`WAITING` for it (0 for a rule not measured).

    Parameters
    ----------
    rule : str
        A rule of the workflow.

    Returns
    -------
    float
    """
    return JOB_SECONDS.get(rule, 0.0) + max((level(r) for r in WAITING.get(rule, ())),
                                            default=0.0)


def job_priority(rule):
    """Snakemake priority of the jobs of ``rule``.

    Parameters
    ----------
    rule : str
        A rule of the workflow.

    Returns
    -------
    int
        Above every other rule for :data:`GATE_RULES` (the first highest), else
        the rule's :func:`level` in tenths of a second (0 for a rule not
        measured: after the study's jobs).
    """
    top = max(round(10 * level(r)) for r in WAITING)
    if rule in GATE_RULES:
        return top + len(GATE_RULES) - GATE_RULES.index(rule)
    return round(10 * level(rule))
