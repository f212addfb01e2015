"""The machine's own baseline: figures that lsbg's code cannot change.

Run as a script (pytest does not collect it: no ``test_`` prefix)::

    python tests/benchmarks/baseline.py [--repeat N]

A shared machine runs the same code at different speeds from hour to hour and
day to day (by up to a factor of two on the 2-core reference machine,
docs/performance.md). A benchmark
figure over its target means a regression only if the machine ran at its usual
speed, so bench_all.py measures two workloads that no change to lsbg touches,
before and after its figures:

* **the interpreter**: a pure-Python loop of 10^7 integer additions at a
  module's top level [s] (what the jobs' Python glue, Snakemake and the
  notebooks run on);
* **compiled scalar arithmetic**: a numba loop, frozen in this file, that
  integrates a damped oscillator with a Hertz-like stiffening spring by 2·10^6
  classical Runge-Kutta steps [s] (the kind of code the compiled engine and the
  TCA kernels run; compiled before it is timed).

Each is the median of ``repeat`` runs in this process. Compare a figure's
ratio to its baseline between days, not the figure alone.
"""

import argparse
import math
import statistics
import time

from numba import njit

#: Additions of the interpreter's loop [-].
PYTHON_ADDITIONS = 10_000_000
#: Runge-Kutta steps of the compiled loop [-].
COMPILED_STEPS = 2_000_000


#: The interpreter's loop at a module's top level, as ``python -c`` runs it: its names
#: are globals (a dictionary's lookups).
_LOOP = compile("total = 0\nfor i in range(additions):\n    total += i\n", "<baseline>", "exec")


def python_loop(additions=PYTHON_ADDITIONS):
    """Seconds of a pure-Python loop of integer additions at a module's top level [s]."""
    names = {"additions": additions}
    start = time.perf_counter()
    exec(_LOOP, names)
    elapsed = time.perf_counter() - start
    assert names["total"] == additions * (additions - 1) // 2
    return elapsed


@njit(cache=False)
def _oscillator(steps, dt):
    """x'' = -c x' - k max(x, 0)^1.5 - x + sin(t), RK4 from rest; returns x(end) [-]."""
    x, v, t = 0.0, 0.0, 0.0
    for _ in range(steps):
        k1x, k1v = v, -0.05 * v - 40.0 * max(x, 0.0) ** 1.5 - x + math.sin(t)
        x2, v2 = x + 0.5 * dt * k1x, v + 0.5 * dt * k1v
        k2x, k2v = v2, -0.05 * v2 - 40.0 * max(x2, 0.0) ** 1.5 - x2 + math.sin(t + 0.5 * dt)
        x3, v3 = x + 0.5 * dt * k2x, v + 0.5 * dt * k2v
        k3x, k3v = v3, -0.05 * v3 - 40.0 * max(x3, 0.0) ** 1.5 - x3 + math.sin(t + 0.5 * dt)
        x4, v4 = x + dt * k3x, v + dt * k3v
        k4x, k4v = v4, -0.05 * v4 - 40.0 * max(x4, 0.0) ** 1.5 - x4 + math.sin(t + dt)
        x += dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x)
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
        t += dt
    return x


def compiled_loop(steps=COMPILED_STEPS):
    """Seconds of the compiled oscillator's loop, compiled beforehand [s]."""
    _oscillator(10, 1e-3)
    start = time.perf_counter()
    x = _oscillator(steps, 1e-3)
    elapsed = time.perf_counter() - start
    if not math.isfinite(x):
        raise RuntimeError("the baseline's oscillator diverged")
    return elapsed


def measure(repeat=5):
    """The baseline's figures, each the median of ``repeat`` runs.

    Parameters
    ----------
    repeat : int
        Runs of each workload [-].

    Returns
    -------
    dict
        ``{"python loop": seconds, "compiled loop": seconds}`` [s].
    """
    return {"python loop": statistics.median(python_loop() for _ in range(repeat)),
            "compiled loop": statistics.median(compiled_loop() for _ in range(repeat))}


def describe(values):
    """One line of the baseline's figures."""
    return (f"python loop ({PYTHON_ADDITIONS:.0e} additions) {values['python loop']:.3f} s, "
            f"compiled loop ({COMPILED_STEPS:.0e} RK4 steps) {values['compiled loop']:.3f} s")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs of each workload (median)")
    args = parser.parse_args(argv)
    print("machine baseline:", describe(measure(args.repeat)))


if __name__ == "__main__":
    main()
