"""The PyBullet engine: the URDF of the assembled pair with lsbg's contact torques.

Each gear sits on a revolute joint with the inertia of its solid mesh; the
pinion is driven by Bullet's velocity motor along the prescribed ramp; the
contact torque of the compiled kernel and the load are applied to the gear
every fixed step (semi-implicit Euler, 1 µs by default). Bullet's own contact
is not used (DESIGN.md §3).

The per-step Python glue is cut to one joint-state read, one kernel call and
one torque write (the motor's target changes during the ramp only). The mesh
reaction on the pinion is not applied: the velocity motor holds the pinion on
its prescribed speed and would absorb it (measured: applying it changes the
gear speed by less than 1e-9 relative, tests/test_dynamics.py). The pybullet
calls pass the client positionally, which parses faster than the keyword.
"""

from __future__ import annotations

import math
import time

import numpy as np

from lsbg.contact import kernels
from lsbg.dynamics.settings import SimulationSettings, pinion_state


def load_pybullet(model, pb, client, settings):
    """Load the pair into a PyBullet client as the engine runs it.

    Zero gravity and damping, the fixed time step of ``settings``, the
    joint speed cap raised, the gear's default joint motor freed, and the
    links' axial inertias checked against the geometry's.

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    pb : module
        :mod:`pybullet`.
    client : int
        Physics client id (DIRECT mode).
    settings : SimulationSettings

    Returns
    -------
    body, pinion_joint, gear_joint : int
    """
    if model.urdf is None:
        raise ValueError("urdf = None: the pybullet engine needs the pair's URDF")
    dt = settings.time_step
    pb.setGravity(0, 0, 0, physicsClientId=client)
    pb.setPhysicsEngineParameter(fixedTimeStep=dt, numSubSteps=0, deterministicOverlappingPairs=1,
                                 physicsClientId=client)
    body = pb.loadURDF(str(model.urdf), useFixedBase=True, flags=pb.URDF_USE_INERTIA_FROM_FILE,
                       physicsClientId=client)
    joints = {pb.getJointInfo(body, j, physicsClientId=client)[1].decode(): j
              for j in range(pb.getNumJoints(body, physicsClientId=client))}
    pj, gj = joints["pinion_joint"], joints["gear_joint"]
    # DESIGN.md §3 pitfalls: damping and the joint speed cap belong to the
    # multibody (set them on the base, in separate calls, and read back).
    pb.changeDynamics(body, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
    pb.changeDynamics(body, -1, maxJointVelocity=100.0 * settings.pinion_speed, physicsClientId=client)
    for link in (pj, gj):
        pb.changeDynamics(body, link, jointDamping=0.0, physicsClientId=client)
        info = pb.getDynamicsInfo(body, link, physicsClientId=client)
        expected = model.pinion_inertia if link == pj else model.gear_inertia
        axial = info[2][2]
        if not math.isclose(axial, expected, rel_tol=1e-6):
            raise ValueError(f"urdf = {model.urdf}: link {link} axial inertia {axial!r} kg m^2 "
                             f"differs from the geometry's {expected!r}")
    # Revolute joints carry a default velocity motor that acts as friction: free the gear.
    pb.setJointMotorControl2(body, gj, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=client)
    return body, pj, gj


def run_pybullet(model, settings: SimulationSettings, apply_pinion_torque=False):
    """Integrate ``model`` in PyBullet (DIRECT mode).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : SimulationSettings
    apply_pinion_torque : bool
        Also apply the mesh reaction to the pinion (which its velocity motor
        absorbs); for the test that shows it changes nothing.

    Returns
    -------
    lsbg.dynamics.RunRecord

    Raises
    ------
    SimulationError
        On a blow-up (checked every step).
    """
    import pybullet

    client = pybullet.connect(pybullet.DIRECT)
    try:
        return _run(model, pybullet, client, settings, apply_pinion_torque)
    finally:
        pybullet.disconnect(client)


def _run(model, pb, client, settings, apply_pinion_torque):
    dt = settings.time_step
    ticks, times, _ = settings.record_grid()
    # whole steps per full-rate interval (SimulationSettings checks it)
    record_steps = ticks * int(round(settings.full_rate_interval / dt))
    body, pj, gj = load_pybullet(model, pb, client, settings)
    phi2_0 = model.initial_gear_angle(settings)
    pb.resetJointState(body, pj, 0.0, 0.0, physicsClientId=client)
    pb.resetJointState(body, gj, phi2_0, 0.0, physicsClientId=client)

    ux, uy, uz = map(float, model.pair.rotation_axis[2])
    vx, vy, vz = map(float, model.pair.rotation_axis[1])
    servo_force = 1e3 * max(settings.load_torque, 1.0)
    load = settings.load_torque
    limit = model.penetration_limit
    arrays = model.contact.arrays
    forces = kernels.compiled_entry(kernels.mesh_forces, 0.0, phi2_0, 0.0, 0.0, *arrays)
    params, sides, table = arrays
    get_states, apply_torque = pb.getJointStates, pb.applyExternalTorque
    step_simulation, motor = pb.stepSimulation, pb.setJointMotorControl2
    world, velocity = pb.WORLD_FRAME, pb.VELOCITY_CONTROL
    joints = (pj, gj)
    # The motor's target during the ramp: the prescribed speed at the end of
    # each step, then the final speed once.
    ramp_steps = int(math.floor(settings.ramp_time / dt + 1e-9)) + 1
    targets = [pinion_state((n + 1) * dt, settings.pinion_speed, settings.ramp_time)[1]
               for n in range(ramp_steps)]
    targets[-1] = settings.pinion_speed

    states = np.empty((len(ticks), 4))
    states[0] = (0.0, phi2_0, 0.0, 0.0)
    start = last = time.monotonic()
    n = 0
    for r in range(1, len(ticks)):
        for n in range(n, int(record_steps[r])):
            (q1, w1, _, _), (q2, w2, _, _) = get_states(body, joints, client)
            gear_torque, pinion_torque, deepest, _, _, _ = forces(q1, q2, w1, w2, params, sides,
                                                                  table)
            if deepest > limit or not gear_torque == gear_torque:
                model.check_state(n * dt, w2, deepest, settings)
            if n < ramp_steps:
                motor(body, pj, velocity, targetVelocity=targets[n], force=servo_force,
                      physicsClientId=client)
            net = gear_torque - load
            apply_torque(body, gj, (net * ux, net * uy, net * uz), world, client)
            if apply_pinion_torque:
                apply_torque(body, pj, (pinion_torque * vx, pinion_torque * vy,
                                        pinion_torque * vz), world, client)
            step_simulation(client)
        n = int(record_steps[r])
        (q1, w1, _, _), (q2, w2, _, _) = get_states(body, joints, client)
        states[r] = (q1, q2, w1, w2)
        if r % 1000 == 0:
            last = model.progress(times[r], settings, start, last)
    wall = time.monotonic() - start
    return model.record(settings, times, states[:, 0], states[:, 1], states[:, 2], states[:, 3],
                        wall, n)
