"""The compiled engine: an embedded Runge-Kutta loop compiled with numba.

Under the prescribed pinion (the paper's boundary) the system has one degree
of freedom, the gear angle: J2 phi2'' = T_contact - T_load with the contact
torque of the compiled kernels (:mod:`lsbg.contact.kernels`). Under the
driveline boundary it has three, pinion, gear and vehicle
(:func:`lsbg.dynamics.driveline.driveline_rates`). This engine integrates
either with an explicit embedded Runge-Kutta pair under adaptive step
control, entirely in compiled code: no Python call per step.

The method is Dormand-Prince 8(5,3) (``"DOP853"``, the default) or 5(4)
(``"RK45"``), with the Butcher tableaux that scipy publishes
(:class:`scipy.integrate.DOP853`, :class:`scipy.integrate.RK45`) and the same
error norm and step-size control as scipy's implementation (Hairer, Nørsett &
Wanner, *Solving Ordinary Differential Equations I*, §II.4 and §II.10): a step
is accepted when the scaled error norm is below 1, with
``scale = atol + rtol max(|y|, |y_new|)``, and the next step is the last one
times ``min(10, 0.9 err^(-1/(q+1)))`` (at least 0.2 after a rejection). Steps
end exactly on the record instants instead of interpolating to them.

A blow-up (a non-finite state, a penetration beyond the contact law's limit,
a runaway speed) is checked after every accepted step and stops the
integration; the Python side raises :class:`~lsbg.dynamics.SimulationError`
with the same diagnostic as the other engines.
"""

from __future__ import annotations

import math
import time

import numpy as np
from numba import njit

from lsbg.contact.kernels import mesh_forces
from lsbg.dynamics.driveline import driveline_rates
from lsbg.dynamics.settings import SimulationError, SimulationSettings, pinion_state

# Step-size control (Hairer's, and scipy's, constants).
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0

#: Outcome codes of :func:`integrate`.
OK, BLOW_UP, STEP_TOO_SMALL = 0, 1, 2


def tableau(method):
    """The Butcher tableau of an embedded pair, from scipy's published coefficients.

    Parameters
    ----------
    method : {"DOP853", "RK45"}

    Returns
    -------
    a, b, c : numpy.ndarray
        Stage coefficients (s x s), weights (s), nodes (s) [-].
    e, e3 : numpy.ndarray
        Error-estimate weights over the s + 1 stages (the last one is the
        derivative at the new point); ``e3`` is DOP853's third-order
        estimate, zeros for RK45 [-].
    blended : bool
        Whether the error norm blends the two estimates (DOP853).
    error_exponent : float
        -1 / (q + 1), q the order of the error estimator [-].
    """
    import scipy.integrate as si

    solver = {"DOP853": si.DOP853, "RK45": si.RK45}[method]
    if method == "DOP853":
        e, e3 = solver.E5, solver.E3
    else:
        e, e3 = solver.E, np.zeros_like(solver.E)
    arrays = [np.ascontiguousarray(v, dtype=float) for v in (solver.A, solver.B, solver.C, e, e3)]
    return (*arrays, method == "DOP853", -1.0 / (solver.error_estimator_order + 1))


#: Systems :func:`integrate` knows (``kind``): the prescribed pinion's gear
#: (2 states) and the driveline (:func:`lsbg.dynamics.driveline.driveline_rates`, 6 states).
PRESCRIBED, DRIVELINE = 0, 1


@njit(cache=True, inline="always")
def _prescribed_rates(t, y, out, row, system, params, sides, table):
    """(phi2', w2') of the gear under the prescribed pinion into ``out[row]``; the deepest
    approach.

    ``system``: the pinion's final speed [rad/s], its ramp time [s], the load
    on the gear [N m] and the gear's inertia [kg m^2].
    """
    phi1, w1 = pinion_state(t, system[0], system[1])
    torque, _, deepest, _, _, _ = mesh_forces(phi1, y[0], w1, y[1], params, sides, table)
    out[row, 0], out[row, 1] = y[1], (torque - system[2]) / system[3]
    return deepest


@njit(cache=True, inline="always")
def _rates(kind, t, y, out, row, system, params, sides, table):
    # (a row index, not a row view: a view costs reference counting at every call)
    if kind == PRESCRIBED:
        return _prescribed_rates(t, y, out, row, system, params, sides, table)
    return driveline_rates(t, y, out, row, system, params, sides, table)


@njit(cache=True, inline="always")
def _combine(weights, row, count, k, y, step, d, out):
    """out = y + step * sum over the first ``count`` stages of weights[row, j] k[j]
    (d: scratch)."""
    n = y.size
    d[:] = 0.0
    for j in range(count):
        w = weights[row, j]
        for i in range(n):
            d[i] += w * k[j, i]
    for i in range(n):
        out[i] = y[i] + step * d[i]


@njit(cache=True)
def integrate(kind, times, y0, system, params, sides, table, a, b, c, e, e3, blended,
              error_exponent, rtol, atol, max_step, depth_limit, speed_limit, speed_index):
    """Integrate a system's state and return it at ``times``.

    Parameters
    ----------
    kind : int
        :data:`PRESCRIBED` or :data:`DRIVELINE`.
    times : numpy.ndarray
        Increasing record instants, the first the initial time [s].
    y0 : numpy.ndarray
        Initial state: rotations [rad], then speeds [rad/s].
    system : numpy.ndarray
        The system's parameters (:func:`_prescribed_rates`,
        :meth:`lsbg.dynamics.driveline.Driveline.system`).
    params, sides, table : numpy.ndarray
        The contact model (:class:`lsbg.contact.MeshContact`).
    a, b, c, e, e3, blended, error_exponent
        The tableau (:func:`tableau`).
    rtol : float
        Relative tolerance [-].
    atol : numpy.ndarray
        Absolute tolerance of each state [rad, rad/s].
    max_step : float
        Largest step [s].
    depth_limit, speed_limit : float
        Penetration [m] and gear speed [rad/s] beyond which the run stops.
    speed_index : int
        The gear speed's index in the state.

    Returns
    -------
    states : numpy.ndarray, shape (len(times), len(y0))
        The state at ``times`` (rows after a failure are NaN).
    status : int
        :data:`OK`, :data:`BLOW_UP` or :data:`STEP_TOO_SMALL`.
    where : numpy.ndarray, shape (4,)
        On failure: time [s], gear speed [rad/s], deepest approach [m], step [s].
    steps, evaluations : int
        Steps tried (accepted and rejected) and right-hand side evaluations.
    """
    stages = b.size
    n = y0.size
    k = np.empty((stages + 1, n))
    y = y0.copy()
    y_stage = np.empty(n)
    y_new = np.empty(n)
    d = np.empty(n)
    d3 = np.empty(n)
    weights = b.reshape((1, stages))
    states = np.full((times.size, n), np.nan)
    where = np.zeros(4)
    t = times[0]
    states[0] = y
    # the first row as an int64, not the literal 0: the driveline's rates (cached on their
    # own) would compile once more for a literal argument
    first = stages - stages
    deepest = _rates(kind, t, y, k, first, system, params, sides, table)
    f = k[0].copy()
    evaluations = 1
    steps = 0
    h = min(max_step, 1e-7)
    for r in range(1, times.size):
        t_end = times[r]
        while t < t_end:
            min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
            rejected = False
            while True:
                if h < min_step:
                    where[0], where[1], where[2], where[3] = t, y[speed_index], deepest, h
                    return states, STEP_TOO_SMALL, where, steps, evaluations
                step = h if t + h < t_end else t_end - t
                steps += 1
                for i in range(n):  # (element loops: an array assignment may copy)
                    k[0, i] = f[i]
                # (each state's sums over the stages in the stages' order, as scipy's)
                for s in range(1, stages):
                    _combine(a, s, s, k, y, step, d, y_stage)
                    _rates(kind, t + c[s] * step, y_stage, k, s, system, params, sides, table)
                _combine(weights, 0, stages, k, y, step, d, y_new)
                deepest_new = _rates(kind, t + step, y_new, k, stages, system, params, sides,
                                     table)
                evaluations += stages
                # Error norm (scipy's RMS norm; DOP853's blend of its 5th- and
                # 3rd-order estimates).
                d[:] = 0.0
                d3[:] = 0.0
                for j in range(stages + 1):
                    ej, e3j = e[j], e3[j]
                    for i in range(n):
                        d[i] += ej * k[j, i]
                        d3[i] += e3j * k[j, i]
                e5 = e3n = 0.0
                for i in range(n):
                    scale = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
                    e5 += (d[i] / scale) ** 2
                    e3n += (d3[i] / scale) ** 2
                if blended:
                    error = 0.0 if e5 == 0.0 and e3n == 0.0 else \
                        step * e5 / math.sqrt((e5 + 0.01 * e3n) * float(n))
                else:
                    error = step * math.sqrt(e5 / float(n))
                if not error == error:  # NaN: the state blew up inside the step
                    where[0], where[1] = t + step, y_new[speed_index]
                    where[2], where[3] = deepest_new, step
                    return states, BLOW_UP, where, steps, evaluations
                if error < 1.0:
                    factor = _MAX_FACTOR if error == 0.0 else min(
                        _MAX_FACTOR, _SAFETY * error ** error_exponent)
                    if rejected:
                        factor = min(1.0, factor)
                    # A step cut short at a record instant keeps the step it had.
                    h = max(h, step * factor) if step < h else step * factor
                    h = min(h, max_step)
                    break
                h = step * max(_MIN_FACTOR, _SAFETY * error ** error_exponent)
                rejected = True
            t = t_end if step == t_end - t else t + step
            for i in range(n):
                y[i] = y_new[i]
                f[i] = k[stages, i]
            deepest = deepest_new
            w = y[speed_index]
            if not (math.isfinite(w) and math.isfinite(deepest)) or deepest > depth_limit \
                    or abs(w) > speed_limit:
                where[0], where[1], where[2], where[3] = t, w, deepest, step
                return states, BLOW_UP, where, steps, evaluations
        for i in range(n):
            states[r, i] = y[i]
    return states, OK, where, steps, evaluations


@njit(cache=True)
def pinion_states(times, speed, ramp_time):
    """:func:`lsbg.dynamics.settings.pinion_state` over an array of times."""
    out = np.empty((times.size, 2))
    for i in range(times.size):
        out[i, 0], out[i, 1] = pinion_state(times[i], speed, ramp_time)
    return out


def run_compiled(model, settings: SimulationSettings):
    """Integrate ``model`` with the compiled embedded Runge-Kutta loop.

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : SimulationSettings
        ``compiled_method``, ``rtol``, ``atol_angle`` and ``atol_speed`` set
        the integration; the largest step is the output interval.

    Returns
    -------
    lsbg.dynamics.RunRecord
        Its ``steps``: the steps tried, accepted and rejected [-].

    Raises
    ------
    SimulationError
        On a blow-up or a step size below what double precision resolves.
    """
    _, times, _ = settings.record_grid()
    angle, speed = settings.atol_angle, settings.atol_speed
    if settings.boundary == "driveline":
        y0, system = model.driveline_problem(settings)
        kind, atol, index = DRIVELINE, np.array([angle] * 3 + [speed] * 3), 4
    else:
        y0 = np.array([model.initial_gear_angle(settings), 0.0])
        system = np.array([settings.pinion_speed, settings.ramp_time, settings.load_torque,
                           model.gear_inertia])
        kind, atol, index = PRESCRIBED, np.array([angle, speed]), 1
    start = time.monotonic()
    states, status, where, steps, _ = integrate(
        kind, times, y0, system, *model.contact.arrays, *tableau(settings.compiled_method),
        settings.rtol, atol, settings.duration / settings.samples, model.penetration_limit,
        model.speed_limit(settings), index)
    wall = time.monotonic() - start
    if status == STEP_TOO_SMALL:
        raise SimulationError(f"t = {where[0]:.9f} s: the compiled engine's step fell to "
                              f"{where[3]:.3g} s, below what double precision resolves "
                              f"(rtol {settings.rtol:g})")
    if status == BLOW_UP:
        model.check_state(where[0], where[1], where[2], settings)
        raise SimulationError(f"t = {where[0]:.9f} s: non-finite error estimate (gear speed "
                              f"{where[1]!r} rad/s)")
    if kind == DRIVELINE:
        pinion = states[:, [0, 3]]
        gear = states[:, [1, 4]]
    else:
        pinion = pinion_states(times, settings.pinion_speed, settings.ramp_time)
        gear = states
    return model.record(settings, times, pinion[:, 0], gear[:, 0], pinion[:, 1], gear[:, 1],
                        wall, steps)
