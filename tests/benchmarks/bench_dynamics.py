"""Benchmark of the meshing simulation: kernels, engines, PyBullet step, compile time.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/bench_dynamics.py [--duration S] [--convergence]

It prints every figure beside its target, measured in this one run on this
machine:

* the contact kernel's cost per evaluation, point and line model, inside a
  compiled loop and called from Python;
* the wall time per simulated second of each engine and contact model at the
  paper's design point (LSBG, 35 deg), and the line model's over the point
  model's (target <= 1.5);
* the PyBullet step against its floor: the loop of the three PyBullet calls
  a step needs (joint-state read, torque write, stepSimulation), measured in
  the same process (target <= 1.2);
* the kernels' first-call compile time (a fresh numba cache) and their load
  time from the on-disk cache, each in a new interpreter;
* with ``--convergence``, the convergence table of both models.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from numba import njit

from lsbg.contact import ContactParameters, kernels
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model
from lsbg.solid.export import write_geometry
from lsbg.experiments.verification import convergence_study, pybullet_step_costs

#: Targets [wall seconds per simulated second] (None: reported only).
TARGETS = {("compiled", "point"): 1.0, ("compiled", "line"): 2.0,
           ("pybullet", "point"): 30.0, ("pybullet", "line"): None,
           ("scipy", "point"): 10.0, ("scipy", "line"): 10.0}
LINE_OVER_POINT = 1.5
ENGINE_OVER_FLOOR = 1.2


@njit
def _kernel_loop(n, phi2, ratio, w1, params, sides, table):
    total = 0.0
    for k in range(n):
        phi1 = 1e-4 * k
        result = kernels.mesh_forces(phi1, phi2 + phi1 * ratio, w1, w1 * ratio, params, sides,
                                     table)
        total += result[0]
    return total


def kernel_costs(model, n=200000):
    """µs per evaluation of the kernel over a sweep of mesh positions under load."""
    phi2 = model.initial_gear_angle(SimulationSettings())
    w1 = SimulationSettings().pinion_speed
    arrays = model.contact.arrays
    _kernel_loop(10, phi2, model.ratio, w1, *arrays)
    start = time.perf_counter()
    _kernel_loop(n, phi2, model.ratio, w1, *arrays)
    compiled = (time.perf_counter() - start) / n * 1e6
    forces = kernels.compiled_entry(kernels.mesh_forces, 0.0, phi2, w1, w1 * model.ratio, *arrays)
    start = time.perf_counter()
    for k in range(n // 10):
        forces(1e-4 * k, phi2 + 1e-4 * k * model.ratio, w1, w1 * model.ratio, *arrays)
    python = (time.perf_counter() - start) / (n // 10) * 1e6
    return compiled, python


_COMPILE_PROBE = """
import time
start = time.perf_counter()
import numpy as np
from lsbg.contact import ContactParameters, MeshContact, kernels
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics.compiled_engine import integrate, tableau
from lsbg.gear.geometry import GearPair
imported = time.perf_counter()
pair = GearPair(GearPairDesign())
for model in ("point", "line"):
    contact = MeshContact(pair, ContactParameters(model=model), gear_inertia=0.0159)
    contact.forces(0.0, -5e-5, 1.0, 0.2)
    contact.pair_contacts(0.0, -5e-5)
    integrate(np.array([0.0, 1e-4]), -5e-5, 0.0, 1.0, 0.1, 1.0, 0.0159,
              *contact.arrays, *tableau("DOP853"), 1e-6, 1e-12, 1e-8, 1e-4, 1e-3, 1e3)
print(imported - start, time.perf_counter() - imported)
"""


def compile_times():
    """(import, first call) [s] with a fresh numba cache, then with the cache on disk."""
    out = {}
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        for label in ("fresh cache (compile)", "warm cache (load)"):
            proc = subprocess.run([sys.executable, "-c", _COMPILE_PROBE], env=env,
                                  capture_output=True, text=True, check=True)
            out[label] = tuple(map(float, proc.stdout.split()))
    return out


def verdict(value, target, smaller=True):
    if target is None:
        return ""
    ok = value <= target if smaller else value >= target
    return "ok" if ok else "OVER TARGET"


def figure(name, value, unit, target=None, smaller=True):
    """One benchmark figure: a row of the summary that bench_all.py prints."""
    return {"figure": name, "value": value, "unit": unit, "target": target,
            "verdict": verdict(value, target, smaller),
            "target_text": "" if target is None else f"{'<=' if smaller else '>='} {target:g}"}


def main(argv=None):
    """Run the benchmark; return its figures (see :func:`figure`)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated time [s]")
    parser.add_argument("--convergence", action="store_true",
                        help="also run the convergence study of both models (minutes)")
    parser.add_argument("--out", type=Path, help="folder for convergence.csv (optional)")
    args = parser.parse_args(argv)
    settings = SimulationSettings(duration=args.duration, samples=round(500 * args.duration),
                                  ramp_time=min(0.2, args.duration / 5))
    print(f"lsbg dynamics benchmark, {os.cpu_count()} cores, {args.duration:g} s simulated")
    figures = []
    times = compile_times()
    print("\n== numba kernels: import and first call, each in a new interpreter [s] ==")
    for label, (imported, first) in times.items():
        print(f"  {label:22s}: import {imported:.2f}, first call {first:.2f}")
        figures.append(figure(f"kernels first call, {label}", first, "s"))
    with tempfile.TemporaryDirectory() as tmp:
        geometry = Path(tmp) / "lsbg35"
        write_geometry(GearPairDesign(), geometry)
        models = {m: load_model(geometry, ContactParameters(model=m)) for m in ("point", "line")}
        print("\n== contact kernel, one evaluation [us] ==")
        for name, model in models.items():
            compiled, python = kernel_costs(model)
            figures.append(figure(f"{name} contact kernel, compiled loop", compiled, "us"))
            print(f"  {name:5s} model: {compiled:.3f} in a compiled loop, {python:.3f} called "
                  f"from Python")
        print("\n== wall time per simulated second, LSBG at 35 deg [s] ==")
        wall = {}
        for engine in ("compiled", "pybullet", "scipy"):
            for name, model in models.items():
                # the kernels' load from the on-disk cache is a once-per-process cost,
                # reported above: a short run first, so that it is not counted here
                model.run(settings.replace(engine=engine, duration=0.002, samples=2,
                                           ramp_time=0.001))
                record = model.run(settings.replace(engine=engine))
                wall[(engine, name)] = per_second = record.wall_time / settings.duration
                target = TARGETS[(engine, name)]
                figures.append(figure(f"{engine} engine, {name} model, per simulated second",
                                      per_second, "s", target))
                shown = f"(target <= {target:g})" if target is not None else ""
                print(f"  {engine:8s} {name:5s}: {per_second:7.2f} {shown:18s} "
                      f"{verdict(per_second, target)}")
        for engine in ("compiled", "pybullet", "scipy"):
            ratio = wall[(engine, "line")] / wall[(engine, "point")]
            print(f"  {engine:8s} line / point: {ratio:.2f} (target <= {LINE_OVER_POINT}) "
                  f"{verdict(ratio, LINE_OVER_POINT)}")
        print("\n== one PyBullet step [us] (point model) ==")
        costs = pybullet_step_costs(models["point"], settings, n=100000)
        for key in ("joint_states", "contact_kernel", "apply_torque", "motor_target",
                    "step_simulation", "floor_steady", "floor_ramp", "floor", "engine_step"):
            print(f"  {key:16s}: {costs[key]:6.2f}")
        print(f"  (floor: the PyBullet calls alone, the motor's target write on the "
              f"{costs['ramp_share']:.0%} ramp steps)")
        figures.append(figure("PyBullet step", costs["engine_step"], "us"))
        figures.append(figure("PyBullet floor (step + joint read + torque write)",
                              costs["floor"], "us"))
        figures.append(figure("PyBullet step / floor", costs["engine_over_floor"], "",
                              ENGINE_OVER_FLOOR))
        print(f"  engine / floor  : {costs['engine_over_floor']:6.2f} "
              f"(target <= {ENGINE_OVER_FLOOR}) {verdict(costs['engine_over_floor'], ENGINE_OVER_FLOOR)}")
        if args.convergence:
            import pandas as pd

            tables = []
            for name, model in models.items():
                table = convergence_study(model, settings, steady_start=settings.ramp_time)
                tables.append(table)
                reference = table[table.engine == "scipy"].iloc[-1]
                print(f"\n== convergence, {name} model: std against scipy at rtol "
                      f"{reference.value:g} [%] ==")
                for row in table.itertuples():
                    dv = 100 * (row.gear_speed_std_deg_s / reference.gear_speed_std_deg_s - 1)
                    df = 100 * (row.tangential_force_std_N / reference.tangential_force_std_N - 1)
                    print(f"  {row.engine:8s} {row.parameter}={row.value:.0e}: speed {dv:+7.3f}, "
                          f"force {df:+7.3f}  ({row.wall_time_s:.1f} s wall)")
            if args.out:
                args.out.mkdir(parents=True, exist_ok=True)
                pd.concat(tables).to_csv(args.out / "convergence.csv", index=False)
    return figures


if __name__ == "__main__":
    main()
