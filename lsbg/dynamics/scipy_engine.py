"""The scipy engine: the equations of motion with scipy's ODE solvers.

Under the prescribed pinion,
J2 phi2'' = T_contact(phi1(t), phi2, omega1(t), omega2) - T_load, with the
pinion's prescribed motion in closed form (:func:`lsbg.dynamics.settings.pinion_state`);
under the driveline boundary, the compiled equations of
:func:`lsbg.dynamics.driveline.driveline_rates` (pinion, gear and vehicle).
LSODA at rtol 1e-8 is the default (DOP853 agrees to 0.02 % in the standard
deviations and takes 3x longer). This engine is the maintained, independent
reference of the compiled one: the same right-hand side, a different solver
driven from Python.

LSODA runs through :func:`scipy.integrate.odeint`, ODEPACK's own driver: the
steps and the interpolation to the record instants stay in Fortran and only
the right-hand side calls Python. :func:`scipy.integrate.solve_ivp` wraps the
same LSODA with a Python call per step, several times slower for the same
right-hand side evaluations. The other methods run through solve_ivp.
"""

from __future__ import annotations

import time

import numpy as np

from lsbg.contact import kernels
from lsbg.dynamics.driveline import STATES, driveline_rates
from lsbg.dynamics.settings import SimulationError, SimulationSettings, pinion_state


def run_scipy(model, settings: SimulationSettings):
    """Integrate ``model`` with odeint (LSODA) or solve_ivp (the other methods).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
    settings : SimulationSettings

    Returns
    -------
    lsbg.dynamics.RunRecord
        Its ``steps``: the right-hand side evaluations [-].

    Raises
    ------
    SimulationError
        If the solver fails or the state blows up.
    """
    arrays = model.contact.arrays
    counter = {"n": 0, "last": time.monotonic()}
    start = time.monotonic()

    def checked(t, gear_speed, deepest):
        counter["n"] += 1
        if counter["n"] % 20000 == 0:
            model.check_state(t, gear_speed, deepest, settings)
            counter["last"] = model.progress(t, settings, start, counter["last"])

    _, times, _ = settings.record_grid()
    if settings.boundary == "driveline":
        y0, system = model.driveline_problem(settings)
        rates = kernels.compiled_entry(driveline_rates, 0.0, y0, np.empty((1, STATES)), 0,
                                       system, *arrays)

        def rhs(t, y):
            out = np.empty((1, STATES))
            checked(t, y[4], rates(t, np.ascontiguousarray(y, dtype=float), out, 0, system,
                                   *arrays))
            return out[0]

        atol = [settings.atol_angle] * 3 + [settings.atol_speed] * 3
        states = _solve(rhs, y0, times, settings, atol)
        return model.record(settings, times, states[0], states[1], states[3], states[4],
                            time.monotonic() - start, counter["n"])
    forces = kernels.compiled_entry(kernels.mesh_forces, 0.0, 0.0, 0.0, 0.0, *arrays)
    inertia, load = model.gear_inertia, settings.load_torque
    w, tr = settings.pinion_speed, settings.ramp_time

    def rhs(t, y):
        phi1, w1 = pinion_state(t, w, tr)
        phi2, w2 = float(y[0]), float(y[1])
        torque, _, deepest, _, _, _ = forces(phi1, phi2, w1, w2, *arrays)
        checked(t, w2, deepest)
        return (w2, (torque - load) / inertia)

    y0 = [model.initial_gear_angle(settings), 0.0]
    angle, speed = _solve(rhs, y0, times, settings, [settings.atol_angle, settings.atol_speed])
    pinion = [pinion_state(t, w, tr) for t in times]
    return model.record(settings, times, [p[0] for p in pinion], angle, [p[1] for p in pinion],
                        speed, time.monotonic() - start, counter["n"])


def _solve(rhs, y0, times, settings, atol):
    """The states at ``times``, one row per state: odeint (LSODA) or solve_ivp."""
    from scipy.integrate import solve_ivp

    max_step = settings.duration / settings.samples
    if settings.method == "LSODA":
        return _odeint(rhs, y0, times, settings.rtol, atol, max_step)
    solution = solve_ivp(rhs, (0.0, settings.duration), y0, method=settings.method,
                         t_eval=times, rtol=settings.rtol, atol=atol, max_step=max_step)
    if solution.status != 0:
        raise SimulationError(f"solve_ivp ({settings.method}) failed: {solution.message}")
    return solution.y


def _odeint(rhs, y0, times, rtol, atol, max_step):
    """LSODA through odeint: the states at ``times``, one row per state [rad, rad/s]."""
    import warnings

    from scipy.integrate import odeint

    with warnings.catch_warnings():
        # a failure is raised below with ODEPACK's message
        warnings.simplefilter("ignore")
        solution, info = odeint(rhs, y0, times, rtol=rtol, atol=atol, hmax=max_step,
                                mxstep=_MAX_STEPS_PER_INTERVAL, full_output=True, tfirst=True)
    if info["message"] != "Integration successful.":
        raise SimulationError(f"odeint (LSODA) failed: {info['message']}")
    return solution.T


#: odeint's step limit between two record instants (its default, 500, is too
#: few before the full-rate record starts: about 1200 steps per 2 ms there).
_MAX_STEPS_PER_INTERVAL = 10**6
