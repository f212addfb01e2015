"""The line model at rest: the mismatch at which the mesh carries a torque.

A compiled root search on the kernels of :mod:`lsbg.contact.kernels` (the
loaded TCA, :meth:`lsbg.contact.mesh.MeshContact.static_gear_angle`, solves
it at every mesh position).
"""

import math

from numba import njit

from lsbg.contact.kernels import _mesh

__all__ = ["static_mismatch"]


@njit(cache=True)
def _static_residual(eps, phi1, base, e2, load, params, sides, table):
    return _mesh(phi1, base - eps / e2, 0.0, 0.0, params, sides, table, None, None)[0] - load


@njit(cache=True)
def static_mismatch(phi1, base, e2, load, limit, params, sides, table):
    """Drive-side mismatch at which the mesh carries a torque at rest.

    The torque at rest grows monotonically with the mismatch eps (the flanks
    pressed together). The root is bracketed by doubling from 1e-6 rad and
    found by regula falsi with the Illinois modification (superlinear, and
    the bracket never lost), to ``1e-18 + 1e-14 eps`` as scipy's brentq in
    :meth:`lsbg.contact.mesh.MeshContact.static_gear_angle` did at 60 times
    the cost.

    Parameters
    ----------
    phi1 : float
        Pinion rotation [rad].
    base : float
        Gear rotation with the flanks just touching [rad].
    e2 : float
        sin(delta_b2) [-].
    load : float
        Torque to carry [N m], > 0.
    limit : float
        Largest mismatch searched [rad].
    params, sides, table : numpy.ndarray
        The model (:func:`mesh_forces`).

    Returns
    -------
    float
        eps [rad]: the gear rotation is ``base - eps / e2`` (negative where
        real flanks interfere at the kinematic position); NaN if the torque
        stays below ``load`` up to ``limit`` (or above it down to -limit).
    """
    a, fa = 0.0, _static_residual(0.0, phi1, base, e2, load, params, sides, table)
    b = 1e-6
    fb = _static_residual(b, phi1, base, e2, load, params, sides, table)
    while fb < 0.0:
        a, fa = b, fb
        b *= 2.0
        if b > limit:
            return math.nan
        fb = _static_residual(b, phi1, base, e2, load, params, sides, table)
    if fa >= 0.0:
        # Real flanks can interfere at the kinematic position (a displacement
        # into mesh): bracket below 0 instead.
        b, fb = a, fa
        a = -1e-6
        fa = _static_residual(a, phi1, base, e2, load, params, sides, table)
        while fa >= 0.0:
            b, fb = a, fa
            a *= 2.0
            if a < -limit:
                return math.nan
            fa = _static_residual(a, phi1, base, e2, load, params, sides, table)
    side = 0
    c = b
    for _ in range(200):
        c = (a * fb - b * fa) / (fb - fa)
        if not a < c < b:
            c = 0.5 * (a + b)
        fc = _static_residual(c, phi1, base, e2, load, params, sides, table)
        if fc == 0.0:
            return c
        if fc < 0.0:
            a, fa = c, fc
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa *= 0.5
            side = 1
        if b - a <= 1e-18 + 1e-14 * abs(c):
            break
    return c
