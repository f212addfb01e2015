"""3-vector helpers: the same bits as numpy's, and the rotation's invariants."""

import math

import numpy as np
import pytest

from lsbg.gear.vectors import cross, rotate, unit


@pytest.mark.parametrize("a_shape, b_shape", [((3,), (3,)), ((3,), (40, 3)), ((40, 3), (3,)),
                                              ((5, 7, 3), (7, 3)), ((6, 3), (6, 3))])
def test_cross_is_numpy_cross_bit_for_bit(a_shape, b_shape):
    rng = np.random.default_rng(7)
    a, b = rng.normal(size=a_shape), rng.normal(size=b_shape)
    assert np.array_equal(cross(a, b), np.cross(a, b))


def test_rotation_keeps_length_and_turns_by_the_angle():
    rng = np.random.default_rng(3)
    axis = unit(rng.normal(size=3))
    v = rng.normal(size=(20, 3))
    angle = rng.uniform(-math.pi, math.pi, size=20)
    turned = rotate(v, axis, angle)
    np.testing.assert_allclose(np.linalg.norm(turned, axis=1), np.linalg.norm(v, axis=1),
                               rtol=1e-14)
    np.testing.assert_allclose(turned @ axis, v @ axis, atol=1e-14)   # along the axis: kept
    # the angle between the parts normal to the axis is the rotation angle
    before = v - np.outer(v @ axis, axis)
    after = turned - np.outer(turned @ axis, axis)
    sine = cross(before, after) @ axis
    cosine = np.einsum("ij,ij->i", before, after)
    np.testing.assert_allclose(np.arctan2(sine, cosine), angle, atol=1e-12)
    np.testing.assert_allclose(rotate(v[0], axis, 2 * math.pi), v[0], atol=1e-14)


def test_unit_vectors_have_length_one():
    v = np.array([[3.0, 4.0, 0.0], [0.0, 0.0, -2.0]])
    np.testing.assert_array_equal(unit(v), [[0.6, 0.8, 0.0], [0.0, 0.0, -1.0]])
