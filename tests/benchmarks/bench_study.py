"""Benchmark of the whole study: ``snakemake -j2`` and ``-j1`` from scratch, the
speed sweep, and the start-up costs every job pays.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_study.py [--no-j1] [--no-speed] [--keep DIR]

Copies the repository's files (``git ls-files``) into a temporary directory and
runs the workflow there (``PYTHONPATH`` pointing at the copy, so the jobs run
the copied lsbg):

1. the default study with ``-j2`` from scratch (target <= 120 s), with the job
   time per rule from Snakemake's job records (``.snakemake/metadata``);
2. the same with ``-j1`` from scratch; -j1 over -j2 is the parallel
   efficiency (target >= 1.8);
3. the speed sweep on top of the finished study (``--configfile
   workflow/config-speed.yaml``: its runs, the curve and the sweep report
   again; target <= 5 min);
4. start-up costs: a new interpreter importing what each stage imports, the
   ``lsbg`` command doing nothing, a short job in a process of its own and
   forked by the workflow's job server, and a notebook kernel executing an
   empty notebook, each the median of three.
"""

import argparse
import base64
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
#: issue 23: the full default study with the contact-state stages, warm cache.
STUDY_TARGET_S = 120.0
SPEED_TARGET_S = 300.0
PARALLEL_TARGET = 1.8


def copy_repository(target):
    listing = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=REPO,
                             capture_output=True, check=True).stdout
    for name in filter(None, listing.decode().split("\0")):
        source = REPO / name
        if source.is_file() and not name.startswith(("results/", "logs/", "reports/")):
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)


def job_records(root):
    """(rule, first output, start, end) of every job [s since the first start], from
    Snakemake's metadata. It keeps one record per output file, each with its own time
    stamps (they differ by milliseconds between the outputs of one job): a job is
    its rule and log file, which every rule names per job."""
    jobs = {}
    folder = root / ".snakemake" / "metadata"
    for entry in sorted(folder.iterdir()):
        meta = json.loads(entry.read_text())
        if meta.get("starttime") and meta.get("endtime"):
            output = base64.urlsafe_b64decode(entry.name.encode()).decode(errors="replace")
            key = (meta["rule"], tuple(meta.get("log") or [output]))
            rule, first, start, end = jobs.get(key, (meta["rule"], output, math.inf, -math.inf))
            jobs[key] = (rule, min(first, output), min(start, meta["starttime"]),
                         max(end, meta["endtime"]))
    origin = min((start for _, _, start, _ in jobs.values()), default=0.0)
    return sorted((rule, first, start - origin, end - origin)
                  for rule, first, start, end in jobs.values())


#: What each start-up probe imports (a new interpreter each).
STARTUP_PROBES = {
    "python alone": "pass",
    # every snakemake run pays it once: its plugins are collected at import (the
    # SLURM executor plugin asks `scontrol show config`, which waits up to 10 s
    # when scontrol is installed but no controller answers)
    "snakemake (import, executor plugins)": "import snakemake.cli",
    "lsbg command line (parser)": "import lsbg.cli; lsbg.cli.build_parser()",
    "simulation stage (lsbg.dynamics)": "import lsbg.dynamics, lsbg.dynamics.dataset",
    "design point stage (geometry, solids, ltca)": "import lsbg.solid.export, lsbg.tca.loaded",
    "aggregate stage (combine, summary)": "import lsbg.aggregate.combine, lsbg.aggregate.summary",
    "report stage (figures, tables)": "import lsbg.tables.paper, lsbg.tables.line_model, "
                                      "lsbg.figures.statistics, lsbg.figures.speed",
}


def median_seconds(command, repeat=3, **kwargs):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, **kwargs)
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2]


def served_startup():
    """A short job in a process of its own and through the workflow's job server
    (lsbg.cli.job_server): ``lsbg practice``, the practice design of the default
    configuration (0.1 s of work; it imports the rating's and the tooth's stages)."""
    from lsbg.cli import job_server

    folder = tempfile.mkdtemp(prefix="bench_served_")
    command = [shutil.which("lsbg") or "lsbg", "-v", "practice", "--out",
               os.path.join(folder, "practice.yaml")]
    one_thread = dict(os.environ, **job_server.ONE_THREAD)
    out = {"a job's start, a process of its own": median_seconds(
        command, env=dict(one_thread, **{job_server.SERVER_ENV: job_server.OFF}))}
    with tempfile.TemporaryDirectory() as tmp:
        server = job_server.start(directory=tmp, environ=one_thread)
        try:
            path = job_server.wait_ready(server)
            out["a job's start, forked by the job server"] = median_seconds(
                command, env=dict(one_thread, **{job_server.SERVER_ENV: path}))
        finally:
            job_server.stop(server)
            shutil.rmtree(folder, ignore_errors=True)
    return out


def startup_costs():
    """{probe: seconds} for the imports, the ``lsbg`` command and a notebook kernel."""
    out = {name: median_seconds([sys.executable, "-c", code])
           for name, code in STARTUP_PROBES.items()}
    out["lsbg --help"] = median_seconds([shutil.which("lsbg") or "lsbg", "--help"])
    out.update(served_startup())
    import nbformat

    with tempfile.TemporaryDirectory() as tmp:
        notebook = Path(tmp) / "empty.ipynb"
        nbformat.write(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("1")]),
                       notebook)
        out["notebook kernel (papermill, one cell)"] = median_seconds(
            [sys.executable, "-m", "papermill", "--log-level", "ERROR", "-k", "python3",
             str(notebook),
             str(Path(tmp) / "out.ipynb")])
    return out


def run_workflow(root, env, jobs, *configfiles):
    """Run snakemake in ``root``; return the wall time [s] (raise with its output on failure)."""
    command = [sys.executable, "-m", "snakemake", f"-j{jobs}"]
    for name in configfiles:
        command += ["--configfile", name]
    print("running:", " ".join(command[2:]), "in", root, flush=True)
    start = time.perf_counter()
    proc = subprocess.run(command, cwd=root, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"snakemake failed (exit {proc.returncode}) after {wall:.0f} s:\n"
                           f"{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
    return wall


def clean(root):
    for name in ("results", "logs", "reports", ".snakemake"):
        shutil.rmtree(root / name, ignore_errors=True)


def print_rules(root, label, cores=1):
    """Print the job time per rule and, for ``cores`` > 1, the timeline and the idle
    core time; return the job records."""
    records = job_records(root)
    per_rule = defaultdict(list)
    for rule, _, start, end in records:
        per_rule[rule].append(end - start)
    total = sum(sum(v) for v in per_rule.values())
    print(f"\njob time per rule, {label} ({len(records)} jobs, {total:.0f} job-s):")
    for rule, times in sorted(per_rule.items(), key=lambda item: -sum(item[1])):
        print(f"  {rule:<22} {len(times):3d} jobs  sum {sum(times):7.1f} s  "
              f"max {max(times):7.1f} s  ({100 * sum(times) / total:4.1f} %)")
    if cores > 1 and records:
        span = max(end for _, _, _, end in records)
        print(f"timeline [s from the first job's start] (first job to last: {span:.1f} s, "
              f"idle core time {cores * span - total:.1f} s):")
        for rule, first, start, end in sorted(records, key=lambda r: r[2]):
            print(f"  {start:6.1f} {end:6.1f}  {rule:<22} {first}")
    return records


def main(argv=None):
    """Run the benchmark; return its figures (rows as in bench_dynamics.figure)."""
    from bench_dynamics import figure

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-j1", action="store_true", help="skip the -j1 run")
    parser.add_argument("--no-speed", action="store_true", help="skip the speed sweep")
    parser.add_argument("--keep", metavar="DIR", help="run in DIR (kept) instead of a temp dir")
    args = parser.parse_args(argv)

    if args.keep:
        root = Path(args.keep).resolve()
        root.mkdir(parents=True, exist_ok=True)
        context = None
    else:
        context = tempfile.TemporaryDirectory(prefix="bench_study_")
        root = Path(context.name)
    figures = []
    try:
        copy_repository(root)
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            [str(root), *filter(None, [os.environ.get("PYTHONPATH")])]))
        print("\n== start-up costs, median of 3 new processes [s] ==")
        for name, seconds in startup_costs().items():
            print(f"  {name:45s} {seconds:6.2f}")
            figures.append(figure(f"start-up: {name}", seconds, "s"))
        walls, job_seconds = {}, {}
        for jobs in ((1, 2) if not args.no_j1 else (2,)):
            clean(root)
            walls[jobs] = run_workflow(root, env, jobs)
            print(f"full study -j{jobs}: {walls[jobs]:.1f} s")
            records = print_rules(root, f"-j{jobs}", cores=jobs)
            job_seconds[jobs] = sum(end - start for _, _, start, end in records)
        figures.append(figure("full study, snakemake -j2 from scratch", walls[2], "s",
                              STUDY_TARGET_S))
        if 1 in walls:
            figures.append(figure("full study, snakemake -j1 from scratch", walls[1], "s"))
            figures.append(figure("parallel efficiency, -j1 / -j2", walls[1] / walls[2], "",
                                  PARALLEL_TARGET, smaller=False))
            # What the machine takes away: the same jobs run slower two at a time (shared
            # caches, the host), and Snakemake's own start-up is not parallel. With the
            # -j2 jobs packed without a gap, -j2 could take at best W2/2 + S.
            contention = job_seconds[2] / job_seconds[1]
            serial = walls[1] - job_seconds[1]
            figures.append(figure("job seconds -j2 / -j1 (two jobs at once run slower)",
                                  contention, ""))
            figures.append(figure("efficiency with the -j2 jobs packed without a gap",
                                  walls[1] / (job_seconds[2] / 2 + serial), ""))
        import xarray as xr

        print("\nintegration time of each run (its wall_time_s attribute):")
        for path in sorted((root / "results" / "runs").glob("*.nc")):
            with xr.open_dataset(path) as ds:
                seconds = float(ds.attrs["wall_time_s"])
            print(f"  {path.name:<40} integration {seconds:7.1f} s")
        if not args.no_speed:
            before = {(rule, out) for rule, out, _, _ in job_records(root)}
            wall = run_workflow(root, env, 2, "workflow/config-speed.yaml")
            speed = [rule for rule, out, _, _ in job_records(root)
                     if (rule, out) not in before or rule in ("speed_run", "speed_curve")]
            print(f"speed sweep on top of the study, -j2: {wall:.1f} s "
                  f"({speed.count('speed_run')} runs)")
            print_rules(root, "with the speed sweep")
            figures.append(figure("speed sweep (runs, curve, sweep report), -j2", wall, "s",
                                  SPEED_TARGET_S))
    finally:
        if context is not None:
            context.cleanup()
    return figures


if __name__ == "__main__":
    rows = main()
    print()
    for row in rows:
        print(f"{row['figure']:58s} {row['value']:9.3g} {row['unit']:3s} "
              f"{row['target_text']:>9s} {row['verdict']}")
