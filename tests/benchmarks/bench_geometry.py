"""Benchmark of the geometry stage: one design point per trace, time per stage.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_geometry.py [--repeat N] [--spiral-angle DEG]

Targets: at most 20 s per design point (DESIGN.md workflow budget); reading a
geometry directory back (``lsbg.solid.directory.read_record``, which hashes every file of
its manifest on each read) at most 50 ms.
"""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import STAGES, write_geometry
from lsbg.solid.directory import read_record

TARGET_S = 20.0
READ_TARGET_S = 0.05


def read_seconds(directory, repeat=5):
    """Median time of ``read_record`` on a written directory, page cache warm [s]."""
    read_record(directory)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        read_record(directory)
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2]


def bench(trace, spiral_angle_deg, out_root):
    """Write one design point; return (timings [s], design.json record, its directory)."""
    design = GearPairDesign.from_config({"trace": trace, "spiral_angle_deg": spiral_angle_deg})
    directory = Path(out_root) / trace
    files = write_geometry(design, directory)
    with open(files["design"], encoding="utf-8") as handle:
        record = json.load(handle)
    return files.timings, record, directory


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="runs per trace (best is shown)")
    parser.add_argument("--spiral-angle", type=float, default=35.0, help="[deg]")
    args = parser.parse_args(argv)
    worst = worst_read = 0.0
    header = f"{'trace':<12}" + "".join(f"{s:>17}" for s in STAGES) + f"{'total':>10}"
    print(header)
    with tempfile.TemporaryDirectory(prefix="bench_geometry_") as tmp:
        for trace in ("logarithmic", "circular"):
            runs = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                timings, record, directory = bench(trace, args.spiral_angle, tmp)
                timings["wall"] = time.perf_counter() - start
                runs.append(timings)
            best = min(runs, key=lambda t: t["total"])
            worst = max(worst, best["total"])
            worst_read = max(worst_read, read_seconds(directory))
            print(f"{trace:<12}" + "".join(f"{best[s]:>16.2f}s" for s in STAGES)
                  + f"{best['total']:>9.2f}s")
            print(f"{'':<12}pinion {record['mesh_triangles_pinion']} triangles, "
                  f"{record['mass_pinion_kg']:.5f} kg (quadrature "
                  f"{record['mass_quadrature_pinion_kg']:.5f}); gear "
                  f"{record['mesh_triangles_gear']} triangles, {record['mass_gear_kg']:.4f} kg "
                  f"(quadrature {record['mass_quadrature_gear_kg']:.4f})")
    verdict = "OK" if worst <= TARGET_S else "TOO SLOW"
    print(f"slowest design point {worst:.2f} s (target <= {TARGET_S:.0f} s): {verdict}")
    read_verdict = "OK" if worst_read <= READ_TARGET_S else "TOO SLOW"
    print(f"reading a geometry directory back (read_record, every file hashed) "
          f"{1e3 * worst_read:.1f} ms (target <= {1e3 * READ_TARGET_S:.0f} ms): {read_verdict}")
    return 0 if worst <= TARGET_S and worst_read <= READ_TARGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
