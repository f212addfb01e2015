"""The compiled engine: an embedded Runge-Kutta loop compiled with numba.

The system has one degree of freedom, the gear angle: the pinion follows its
prescribed motion, so J2 phi2'' = T_contact - T_load with the contact torque
of the compiled kernels (:mod:`lsbg.contact.kernels`). This engine integrates
that equation with an explicit embedded Runge-Kutta pair under adaptive step
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


@njit(cache=True)
def _derivative(t, phi2, w2, speed, ramp_time, load, inertia, params, sides, table):
    """(phi2', w2', deepest approach) of the gear under the prescribed pinion."""
    phi1, w1 = pinion_state(t, speed, ramp_time)
    torque, _, deepest, _, _, _ = mesh_forces(phi1, phi2, w1, w2, params, sides, table)
    return w2, (torque - load) / inertia, deepest


@njit(cache=True)
def integrate(times, phi2_0, w2_0, speed, ramp_time, load, inertia, params, sides, table,
              a, b, c, e, e3, blended, error_exponent, rtol, atol_angle, atol_speed, max_step,
              depth_limit, speed_limit):
    """Integrate the gear's motion and return its state at ``times``.

    Parameters
    ----------
    times : numpy.ndarray
        Increasing record instants, the first the initial time [s].
    phi2_0, w2_0 : float
        Initial gear rotation [rad] and speed [rad/s].
    speed, ramp_time : float
        The pinion's final speed [rad/s] and ramp duration [s].
    load, inertia : float
        Load torque on the gear [N m] and its axial inertia [kg m^2].
    params, sides, table : numpy.ndarray
        The contact model (:class:`lsbg.contact.MeshContact`).
    a, b, c, e, e3, blended, error_exponent
        The tableau (:func:`tableau`).
    rtol : float
        Relative tolerance [-].
    atol_angle, atol_speed : float
        Absolute tolerances [rad, rad/s].
    max_step : float
        Largest step [s].
    depth_limit, speed_limit : float
        Penetration [m] and gear speed [rad/s] beyond which the run stops.

    Returns
    -------
    states : numpy.ndarray, shape (len(times), 2)
        Gear rotation and speed at ``times`` (rows after a failure are NaN).
    status : int
        :data:`OK`, :data:`BLOW_UP` or :data:`STEP_TOO_SMALL`.
    where : numpy.ndarray, shape (4,)
        On failure: time [s], gear speed [rad/s], deepest approach [m], step [s].
    steps, evaluations : int
        Steps tried (accepted and rejected) and right-hand side evaluations.
    """
    stages = b.size
    k_phi = np.empty(stages + 1)
    k_w = np.empty(stages + 1)
    states = np.full((times.size, 2), np.nan)
    where = np.zeros(4)
    t, phi, w = times[0], phi2_0, w2_0
    states[0, 0], states[0, 1] = phi, w
    f_phi, f_w, deepest = _derivative(t, phi, w, speed, ramp_time, load, inertia, params, sides,
                                      table)
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
                    where[0], where[1], where[2], where[3] = t, w, deepest, h
                    return states, STEP_TOO_SMALL, where, steps, evaluations
                step = h if t + h < t_end else t_end - t
                steps += 1
                k_phi[0], k_w[0] = f_phi, f_w
                for s in range(1, stages):
                    d_phi = 0.0
                    d_w = 0.0
                    for j in range(s):
                        d_phi += a[s, j] * k_phi[j]
                        d_w += a[s, j] * k_w[j]
                    k_phi[s], k_w[s], _ = _derivative(t + c[s] * step, phi + step * d_phi,
                                                      w + step * d_w, speed, ramp_time, load,
                                                      inertia, params, sides, table)
                d_phi = 0.0
                d_w = 0.0
                for j in range(stages):
                    d_phi += b[j] * k_phi[j]
                    d_w += b[j] * k_w[j]
                phi_new, w_new = phi + step * d_phi, w + step * d_w
                k_phi[stages], k_w[stages], deepest_new = _derivative(
                    t + step, phi_new, w_new, speed, ramp_time, load, inertia, params, sides, table)
                evaluations += stages
                # Error norm (scipy's RK45 norm; DOP853's blend of its 5th- and
                # 3rd-order estimates).
                scale_phi = atol_angle + rtol * max(abs(phi), abs(phi_new))
                scale_w = atol_speed + rtol * max(abs(w), abs(w_new))
                e5_phi = e3_phi = e5_w = e3_w = 0.0
                for j in range(stages + 1):
                    e5_phi += e[j] * k_phi[j]
                    e5_w += e[j] * k_w[j]
                    e3_phi += e3[j] * k_phi[j]
                    e3_w += e3[j] * k_w[j]
                e5 = (e5_phi / scale_phi) ** 2 + (e5_w / scale_w) ** 2
                if blended:
                    e3n = (e3_phi / scale_phi) ** 2 + (e3_w / scale_w) ** 2
                    error = 0.0 if e5 == 0.0 and e3n == 0.0 else \
                        step * e5 / math.sqrt((e5 + 0.01 * e3n) * 2.0)
                else:
                    error = step * math.sqrt(e5 / 2.0)
                if not error == error:  # NaN: the state blew up inside the step
                    where[0], where[1], where[2], where[3] = t + step, w_new, deepest_new, step
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
            phi, w = phi_new, w_new
            f_phi, f_w, deepest = k_phi[stages], k_w[stages], deepest_new
            if not (math.isfinite(w) and math.isfinite(deepest)) or deepest > depth_limit \
                    or abs(w) > speed_limit:
                where[0], where[1], where[2], where[3] = t, w, deepest, step
                return states, BLOW_UP, where, steps, evaluations
        states[r, 0], states[r, 1] = phi, w
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
    start = time.monotonic()
    states, status, where, steps, _ = integrate(
        times, model.initial_gear_angle(settings), 0.0, settings.pinion_speed,
        settings.ramp_time, settings.load_torque, model.gear_inertia, *model.contact.arrays,
        *tableau(settings.compiled_method), settings.rtol, settings.atol_angle,
        settings.atol_speed, settings.duration / settings.samples, model.penetration_limit,
        model.speed_limit(settings))
    wall = time.monotonic() - start
    if status == STEP_TOO_SMALL:
        raise SimulationError(f"t = {where[0]:.9f} s: the compiled engine's step fell to "
                              f"{where[3]:.3g} s, below what double precision resolves "
                              f"(rtol {settings.rtol:g})")
    if status == BLOW_UP:
        model.check_state(where[0], where[1], where[2], settings)
        raise SimulationError(f"t = {where[0]:.9f} s: non-finite error estimate (gear speed "
                              f"{where[1]!r} rad/s)")
    pinion = pinion_states(times, settings.pinion_speed, settings.ramp_time)
    return model.record(settings, times, pinion[:, 0], states[:, 0], pinion[:, 1], states[:, 1],
                        wall, steps)
