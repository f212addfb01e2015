"""Benchmark of the contact state: one surface TCA and one V-H map per design point.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_tca.py [--repeat N] [--spiral-angle DEG]

Targets (issue 23), on one core with numba's cache on disk (a first call per
process loads the compiled kernels and is timed apart):

* one unloaded TCA from the surfaces, 200 positions over a mesh cycle, with
  its backlash search on the coast flanks: <= 2 s;
* one 9 x 9 V-H map (unloaded TCA and loaded TCA per cell, the study's
  settings): <= 60 s;
* the uniform bed's loaded TCA over a load range (issue 39), 11 torques (10 %
  to 150 % of the rated torque and the paper's), 200 positions over a mesh
  cycle on the crowned flanks: <= 50 ms per torque, as the optimiser's
  :func:`lsbg.optimise.loaded.loaded_points` runs it (the equilibria of
  :func:`lsbg.tca.loaded.loaded_tca`, bit for bit, and every contact point's
  load); the full :func:`~lsbg.tca.loaded.loaded_tca` per torque (its mesh
  stiffness, load sharing and pattern besides) is printed beside it.
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_dynamics import figure  # noqa: E402
from bench_tooth import TORQUES  # noqa: E402  (the FE load range's torques)

from lsbg.contact import ContactParameters, MeshContact  # noqa: E402
from lsbg.gear.design import GearPairDesign  # noqa: E402
from lsbg.gear.geometry import GearPair  # noqa: E402
from lsbg.optimise.loaded import loaded_points  # noqa: E402
from lsbg.tca.analysis import tooth_contact_analysis  # noqa: E402
from lsbg.tca.loaded import loaded_tca  # noqa: E402
from lsbg.tca.misalignment import Misalignment  # noqa: E402
from lsbg.tca.modification import FlankModification  # noqa: E402
from lsbg.tca.separation import SeparationField  # noqa: E402
from lsbg.tca.vh_map import misalignment_map  # noqa: E402

TCA_TARGET_S = 2.0
MAP_TARGET_S = 60.0
LOAD_RANGE_TARGET_S = 0.05
#: The study's practice default (workflow/config.yaml) and the paper's load.
MODIFICATION = FlankModification(25e-6, 5e-6)
LOAD = 1964.99


def best_of(repeat, function):
    """Least wall time of ``repeat`` calls [s] and the last result."""
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return min(times), result


def main(argv=None):
    """Run the benchmark; return its figures (see bench_dynamics.figure)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of each TCA (best shown)")
    parser.add_argument("--spiral-angle", type=float, default=35.0, help="[deg]")
    args = parser.parse_args(argv)
    rows = []
    start = time.perf_counter()
    first = GearPair(GearPairDesign.from_config({"trace": "logarithmic",
                                                 "spiral_angle_deg": args.spiral_angle}))
    tooth_contact_analysis(first, MODIFICATION, positions=8)
    print(f"first call (compiled kernels loaded or compiled): {time.perf_counter() - start:.2f} s")
    for trace in ("logarithmic", "circular"):
        pair = GearPair(GearPairDesign.from_config({"trace": trace,
                                                    "spiral_angle_deg": args.spiral_angle}))
        seconds, ds = best_of(args.repeat, lambda: tooth_contact_analysis(pair, MODIFICATION))
        print(f"{trace:12s} TCA, 200 positions: {seconds:.3f} s (target <= {TCA_TARGET_S:g} s); "
              f"TE {ds.attrs['transmission_error_peak_to_peak_urad']:.4g} urad peak to peak")
        rows.append(figure(f"TCA from the surfaces, 200 positions, {trace}", seconds, "s",
                           TCA_TARGET_S))
        seconds, vh = best_of(1, lambda: misalignment_map(pair, MODIFICATION, load_torque=LOAD))
        print(f"{trace:12s} V-H map, 9 x 9: {seconds:.1f} s (target <= {MAP_TARGET_S:g} s); "
              f"pattern moves {vh.attrs['pattern_shift_lengthwise_per_0_1_P']:.3g} mm per 0.1 mm P")
        rows.append(figure(f"V-H map 9 x 9 (unloaded + loaded TCA per cell), {trace}", seconds,
                           "s", MAP_TARGET_S))
        contact = MeshContact(pair, ContactParameters(model="line"), separation=SeparationField(
            pair, MODIFICATION, Misalignment()))
        count = len(TORQUES)
        seconds, loaded = best_of(args.repeat, lambda: loaded_points(contact, TORQUES, 200))
        single, _ = best_of(1, lambda: [loaded_tca(contact, t, phases=200) for t in TORQUES])
        te = np.ptp(loaded.transmission_error, axis=1) * 1e6
        print(f"{trace:12s} uniform-bed loaded TCA over a load range, {count} torques x 200 "
              f"positions: {seconds / count * 1e3:.1f} ms per torque (target <= "
              f"{LOAD_RANGE_TARGET_S * 1e3:g} ms); the full loaded_tca {single / count * 1e3:.0f} "
              f"ms per torque; TE {te[0]:.1f}-{te[-1]:.1f} urad peak to peak")
        rows.append(figure(f"uniform-bed loaded TCA over a load range, per torque, {trace}",
                           seconds / count, "s", LOAD_RANGE_TARGET_S))
    return rows


if __name__ == "__main__":
    figures = main()
    sys.exit(1 if any(row["verdict"] == "OVER TARGET" for row in figures) else 0)
