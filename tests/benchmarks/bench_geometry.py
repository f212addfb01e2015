"""Benchmark of the geometry stage: one design point per trace, time per stage.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_geometry.py [--repeat N] [--spiral-angle DEG]

Target: at most 20 s per design point (DESIGN.md workflow budget).
"""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

from lsbg.design import GearPairDesign
from lsbg.export import STAGES, write_geometry

TARGET_S = 20.0


def bench(trace, spiral_angle_deg, out_root):
    """Write one design point; return (timings [s], design.json record)."""
    design = GearPairDesign.from_config({"trace": trace, "spiral_angle_deg": spiral_angle_deg})
    files = write_geometry(design, Path(out_root) / trace)
    with open(files["design"], encoding="utf-8") as handle:
        record = json.load(handle)
    return files.timings, record


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="runs per trace (best is shown)")
    parser.add_argument("--spiral-angle", type=float, default=35.0, help="[deg]")
    args = parser.parse_args(argv)
    worst = 0.0
    header = f"{'trace':<12}" + "".join(f"{s:>17}" for s in STAGES) + f"{'total':>10}"
    print(header)
    with tempfile.TemporaryDirectory(prefix="bench_geometry_") as tmp:
        for trace in ("logarithmic", "circular"):
            runs = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                timings, record = bench(trace, args.spiral_angle, tmp)
                timings["wall"] = time.perf_counter() - start
                runs.append(timings)
            best = min(runs, key=lambda t: t["total"])
            worst = max(worst, best["total"])
            print(f"{trace:<12}" + "".join(f"{best[s]:>16.2f}s" for s in STAGES)
                  + f"{best['total']:>9.2f}s")
            print(f"{'':<12}pinion {record['mesh_triangles_pinion']} triangles, "
                  f"{record['mass_pinion_kg']:.5f} kg (quadrature "
                  f"{record['mass_quadrature_pinion_kg']:.5f}); gear "
                  f"{record['mesh_triangles_gear']} triangles, {record['mass_gear_kg']:.4f} kg "
                  f"(quadrature {record['mass_quadrature_gear_kg']:.4f})")
    verdict = "OK" if worst <= TARGET_S else "TOO SLOW"
    print(f"slowest design point {worst:.2f} s (target <= {TARGET_S:.0f} s): {verdict}")
    return 0 if worst <= TARGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
