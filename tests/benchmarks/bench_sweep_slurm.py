"""Benchmark: a parameter sweep of 200+ runs locally (-j2) and through the SLURM profile.

Run as a script on a machine with SLURM up (``.ci/slurm-up``)::

    python tests/benchmarks/bench_sweep_slurm.py [--values 100] [--batch 25]

In two copies of the repository (``git ls-files``, as bench_study.py), with the
test configuration (50 ms simulated per run; ``--configfile workflow/config.yaml``
for the paper's 1 s) and one sweep of
``contact.dynamic_friction`` over ``--values`` values at the paper's point, both
traces (2 x values runs, ``--batch`` points per job):

1. the design points' geometry first, untimed (both copies);
2. ``snakemake -j2`` of the sweep's dataset: the local wall time;
3. ``snakemake --profile workflow/profiles/slurm`` of the same: the SLURM wall time;
4. the two datasets compared (they must be equal: the same runs).

Prints each figure beside its target (SLURM <= 1.3 x local) and the per-batch
cost from Snakemake's job records, from which docs/scaling.md extrapolates to N
nodes.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_study import copy_repository, job_records  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
TARGET_RATIO = 1.3


def snakemake(root, *args):
    env = dict(os.environ, PYTHONPATH=str(root))
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=root, env=env,
                          capture_output=True, text=True, timeout=3600)
    if proc.returncode:
        raise SystemExit(f"snakemake {' '.join(args)} failed:\n{proc.stdout}{proc.stderr}")
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--values", type=int, default=100, help="swept values (runs: 2x)")
    parser.add_argument("--batch", type=int, default=25, help="points per job")
    parser.add_argument("--configfile", default="workflow/config-test.yaml",
                        help="the study's configuration (the test config: 50 ms per run; "
                             "workflow/config.yaml: the paper's 1 s)")
    args = parser.parse_args()
    import xarray as xr
    import yaml

    values = [round(0.2 * k / (args.values - 1), 6) for k in range(args.values)]
    sweep = {"sweeps": {"friction": {"contact.dynamic_friction": values,
                                     "batch_size": args.batch}}}
    times = {}
    with tempfile.TemporaryDirectory(prefix="bench_sweep_") as tmp:
        roots = {}
        for mode in ("local", "slurm"):
            root = Path(tmp) / mode
            root.mkdir()
            copy_repository(root)
            (root / "sweep.yaml").write_text(yaml.safe_dump(sweep))
            config = ("--configfile", args.configfile, "sweep.yaml")
            snakemake(root, "-j2", "results/geometry/logarithmic_beta35",
                      "results/geometry/circular_beta35", *config)
            roots[mode] = (root, config)
        root, config = roots["local"]
        times["local"] = snakemake(root, "-j2", "results/sweeps/friction.nc", *config)
        root, config = roots["slurm"]
        times["slurm"] = snakemake(root, "--profile", "workflow/profiles/slurm",
                                   "results/sweeps/friction.nc", *config)
        with xr.open_dataset(roots["local"][0] / "results/sweeps/friction.nc") as a, \
                xr.open_dataset(roots["slurm"][0] / "results/sweeps/friction.nc") as b:
            xr.testing.assert_equal(a, b)
        records = [r for r in job_records(roots["local"][0]) if "_batch" in r[0]]
        batch_seconds = sorted(end - start for _, _, start, end in records)
    runs = 2 * args.values
    jobs = len(batch_seconds)
    ratio = times["slurm"] / times["local"]
    median = batch_seconds[len(batch_seconds) // 2] if batch_seconds else float("nan")
    print(f"sweep of {runs} runs in {jobs} batch jobs of {args.batch} points "
          f"(+1 combine): datasets equal")
    print(f"  local  snakemake -j2            {times['local']:8.1f} s")
    print(f"  SLURM  --profile slurm          {times['slurm']:8.1f} s")
    print(f"  SLURM / local                   {ratio:8.2f}     target <= {TARGET_RATIO}"
          + ("" if ratio <= TARGET_RATIO else "  OVER TARGET"))
    print(f"  batch job (local), median       {median:8.1f} s  ({median / args.batch:.2f} s a run)")


if __name__ == "__main__":
    main()
