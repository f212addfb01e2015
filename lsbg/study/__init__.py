"""The study as Snakemake runs it: its plan, its configuration's checks, its costs and order.

What ``workflow/rules/common.smk`` imports: :mod:`lsbg.study.plan` (the design
points, runs and file names: ``STUDY``), :mod:`lsbg.study.checks` (the
configuration checked before any job), :mod:`lsbg.study.resources` (the cost
guard), :mod:`lsbg.study.sweep_checks`, :mod:`lsbg.study.stages` (the sources
each rule runs) and :mod:`lsbg.study.job_order` (the rules' priorities).
"""
