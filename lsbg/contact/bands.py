"""Where the line model's bands of a contact line lie in the field of contact.

The line model cuts each contact line into bands across the face width (its
band table, :attr:`lsbg.contact.mesh.MeshContact.arrays`). At a turn Psi of the
line in the plane of action a band spans the polar angles Psi + theta_in ..
Psi + theta_out; the part of it inside the field [psi_lo, psi_hi] carries load,
and acts at the middle of that part, as the compiled kernel does
(:func:`lsbg.contact.kernels._line_side`). The FE loaded TCA's contact points
(:func:`lsbg.tooth.contact_points.contact_points`, one line at a time) and the
optimiser's loaded TCA (:func:`lsbg.optimise.loaded.mesh_points`, every line of
every phase at once) both read the bands here.

SI inside.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from lsbg.contact import kernels as k

__all__ = ["BandPoints", "band_points"]

#: The bands of contact lines at their turns (arrays of shape ``turn.shape + (bands,)``).
BandPoints = namedtuple("BandPoints", "inside fraction rho psi lever length edge bottom top")


def band_points(band, turn, psi_lo, psi_hi, last=np.inf):
    """The bands of contact lines at the given turns: what lies in the field, and where.

    Parameters
    ----------
    band : numpy.ndarray, shape (bands, columns)
        The drive side's band table (``MeshContact.arrays[2][0, :bands]``).
    turn : float or array_like
        Turns Psi of the contact lines in the plane of action [rad].
    psi_lo, psi_hi : float or array_like
        Polar angles bounding the field across the profile [rad], scalars or
        one per band.
    last : float, optional
        The last turn at which a line is in mesh [rad]: a line beyond it has
        no band inside (default: none beyond).

    Returns
    -------
    BandPoints
        ``inside`` (a band's part in the field is not empty), ``fraction`` of
        the band inside [-], the cone distance ``rho`` [m], polar angle ``psi``
        [rad], ``lever`` [m] and ``length`` [m] of the part inside at its
        middle, ``edge`` (-1: the field's lower end cuts the band, +1: its
        upper end, 0: neither or not inside), and the part's polar range
        ``bottom`` .. ``top`` [rad].
    """
    turn = np.asarray(turn, dtype=float)[..., None]
    a = turn + band[:, k.B_THETA_IN]
    b = turn + band[:, k.B_THETA_OUT]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    top, bottom = np.minimum(hi, psi_hi), np.maximum(lo, psi_lo)
    inside = (top > bottom) & (turn <= last)
    span = np.where(hi > lo, hi - lo, 1.0)
    fraction = np.where(inside, (top - bottom) / span, 0.0)
    # a band cut by the field's edge acts at the middle of its inside part
    t = np.where(inside & (fraction < 1.0), 0.5 * (top + bottom - a - b) / (b - a), 0.0)
    rho = band[:, k.B_RHO] + t * band[:, k.B_D_RHO]
    cos_t = band[:, k.B_COS] + t * band[:, k.B_D_COS]
    sin_t = band[:, k.B_SIN] + t * band[:, k.B_D_SIN]
    psi = turn + np.arctan2(sin_t, cos_t)
    lever = band[:, k.B_LEVER] + t * band[:, k.B_D_LEVER]
    length = fraction * band[:, k.B_LENGTH]
    edge = np.where(inside, np.where(lo < psi_lo, -1, 0) + np.where(hi > psi_hi, 1, 0), 0)
    return BandPoints(inside, fraction, rho, psi, lever, length, edge, bottom, top)
