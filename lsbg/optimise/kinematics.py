"""The contact's speeds and the flanks' relative curvature at points of the plane of action.

Both axes pass through the apex, so the surface velocity of member i at a
point p is omega_i u_i x p (u_i its forward rotation axis, omega_2 = omega_1
z1/z2). The relative angular velocity omega_1 u_1 - omega_2 u_2 lies along the
pitch line, which lies in the plane of action: the **sliding velocity**
v_1 - v_2 is normal to that plane, along its normal N, and vanishes on the
pitch line (DESIGN.md §2). The contact lines move within the plane of action,
so the surfaces' velocities along N relative to the contact are their own:
the **sum (rolling) speed** across the contact line, which drags the oil into
the contact, is V_sum = |(v_1 + v_2) . N| and the entrainment speed V_sum/2
(the tangent plane of the flanks holds N and the contact line). These are the
exact kinematics of the pair, not the virtual cylindrical gear's.

The **relative curvature** across the contact line, 1/R = kappa_1 + kappa_2,
is :func:`lsbg.tooth.local.relative_curvature` of the exact flanks,
tabulated once per pair over the bands' distances from the apex and the
field's width and interpolated (linearly in the radius R, which runs nearly
linearly along the profile, as :class:`lsbg.tooth.contact_points.FECompliance`
does). Where the field ends on a base cone's tangency line (a small pinion's
undercut) the radius goes to zero: the table stops short of it by 0.5 % of the
field's width, and points beyond take the value there.

SI units.
"""

from __future__ import annotations

import numpy as np

__all__ = ["contact_speeds", "CurvatureTable", "CURVATURE_POINTS"]

#: Points of the curvature table across the field of contact [-].
CURVATURE_POINTS = 121
#: The table's inset from an edge on a base cone's tangency line, as a fraction
#: of the field's width [-].
TANGENCY_INSET = 0.005


def contact_speeds(pair, cone_distance, profile_angle, pinion_speed):
    """Sliding and sum speeds of the drive flanks at points of the plane of action.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    cone_distance, profile_angle : array_like
        (rho [m], psi [rad]) in the drive side's plane of action, broadcast.
    pinion_speed : float
        omega_1, forward [rad/s].

    Returns
    -------
    sliding : numpy.ndarray
        |v_1 - v_2| [m/s]; 0 on the pitch line.
    rolling : numpy.ndarray
        Sum of the surfaces' speeds across the contact line, |(v_1 + v_2) . N|
        [m/s] (twice the entrainment speed).
    """
    plane = pair.planes["drive"]
    z1, z2 = pair.design.teeth
    point = plane.point(cone_distance, profile_angle)
    v1 = pinion_speed * np.cross(pair.rotation_axis[1], point)
    v2 = pinion_speed * z1 / z2 * np.cross(pair.rotation_axis[2], point)
    return np.linalg.norm(v1 - v2, axis=-1), np.abs((v1 + v2) @ plane.normal)


class CurvatureTable:
    """Relative curvature of the drive flanks across the contact line over the field.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    cone_distances : array_like
        Distances from the apex the table holds (the line model's band
        centres, and the face's ends) [m], increasing.
    points : int
        Points across the field of contact [-].
    """

    def __init__(self, pair, cone_distances, points=CURVATURE_POINTS):
        from lsbg.tooth.local import relative_curvature

        plane = pair.planes["drive"]
        psi_lo, psi_hi = plane.field[:2]
        inset = TANGENCY_INSET * (psi_hi - psi_lo)
        tangency = np.array(list(plane.tangency_angle.values()))
        lo = psi_lo + (inset if np.any(np.abs(tangency - psi_lo) < inset) else 0.0)
        hi = psi_hi - (inset if np.any(np.abs(tangency - psi_hi) < inset) else 0.0)
        self.rho = np.asarray(cone_distances, dtype=float)
        self.psi = np.linspace(lo, hi, int(points))
        rho, psi = np.meshgrid(self.rho, self.psi, indexing="ij")
        curvature = relative_curvature(pair, rho.ravel(), psi.ravel()).reshape(rho.shape)
        #: relative radius of curvature R [m] on the table
        self.radius = 1.0 / curvature

    def __call__(self, cone_distance, profile_angle):
        """Relative curvature 1/R at points (rho [m], psi [rad]) [1/m], bilinear in R."""
        rho = np.clip(np.asarray(cone_distance, float), self.rho[0], self.rho[-1])
        psi = np.clip(np.asarray(profile_angle, float), self.psi[0], self.psi[-1])
        i = np.clip(np.searchsorted(self.rho, rho) - 1, 0, self.rho.size - 2)
        j = np.clip(np.searchsorted(self.psi, psi) - 1, 0, self.psi.size - 2)
        wi = (rho - self.rho[i]) / (self.rho[i + 1] - self.rho[i])
        wj = (psi - self.psi[j]) / (self.psi[j + 1] - self.psi[j])
        r = self.radius
        radius = ((1 - wi) * ((1 - wj) * r[i, j] + wj * r[i, j + 1])
                  + wi * ((1 - wj) * r[i + 1, j] + wj * r[i + 1, j + 1]))
        return 1.0 / radius
