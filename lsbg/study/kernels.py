"""The study's compiled kernels, compiled once before the jobs that call them.

From an empty numba cache every job compiles the kernels it calls (seconds for
those of a design point), and the study's first two jobs, the sweeps of both
traces, would compile the same kernels at the same time. The workflow's first job (rule ``kernels``, ``lsbg kernels``) runs
every kernel of a design point once, on a small case of the study's own design
and flanks, so that numba's cache holds them when the sweeps start; meanwhile
the other core builds the paper point's geometry. With a warm cache it only
loads them.

The small case calls the kernels through the stages' own functions (the
geometry's picture, the loaded TCA, both contact models' compiled runs, the
unloaded TCA, the statistics' block bootstrap, the FE stiffness's factor of a
meshed cube), so each is compiled for the argument types the study's jobs pass.
"""

from __future__ import annotations

import dataclasses
import importlib
import tempfile
import time
from pathlib import Path

import numpy as np

__all__ = ["compile_kernels", "called_kernels", "kernel_signatures"]

#: Positions of the small case's loaded and unloaded TCA [-] (the fewest they take).
POSITIONS = 8


def called_kernels():
    """``{module.function: numba dispatcher}`` of every lsbg kernel called in this process
    (compiled, or loaded from numba's cache).

    A kernel that only other kernels call gets no signature of its own when its callers
    are loaded from the cache (its code is in theirs), so it is not listed then.

    Returns
    -------
    dict
        Over the modules of :data:`lsbg.numba_cache.COMPILED_MODULES`.
    """
    from numba.core.dispatcher import Dispatcher

    from lsbg.numba_cache import COMPILED_MODULES, numba_module_name

    package = Path(__file__).resolve().parents[1]
    found = {}
    for path in COMPILED_MODULES:
        name = numba_module_name(package / path)
        for attribute, value in sorted(vars(importlib.import_module(name)).items()):
            if isinstance(value, Dispatcher) and value.py_func.__module__ == name \
                    and value.signatures:
                found[f"{name}.{attribute}"] = value
    return found


def kernel_signatures():
    """``{module.function: number of signatures}`` of :func:`called_kernels`.

    Returns
    -------
    dict
    """
    return {name: len(kernel.signatures) for name, kernel in called_kernels().items()}


def compile_kernels(design, flanks, point, line, simulation):
    """Run every kernel of a design point once: compiled into numba's cache, or loaded.

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
        The study's design (its paper point).
    flanks : lsbg.tca.separation.RealFlanks
        The study's flanks (modification and displacements); conjugate flanks are
        crowned here, so that the separation kernel is called too.
    point, line : lsbg.contact.ContactParameters
        The study's point and line models.
    simulation : lsbg.dynamics.SimulationSettings
        The study's runs; the small case runs 4 ms of them with the compiled engine.

    Returns
    -------
    dict
        ``seconds`` (wall time [s]) and ``kernels`` (:func:`kernel_signatures`
        afterwards).
    """
    from lsbg.dynamics import simulate
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.export import write_geometry
    from lsbg.stats.bootstrap import std_ci
    from lsbg.tca.analysis import tooth_contact_analysis
    from lsbg.tca.loaded import ltca_for_geometry
    from lsbg.tca.separation import RealFlanks

    start = time.perf_counter()
    # the FE factor's first: the paper point's compliance can start on the other core
    # as soon as its geometry is built
    _factor_cube()
    if flanks.is_conjugate:  # (the searches' real flanks call the separation kernel anyway)
        flanks = RealFlanks.from_config({"lengthwise_crowning_um": 25.0})
    short = dataclasses.replace(simulation, engine="compiled", duration=0.004, samples=4,
                                ramp_time=0.002, full_rate_after=0.002)
    with tempfile.TemporaryDirectory(prefix="lsbg_kernels_") as folder:
        geometry = Path(folder) / "pair"
        write_geometry(design, geometry, step=False)
        ltca_for_geometry(geometry, simulation.load_torque, line, phases=POSITIONS,
                          flanks=flanks)
        for model in (point, line):
            simulate(geometry, short, model, flanks=flanks)
        # the torsional driveline's equations (the boundary cases' runs), its defaults
        simulate(geometry, dataclasses.replace(short, boundary="driveline"), line,
                 flanks=flanks, driveline={})
    tooth_contact_analysis(GearPair(design), flanks.modification, flanks.misalignment,
                           positions=POSITIONS)
    std_ci(np.sin(np.arange(64.0)), n_boot=100)
    return {"seconds": time.perf_counter() - start, "kernels": kernel_signatures()}


def _factor_cube():
    """Factor the FE stiffness of a steel cube (a 2 x 2 x 2 tensor mesh, clamped
    below) as the FE compliance factors a gear segment's: the factor's kernels
    (:mod:`lsbg.tooth.cholesky`) for the segments' argument types."""
    from skfem import MeshTet

    from lsbg.tooth.elasticity import ElasticSegment
    from lsbg.tooth.segment import SegmentMesh

    mesh = MeshTet.init_tensor(*(np.linspace(0.0, 0.01, 3),) * 3)
    bottom = np.flatnonzero(mesh.p[2] == 0.0)
    ElasticSegment(SegmentMesh(mesh.p, mesh.t, bottom, 1, 1, 0.005, 0.005), 2.1e11, 0.3)
