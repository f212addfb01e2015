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


def _statistics(time, speed, force, time_full, speed_full, force_full, start):
    keep = time > start
    keep_full = time_full >= start - 1e-9
    return {"gear_speed_mean_deg_s": float(speed[keep].mean()),
            "gear_speed_std_deg_s": float(speed[keep].std(ddof=1)),
            "tangential_force_mean_N": float(force[keep].mean()),
            "tangential_force_std_N": float(force[keep].std(ddof=1)),
            "gear_speed_full_std_deg_s": float(speed_full[keep_full].std(ddof=1)),
            "tangential_force_full_std_N": float(force_full[keep_full].std(ddof=1))}


def steady_statistics(record, start):
    """Mean and standard deviation of gear speed and tangential force after ``start``.

    Parameters
    ----------
    record : lsbg.dynamics.RunRecord or xarray.Dataset
        A run, in memory or as written (``lsbg simulate``).
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
    if hasattr(record, "data_vars"):
        return _statistics(record["time"].values, record["gear_speed"].values,
                           record["tangential_force"].values, record["time_full"].values,
                           record["gear_speed_full"].values,
                           record["tangential_force_full"].values, start)
    samples, full = record.samples, record.full_rate
    return _statistics(samples.time, np.degrees(samples.gear_speed), samples.tangential_force,
                       full.time, np.degrees(full.gear_speed), full.tangential_force, start)


#: Settings a run of each engine depends on (keys of SimulationSettings.to_dict).
_ENGINE_KEYS = {
    "pybullet": ("time_step_s",),
    "scipy": ("rtol", "atol_angle_rad", "atol_speed_rad_s", "method"),
    "compiled": ("rtol", "atol_angle_rad", "atol_speed_rad_s", "compiled_method"),
}
_COMMON_KEYS = ("engine", "duration_s", "samples", "pinion_speed_deg_s", "ramp_time_s",
                "load_torque_N_m", "full_rate_hz", "full_rate_after_s")


def convergence_plan(settings: SimulationSettings, engines, time_steps=TIME_STEPS,
                     tolerances=TOLERANCES):
    """The runs of a convergence study: each engine at each of its settings.

    Parameters
    ----------
    settings : lsbg.dynamics.SimulationSettings
        The defaults (their ``time_step`` and ``rtol`` are marked ``is_default``).
    engines : sequence of str
        Engines to study: pybullet over ``time_steps``, scipy and compiled over
        ``tolerances``.
    time_steps, tolerances : sequence of float
        [s], [-]

    Returns
    -------
    list of tuple
        ``(engine, parameter, value, settings, is_default)`` per run.
    """
    plan = []
    for engine in engines:
        if engine == "pybullet":
            plan += [(engine, "time_step_s", dt, settings.replace(engine=engine, time_step=dt),
                      math.isclose(dt, settings.time_step)) for dt in time_steps]
        elif engine in TOLERANCE_ENGINES:
            plan += [(engine, "rtol", tol, settings.replace(engine=engine, rtol=tol),
                      math.isclose(tol, settings.rtol)) for tol in tolerances]
        else:
            raise ValueError(f"engine {engine!r}: must be one of pybullet, "
                             f"{', '.join(TOLERANCE_ENGINES)}")
    return plan


def _matches(ds, settings, params):
    """The first setting in which a written run differs from ``settings`` and
    ``params`` (None if it is the run they describe)."""
    from lsbg.contact import ContactParameters

    wanted = settings.to_dict()
    for key in _COMMON_KEYS + _ENGINE_KEYS[settings.engine]:
        have = ds.attrs.get(f"solver_{key}")
        value = wanted[key]
        same = (have == value if isinstance(value, str)
                else have is not None and math.isclose(float(have), float(value), rel_tol=1e-9))
        if not same:
            return f"solver_{key} = {have!r}, not {value!r}"
    if ContactParameters.from_dict(ds.attrs, prefix="contact_") != params:
        return "contact settings"
    return None


def convergence_study(model: MeshingModel, settings: SimulationSettings, steady_start=0.2,
                      time_steps=TIME_STEPS, tolerances=TOLERANCES, engines=None, known=(),
                      default_runs=None):
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
    engines : sequence of str, optional
        Engines in the table (default all three).
    known : sequence of xarray.Dataset
        Runs already made (``lsbg simulate``): a run of the plan that is among
        them is read, not run again.
    default_runs : dict, optional
        Filled with engine -> :class:`lsbg.dynamics.RunRecord` of each run made
        here at the default settings (so that a caller can write it instead of
        running it once more).

    Returns
    -------
    pandas.DataFrame
        One row per run, columns :data:`COLUMNS`.

    Raises
    ------
    ValueError
        If a known run is of this model and engine at a value of the plan but
        differs from it in another setting (naming the file and the setting).
    """
    design = model.pair.design
    engines = ("pybullet",) + TOLERANCE_ENGINES if engines is None else tuple(engines)
    plan = convergence_plan(settings, engines, time_steps, tolerances)
    params = model.contact.params
    made = {}
    for ds in known:
        engine = ds.attrs.get("solver_engine")
        if ds.attrs.get("contact_model") != params.model or engine not in engines:
            continue
        key = "time_step_s" if engine == "pybullet" else "rtol"
        for slot in plan:
            if slot[0] == engine and math.isclose(float(ds.attrs[f"solver_{key}"]), slot[2],
                                                  rel_tol=1e-9):
                differs = _matches(ds, slot[3], params)
                if differs:
                    raise ValueError(f"{ds.encoding.get('source', 'known run')}: a {engine} "
                                     f"run at {key} = {slot[2]:g} with {differs}")
                made[id(slot)] = ds
    rows = []
    for slot in plan:
        engine, parameter, value, run_settings, is_default = slot
        if id(slot) in made:
            ds = made[id(slot)]
            statistics = steady_statistics(ds, steady_start)
            wall, steps = float(ds.attrs["wall_time_s"]), int(ds.attrs["integrator_steps"])
        else:
            record = model.run(run_settings)
            if is_default and default_runs is not None:
                default_runs[engine] = record
            statistics = steady_statistics(record, steady_start)
            wall, steps = record.wall_time, record.steps
        rows.append({"trace": design.trace, "spiral_angle_deg": math.degrees(design.spiral_angle),
                     "contact_model": params.model, "engine": engine, "parameter": parameter,
                     "value": value, "is_default": bool(is_default), **statistics,
                     "wall_time_s": wall, "steps": steps})
    return pd.DataFrame(rows, columns=list(COLUMNS))


def pybullet_step_costs(model: MeshingModel, settings: SimulationSettings, n=20000, repeats=9):
    """Wall time of each part of one PyBullet engine step, and of the whole step [µs].

    Each part is timed on ``n`` repetitions of the call the engine makes per
    step, made as the engine makes it (client passed positionally), in the
    engine's own setting (the pair's URDF loaded, the pinion on its speed
    servo at the final speed, the gear turning: a step costs about 0.7 µs more
    than with both at rest). The *floor* is what the PyBullet calls of a run
    cost alone: a loop of the joint-state read (values unpacked), a torque
    write built from one of them and the step, plus the motor's target write
    on the run's share of ramp steps (the prescribed ramp needs it); the
    *engine step* is a real run of ``n`` steps with that share of ramp steps.
    Floor and engine are timed in turn ``repeats`` times: the parts' least
    times are reported, and the engine over the floor as the median of the
    ratios of each turn, which takes the machine's drift out of both alike.

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : lsbg.dynamics.SimulationSettings
        Time step, load and ramp share.
    n : int
        Steps per timing [-].
    repeats : int
        Timings of each part, the least kept [-].

    Returns
    -------
    dict
        µs per step: ``joint_states``, ``contact_kernel``, ``apply_torque``,
        ``motor_target``, ``step_simulation``, ``floor_steady`` and
        ``floor_ramp`` (the PyBullet calls of a step after and during the
        ramp, in one loop), ``floor`` (their mean over the run's steps),
        ``engine_step``; ``ramp_share`` [-], and ``engine_over_floor``, the
        median ratio of the turns [-].
    """
    import pybullet as pb

    from lsbg.contact import kernels
    from lsbg.dynamics.pybullet_engine import load_pybullet, run_pybullet

    duration = n * settings.time_step
    ramp_share = settings.ramp_time / settings.duration
    # the settings' full-rate interval throughout: the record instants of a
    # run's steady state
    run = settings.replace(engine="pybullet", duration=duration, samples=1,
                           ramp_time=duration * ramp_share, full_rate_after=0.0)
    client = pb.connect(pb.DIRECT)
    try:
        body, pj, gj = load_pybullet(model, pb, client, settings)
        phi2 = model.initial_gear_angle(settings)
        # the engine's operating state: pinion on its speed servo, gear turning
        w1 = settings.pinion_speed
        servo_force = 1e3 * max(settings.load_torque, 1.0)
        pb.resetJointState(body, pj, 0.0, w1, physicsClientId=client)
        pb.resetJointState(body, gj, phi2, w1 * model.ratio, physicsClientId=client)
        pb.setJointMotorControl2(body, pj, pb.VELOCITY_CONTROL, targetVelocity=w1,
                                 force=servo_force, physicsClientId=client)
        joints, world, velocity = (pj, gj), pb.WORLD_FRAME, pb.VELOCITY_CONTROL
        get_states, apply_torque, step = pb.getJointStates, pb.applyExternalTorque, pb.stepSimulation
        motor = pb.setJointMotorControl2
        arrays = model.contact.arrays
        torque_of = kernels.compiled_entry(kernels.gear_torque, 0.0, phi2, 0.0, 0.0, *arrays)
        params, sides, table = arrays
        ratio = model.ratio
        ux, uy, uz = map(float, model.pair.rotation_axis[2])

        def timed(loop):
            begin = time.perf_counter()
            loop()
            return (time.perf_counter() - begin) / n * 1e6

        def states():
            for _ in range(n):
                get_states(body, joints, client)

        def kernel():
            for k in range(n):
                torque_of(1e-4 * k, phi2 + 1e-4 * k * ratio, w1, w1 * ratio, params, sides, table)

        def torque():
            for _ in range(n):
                apply_torque(body, gj, (0.0, 0.0, 1.0), world, client)

        def target():
            for _ in range(n):
                motor(body, pj, velocity, 0.0, w1, servo_force, 0.1, 1.0, -1.0, client)

        def steps():
            for _ in range(n):
                step(client)

        # the engine's step without the contact computation: read the
        # state's values and write a torque built from one
        def floor_steady():
            for _ in range(n):
                (q1, speed1, _, _), (q2, speed2, _, _) = get_states(body, joints, client)
                apply_torque(body, gj, (speed2 * ux, speed2 * uy, speed2 * uz), world, client)
                step(client)

        def floor_ramp():
            for _ in range(n):
                (q1, speed1, _, _), (q2, speed2, _, _) = get_states(body, joints, client)
                motor(body, pj, velocity, 0.0, w1, servo_force, 0.1, 1.0, -1.0, client)
                apply_torque(body, gj, (speed2 * ux, speed2 * uy, speed2 * uz), world, client)
                step(client)

        parts = (("joint_states", states), ("contact_kernel", kernel), ("apply_torque", torque),
                 ("motor_target", target), ("step_simulation", steps),
                 ("floor_steady", floor_steady), ("floor_ramp", floor_ramp))
        costs = {name: [] for name, _ in parts}
        costs["floor"], costs["engine_step"] = [], []
        for _ in range(repeats):
            for name, loop in parts:
                costs[name].append(timed(loop))
            costs["floor"].append((1 - ramp_share) * costs["floor_steady"][-1]
                                  + ramp_share * costs["floor_ramp"][-1])
            record = run_pybullet(model, run)
            costs["engine_step"].append(record.wall_time / record.steps * 1e6)
    finally:
        pb.disconnect(client)
    ratios = np.array(costs["engine_step"]) / np.array(costs["floor"])
    costs = {name: min(values) for name, values in costs.items()}
    costs["ramp_share"] = ramp_share
    costs["engine_over_floor"] = float(np.median(ratios))
    return costs
