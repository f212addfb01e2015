"""Benchmark of the whole study: ``snakemake -j2`` with the default configuration.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_study.py [--jobs 2] [--configfile FILE] [--keep DIR]

Copies the repository's files (``git ls-files``) into a temporary directory,
runs the workflow there (``PYTHONPATH`` pointing at the copy, so the jobs run
the copied lsbg), and prints the wall time of the whole study, the time of one
simulation (the runs' ``wall_time_s`` attribute: the integration alone, and
the Snakemake job, which adds start-up and writing), and the time per rule
from Snakemake's job records (``.snakemake/metadata``), so that the rule that
dominates is visible.

Target: the full study in at most 20 min on two cores.
"""

import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
TARGET_S = 20 * 60


def copy_repository(target):
    listing = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=REPO,
                             capture_output=True, check=True).stdout
    for name in filter(None, listing.decode().split("\0")):
        source = REPO / name
        if source.is_file() and not name.startswith(("results/", "logs/", "reports/")):
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)


def job_records(root):
    """(rule, output, seconds) of every job, from Snakemake's metadata."""
    records = []
    folder = root / ".snakemake" / "metadata"
    for entry in folder.iterdir():
        meta = json.loads(entry.read_text())
        if meta.get("starttime") and meta.get("endtime"):
            output = base64.urlsafe_b64decode(entry.name.encode()).decode(errors="replace")
            seconds = max(0.0, meta["endtime"] - meta["starttime"])
            records.append((meta["rule"], output, seconds))
    return records


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", "-j", type=int, default=2, help="parallel jobs (default 2)")
    parser.add_argument("--configfile", help="extra configuration (default: the study's)")
    parser.add_argument("--keep", metavar="DIR", help="run in DIR (kept) instead of a temp dir")
    args = parser.parse_args(argv)

    if args.keep:
        root = Path(args.keep).resolve()
        root.mkdir(parents=True, exist_ok=True)
        context = None
    else:
        context = tempfile.TemporaryDirectory(prefix="bench_study_")
        root = Path(context.name)
    try:
        copy_repository(root)
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            [str(root), *filter(None, [os.environ.get("PYTHONPATH")])]))
        command = [sys.executable, "-m", "snakemake", f"-j{args.jobs}"]
        if args.configfile:
            command += ["--configfile", str(Path(args.configfile).resolve())]
        print("running:", " ".join(command[2:]), "in", root, flush=True)
        start = time.perf_counter()
        proc = subprocess.run(command, cwd=root, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - start
        if proc.returncode != 0:
            print(proc.stdout[-4000:], proc.stderr[-4000:], sep="\n")
            print(f"snakemake failed (exit {proc.returncode}) after {wall:.0f} s")
            return 1

        import xarray as xr

        runs = {}
        for path in sorted((root / "results" / "runs").glob("*.nc")):
            with xr.open_dataset(path) as ds:
                runs[path.name] = float(ds.attrs["wall_time_s"])
        records = job_records(root)
        per_rule = defaultdict(list)
        for rule, _, seconds in records:
            per_rule[rule].append(seconds)
        jobs = {Path(out).name: seconds for rule, out, seconds in records if rule == "simulate"}

        print(f"\nfull study: {wall:.0f} s wall ({wall / 60:.1f} min) with -j{args.jobs}, "
              f"{len(records)} jobs")
        print("\none simulation (integration = the run's wall_time_s; job = Snakemake job):")
        for name, seconds in runs.items():
            job = jobs.get(name, float("nan"))
            print(f"  {name:<36} integration {seconds:7.1f} s   job {job:7.1f} s")
        print("\njob time per rule (sum over its jobs; with -j2 two run at once):")
        total = sum(sum(v) for v in per_rule.values())
        for rule, times in sorted(per_rule.items(), key=lambda item: -sum(item[1])):
            print(f"  {rule:<22} {len(times):3d} jobs  sum {sum(times):7.1f} s  "
                  f"max {max(times):7.1f} s  ({100 * sum(times) / total:4.1f} %)")
        verdict = "OK" if wall <= TARGET_S else "TOO SLOW"
        print(f"\nfull study {wall / 60:.1f} min (target <= {TARGET_S / 60:.0f} min): {verdict}")
        return 0 if wall <= TARGET_S else 1
    finally:
        if context is not None:
            context.cleanup()


if __name__ == "__main__":
    sys.exit(main())
