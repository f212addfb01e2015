"""Local contact: the flanks' relative curvature, Hertz's pressure and approach.

The finite elements (:mod:`lsbg.tooth.compliance`) give the deflection of the
tooth's middle surface; between it and the flank lies the local contact
deformation, nonlinear in load. Along a contact line the flanks touch as two
cylinders whose radii are those of the flanks' normal sections across the
line (the line contact of Hertz, Johnson 1985 §4.2 and §5.6): per unit length
q [N/m],

* half width b = sqrt(4 q R / (pi E*)) and peak pressure p0 = sqrt(q E* / (pi R)),
  1/R = kappa_1 + kappa_2 the relative curvature across the line;
* the approach of each flank to its tooth's middle surface at depth h (the half
  thickness), delta_i = q (1 - nu^2)/(pi E) [2 ln(2 h / b) - nu/(1 - nu)]
  (:func:`lsbg.tooth.reference.line_contact_approach`, Weber and Banaschek's
  form of it).

The curvatures are those of lsbg's exact flanks, by central differences of
:meth:`lsbg.geometry.GearPair.flank`; the direction across the line is the
flank's tangent perpendicular to the contact line, whose direction on the
flank is that of the generating curve.

SI units.
"""

from __future__ import annotations

import numpy as np

from lsbg.tooth.reference import line_contact_approach, line_contact_half_width, reduced_modulus

__all__ = ["normal_curvature_across", "relative_curvature", "local_approach", "peak_pressure"]


def normal_curvature_across(pair, member, cone_distance, profile_angle, step=1e-6):
    """Normal curvature of a member's drive flank across the contact line [1/m].

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    member : {1, 2}
    cone_distance, profile_angle : array_like
        Contact point (rho [m], psi [rad]) in the drive side's plane of action.
    step : float
        Relative finite-difference step [-].

    Returns
    -------
    numpy.ndarray
        Curvature, positive where the flank is convex (seen from outside the
        tooth) [1/m].
    """
    from lsbg.tooth.compliance import drive_flank, member_polar_angle

    plane = pair.planes["drive"]
    rho = np.atleast_1d(np.asarray(cone_distance, float))
    psi = np.broadcast_to(np.asarray(profile_angle, float), rho.shape)

    def surface(r, t):
        return pair.flank(member, "drive", r, member_polar_angle(pair, member, r, t))

    h_r = step * rho
    h_t = step * np.ones_like(rho)
    _, n = surface(rho, psi)
    _, outward, _ = drive_flank(pair, member, rho, member_polar_angle(pair, member, rho, psi))
    xr1, nr1 = surface(rho + h_r, psi)
    xr0, nr0 = surface(rho - h_r, psi)
    xt1, nt1 = surface(rho, psi + h_t)
    xt0, nt0 = surface(rho, psi - h_t)
    sign = np.sum(outward * n, axis=-1)[..., None]
    x_r, x_t = (xr1 - xr0) / (2 * h_r[:, None]), (xt1 - xt0) / (2 * h_t[:, None])
    n_r, n_t = sign * (nr1 - nr0) / (2 * h_r[:, None]), sign * (nt1 - nt0) / (2 * h_t[:, None])
    # the contact line's direction on the flank: along rho at psi = turn + theta(rho)
    slope = (plane.curve.polar_angle(rho + h_r) - plane.curve.polar_angle(rho - h_r)) / (2 * h_r)
    line = x_r + slope[:, None] * x_t
    across = np.cross(outward, line)
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    # express "across" in the (x_r, x_t) basis, then kappa = (dN . dX) / (dX . dX)
    basis = np.stack([x_r, x_t], axis=2)  # (n, 3, 2)
    gram = np.einsum("nia,nib->nab", basis, basis)
    rhs = np.einsum("nia,ni->na", basis, across)
    ab = np.linalg.solve(gram, rhs[..., None])[..., 0]
    dx = ab[:, :1] * x_r + ab[:, 1:] * x_t
    dn = ab[:, :1] * n_r + ab[:, 1:] * n_t
    return np.sum(dn * dx, axis=1) / np.sum(dx * dx, axis=1)


def relative_curvature(pair, cone_distance, profile_angle):
    """Relative curvature 1/R = kappa_1 + kappa_2 of the drive flanks across the line [1/m].

    Parameters
    ----------
    pair : lsbg.geometry.GearPair
    cone_distance, profile_angle : array_like
        Contact points in the plane of action [m, rad].

    Returns
    -------
    numpy.ndarray
    """
    return (normal_curvature_across(pair, 1, cone_distance, profile_angle)
            + normal_curvature_across(pair, 2, cone_distance, profile_angle))


def peak_pressure(load_per_length, curvature, young_modulus, poisson_ratio):
    """Hertz peak pressure of line contact [Pa], zero where unloaded.

    Parameters
    ----------
    load_per_length : array_like
        q [N/m], >= 0.
    curvature : array_like
        Relative curvature 1/R [1/m], > 0.
    young_modulus, poisson_ratio : float
        Both members' E [Pa] and nu [-].

    Returns
    -------
    numpy.ndarray
    """
    from lsbg.tooth.reference import line_contact_peak_pressure

    q = np.asarray(load_per_length, float)
    curvature = np.broadcast_to(np.asarray(curvature, float), q.shape)
    out = np.zeros(q.shape)
    loaded = q > 0
    if np.any(loaded):
        e_star = reduced_modulus(young_modulus, poisson_ratio, young_modulus, poisson_ratio)
        out[loaded] = line_contact_peak_pressure(q[loaded], 1.0 / curvature[loaded], e_star)
    return out


def local_approach(load_per_length, curvature, depth_pinion, depth_gear, young_modulus,
                   poisson_ratio):
    """Local contact approach of both flanks to their teeth's middle surfaces [m].

    Parameters
    ----------
    load_per_length : array_like
        q [N/m], >= 0.
    curvature : array_like
        Relative curvature across the contact line [1/m].
    depth_pinion, depth_gear : array_like
        Half thickness of each tooth under the point [m].
    young_modulus, poisson_ratio : float
        E [Pa], nu [-].

    Returns
    -------
    numpy.ndarray
        Sum of both members' approach; zero where unloaded.
    """
    q = np.asarray(load_per_length, float)
    shape = q.shape
    curvature, h1, h2 = (np.broadcast_to(np.asarray(v, float), shape)
                         for v in (curvature, depth_pinion, depth_gear))
    out = np.zeros(shape)
    loaded = q > 0
    if np.any(loaded):
        e_star = reduced_modulus(young_modulus, poisson_ratio, young_modulus, poisson_ratio)
        b = line_contact_half_width(q[loaded], 1.0 / curvature[loaded], e_star)
        # the formula holds for h >> b; a load so high that b nears h is far
        # beyond any gear's, and the approach is kept from turning negative
        both = line_contact_approach(np.tile(q[loaded], 2), young_modulus, poisson_ratio,
                                     np.tile(b, 2), np.concatenate([h1[loaded], h2[loaded]]))
        out[loaded] = np.maximum(both, 0.0).reshape(2, -1).sum(axis=0)
    return out
