"""Every performance figure of lsbg against its target, in one run on this machine.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_all.py [--no-j1] [--no-speed]

Runs bench_dynamics.py (kernels, engines per simulated second, the PyBullet
step against its floor, compile and cache-load times), bench_tca.py (the
surface TCA and the V-H map of a design point, the uniform bed's loaded TCA over
a load range), bench_tooth.py (the FE
compliance, the FE loaded TCA of a design point and its load range, seconds
per torque) and bench_study.py (the start-up costs, the full study with -j2
and -j1, the speed sweep), then prints one table: figure, value, target,
verdict. About 10 minutes on two cores.

Before and after the figures it measures the machine's baseline (baseline.py:
an interpreter loop and a compiled loop that no change to lsbg touches), so
that a figure over its target on a slow hour is not read as a regression.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import baseline  # noqa: E402
import bench_dynamics  # noqa: E402
import bench_study  # noqa: E402
import bench_tca  # noqa: E402
import bench_tooth  # noqa: E402


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    before = baseline.measure()
    print("machine baseline before:", baseline.describe(before))
    # the tooth's benchmark pins this process to one CPU: after the study (-j2)
    rows = (bench_dynamics.main([]) + bench_tca.main([]) + bench_study.main(argv)
            + bench_tooth.main([]))
    after = baseline.measure()   # on the pinned core, as the tooth's figures
    rows += [bench_dynamics.figure(f"machine baseline: {name}, {when}", value, "s")
             for when, values in (("before", before), ("after", after))
             for name, value in values.items()]
    print("\n== lsbg benchmark: every figure against its target ==")
    for row in rows:
        print(f"  {row['figure']:62s} {row['value']:9.3g} {row['unit']:3s} "
              f"{row['target_text']:>9s}  {row['verdict']}")
    over = [row["figure"] for row in rows if row["verdict"] == "OVER TARGET"]
    print(f"\n{len(rows)} figures, {len(over)} over target" + (f": {over}" if over else ""))
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
