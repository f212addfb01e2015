"""Numerical verification of the meshing simulation: convergence and cost.

The contact resonance of the pair sits near 10 kHz and the IMPACT law damps it
very little at micrometre penetrations, so the standard deviations of gear
speed and tangential force (the quantities the paper compares) depend on the
integration. :func:`convergence_study` runs one design point with the PyBullet
engine at several fixed time steps and with the scipy engine at several
tolerances, and tabulates those standard deviations; the default settings must
sit in the range where halving the step (or tightening the tolerance) no
longer changes them much.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pandas as pd

from lsbg.dynamics import MeshingModel, SimulationSettings

#: Time steps of the PyBullet engine in the convergence study [s].
TIME_STEPS = (4e-6, 2e-6, 1e-6)
#: Relative tolerances of the scipy engine in the convergence study [-].
TOLERANCES = (1e-6, 1e-8, 1e-10)

#: Columns of the convergence table.
COLUMNS = ("trace", "spiral_angle_deg", "engine", "parameter", "value", "is_default",
           "gear_speed_mean_deg_s", "gear_speed_std_deg_s", "tangential_force_mean_N",
           "tangential_force_std_N", "wall_time_s", "steps")


def steady_statistics(record, start):
    """Mean and standard deviation of gear speed and tangential force after ``start``.

    Parameters
    ----------
    record : lsbg.dynamics.RunRecord
    start : float
        Start of the steady state [s]; samples strictly after it count.

    Returns
    -------
    dict
        ``gear_speed_mean_deg_s``, ``gear_speed_std_deg_s``,
        ``tangential_force_mean_N``, ``tangential_force_std_N``.
    """
    keep = record.time > start
    speed = np.degrees(record.gear_speed[keep])
    force = record.tangential_force[keep]
    return {"gear_speed_mean_deg_s": float(speed.mean()),
            "gear_speed_std_deg_s": float(speed.std(ddof=1)),
            "tangential_force_mean_N": float(force.mean()),
            "tangential_force_std_N": float(force.std(ddof=1))}


def convergence_study(model: MeshingModel, settings: SimulationSettings, steady_start=0.2,
                      time_steps=TIME_STEPS, tolerances=TOLERANCES):
    """Standard deviations against time step (PyBullet) and tolerance (scipy).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : lsbg.dynamics.SimulationSettings
        The default settings; their ``time_step`` and ``rtol`` are marked
        ``is_default`` in the table.
    steady_start : float
        Start of the steady state [s].
    time_steps : sequence of float
        PyBullet time steps [s].
    tolerances : sequence of float
        scipy relative tolerances [-].

    Returns
    -------
    pandas.DataFrame
        One row per run, columns :data:`COLUMNS`.
    """
    design = model.pair.design
    rows = []
    runs = [("pybullet", "time_step_s", dt, settings.replace(engine="pybullet", time_step=dt),
             math.isclose(dt, settings.time_step)) for dt in time_steps]
    runs += [("scipy", "rtol", tol, settings.replace(engine="scipy", rtol=tol),
              math.isclose(tol, settings.rtol)) for tol in tolerances]
    for engine, parameter, value, run_settings, is_default in runs:
        record = model.run(run_settings)
        rows.append({"trace": design.trace, "spiral_angle_deg": math.degrees(design.spiral_angle),
                     "engine": engine, "parameter": parameter, "value": value,
                     "is_default": bool(is_default), **steady_statistics(record, steady_start),
                     "wall_time_s": record.wall_time, "steps": record.steps})
    return pd.DataFrame(rows, columns=list(COLUMNS))


def pybullet_step_costs(model: MeshingModel, settings: SimulationSettings, n=20000):
    """Wall time of each part of one PyBullet engine step [µs].

    Times ``n`` repetitions of each call the engine makes per step, in the
    engine's own setting (the pair's URDF loaded, the gears in mesh under load).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : lsbg.dynamics.SimulationSettings
    n : int
        Repetitions per part [-].

    Returns
    -------
    dict
        Part -> µs per step: ``joint_states``, ``contact_kernel``,
        ``apply_torques``, ``step_simulation``, ``sum``.
    """
    import pybullet as pb

    client = pb.connect(pb.DIRECT)
    try:
        body, pj, gj = model.load_pybullet(pb, client, settings)
        phi2 = model.initial_gear_angle(settings)
        w1 = settings.pinion_speed
        w2 = w1 * model.ratio

        def timed(fn):
            start = time.perf_counter()
            for _ in range(n):
                fn()
            return (time.perf_counter() - start) / n * 1e6

        costs = {
            "joint_states": timed(lambda: pb.getJointStates(body, (pj, gj), physicsClientId=client)),
            "contact_kernel": timed(lambda: model.contact.evaluate(0.0123, phi2 + 0.0123 * model.ratio,
                                                                   w1, w2)),
            "apply_torques": timed(lambda: (
                pb.applyExternalTorque(body, gj, (0.0, 0.0, 1.0), pb.WORLD_FRAME, physicsClientId=client),
                pb.applyExternalTorque(body, pj, (0.0, 0.0, 1.0), pb.WORLD_FRAME, physicsClientId=client))),
            "step_simulation": timed(lambda: pb.stepSimulation(physicsClientId=client)),
        }
    finally:
        pb.disconnect(client)
    costs["sum"] = sum(costs.values())
    return costs
