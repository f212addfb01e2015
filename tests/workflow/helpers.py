"""What the workflow's tests share: running Snakemake in a folder, reading its plan, a copy
of the repository to run a study in (the session's study: tests/workflow/conftest.py)."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[2]
SNAKEFILE = REPO / "Snakefile"
TEST_CONFIG = "workflow/config-test.yaml"


def snakemake(*args, cwd, env=None, check=None, module="snakemake"):
    """Run ``python -m snakemake ARGS`` in ``cwd``; return the completed process (text).

    ``check=True`` asserts exit code 0 and shows the output if not; ``module`` is the
    one run with ``-m`` (tests.workflow.slurm_polling for the test cluster).
    """
    proc = subprocess.run([sys.executable, "-m", module, *map(str, args)], cwd=cwd,
                          env=env, capture_output=True, text=True, timeout=600)
    proc.output = proc.stdout + proc.stderr
    if check:
        assert proc.returncode == 0, proc.output[-6000:]
    return proc


_JOB = re.compile(r"^(?:local)?rule (\w+):\n((?:    .*\n)+)", re.MULTILINE)


def planned_jobs(output):
    """The jobs of a dry run: {(rule, output files)} parsed from Snakemake's listing."""
    jobs = set()
    for rule, body in _JOB.findall(output):
        fields = dict(re.findall(r"^    (\w+): (.*)$", body, re.MULTILINE))
        jobs.add((rule, fields.get("output", "")))
    return jobs


def rules_of(jobs):
    return sorted(rule for rule, _ in jobs)


def job_inputs(output):
    """rule -> input files (of its first job) in a dry run's listing."""
    inputs = {}
    for rule, body in _JOB.findall(output):
        fields = dict(re.findall(r"^    (\w+): (.*)$", body, re.MULTILINE))
        inputs.setdefault(rule, fields.get("input", "").split(", "))
    return inputs


def write_yaml(path, data):
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def copy_repository(target):
    """Copy the repository's files (tracked and untracked, not ignored) to ``target``."""
    try:
        listing = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"],
                                 cwd=REPO, capture_output=True, check=True).stdout
        files = [f for f in listing.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        skip = {".git", "results", "logs", ".snakemake", "__pycache__", ".pytest_cache"}
        files = [str(p.relative_to(REPO)) for p in REPO.rglob("*")
                 if p.is_file() and not skip & set(p.relative_to(REPO).parts)]
    for name in files:
        source = REPO / name
        if source.is_file() and not name.startswith(("results/", "logs/", "reports/")):
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)
    return target


def repository_with_env(target):
    """A copy of the repository in ``target`` (:func:`copy_repository`) and an environment
    whose lsbg is the copy's (its folder first on ``PYTHONPATH``): (directory, environment)."""
    root = copy_repository(target)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(root), *filter(None, [os.environ.get("PYTHONPATH")])]))
    return root, env


def copy_of_study(study, target):
    """A copy of a finished study (its repository, results, reports and Snakemake's records,
    time stamps kept) in ``target`` and an environment whose lsbg is the copy's: a test that
    adds to the study runs there and leaves the session's study as it is. Its inputs are
    named relative to the study's root, so Snakemake finds nothing to do in the copy."""
    root, env = study
    shutil.copytree(root, target, symlinks=True)
    return target, dict(env, PYTHONPATH=os.pathsep.join(
        [str(target), *[p for p in env["PYTHONPATH"].split(os.pathsep) if p != str(root)]]))


def dry_run(study, *configfiles):
    root, env = study
    proc = snakemake("-n", "--configfile", TEST_CONFIG, *configfiles, cwd=root, env=env,
                     check=True)
    return planned_jobs(proc.output), proc.output


def report_text(path):
    """A rendered report's visible text, one line."""
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"<style.*?</style>|<script.*?</script>", "", text, flags=re.S)
    text = re.sub(r"data:[\w/+]+;base64,[A-Za-z0-9+/=]+", "", text)
    return " ".join(re.sub(r"<[^>]+>", " ", text).split())


#: Unit symbols a dataset of lsbg may write (UDUNITS spellings), before SI prefixes.
UNIT_SYMBOLS = {"m", "s", "N", "Pa", "rad", "Hz", "g", "W", "J"}
#: ... and those taken without a prefix.
PLAIN_UNITS = {"1", "%", "percent", "degree", "deg", "arcsec", "kg"}
_UNIT_TOKEN = re.compile(r"[A-Za-z%]+|\d+(?:\.\d+)?|[ /()*^.-]")


def unit_problem(units):
    """Why ``units`` is not a unit string as UDUNITS reads it (None if it is): every word
    a known symbol with at most one SI prefix (``um``, ``N m``, ``deg/s``; ``u`` fails),
    numbers only as factors or exponents, parentheses balanced."""
    text = str(units)
    if not text.strip() or "".join(_UNIT_TOKEN.findall(text)) != text:
        return f"{units!r}: not made of unit symbols"
    depth = 0
    for token in _UNIT_TOKEN.findall(text):
        depth += (token == "(") - (token == ")")
        if depth < 0:
            return f"{units!r}: unbalanced parentheses"
        if token[0].isalpha() or token == "%":
            if token not in PLAIN_UNITS and not (
                    token in UNIT_SYMBOLS or (token[0] in "kMGmun" and token[1:] in UNIT_SYMBOLS)):
                return f"{units!r}: {token!r} is not a unit symbol"
    return "unbalanced parentheses" if depth else None


def dataset_label_problems(folder):
    """Every variable and coordinate of every NetCDF file under ``folder`` without
    ``units`` and ``long_name``, or whose units are not a unit string
    (:func:`unit_problem`): one line each, ``file: variable: what``."""
    import xarray as xr

    problems = []
    for path in sorted(Path(folder).rglob("*.nc")):
        with xr.open_dataset(path) as ds:
            for name, variable in ds.variables.items():
                missing = [k for k in ("units", "long_name") if not variable.attrs.get(k)]
                why = (f"no {' and no '.join(missing)}" if missing
                       else unit_problem(variable.attrs["units"]))
                if why:
                    problems.append(f"{path.relative_to(folder)}: {name}: {why}")
    return problems
