# lsbg: the complete study (paper reproduction, spiral-angle sweep, verification)
# as one Snakemake workflow. Run from the repository root:
#
#     snakemake -j2                                   # everything (rule all)
#     snakemake -j2 --configfile workflow/config-test.yaml   # a tiny version
#     snakemake --executor slurm --profile workflow/profiles/slurm
#
# The configuration (workflow/config.yaml, validated against
# lsbg/schemas/config.schema.yaml before any job runs) holds the design, the
# sweep, the engines, the simulation, contact, contact-state and statistics
# settings. Rules live in workflow/rules/*.smk and call the lsbg command line
# only; the plan (config checks, design points, file names) is lsbg.study.plan,
# glued in by workflow/rules/common.smk. The speed sweep
# (workflow/rules/speed.smk, e.g. --configfile workflow/config-speed.yaml) and
# extensions (workflow/extensions/*.smk) are included when `extensions:` names them.

from snakemake.utils import min_version

min_version("9.0")


configfile: os.path.join(workflow.basedir, "workflow", "config.yaml")


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/points.smk"
include: "workflow/rules/tooth.smk"
include: "workflow/rules/rating.smk"
include: "workflow/rules/contact_state.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/aggregate.smk"
include: "workflow/rules/checks.smk"
include: "workflow/rules/reports.smk"


# Optional stages and extensions: each adds rules and appends its targets to
# EXTENSION_TARGETS.
if STUDY.speed_sweep:

    include: "workflow/rules/speed.smk"


if STUDY.sweeps:

    include: "workflow/rules/sweeps.smk"


if STUDY.cutter_points:

    include: "workflow/rules/cutter.smk"


if STUDY.practice:

    include: "workflow/rules/practice.smk"


if STUDY.optimise:

    include: "workflow/rules/optimise.smk"
    include: "workflow/rules/trace_study.smk"
    include: "workflow/rules/matched.smk"


for extension in config["extensions"]:

    include: extension_file(extension)


# results/config.yaml (the settings lsbg reads) follows the configuration of
# every run that executes jobs (see lsbg.study.plan.write_study_config). A local
# run forks its jobs from the job server and runs without Snakemake's default job
# rate limit, whose timers kept Snakemake itself busy (lsbg.study.job_order).
onstart:
    check_analyses()
    report_search_estimate()
    plan.write_study_config(FILES["study_config"], config)
    start_job_server()
    plan.lift_job_rate_limit(workflow)


onsuccess:
    stop_job_server()


onerror:
    stop_job_server()


# The default target must be defined here, in the top-level Snakefile
# (a default target in an included file is ignored).
rule all:
    default_target: True
    input:
        STUDY.targets,
        EXTENSION_TARGETS,


# Now that every rule is defined: each one's priority from the rule graph
# (lsbg.study.job_order) and its software (--software-deployment-method conda).
finish_rules(workflow.rules)
