"""The bearing pattern and the contact ellipses of a tooth contact analysis.

From the contact search (:func:`lsbg.tca.surface.contact_search`): the
instantaneous contact ellipse at the marking-compound thickness, from the
first and second moments of the grid points inside it (a filled ellipse of
semi-axes a, b has variances a^2/4 and b^2/4 along them), in true size and
in the gear flank's chart; and the bearing pattern, the part of the gear
flank whose least separation over the mesh cycle is at most the marking
thickness, with its centre and extent.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.tca import surface

#: Marking-compound thickness (0.00025 in) [m].
MARKING_COMPOUND = 6.35e-6


def chart_ellipses(out):
    """The contact regions as ellipses in the gear flank's chart.

    The chart is cone distance R against height h above the root cone, the
    plane a bearing pattern is drawn in; it is not to scale along the tooth
    (a step along a spiral tooth moves R by about cos(beta) of its length),
    so these ellipses are for drawing, :func:`contact_ellipses` gives the
    true size.

    Returns
    -------
    centre : numpy.ndarray, shape (n, 2)
        (R, h) of the region's centroid [m].
    semi_major, semi_minor : numpy.ndarray, shape (n,)
        In chart units [m].
    angle : numpy.ndarray, shape (n,)
        Signed angle of the major axis from the R axis towards +h [rad].
    """
    count = out[:, surface.O_COUNT]
    n = np.maximum(count, 1.0)
    r, h = out[:, surface.O_CR] / n, out[:, surface.O_CH] / n
    rr = out[:, surface.O_CRR] / n - r * r
    rh = out[:, surface.O_CRH] / n - r * h
    hh = out[:, surface.O_CHH] / n - h * h
    mean, half_difference = 0.5 * (rr + hh), np.hypot(0.5 * (rr - hh), rh)
    major = np.maximum(mean + half_difference, 0.0)
    minor = np.maximum(mean - half_difference, 0.0)
    angle = 0.5 * np.arctan2(2 * rh, rr - hh)
    empty = count < 1
    semi_major, semi_minor = 2 * np.sqrt(major), 2 * np.sqrt(minor)
    semi_major[empty] = semi_minor[empty] = 0.0
    return np.stack([r, h], axis=1), semi_major, semi_minor, angle



def contact_ellipses(out):
    """Centres [m] (gear frame), semi-axes [m] and major-axis directions of the
    contact regions from their point moments (one row per position).

    Returns
    -------
    centre : numpy.ndarray, shape (n, 3)
    semi_major, semi_minor : numpy.ndarray, shape (n,)
    major_axis : numpy.ndarray, shape (n, 3)
    """
    count = out[:, surface.O_COUNT]
    n = np.maximum(count, 1.0)
    centre = out[:, surface.O_SX:surface.O_SZ + 1] / n[:, None]
    s = out[:, surface.O_SXX:surface.O_SZZ + 1] / n[:, None]
    cov = np.empty((out.shape[0], 3, 3))
    cov[:, 0, 0], cov[:, 0, 1], cov[:, 0, 2] = s[:, 0], s[:, 1], s[:, 2]
    cov[:, 1, 1], cov[:, 1, 2], cov[:, 2, 2] = s[:, 3], s[:, 4], s[:, 5]
    cov[:, 1, 0], cov[:, 2, 0], cov[:, 2, 1] = s[:, 1], s[:, 2], s[:, 4]
    cov -= centre[:, :, None] * centre[:, None, :]
    values, vectors = np.linalg.eigh(cov)
    values = np.maximum(values, 0.0)
    semi_major, semi_minor = 2 * np.sqrt(values[:, 2]), 2 * np.sqrt(values[:, 1])
    empty = count < 1
    semi_major[empty] = semi_minor[empty] = 0.0
    return centre, semi_major, semi_minor, vectors[:, :, 2]



def profile_height(pair, cone_distance, polar_angle):
    """Height of gear flank points above the gear's root cone [m].

    The arc R (theta - theta_root) on the sphere of radius R about the apex:
    0 on the root cone, the tooth depth at the tip.

    Parameters
    ----------
    cone_distance : array_like
        R [m].
    polar_angle : array_like
        theta, about the gear axis [rad].
    """
    return np.asarray(cone_distance) * (np.asarray(polar_angle) - pair.design.root_angle(2))



def bearing_pattern(raster, limits, pair, marking=MARKING_COMPOUND):
    """Extent and centre of the bearing pattern on the gear flank.

    Parameters
    ----------
    raster : numpy.ndarray, shape (a, b)
        Least separation over the mesh cycle on the gear-flank raster [m].
    limits : array_like
        R_lo, R_hi [m], theta_lo, theta_hi [rad] of the raster.
    pair : lsbg.gear.geometry.GearPair
    marking : float
        Marking-compound thickness [m].

    Returns
    -------
    dict
        ``centre_cone_distance``, ``centre_height`` (area centroid) [m],
        ``toe``, ``heel`` (cone distances of its ends) [m], ``length`` and
        ``height`` (its extents) [m], ``area`` [m^2]; NaN without a pattern.
    """
    rho, theta = raster_centres(raster.shape, limits)
    big_rho, big_theta = np.meshgrid(rho, theta, indexing="ij")
    height = profile_height(pair, big_rho, big_theta)
    inside = raster <= marking
    cell = (rho[1] - rho[0]) * (theta[1] - theta[0]) * big_rho
    if not inside.any():
        nan = math.nan
        return dict(centre_cone_distance=nan, centre_height=nan, toe=nan, heel=nan,
                    length=nan, height=nan, area=0.0)
    weight = np.where(inside, cell, 0.0)
    step = rho[1] - rho[0]
    toe, heel = big_rho[inside].min() - step / 2, big_rho[inside].max() + step / 2
    return dict(centre_cone_distance=float((weight * big_rho).sum() / weight.sum()),
                centre_height=float((weight * height).sum() / weight.sum()),
                toe=float(toe), heel=float(heel), length=float(heel - toe),
                height=float(np.ptp(height[inside])), area=float(weight.sum()))



def raster_centres(shape, limits):
    """Cell centres of the gear-flank raster: cone distance [m], polar angle [rad]."""
    a, b = shape
    rho = limits[0] + (np.arange(a) + 0.5) * (limits[1] - limits[0]) / a
    theta = limits[2] + (np.arange(b) + 0.5) * (limits[3] - limits[2]) / b
    return rho, theta
