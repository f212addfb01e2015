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
:meth:`lsbg.gear.geometry.GearPair.flank`; the direction across the line is the
flank's tangent perpendicular to the contact line, whose direction on the
flank is that of the generating curve.

SI units.
"""

from __future__ import annotations

import numpy as np

from lsbg.gear.flank import drive_flank, member_polar_angle
from lsbg.tooth.reference import line_contact_approach, line_contact_half_width, reduced_modulus

__all__ = ["normal_curvature_across", "relative_curvature", "local_approach", "peak_pressure",
           "HertzLines"]


def normal_curvature_across(pair, member, cone_distance, profile_angle, step=1e-6):
    """Normal curvature of a member's drive flank across the contact line [1/m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
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
    pair : lsbg.gear.geometry.GearPair
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

    Notes
    -----
    Per member, delta = q A [2 ln(2 h/b) - nu/(1 - nu)] with A = (1 - nu^2)/(pi E)
    grows with q while its bracket exceeds 1 (d delta/d q = A (bracket - 1),
    as b ~ sqrt(q)), peaks where the bracket is 1 (b = 2 h exp(-(1 + nu/(1 - nu))/2),
    about h: the formula, made for b << h, is out of its range) and then
    falls to zero. A load per length so high is beyond a gear's, except on a
    band that the field of contact cuts to a sliver of its length: with an
    approach that fell as its load rose, such a band turned into a rigid post
    in the LTCA (kilonewtons on a micrometre of line, q ~ 6e9 N/m, a "Hertz
    pressure" of 1e5 MPa), and the contact problem lost the monotonicity that
    makes its solution unique. Past the maximum the bracket is held at 1:
    delta = q A, continuous and increasing. Below it (b < ~h, every load of a
    whole band) nothing changes.
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
        q2 = np.tile(q[loaded], 2)
        both = line_contact_approach(q2, young_modulus, poisson_ratio, np.tile(b, 2),
                                     np.concatenate([h1[loaded], h2[loaded]]))
        # beyond the formula's maximum (its bracket down to 1, b ~ h) it would
        # fall to zero: held at the bracket's 1 there, see the function's notes
        floor = q2 * (1 - poisson_ratio**2) / (np.pi * young_modulus)
        out[loaded] = np.maximum(both, floor).reshape(2, -1).sum(axis=0)
    return out


class HertzLines:
    """Local approach of a fixed set of line contacts and its derivative, for solvers.

    :func:`local_approach` in the form a Newton iteration needs: inputs
    checked once, the constants of each contact prepared once, and the load
    the contact problem solves for (the force on a band of length l, not q).
    Per member k, with A = (1 - nu^2)/(pi E) and b = sqrt(4 q R/(pi E*)),

        delta_k = q A [2 ln(2 h_k/b) - nu/(1 - nu)],
        d delta_k/d q = delta_k/q - A        (b ~ sqrt(q): d ln b/d q = 1/(2 q)),

    the bracket held at 1 past the maximum as in :func:`local_approach`
    (delta_k = q A, derivative A there).

    Parameters
    ----------
    length : array_like
        Length l of each band [m], > 0.
    curvature : array_like
        Relative curvature 1/R across the contact line [1/m], > 0.
    depth_pinion, depth_gear : array_like
        Half thickness of each tooth under the point [m], > 0.
    young_modulus, poisson_ratio : float
        E [Pa], nu [-] of both members.
    """

    def __init__(self, length, curvature, depth_pinion, depth_gear, young_modulus,
                 poisson_ratio):
        from lsbg.tooth.reference import _poisson, _positive

        self.length = _positive("length", length)
        shape = self.length.shape
        curvature, h1, h2 = (np.broadcast_to(_positive(name, v), shape) for name, v in (
            ("curvature", curvature), ("depth_pinion", depth_pinion),
            ("depth_gear", depth_gear)))
        e = float(_positive("young_modulus", young_modulus))
        nu = float(_poisson(poisson_ratio))
        e_star = reduced_modulus(e, nu, e, nu)
        self._a = (1 - nu**2) / (np.pi * e)
        # b^2 = (4 R/(pi E*)) q: the part of 2 ln(2 h/b) that does not depend on q
        width = 4.0 / (curvature * np.pi * e_star)
        self._constant = np.stack([2 * np.log(2 * h1) - np.log(width) - nu / (1 - nu),
                                   2 * np.log(2 * h2) - np.log(width) - nu / (1 - nu)])

    def _bracket(self, forces):
        q = np.asarray(forces, float) / self.length
        loaded = q > 0
        bracket = np.maximum(self._constant - np.log(np.where(loaded, q, 1.0)), 1.0)
        return q, loaded, bracket

    def approach(self, forces):
        """Both members' local approach under the band forces [N] [m]; 0 where unloaded."""
        q, loaded, bracket = self._bracket(forces)
        return np.where(loaded, q * self._a * bracket.sum(axis=0), 0.0)

    def tangent(self, forces):
        """Derivative of :meth:`approach` by each band's own force [m/N].

        Infinite (logarithmically) as a force tends to 0: where a force is 0
        it is returned as ``inf``; a solver linearises there otherwise.
        """
        _, loaded, bracket = self._bracket(forces)
        slope = self._a * np.where(bracket > 1.0, bracket - 1.0, 1.0).sum(axis=0)
        return np.where(loaded, slope / self.length, np.inf)
