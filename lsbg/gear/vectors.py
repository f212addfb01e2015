"""3-vector helpers of the flank and contact geometry: rotation, cross product, unit vectors.

Functions on arrays of shape (..., 3); the geometry calls them on single
vectors by the thousand, so they avoid numpy's general-purpose overhead where
that costs more than the arithmetic.
"""

import numpy as np


def rotate(vectors, axis, angle):
    """Rotate vectors about a unit axis through the origin (Rodrigues).

    Parameters
    ----------
    vectors : array_like, shape (..., 3)
        Vectors to rotate [any length unit].
    axis : array_like, shape (3,)
        Unit rotation axis [-].
    angle : array_like
        Rotation angle, right-handed about ``axis``, broadcast against
        ``vectors[..., 0]`` [rad].

    Returns
    -------
    numpy.ndarray, shape (..., 3)
    """
    v = np.asarray(vectors, dtype=float)
    k = np.asarray(axis, dtype=float)
    a = np.asarray(angle, dtype=float)[..., None]
    cos, sin = np.cos(a), np.sin(a)
    return v * cos + cross(k, v) * sin + k * (v @ k)[..., None] * (1 - cos)


def cross(a, b):
    """Cross product a x b of 3-vectors over the last axis (broadcast).

    The products and differences of :func:`numpy.cross`, so the same bits,
    without its axis bookkeeping: much faster on single vectors,
    which the flank and contact geometry rotate by the thousand.

    Parameters
    ----------
    a, b : array_like, shape (..., 3)
        Vectors [any unit].

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        [unit of a times unit of b].
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.ndim == 1 and b.ndim == 1:
        a0, a1, a2 = a.tolist()
        b0, b1, b2 = b.tolist()
        return np.array((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0))
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=-1)


def unit(v):
    """Vectors scaled to unit length over the last axis.

    Parameters
    ----------
    v : array_like, shape (..., 3)
        Non-zero vectors [any unit].

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        [-].
    """
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)
