"""Numerical verification of the meshing simulation: convergence and cost.

The point model's contact resonance sits near 9 kHz and the IMPACT law damps
it very little at micrometre penetrations, so the standard deviations of gear
speed and tangential force (the quantities the paper compares) depend on the
integration. :func:`convergence_study` runs one design point and contact model
with the PyBullet engine at several fixed time steps and with the scipy and
compiled engines at several tolerances, and tabulates those standard
deviations (of the output samples and of the full-rate record); the default
settings must sit in the range where halving the step (or tightening the
tolerance) no longer changes them much.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pandas as pd

from lsbg.dynamics import MeshingModel, SimulationSettings

#: Time steps of the PyBullet engine in the convergence study [s].
TIME_STEPS = (4e-6, 2e-6, 1e-6)
#: Relative tolerances of the scipy and compiled engines in the convergence study [-].
TOLERANCES = (1e-6, 1e-8, 1e-10)
#: Engines with a tolerance (the others have a time step).
TOLERANCE_ENGINES = ("scipy", "compiled")

#: Columns of the convergence table.
COLUMNS = ("trace", "spiral_angle_deg", "contact_model", "engine", "parameter", "value",
           "is_default", "gear_speed_mean_deg_s", "gear_speed_std_deg_s",
           "tangential_force_mean_N", "tangential_force_std_N", "gear_speed_full_std_deg_s",
           "tangential_force_full_std_N", "wall_time_s", "steps")


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
        ``tangential_force_mean_N``, ``tangential_force_std_N`` of the output
        samples, ``gear_speed_full_std_deg_s`` and
        ``tangential_force_full_std_N`` of the full-rate record.
    """
    samples, full = record.samples, record.full_rate
    keep = samples.time > start
    speed = np.degrees(samples.gear_speed[keep])
    force = samples.tangential_force[keep]
    keep_full = full.time >= start - 1e-9
    return {"gear_speed_mean_deg_s": float(speed.mean()),
            "gear_speed_std_deg_s": float(speed.std(ddof=1)),
            "tangential_force_mean_N": float(force.mean()),
            "tangential_force_std_N": float(force.std(ddof=1)),
            "gear_speed_full_std_deg_s": float(np.degrees(full.gear_speed[keep_full]).std(ddof=1)),
            "tangential_force_full_std_N": float(full.tangential_force[keep_full].std(ddof=1))}


def convergence_study(model: MeshingModel, settings: SimulationSettings, steady_start=0.2,
                      time_steps=TIME_STEPS, tolerances=TOLERANCES):
    """Standard deviations against time step (PyBullet) and tolerance (scipy, compiled).

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
        Relative tolerances of the scipy and compiled engines [-].

    Returns
    -------
    pandas.DataFrame
        One row per run, columns :data:`COLUMNS`.
    """
    design = model.pair.design
    rows = []
    runs = [("pybullet", "time_step_s", dt, settings.replace(engine="pybullet", time_step=dt),
             math.isclose(dt, settings.time_step)) for dt in time_steps]
    runs += [(engine, "rtol", tol, settings.replace(engine=engine, rtol=tol),
              math.isclose(tol, settings.rtol)) for engine in TOLERANCE_ENGINES
             for tol in tolerances]
    for engine, parameter, value, run_settings, is_default in runs:
        record = model.run(run_settings)
        rows.append({"trace": design.trace, "spiral_angle_deg": math.degrees(design.spiral_angle),
                     "contact_model": model.contact.params.model, "engine": engine, "parameter": parameter, "value": value,
                     "is_default": bool(is_default), **steady_statistics(record, steady_start),
                     "wall_time_s": record.wall_time, "steps": record.steps})
    return pd.DataFrame(rows, columns=list(COLUMNS))


def pybullet_step_costs(model: MeshingModel, settings: SimulationSettings, n=20000):
    """Wall time of each part of one PyBullet engine step, and of the whole step [µs].

    Times ``n`` repetitions of each call the engine makes per step, made as
    the engine makes it (client passed positionally), in the engine's own
    setting (the pair's URDF loaded, the gears in mesh under load); the
    *floor* is a loop of the three PyBullet calls alone (joint-state read,
    torque write, step); the *engine step* is a real run of ``n`` steps.

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : lsbg.dynamics.SimulationSettings
        Time step and load; the engine step is timed on a run of ``n`` steps.
    n : int
        Repetitions per part [-].

    Returns
    -------
    dict
        µs per step: ``joint_states``, ``contact_kernel``, ``apply_torque``,
        ``step_simulation``, ``floor`` (the three PyBullet calls in one
        loop), ``engine_step``; and ``engine_over_floor`` [-].
    """
    import pybullet as pb

    from lsbg.contact import kernels
    from lsbg.dynamics.pybullet_engine import load_pybullet, run_pybullet

    client = pb.connect(pb.DIRECT)
    try:
        body, pj, gj = load_pybullet(model, pb, client, settings)
        phi2 = model.initial_gear_angle(settings)
        pb.resetJointState(body, gj, phi2, 0.0, physicsClientId=client)
        joints, world = (pj, gj), pb.WORLD_FRAME
        get_states, apply_torque, step = pb.getJointStates, pb.applyExternalTorque, pb.stepSimulation
        arrays = model.contact.arrays
        forces = kernels.compiled_entry(kernels.mesh_forces, 0.0, phi2, 0.0, 0.0, *arrays)
        w1 = settings.pinion_speed
        w2 = w1 * model.ratio

        def timed(loop):
            begin = time.perf_counter()
            loop()
            return (time.perf_counter() - begin) / n * 1e6

        def states():
            for _ in range(n):
                get_states(body, joints, client)

        def kernel():
            for k in range(n):
                forces(1e-3 * k, phi2 + 1e-3 * k * model.ratio, w1, w2, *arrays)

        def torque():
            for _ in range(n):
                apply_torque(body, gj, (0.0, 0.0, 1.0), world, client)

        def steps():
            for _ in range(n):
                step(client)

        def floor():
            for _ in range(n):
                get_states(body, joints, client)
                apply_torque(body, gj, (0.0, 0.0, 1.0), world, client)
                step(client)

        costs = {"joint_states": timed(states), "contact_kernel": timed(kernel),
                 "apply_torque": timed(torque), "step_simulation": timed(steps),
                 "floor": timed(floor)}
    finally:
        pb.disconnect(client)
    duration = n * settings.time_step
    run = settings.replace(engine="pybullet", duration=duration, samples=1, ramp_time=0.0,
                           full_rate=1.0 / duration, full_rate_after=0.0)
    record = run_pybullet(model, run)
    costs["engine_step"] = record.wall_time / record.steps * 1e6
    costs["engine_over_floor"] = costs["engine_step"] / costs["floor"]
    return costs
