"""Benchmark of the tooth stage: the FE compliance and the FE loaded TCA of a design point.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_tooth.py [--repeat N] [--spiral-angle DEG] [--no-pin]

Targets, on one core (the process is pinned to one CPU unless ``--no-pin``;
gmsh and scikit-fem are imported before the clock starts, about 0.5 s):

* the FE compliance of a design point, both members, the default mesh
  (:class:`lsbg.tooth.compliance.FEMeshSettings`): <= 8 s (issue 39; 10 s before);
* one FE loaded TCA over a mesh cycle, 200 positions: <= 3 s;
* the FE loaded TCA over a load range (:func:`lsbg.tooth.load_range.fe_load_range`),
  11 torques (10 % to 150 % of the rated torque and the paper's), 200
  positions: <= 1 s per torque (issue 39), beside the single-torque run's
  time, which a load range of single runs costs per torque.

Each figure is the median of ``--repeat`` runs (the machine may be shared),
with the fastest and slowest beside it, and the compliance's degrees of
freedom beside :func:`lsbg.tooth.resources.fe_resource_estimate`'s.
"""

import argparse
import os
import resource
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_dynamics import figure  # noqa: E402

from lsbg.contact import ContactParameters, MeshContact  # noqa: E402
from lsbg.gear.design import GearPairDesign  # noqa: E402
from lsbg.gear.geometry import GearPair  # noqa: E402
from lsbg.tooth.compliance import FEMeshSettings, tooth_compliance  # noqa: E402
from lsbg.tooth.load_range import fe_load_range  # noqa: E402
from lsbg.tooth.ltca import fe_loaded_tca  # noqa: E402
from lsbg.tooth.resources import fe_resource_estimate  # noqa: E402

COMPLIANCE_TARGET_S = 8.0
LTCA_TARGET_S = 3.0
LOAD_RANGE_TARGET_S = 1.0
#: The paper's gear torque [N m].
LOAD = 1964.99
#: About the pair's rated pitting torque on the gear (ISO 10300) [N m].
RATED = 480.0
#: The load range: ten torques from 10 % to 150 % of the rated one, and the paper's [N m].
TORQUES = [RATED * (0.1 + 0.14 * i) for i in range(10)] + [LOAD]


def timed(repeat, function):
    """Median, least and largest wall time of ``repeat`` calls [s], and the last result."""
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), max(times), result


def main(argv=None):
    """Run the benchmark; return its figures (see bench_dynamics.figure)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of each figure (median shown)")
    parser.add_argument("--spiral-angle", type=float, default=35.0, help="[deg]")
    parser.add_argument("--no-pin", action="store_true", help="do not pin to one CPU")
    args = parser.parse_args(argv)
    if not args.no_pin and hasattr(os, "sched_setaffinity"):
        cpu = min(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpu})
        print(f"pinned to CPU {cpu} of {os.cpu_count()}")
    start = time.perf_counter()
    import gmsh  # noqa: F401
    import skfem  # noqa: F401
    print(f"imports (gmsh, scikit-fem): {time.perf_counter() - start:.2f} s")
    settings = FEMeshSettings()
    print(f"default mesh: tooth_size {settings.tooth_size} m_mn, body_size {settings.body_size}, "
          f"fillet_radius {settings.fillet_radius} m_mn, grid {settings.face_points} x "
          f"{settings.profile_points}")
    rows = []
    for trace in ("logarithmic", "circular"):
        pair = GearPair(GearPairDesign.from_config({"trace": trace,
                                                    "spiral_angle_deg": args.spiral_angle}))
        estimate = fe_resource_estimate(pair, settings)
        median, least, most, compliance = timed(args.repeat, lambda: tooth_compliance(pair))
        dofs = compliance.attrs["fe_dofs_pinion"] + compliance.attrs["fe_dofs_gear"]
        print(f"{trace:12s} FE compliance: {median:.2f} s (target <= {COMPLIANCE_TARGET_S:g} s; "
              f"{least:.2f}-{most:.2f}); {dofs} DOFs (pinion "
              f"{compliance.attrs['fe_dofs_pinion']}, gear {compliance.attrs['fe_dofs_gear']}); "
              f"estimated {estimate.dofs} DOFs, {estimate.seconds:.1f} s, "
              f"{estimate.memory / 1e9:.2f} GB")
        rows.append(figure(f"FE compliance of a design point (both members), {trace}", median,
                           "s", COMPLIANCE_TARGET_S))
        contact = MeshContact(pair, ContactParameters(model="line"))
        median, least, most, out = timed(
            args.repeat, lambda: fe_loaded_tca(contact, compliance, LOAD, phases=200))
        print(f"{trace:12s} FE loaded TCA, 200 positions: {median:.2f} s (target <= "
              f"{LTCA_TARGET_S:g} s; {least:.2f}-{most:.2f}); mesh stiffness "
              f"{float(out['mesh_stiffness'].mean()):.1f} N/um, root stress "
              f"{out.attrs['max_root_stress_pinion_MPa']:.0f} / "
              f"{out.attrs['max_root_stress_gear_MPa']:.0f} MPa (pinion / gear)")
        rows.append(figure(f"FE loaded TCA, 200 positions, {trace}", median, "s", LTCA_TARGET_S))
        single = median
        median, least, most, out = timed(
            args.repeat, lambda: fe_load_range(contact, compliance, TORQUES, phases=200))
        count = len(TORQUES)
        print(f"{trace:12s} FE load range, {count} torques, 200 positions: "
              f"{median / count:.3f} s per torque (target <= {LOAD_RANGE_TARGET_S:g} s; "
              f"{least / count:.3f}-{most / count:.3f}; {median:.2f} s in all) against "
              f"{single:.3f} s per single-torque fe_loaded_tca ({count} of them: "
              f"{count * single:.1f} s), {single * count / median:.1f} times faster; root "
              f"stress {float(out['cycle_max_root_stress_pinion'][0]):.0f}-"
              f"{float(out['cycle_max_root_stress_pinion'][-1]):.0f} MPa (pinion)")
        rows.append(figure(f"FE load range per torque ({count} x 200 positions), {trace}",
                           median / count, "s", LOAD_RANGE_TARGET_S))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(f"peak memory of the process: {peak / 1e9:.2f} GB")
    return rows


if __name__ == "__main__":
    figures = main()
    sys.exit(1 if any(row["verdict"] == "OVER TARGET" for row in figures) else 0)
