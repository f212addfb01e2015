"""Benchmark of the meshing simulation: convergence table, speed, per-step cost.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_dynamics.py [--duration S] [--traces logarithmic circular]
        [--out results/benchmarks]

For each trace at the paper's design point it runs PyBullet at dt = 4e-6,
2e-6, 1e-6 s and scipy at rtol = 1e-6, 1e-8, 1e-10 (the paper's settings
otherwise: 1 s, 500 samples), prints the standard deviations of gear speed and
tangential force after 0.2 s, the wall time per simulated second of each
engine at its default setting against its target (PyBullet <= 30 s, scipy
<= 10 s), and the cost of each part of one PyBullet step.
"""

import argparse
import tempfile
from pathlib import Path

import pandas as pd

from lsbg.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model
from lsbg.export import write_geometry
from lsbg.verification import convergence_study, pybullet_step_costs

TARGETS = {"pybullet": 30.0, "scipy": 10.0}  # wall seconds per simulated second


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated time [s]")
    parser.add_argument("--traces", nargs="+", default=["logarithmic", "circular"])
    parser.add_argument("--out", type=Path, help="folder for convergence.csv (optional)")
    args = parser.parse_args(argv)
    settings = SimulationSettings(duration=args.duration, samples=round(500 * args.duration),
                                  ramp_time=min(0.2, args.duration / 5))
    tables = []
    with tempfile.TemporaryDirectory() as tmp:
        for trace in args.traces:
            geometry = Path(tmp) / trace
            write_geometry(GearPairDesign(trace=trace), geometry)
            model = load_model(geometry)
            table = convergence_study(model, settings, steady_start=settings.ramp_time)
            tables.append(table)
            print(f"\n== {trace}: standard deviations after {settings.ramp_time} s ==")
            cols = ["engine", "parameter", "value", "gear_speed_std_deg_s", "tangential_force_std_N",
                    "gear_speed_mean_deg_s", "wall_time_s"]
            print(table[cols].to_string(index=False, float_format=lambda v: f"{v:.6g}"))
            reference = table[(table.engine == "scipy")].iloc[-1]
            for _, row in table.iterrows():
                dv = 100 * (row.gear_speed_std_deg_s / reference.gear_speed_std_deg_s - 1)
                df = 100 * (row.tangential_force_std_N / reference.tangential_force_std_N - 1)
                print(f"  {row.engine:8s} {row.parameter}={row.value:.0e}: speed std {dv:+6.2f} %, "
                      f"force std {df:+6.2f} % vs scipy rtol {reference.value:.0e}")
            for _, row in table[table.is_default].iterrows():
                per_second = row.wall_time_s / settings.duration
                verdict = "ok" if per_second <= TARGETS[row.engine] else "OVER TARGET"
                print(f"  {row.engine} default: {per_second:.1f} s wall per simulated second "
                      f"(target <= {TARGETS[row.engine]:.0f} s) {verdict}")
            costs = pybullet_step_costs(model, settings)
            print("  PyBullet step cost [us]: " + ", ".join(f"{k} {v:.2f}" for k, v in costs.items()))
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        pd.concat(tables).to_csv(args.out / "convergence.csv", index=False)


if __name__ == "__main__":
    main()
