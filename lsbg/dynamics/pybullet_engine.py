"""The PyBullet engine: the URDF of the assembled pair with lsbg's contact torques.

Each gear sits on a revolute joint with the inertia of its solid mesh; the
pinion is driven by Bullet's velocity motor along the prescribed ramp; the
contact torque of the compiled kernel and the load are applied to the gear
every fixed step (semi-implicit Euler, 1 µs by default). Bullet's own contact
is not used (DESIGN.md §3).

The per-step Python glue is cut to one joint-state read, one kernel call and
one torque write (the motor's target changes during the ramp only); the
read that starts a step is the state at the record instant the previous
step ended on, and the states are checked for a blow-up in blocks of
record instants by the compiled kernel. The mesh
reaction on the pinion is not applied: the velocity motor holds the pinion on
its prescribed speed and would absorb it (measured: applying it changes the
gear speed by less than 1e-9 relative, tests/dynamics/test_model.py). The pybullet
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
        Its ``steps``: the fixed PyBullet steps of ``settings.time_step`` [-].

    Raises
    ------
    SimulationError
        On a blow-up (the states checked every ``CHECK_BLOCK`` record instants).
    """
    import pybullet

    client = pybullet.connect(pybullet.DIRECT)
    try:
        return _run(model, pybullet, client, settings, apply_pinion_torque)
    finally:
        pybullet.disconnect(client)


#: Record instants per blow-up check and progress report [-].
CHECK_BLOCK = 1000


def _run(model, pb, client, settings, apply_pinion_torque):
    dt = settings.time_step
    ticks, times, _ = settings.record_grid()
    # whole steps per full-rate interval (SimulationSettings checks it)
    record_steps = [int(k) for k in ticks * int(round(settings.full_rate_interval / dt))]
    body, pj, gj = load_pybullet(model, pb, client, settings)
    phi2_0 = model.initial_gear_angle(settings)
    pb.resetJointState(body, pj, 0.0, 0.0, physicsClientId=client)
    pb.resetJointState(body, gj, phi2_0, 0.0, physicsClientId=client)

    arrays = model.contact.arrays
    calls = _Calls(pb, client, body, pj, gj, model, settings, arrays, phi2_0)
    # The motor's target during the ramp: the prescribed speed at the end of
    # each step, then the final speed once.
    ramp_steps = int(math.floor(settings.ramp_time / dt * (1 + 1e-12))) + 1
    targets = [pinion_state((n + 1) * dt, settings.pinion_speed, settings.ramp_time)[1]
               for n in range(ramp_steps)]
    targets[-1] = settings.pinion_speed
    # record intervals that hold a ramp step take the step-by-step loop
    ramp_intervals = int(np.searchsorted(record_steps, ramp_steps, side="left"))
    if apply_pinion_torque:
        ramp_intervals = len(record_steps) - 1

    states = [(0.0, phi2_0, 0.0, 0.0)]
    start = last = time.monotonic()
    checked = 0
    r = 0
    while r < len(record_steps) - 1:
        stop = min(r + CHECK_BLOCK, len(record_steps) - 1)
        if r < ramp_intervals:
            stop = min(stop, ramp_intervals)
            _ramp(calls, record_steps, r, stop, targets, states, apply_pinion_torque)
        else:
            _steady(calls, record_steps, r, stop, states)
        r = stop
        # a blow-up persists once it happens: check the block's states
        block = np.array(states[checked:])
        model.check_states(settings, times[checked:r + 1], *block.T)
        checked = r + 1
        last = model.progress(times[r], settings, start, last)
    wall = time.monotonic() - start
    phi1, phi2, w1, w2 = np.array(states).T
    return model.record(settings, times, phi1, phi2, w1, w2, wall, record_steps[-1])


class _Calls:
    """The PyBullet calls and constants of a step, looked up once."""

    def __init__(self, pb, client, body, pj, gj, model, settings, arrays, phi2_0):
        self.client, self.body, self.pj, self.gj = client, body, pj, gj
        self.joints = (pj, gj)
        self.get_states, self.apply_torque = pb.getJointStates, pb.applyExternalTorque
        self.step_simulation, self.motor = pb.stepSimulation, pb.setJointMotorControl2
        self.world, self.velocity = pb.WORLD_FRAME, pb.VELOCITY_CONTROL
        self.gear_axis = tuple(map(float, model.pair.rotation_axis[2]))
        self.pinion_axis = tuple(map(float, model.pair.rotation_axis[1]))
        self.servo_force = 1e3 * max(settings.load_torque, 1.0)
        self.load = settings.load_torque
        self.params, self.sides, self.table = arrays
        self.torque_of = kernels.compiled_entry(kernels.gear_torque, 0.0, phi2_0, 0.0, 0.0, *arrays)
        self.forces = kernels.compiled_entry(kernels.mesh_forces, 0.0, phi2_0, 0.0, 0.0, *arrays)


def _ramp(c, record_steps, first, stop, targets, states, apply_pinion_torque):
    """Record intervals ``first`` to ``stop`` step by step, the motor's target
    set at every ramp step (and the mesh reaction on the pinion if asked)."""
    get_states, body, joints, client = c.get_states, c.body, c.joints, c.client
    torque_of, forces, params, sides, table, load = (c.torque_of, c.forces, c.params, c.sides,
                                                     c.table, c.load)
    apply_torque, gear_joint, world, step_simulation = (c.apply_torque, c.gj, c.world,
                                                        c.step_simulation)
    motor, pinion_joint, velocity, servo_force = c.motor, c.pj, c.velocity, c.servo_force
    ux, uy, uz = c.gear_axis
    vx, vy, vz = c.pinion_axis
    ramp_steps = len(targets)
    for r in range(first, stop):
        for n in range(record_steps[r], record_steps[r + 1]):
            (q1, w1, _, _), (q2, w2, _, _) = get_states(body, joints, client)
            if n < ramp_steps:
                # positional: targetPosition, targetVelocity, force, positionGain,
                # velocityGain, maxVelocity (pybullet's defaults), client
                motor(body, pinion_joint, velocity, 0.0, targets[n], servo_force, 0.1, 1.0, -1.0,
                      client)
            if apply_pinion_torque:
                torque, pinion, _, _, _, _ = forces(q1, q2, w1, w2, params, sides, table)
                apply_torque(body, pinion_joint, (pinion * vx, pinion * vy, pinion * vz), world,
                             client)
            else:
                torque = torque_of(q1, q2, w1, w2, params, sides, table)
            net = torque - load
            apply_torque(body, gear_joint, (net * ux, net * uy, net * uz), world, client)
            step_simulation(client)
        (q1, w1, _, _), (q2, w2, _, _) = get_states(body, joints, client)
        states.append((q1, q2, w1, w2))


def _steady(c, record_steps, first, stop, states):
    """Record intervals ``first`` to ``stop`` after the ramp: one joint-state
    read, one kernel call and one torque write per step, every name a local
    (the hottest Python loop of lsbg). The read that starts a step is the
    state at the instant the previous step ended, so the record instants'
    states come without a read of their own."""
    get_states, body, joints, client = c.get_states, c.body, c.joints, c.client
    torque_of, params, sides, table, load = c.torque_of, c.params, c.sides, c.table, c.load
    apply_torque, gear_joint, world, step_simulation = (c.apply_torque, c.gj, c.world,
                                                        c.step_simulation)
    ux, uy, uz = c.gear_axis
    append = states.append
    now = get_states(body, joints, client)
    for r in range(first, stop):
        for _ in range(record_steps[r + 1] - record_steps[r]):
            (q1, w1, _, _), (q2, w2, _, _) = now
            net = torque_of(q1, q2, w1, w2, params, sides, table) - load
            apply_torque(body, gear_joint, (net * ux, net * uy, net * uz), world, client)
            step_simulation(client)
            now = get_states(body, joints, client)
        (q1, w1, _, _), (q2, w2, _, _) = now
        append((q1, q2, w1, w2))
