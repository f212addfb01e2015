"""The study as Snakemake runs it: its plan, its configuration's checks, its costs and order.

What ``workflow/rules/common.smk`` imports: :mod:`lsbg.study.plan` (the
study's runs and files: ``STUDY``; its design points and file names are
:mod:`lsbg.study.points`, what each rule depends on :mod:`lsbg.study.params`),
:mod:`lsbg.study.checks` (the configuration checked before any job: it calls
each stage's own checks), :mod:`lsbg.study.resources` (the cost guard),
:mod:`lsbg.study.sweep_checks`, :mod:`lsbg.study.stages` (the sources each
rule runs) and :mod:`lsbg.study.job_order` (the rules' priorities).
"""
