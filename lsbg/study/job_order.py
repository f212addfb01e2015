"""The order in which Snakemake starts the study's ready jobs on a few cores.

Snakemake knows the DAG but not what a job costs, so the order in which it
starts the ready jobs decides how long the cores sit idle. Each rule gets a
priority from its *level*: its own measured job seconds plus the longest chain
of rules that wait for it, down to the last report (the "highest level first"
list schedule; Adam, Chandy & Dickson, Commun. ACM 17(12), 1974). The longest
remaining chain starts first and short jobs are left for the end, where they
fill the cores; the paper point's geometry and loaded TCA, which every report
and aggregate waits for, come first by the same rule.

Nothing here is kept by hand but the measurement: the rule graph
(:func:`rule_graph`) is read from the rules themselves once the Snakefile has
defined them all (their input and output files; an input function is asked
with sample wildcards), and :func:`assign_priorities` sets each rule's
priority. :data:`JOB_SECONDS` holds the job times measured by
tests/benchmarks/bench_study.py; a rule not measured counts 0 s (a new stage
runs after the study's measured jobs until it is measured).
"""

from __future__ import annotations

import re

__all__ = ["JOB_SECONDS", "rule_graph", "levels", "assign_priorities", "lift_job_rate_limit"]

#: Wall time [s] of one job of each rule of the default study, ``snakemake -j2``
#: on the 2-core reference machine from a fresh copy with an empty numba cache
#: (tests/benchmarks/bench_study.py: the mean of each rule's jobs),
#: with the practice design, the load curves, the ease-off searches and the best design
#: point, the job server and the kernels' job.
JOB_SECONDS = {"kernels": 14.7, "paper_geometry": 4.3, "paper_ltca": 0.3,
               "tooth_compliance": 8.8, "fe_ltca": 1.2, "fe_sensitivity": 3.9,
               "sweep_points": 16.5, "sweep_contact_state": 9.8, "contact_state": 6.8,
               "convergence_point": 11.6, "convergence_line": 9.5, "sensitivity": 12.3,
               "rating": 0.5, "checks": 1.2, "combine": 3.0, "summary": 3.2,
               "rating_sweep": 0.3, "load_curve": 3.0, "practice_design": 0.2,
               "practice_geometry": 0.6, "practice_compliance": 9.4,
               "practice_contact_state": 3.0, "practice_fe_ltca": 1.6,
               "practice_fe_envelope": 2.4, "practice_run": 1.8, "practice_rating": 0.3,
               "optimise": 8.5, "optimise_release": 20.0, "optimise_converged_front": 15.0,
               "trace_fronts": 4.0,
               # not measured on the reference machine: the tiny study's job
               "matched_pairs": 10.0,
               "best_contact_state": 3.1,
               "best_fe_ltca": 1.6, "best_fe_envelope": 2.4, "best_run": 1.4,
               "best_rating": 0.3, "report_paper": 18.8, "report_sweep": 8.6,
               "report_verification": 5.3,
               # the practice and best pairs' crowning cases (lsbg sensitivity alone)
               "practice_sensitivity": 6.5, "best_sensitivity": 6.5}

_FIELD = re.compile(r"\{[^{}]*\}")


class _Wildcards(dict):
    """Sample wildcards for an input function: attribute access, a sample for any name."""

    def __getattr__(self, name):
        return self.get(name, "x")


def _pattern(text):
    """A file pattern's regex: each ``{wildcard}`` matches any text."""
    parts = _FIELD.split(str(text))
    return re.compile(".+".join(re.escape(part) for part in parts) + r"\Z")


def _files(value, samples):
    """The file names (or patterns) of a rule's input item: a function is asked with
    ``samples``; one that needs more than sample wildcards gives nothing."""
    if callable(value):
        try:
            value = value(_Wildcards(samples))
        except Exception:  # an input function of a rule needs its real wildcards
            return []
    if isinstance(value, (str, bytes)):
        return [str(value)]
    try:
        return [str(v) for item in value for v in _files(item, samples)]
    except TypeError:
        return []


def rule_graph(rules, samples=None):
    """``{rule name: names of the rules whose jobs read its outputs}``.

    Parameters
    ----------
    rules : iterable
        Snakemake rules (``workflow.rules``): ``name``, ``input`` (files,
        patterns or functions of the wildcards) and ``output`` (patterns).
    samples : dict, optional
        Sample wildcards for input functions (``{"trace": "logarithmic", ...}``).

    Returns
    -------
    dict
    """
    rules = list(rules)
    outputs = {rule.name: [_pattern(o) for o in rule.output] for rule in rules}
    waiting = {rule.name: set() for rule in rules}
    for reader in rules:
        wanted = [_FIELD.sub("X", f) for f in _files(list(reader.input), samples or {})]
        for producer, patterns in outputs.items():
            if producer != reader.name and any(p.match(f) for p in patterns for f in wanted):
                waiting[producer].add(reader.name)
    return {name: sorted(readers) for name, readers in waiting.items()}


def levels(graph, seconds=JOB_SECONDS):
    """Job seconds from the start of a job of each rule to the end of the study [s].

    Parameters
    ----------
    graph : dict
        :func:`rule_graph`.
    seconds : dict
        Measured job seconds by rule (0 for a rule not in it).

    Returns
    -------
    dict
    """
    found = {}

    def level(rule, path=()):
        if rule not in found:
            after = [level(r, path + (rule,)) for r in graph.get(rule, ()) if r not in path]
            found[rule] = seconds.get(rule, 0.0) + max(after, default=0.0)
        return found[rule]

    for rule in graph:
        level(rule)
    return found


def assign_priorities(rules, samples=None, seconds=JOB_SECONDS):
    """Set each rule's Snakemake priority to its level in tenths of a second.

    Parameters
    ----------
    rules : iterable
        ``workflow.rules``, once the Snakefile has defined them all.
    samples : dict, optional
        Sample wildcards for input functions (:func:`rule_graph`).
    seconds : dict

    Returns
    -------
    dict
        ``{rule name: priority}``.
    """
    rules = list(rules)
    found = levels(rule_graph(rules, samples), seconds)
    priorities = {}
    for rule in rules:
        priorities[rule.name] = round(10 * found.get(rule.name, 0.0))
        rule.priority = priorities[rule.name]
    return priorities


#: Snakemake's default limit on job starts (``--max-jobs-per-timespan 100/1s``):
#: (jobs, timespan [s]).
DEFAULT_RATE_LIMIT = (100, 1.0)


def lift_job_rate_limit(workflow):
    """Take Snakemake's default job rate limit off a local run (from ``onstart``).

    Snakemake 9 keeps a rate limiter even for local jobs (100 starts a second
    by default). With it, every pass of the scheduler that finds jobs waiting
    for a core arms a one-second timer that wakes the scheduler again, and every
    such wake-up arms another: the timers multiply with the jobs that finished,
    and each wake-up checks the size of every ready job's input files. On the
    study's 66 jobs over two cores this kept the Snakemake process busy 9 to 15 s
    of a core's time, against 3 to 4 s without the limiter
    (docs/performance.md), time the jobs lost to it. A local run starts at most
    ``-j`` jobs at a time, so the limit never bites there. A limit the user set
    (any other value than the default), SLURM and other executors keep theirs.

    Parameters
    ----------
    workflow : snakemake.workflow.Workflow
        The running workflow (``workflow`` in the Snakefile), its scheduler made.

    Returns
    -------
    bool
        Whether the limiter was taken off.
    """
    scheduler = getattr(workflow, "scheduler", None)
    limiter = getattr(scheduler, "job_rate_limiter", None)
    if limiter is None or not workflow.local_exec or workflow.remote_exec:
        return False
    if (limiter.max_jobs, float(limiter.timespan)) != DEFAULT_RATE_LIMIT:
        return False
    scheduler.job_rate_limiter = None
    return True
