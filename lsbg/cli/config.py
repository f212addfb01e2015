"""``lsbg check-config``: the workflow's configuration check, outside Snakemake.

Snakemake reads a ``--configfile`` before the workflow's own code runs and,
on a YAML syntax error, says only "Config file is not valid JSON or YAML",
naming neither the file nor the line. This command reads the same files the
same way (``workflow/config.yaml``, then each given file merged over it, as
``snakemake --configfile`` does), names the file, line and column of a syntax
error, and runs :func:`lsbg.study.checks.check_config`, the check the
workflow runs before any job.
"""

from __future__ import annotations

import sys
from pathlib import Path

from lsbg.cli.options import CommandError
from lsbg.config import SCHEMA_PATH, merge_config
from lsbg.files import read_yaml_file as _read_yaml

__all__ = ["add_check_config_parser", "merge_config"]

#: The repository of a clone (an editable install): its workflow is beside lsbg/.
REPO = Path(__file__).resolve().parents[2]
#: The workflow folder: the clone's, else the current directory's (a pip-installed lsbg).
WORKFLOW_DIR = REPO / "workflow" if (REPO / "workflow").is_dir() else Path("workflow")


def add_check_config_parser(subparsers):
    parser = subparsers.add_parser(
        "check-config", help="check a workflow configuration as snakemake would, naming "
                             "the file and line of a YAML error")
    parser.add_argument("configfiles", nargs="*", metavar="CONFIGFILE",
                        help="files given to snakemake --configfile (merged in order over "
                             "workflow/config.yaml)")
    parser.add_argument("--workflow-dir", type=Path, default=WORKFLOW_DIR,
                        help="the workflow folder holding config.yaml (default: %(default)s)")
    parser.set_defaults(handler=run_check_config)


def run_check_config(args):
    """Handler of ``lsbg check-config`` [exit code]."""
    from lsbg.study.checks import check_config
    from lsbg.study.plan import design_points

    base = args.workflow_dir / "config.yaml"
    if not base.is_file():
        raise CommandError(f"--workflow-dir {args.workflow_dir}: no config.yaml there")
    given = {}  # what the study's files set over the workflow's config.yaml
    for path in args.configfiles:
        given = merge_config(given, _read_yaml(path, "configfile"))
    config = merge_config(_read_yaml(base, "workflow config"), given)
    problems = check_config(config, _read_yaml(SCHEMA_PATH, "schema"), given=given)
    if problems:
        for line in problems:
            print(f"invalid configuration: {line}", file=sys.stderr)
        return 2
    print(f"configuration is valid: {len(design_points(config))} design points")
    return 0
