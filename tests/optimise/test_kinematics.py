"""The contact's sliding and rolling speeds, and the relative curvature's table."""

import math

import numpy as np
import pytest

from lsbg.optimise.kinematics import CurvatureTable, contact_speeds
from lsbg.tooth.local import relative_curvature

SPEED = math.radians(7703.0)


@pytest.mark.parametrize("trace", ["logarithmic", "circular"])
def test_sliding_is_the_relative_rotation_about_the_pitch_line(pairs, trace):
    pair = pairs[trace]
    plane = pair.planes["drive"]
    rng = np.random.default_rng(0)
    rho = rng.uniform(pair.design.inner_cone_distance, pair.design.outer_cone_distance, 40)
    psi = rng.uniform(*plane.field[:2], 40)
    sliding, _ = contact_speeds(pair, rho, psi, SPEED)
    z1, z2 = pair.design.teeth
    # omega_rel = omega1 u1 - omega2 u2 lies along the pitch line, which is in the plane of
    # action: |omega_rel x p| = |omega_rel| rho |sin psi|
    relative = np.linalg.norm(SPEED * pair.rotation_axis[1] - SPEED * z1 / z2
                              * pair.rotation_axis[2])
    np.testing.assert_allclose(sliding, relative * rho * np.abs(np.sin(psi)), rtol=1e-12)
    assert contact_speeds(pair, pair.design.mean_cone_distance, 0.0, SPEED)[0] < 1e-12


def test_a_member_does_not_roll_on_its_base_cones_tangency_line(pairs):
    pair = pairs["logarithmic"]
    plane = pair.planes["drive"]
    rho = pair.design.mean_cone_distance
    for member in (1, 2):
        psi = plane.tangency_angle[member]
        sliding, rolling = contact_speeds(pair, rho, psi, SPEED)
        # one surface at rest across the line: its mate's speed is the sliding and the sum
        assert rolling == pytest.approx(sliding, rel=1e-12)
    # at the pitch point the surfaces roll at the same speed, omega1 times the distance
    # from the pinion's tangency line along the normal
    _, rolling = contact_speeds(pair, rho, 0.0, SPEED)
    point = plane.point(rho, 0.0)
    assert rolling == pytest.approx(2 * abs(SPEED * np.cross(pair.rotation_axis[1], point)
                                            @ plane.normal), rel=1e-12)


def test_curvature_table_interpolates_the_exact_curvature(pairs):
    pair = pairs["circular"]
    design, plane = pair.design, pair.planes["drive"]
    edges = np.linspace(design.inner_cone_distance, design.outer_cone_distance, 21)
    table = CurvatureTable(pair, edges)
    rng = np.random.default_rng(1)
    rho = rng.uniform(edges[0], edges[-1], 30)
    psi = rng.uniform(0.95 * plane.field[0], 0.95 * plane.field[1], 30)
    np.testing.assert_allclose(table(rho, psi), relative_curvature(pair, rho, psi), rtol=2e-4)
