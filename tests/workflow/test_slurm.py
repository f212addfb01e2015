"""The tiny study on a real SLURM cluster, through workflow/profiles/slurm.

Needs SLURM with accounting on this machine: ``.ci/slurm-up`` brings up a
one-node cluster (``.ci/run`` calls it before pytest). Without SLURM the tests
skip, with the reason; in CI (``CI=true``) a missing SLURM is a failure.

One module fixture runs, in a copy of the repository (as tests/workflow/test_workflow.py
does), the README's command

    snakemake --profile workflow/profiles/slurm --configfile workflow/config-test.yaml

without the practice stage and two of the three reports (:data:`NO_PRACTICE`,
:data:`WITHOUT`), twice: the first time one running job is cancelled (``scancel``) while it
computes, and Snakemake must report it and fail; the second time, the same
command must complete the DAG. Snakemake runs with its status checks at most 2 s apart
(tests/workflow/slurm_polling.py: the plugin's interval grows without a cap on a quiet
cluster); everything else is the README's command. Its outputs are compared with the session's study
(tests/workflow/conftest.py: the same config run locally with -j2, made meanwhile):
the same files but those it leaves out, and results/summary.csv byte for byte (the
summary reads neither the practice stage nor the reports).
"""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from collections import Counter
from pathlib import Path
from types import SimpleNamespace
from xml.etree import ElementTree

import pandas as pd
import pytest
import xarray as xr
import yaml

from tests.workflow.helpers import TEST_CONFIG, repository_with_env, snakemake

PROFILE = "workflow/profiles/slurm"
#: The practice design's stage left out here: its rules are the paper point's commands
#: again (tests/workflow/test_workflow.py runs them), and 14 more SLURM jobs would double
#: this module's time. Written into each copy by :func:`copy_with_env`.
NO_PRACTICE = "no-practice.yaml"
#: Two of the three reports left out too: the three are one command (``lsbg report``,
#: a notebook in a kernel of its own) with the same resources, and the verification
#: report, which stays, is the job this module cancels. The paper and sweep reports
#: were the run's two longest jobs (23-34 s and 14-19 s of a one-node cluster's CPU).
WITHOUT = ("report_paper", "report_sweep")
COMMAND = ("--profile", PROFILE, "--configfile", TEST_CONFIG, NO_PRACTICE,
           "--omit-from", *WITHOUT)
#: Snakemake's command line with the status checks at most 2 s apart (the plugin's own
#: interval grows by 10 s per check that sees no job end: tests/workflow/slurm_polling.py).
SNAKEMAKE = "tests.workflow.slurm_polling"
#: The rule of the job that the fault test cancels while it computes: a job of
#: seconds even in the tiny study (its notebook's kernel a process of its own, which
#: the cancellation must end too), on which no other job waits, so that the rerun is
#: that one job. (The sensitivity job, cancelled before, made the rerun redo the
#: summary, the rating and two reports: 57 s of the module's time.)
CANCEL_RULE = "report_verification"
#: The session study's outputs that this run does not make: the practice stage's and two
#: reports (left out here) and what other tests add to that study (extensions, sweeps).
NOT_RUN_HERE = ("results/practice", "results/best", "results/optimise", "results/load_curves",
                "results/extensions", "results/sweeps", "reports/paper.html",
                "reports/sweep.html")
#: The rules of seconds that the workflow declares local (``localrule: True``): the
#: submitting Snakemake runs their jobs itself, not as SLURM jobs of two Snakemake starts
#: each (docs/scaling.md).
LOCAL_RULES = {"checks", "combine", "fe_ltca", "fe_sensitivity", "paper_ltca", "rating",
               "rating_sweep", "summary",
               # the cutter sweep's points without an FE compliance of their own (the
               # LSBG's FE is the tooth stage's; the test config's one nominal cutter)
               "cutter_lsbg", "cutter_face_milled_r95_25"}
#: Suffixes of lsbg's temporaries (lsbg.files.TEMPORARY_SUFFIXES).
PARTIAL = (".part", ".tmp", ".old")

pytestmark = pytest.mark.slow


def run_text(*args, timeout=30):
    proc = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    return proc.returncode, proc.stdout + proc.stderr


def slurm_problem():
    """None if SLURM is usable here (a node up in sinfo, sacct answering), else why not."""
    for tool in ("sinfo", "sbatch", "squeue", "scancel", "sacct"):
        if shutil.which(tool) is None:
            return f"{tool} is not on the PATH (run .ci/slurm-up as root)"
    try:
        code, out = run_text("sinfo", "-h", "-o", "%T")
        if code:
            return f"sinfo failed: {out.strip()}"
        states = out.split()
        if not set(states) & {"idle", "mixed", "allocated", "completing"}:
            return f"no usable node in sinfo (states: {states or 'none'})"
        code, out = run_text("sacct", "-n", "-X", "-S", "now-1minutes")
        if code:
            return f"sacct fails (slurmdbd not running?): {out.strip()}"
    except subprocess.TimeoutExpired as error:
        return f"{error.cmd[0]} does not answer"
    return None


@pytest.fixture(scope="module")
def cluster():
    problem = slurm_problem()
    if problem:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true but SLURM is not usable: {problem}")
        pytest.skip(f"no SLURM cluster here: {problem}")


def jobs_of_dag(output):
    """rule -> number of jobs, from the 'Job stats' table that Snakemake prints first."""
    table = output.split("Job stats:", 1)[1].split("\ntotal", 1)[0]
    counts = {rule: int(n) for rule, n in re.findall(r"^(\w+)\s+(\d+)$", table, re.MULTILINE)}
    counts.pop("all", None)              # a local rule: it only collects the targets
    return counts


def local_jobs(output):
    """rule -> number of jobs that the submitting Snakemake ran itself ("localrule" blocks)."""
    return Counter(re.findall(r"^localrule (\w+):$", output, re.MULTILINE))


def submitted_jobs(output):
    """The SLURM job ids that the slurm executor reported for its submissions."""
    return re.findall(r"has been submitted with SLURM jobid (\d+)", output)


def run_id(output):
    return re.search(r"SLURM run ID: (\S+)", output).group(1)


def lsbg_runs_in(job):
    """Whether an ``lsbg`` process of SLURM job ``job`` runs on this (the only) node."""
    for process in Path("/proc").iterdir():
        if not process.name.isdigit():
            continue
        try:
            command = (process / "cmdline").read_bytes().split(b"\0")
            if any(part.endswith(b"/lsbg") or part == b"lsbg" for part in command[:2]):
                if f"SLURM_JOB_ID={job}".encode() in (process / "environ").read_bytes().split(b"\0"):
                    return True
        except OSError:                         # the process ended meanwhile
            continue
    return False


def cancel_one_running_job(lines, proc):
    """Wait until ``lsbg`` computes in a job of CANCEL_RULE, then scancel that job.

    ``lines``: Snakemake's output so far (filled by a reader thread). Returns
    the SLURM job id.
    """
    uuid = None
    while proc.poll() is None:
        if uuid is None:
            found = re.search(r"SLURM run ID: (\S+)", "".join(lines))
            uuid = found and found.group(1)
        if uuid:
            code, out = run_text("squeue", "-h", "--name", uuid, "-t", "RUNNING", "-o", "%i|%k")
            for line in out.split():
                job, _, comment = line.partition("|")
                # sbatch's comment: the rule, and its wildcards if it has any
                if re.fullmatch(rf"rule_{CANCEL_RULE}(_wildcards_.*)?", comment) \
                        and lsbg_runs_in(job):
                    time.sleep(1)
                    subprocess.run(["scancel", job], check=True)
                    return job
        time.sleep(0.3)
    raise AssertionError(f"the run ended before a {CANCEL_RULE} job could be cancelled:\n"
                         + "".join(lines)[-4000:])


class Run:
    """``python -m SNAKEMAKE ARGS`` started in ``cwd``; its output collected as it comes."""

    def __init__(self, *args, cwd, env):
        self.start = time.monotonic()
        self.proc = subprocess.Popen([sys.executable, "-m", SNAKEMAKE, *args], cwd=cwd,
                                     env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True)
        self.lines = []
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.append(line)

    def finish(self, timeout):
        """Wait for the end; returncode, output and seconds.

        After ``timeout`` s (or an error) Snakemake is interrupted (SIGINT, on
        which it cancels its SLURM jobs; on SIGTERM it would wait for them), and
        killed if it does not end within 120 s.
        """
        try:
            self.proc.wait(timeout=timeout)
        finally:
            if self.proc.poll() is None:
                self.proc.send_signal(signal.SIGINT)
                try:
                    self.proc.wait(timeout=120)
                except subprocess.TimeoutExpired:
                    self.proc.kill()
                    self.proc.wait()
        self.reader.join(timeout=30)
        return SimpleNamespace(returncode=self.proc.returncode, output="".join(self.lines),
                               seconds=time.monotonic() - self.start)


def copy_with_env(tmp_path_factory, name):
    """A copy of the repository and an environment whose lsbg is the copy's."""
    root, env = repository_with_env(tmp_path_factory.mktemp(name))
    (root / NO_PRACTICE).write_text("practice:\n  enabled: false\n", encoding="utf-8")
    return root, env


@pytest.fixture(scope="module")
def slurm_study(cluster, request, tmp_path_factory):
    """The test config through the SLURM profile, with one job cancelled, then rerun; the
    session's study (the same config run locally with -j2) for the comparison, made
    meanwhile when this module runs first (tests/conftest.py puts it first)."""
    root, env = copy_with_env(tmp_path_factory, "slurm")
    done = {}

    def through_slurm():
        try:
            # 1. The run with a fault.
            run = Run(*COMMAND, cwd=root, env=env)
            try:
                done["cancelled"] = cancel_one_running_job(run.lines, run.proc)
            finally:
                done["fault"] = run.finish(timeout=900)
            # 2. The same command again.
            start = time.monotonic()
            done["rerun"] = snakemake(*COMMAND, cwd=root, env=env, module=SNAKEMAKE)
            done["rerun"].seconds = time.monotonic() - start
        except BaseException as error:  # raised again below, in the test's thread
            done["error"] = error

    thread = threading.Thread(target=through_slurm)
    thread.start()
    try:
        local_root = request.getfixturevalue("study")[0]
    finally:
        thread.join()
    if "error" in done:
        raise done["error"]
    print(f"\nSLURM: {done['fault'].seconds:.0f} s with the cancelled job, "
          f"{done['rerun'].seconds:.0f} s for the rerun")
    return SimpleNamespace(root=root, env=env, fault=done["fault"], rerun=done["rerun"],
                           local_root=local_root, cancelled=done["cancelled"])


def sacct_jobs(job_ids):
    """SLURM job id -> (job name, state, comment) according to sacct (slurmdbd)."""
    code, out = run_text("sacct", "-n", "-X", "-P", "-j", ",".join(job_ids),
                         "-o", "JobID,JobName%80,State,Comment%200", timeout=60)
    assert code == 0, out
    jobs = {}
    for line in out.splitlines():
        job, name, state, comment = line.split("|", 3)
        jobs[job] = (name, state.split()[0], comment)     # "CANCELLED by 0" -> CANCELLED
    return jobs


def test_a_cancelled_job_is_reported_and_the_same_command_completes_the_dag(slurm_study):
    fault, rerun = slurm_study.fault, slurm_study.rerun
    job = slurm_study.cancelled
    assert fault.returncode != 0, fault.output[-4000:]
    assert f"Error in rule {CANCEL_RULE}" in fault.output, fault.output[-4000:]
    assert re.search(rf"SLURM-job '{job}' failed, SLURM status is: 'CANCELLED'",
                     fault.output), fault.output[-4000:]
    assert rerun.returncode == 0, rerun.output[-6000:]
    # the rerun redid the cancelled job (among the jobs it submitted)
    assert re.search(rf"^\s*rule {CANCEL_RULE}:", rerun.output, re.MULTILINE)
    dry = snakemake("-n", *COMMAND, cwd=slurm_study.root, env=slurm_study.env, check=True)
    assert "Nothing to be done" in dry.output, dry.output[-3000:]


def test_every_job_of_the_dag_was_submitted_with_sbatch_and_completed(slurm_study):
    """... but those of the local rules, which the submitting Snakemake ran, once each."""
    fault, rerun = slurm_study.fault, slurm_study.rerun
    dag = jobs_of_dag(fault.output)
    local = local_jobs(fault.output) + local_jobs(rerun.output)
    assert set(local) == LOCAL_RULES and local == {r: dag[r] for r in LOCAL_RULES}, (local, dag)
    dag = {rule: n for rule, n in dag.items() if rule not in LOCAL_RULES}
    assert sum(dag.values()) >= 13, dag
    first, second = submitted_jobs(fault.output), submitted_jobs(rerun.output)
    jobs = sacct_jobs(first + second)
    assert set(jobs) == set(first + second), (jobs, first, second)
    for job in first:
        assert jobs[job][0] == run_id(fault.output), jobs[job]
    for job in second:
        assert jobs[job][0] == run_id(rerun.output), jobs[job]
    states = Counter(state for _, state, _ in jobs.values())
    assert states == {"COMPLETED": sum(dag.values()), "CANCELLED": 1}, (states, jobs)
    assert jobs[slurm_study.cancelled][1] == "CANCELLED"
    # One COMPLETED job per job of the DAG: rule and wildcards in sbatch's --comment.
    completed = [comment for _, state, comment in jobs.values() if state == "COMPLETED"]
    assert len(set(completed)) == len(completed), completed
    rules = Counter(re.match(r"rule_(.+?)(?:_wildcards_.*)?$", c).group(1) for c in completed)
    assert rules == dag, (rules, dag)


def test_jobs_run_the_lsbg_of_the_submitting_environment(slurm_study):
    """The jobs' Snakemake imported the copy's lsbg (PYTHONPATH exported by sbatch)."""
    logs = sorted((slurm_study.root / ".snakemake" / "slurm_logs").rglob("*.log"))
    ids = set(submitted_jobs(slurm_study.fault.output) + submitted_jobs(slurm_study.rerun.output))
    assert {log.stem for log in logs} == ids
    for log in logs:
        text = log.read_text(errors="replace")
        assert "lsbg is imported from" not in text, (log, text[-2000:])
        assert f"Working directory: {slurm_study.root}" in text, (log, text[:2000])


def check_readable(path):
    """Open ``path`` with the reader of its kind (fails on a truncated or corrupt file)."""
    suffix = path.suffix
    if suffix == ".nc":
        with xr.open_dataset(path) as ds:
            ds.load()                       # Fletcher-32 checksums verified on read
    elif suffix == ".csv":
        assert len(pd.read_csv(path)) > 0
    elif suffix in (".json", ".ipynb"):
        json.loads(path.read_text())
    elif suffix in (".yaml", ".yml"):
        yaml.safe_load(path.read_text())
    elif suffix in (".urdf", ".xml"):
        ElementTree.parse(path)
    elif suffix == ".html":
        assert path.read_text().rstrip().endswith("</html>")
    elif suffix == ".png":
        from PIL import Image
        with Image.open(path) as image:
            image.verify()
    elif suffix == ".stl":
        assert path.stat().st_size > 84         # header and triangle count at least
    else:
        assert path.stat().st_size > 0 or path.name == ".snakemake_timestamp", path


def outputs(root):
    return sorted(p.relative_to(root) for folder in ("results", "reports")
                  for p in (root / folder).rglob("*") if p.is_file())


def test_after_the_rerun_every_output_is_readable_and_no_partial_file_is_left(slurm_study):
    root = slurm_study.root
    files = outputs(root)
    partial = [f for f in files if f.name.endswith(PARTIAL)]
    leftovers = [p for p in root.rglob("*") if p.name.endswith(PARTIAL)
                 and ".snakemake" not in p.parts]
    assert not partial and not leftovers, (partial, leftovers)
    assert files == [f for f in outputs(slurm_study.local_root)
                     if not f.as_posix().startswith(NOT_RUN_HERE)]
    for name in files:
        check_readable(root / name)


def test_summary_is_byte_identical_to_a_local_run(slurm_study):
    name = "results/summary.csv"
    assert (slurm_study.root / name).read_bytes() == (slurm_study.local_root / name).read_bytes()
