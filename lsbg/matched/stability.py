"""A design's stability: a proxy from the loaded TE, and the full run it screens for.

**The proxy.** The loaded transmission error at the load over one mesh cycle
(:func:`lsbg.optimise.loaded.loaded_points`, the line model on the uniform bed,
the search's model) is the quasi-static mesh deflection; its mesh harmonics
drive the system linearised about its mean mesh (Ozguven & Houser 1988: the
static TE as the mesh's displacement excitation). With the mesh's tangent
torsional stiffness at the load k_theta (the torque's change over the mean loaded
TE's, +-:data:`STEP` of the load: an ease-off that loads part of the line makes it
well below the conjugate flanks' mean) and the mesh's damping
c_theta = 2 zeta k_theta / omega_n (the line contact's stiffness-proportional
damping, omega_n its mesh mode at the conjugate mean stiffness,
:class:`lsbg.contact.MeshContact`), the mesh torque on the gear is

    T_m = k_theta (rho phi1 - phi2 - delta) + c_theta (rho phi1' - phi2' - delta'),

delta the loaded TE's fluctuation [rad] and rho = e1 / e2 (= z1 / z2). Under
``boundary = "driveline"`` the coordinates are (phi1, phi2, phi_v) of
:meth:`lsbg.dynamics.driveline.Driveline.matrices` (the drive end held); under
the prescribed pinion phi1's fluctuation is 0 and the gear (its own inertia)
rests on the mesh alone. Each harmonic k of the mesh frequency f_z = z1 W / (2 pi)
then gives the gear's speed and the mesh torque's fluctuation by the frequency
response (K - w^2 M + i w C)^-1 (k_theta + i w c_theta) delta_k [rho, -1, 0]; the
std of a steady periodic response is sqrt(sum_k 2 |y_k|^2) over the harmonics.

What the proxy leaves out (the full run has it): the mesh stiffness's own
variation over the cycle (parametric excitation), contact loss, and the
driveline's slow modes excited by the run's start. :func:`full_run_stds` is
the full run of the same design (:func:`lsbg.dynamics.simulate`, the line
model on the uniform bed), from which the proxy's error is measured.

The tangential force here is the mesh torque over the gear's outer pitch radius
(the runs' ``tangential_force_outer``, Eq. 13's quantity), which the proxy
gives; the runs' ``tangential_force`` sums the force at each point of action.

SI inside; a std of the gear's speed in deg/s and of the tangential force in N,
as the run datasets hold them.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["STABILITY_QUANTITIES", "BOUNDARIES", "harmonics", "response_stds", "proxy_stds",
           "full_run_stds", "uniform_bed_contact"]

#: The quantities of the stability answer (run dataset variables) [deg/s], [N].
STABILITY_QUANTITIES = ("gear_speed", "tangential_force_outer")
#: The relative torque step of the mesh's tangent stiffness [-].
STEP = 0.05
#: The boundaries each design is answered at (``simulation.boundary``).
BOUNDARIES = ("prescribed_pinion", "driveline")


def harmonics(values):
    """The complex amplitudes c_k, k = 1 .. n // 2, of one period's equally spaced samples.

    ``values(t) - mean = sum_k 2 Re(c_k exp(i k w t))`` (the Nyquist term, for an even
    n, halved so that the same sum holds).

    Parameters
    ----------
    values : array_like
        (n,) samples over one period, n >= 2.

    Returns
    -------
    numpy.ndarray of complex
        (n // 2,), the units of ``values``.
    """
    values = np.asarray(values, float)
    c = np.fft.rfft(values - values.mean())[1:] / values.size
    if values.size % 2 == 0:
        c[-1] *= 0.5
    return c


def response_stds(te, mesh_frequency, stiffness, damping, mass, shaft_stiffness,
                  shaft_damping, ratio, radius):
    """The steady stds of the gear's speed and the tangential force under a TE excitation.

    Parameters
    ----------
    te : array_like
        The loaded TE over one mesh cycle at equally spaced positions [rad at the gear].
    mesh_frequency : float
        f_z [Hz].
    stiffness, damping : float
        k_theta [N m/rad] and c_theta [N m s/rad] of the mesh at the gear.
    mass : numpy.ndarray
        (n, n) inertias [kg m^2]; coordinates (phi1, phi2, ...) or, n = 1, (phi2,).
    shaft_stiffness, shaft_damping : numpy.ndarray
        (n, n) the stiffness and the damping of everything but the mesh [N m/rad],
        [N m s/rad].
    ratio : float
        rho [-].
    radius : float
        The radius the tangential force is the mesh torque over [m].

    Returns
    -------
    dict
        ``gear_speed`` [deg/s] and ``tangential_force_outer`` [N] (the mesh torque
        over ``radius``): their stds.
    """
    c = harmonics(te)
    n = len(mass)
    # the mesh's coupling vector: the deflection rho phi1 - phi2 (phi2 alone for n = 1)
    g = np.array([-1.0]) if n == 1 else np.r_[ratio, -1.0, np.zeros(n - 2)]
    gear = 0 if n == 1 else 1
    mesh_k = stiffness * np.outer(g, g)
    mesh_c = damping * np.outer(g, g)
    speed2, torque2 = 0.0, 0.0
    for k, ck in enumerate(c, start=1):
        w = 2 * math.pi * k * mesh_frequency
        mesh = stiffness + 1j * w * damping
        dynamic = shaft_stiffness + mesh_k - w**2 * mass + 1j * w * (shaft_damping + mesh_c)
        x = np.linalg.solve(dynamic, mesh * ck * g)
        speed2 += 2 * abs(1j * w * x[gear]) ** 2
        torque2 += 2 * abs(mesh * (g @ x - ck)) ** 2
    return {"gear_speed": math.degrees(math.sqrt(speed2)),
            "tangential_force_outer": math.sqrt(torque2) / radius}


def uniform_bed_contact(model):
    """Whether ``model``'s contact is the line model on the uniform bed (the proxy's)."""
    p = model.contact.params
    return p.model == "line" and model.contact.slice_stiffness is None


def proxy_stds(model, boundary, load_torque, pinion_speed, phases=32):
    """The proxy's stds of one design (module docstring).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
        The design's model (:func:`lsbg.dynamics.load_model` on its flanks, the line
        model on the uniform bed; a driveline for ``boundary = "driveline"``).
    boundary : str
        One of :data:`BOUNDARIES`.
    load_torque : float
        The gear's load [N m].
    pinion_speed : float
        W [rad/s].
    phases : int
        Positions of the loaded TE over one base pitch [-], >= 4.

    Returns
    -------
    dict
        ``gear_speed`` [deg/s], ``tangential_force_outer`` [N] (the mesh torque over
        the gear's outer pitch radius, as the run's variable of that name),
        ``te_peak_to_peak`` [rad].
    """
    from lsbg.optimise.loaded import loaded_points

    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary = {boundary!r}: one of {', '.join(BOUNDARIES)}")
    if not uniform_bed_contact(model):
        raise ValueError("the proxy is defined for the line model on the uniform bed")
    contact = model.contact
    torques = load_torque * (1.0 + np.array([0.0, -STEP, STEP]))
    te = loaded_points(contact, torques, phases).transmission_error
    # the mesh's tangent stiffness at the load: the torque over the mean TE's change
    k_theta = 2 * STEP * load_torque / (te[2].mean() - te[1].mean())
    te = te[0]
    # the line contact's damping is stiffness-proportional, c = 2 zeta k / omega_n with
    # omega_n the mesh mode at the conjugate flanks' mean stiffness (MeshContact)
    omega_n = 2 * math.pi * contact.natural_frequency(contact.gear_inertia)
    c_theta = 2 * contact.params.damping_ratio * k_theta / omega_n
    design = model.pair.design
    ratio = contact.e1 / contact.e2
    if boundary == "driveline":
        if model.driveline is None:
            raise ValueError("boundary = 'driveline': the model has no driveline")
        d = model.driveline
        # everything but the mesh: the matrices at no mesh stiffness
        mass, shaft_stiffness = d.matrices(0.0, ratio)
        cp, ch = d.damping(ratio)
        shaft_damping = np.array([[cp, 0, 0], [0, ch, -ch], [0, -ch, ch]])
    else:
        mass = np.array([[model.gear_inertia]])
        shaft_stiffness = shaft_damping = np.zeros((1, 1))
    frequency = design.pinion_teeth * pinion_speed / (2 * math.pi)
    out = response_stds(te, frequency, k_theta, c_theta, mass, shaft_stiffness, shaft_damping,
                        ratio, design.pitch_diameter(2) / 2)
    out["te_peak_to_peak"] = float(np.ptp(te))
    return out


def full_run_stds(model, settings, start):
    """The stds of one design's full run (:meth:`lsbg.dynamics.MeshingModel.run`).

    Parameters
    ----------
    model : lsbg.dynamics.MeshingModel
        The design's model (as :func:`proxy_stds`').
    settings : lsbg.dynamics.SimulationSettings
        Its ``boundary`` the boundary answered.
    start : float
        Start of the steady state [s].

    Returns
    -------
    dict
        ``gear_speed`` [deg/s], ``tangential_force_outer`` [N] (the contact torque
        over the gear's outer pitch radius, as the proxy's), ``wall_time`` [s].

    Raises
    ------
    lsbg.dynamics.SimulationError
        If the run blows up.
    """
    from lsbg.aggregate.runs import full_rate_series
    from lsbg.dynamics.dataset import run_dataset

    ds = run_dataset(model.run(settings), model, settings)
    return {name: float(np.std(full_rate_series(ds, name, start)))
            for name in STABILITY_QUANTITIES} | {"wall_time": float(ds.attrs["wall_time_s"])}
