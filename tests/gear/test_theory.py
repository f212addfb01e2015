"""Tests of the rigid-gear predictions (paper Eq. 12–13)."""

import numpy as np
import pytest

from lsbg.gear.theory import deg_per_s_from_rpm, gear_speed, rpm_from_deg_per_s, tangential_force


def test_gear_speed_paper_value():
    n2 = gear_speed(7703.0, 9, 37)
    assert round(float(n2), 3) == 1873.703  # Table 3
    assert n2 == pytest.approx(7703 * 9 / 37, rel=1e-15)


def test_gear_speed_is_unit_agnostic_and_vectorised():
    n1 = np.array([7703.0, 0.0, -360.0])
    np.testing.assert_allclose(gear_speed(np.deg2rad(n1), 9, 37),
                               np.deg2rad(gear_speed(n1, 9, 37)))
    np.testing.assert_allclose(gear_speed(370.0, np.array([9, 37]), 37),
                               [90.0, 370.0])


@pytest.mark.parametrize("z1, z2", [(0, 37), (9, 0), (9, -37)])
def test_gear_speed_rejects_bad_tooth_numbers(z1, z2):
    with pytest.raises(ValueError, match="tooth numbers"):
        gear_speed(7703.0, z1, z2)


def test_tangential_force_paper_value():
    force = tangential_force(1964.99, 0.1665)
    assert force == pytest.approx(23603.48, abs=0.01)  # Table 3
    assert force == pytest.approx(2 * 1964.99 / 0.1665, rel=1e-15)


def test_tangential_force_vectorised_and_validated():
    np.testing.assert_allclose(tangential_force([1.0, 2.0], [0.5, 0.1]),
                               [4.0, 40.0])
    with pytest.raises(ValueError, match="pitch_diameter"):
        tangential_force(1964.99, 0.0)


def test_paper_pinion_speed_is_not_4500_rpm():
    rpm = rpm_from_deg_per_s(7703.0)
    assert round(float(rpm), 1) == 1283.8
    assert rpm != pytest.approx(4500.0, rel=0.5)


def test_rpm_round_trip():
    assert deg_per_s_from_rpm(1.0) == 6.0
    speeds = np.array([0.0, 1.5, 7703.0, -42.0])
    np.testing.assert_allclose(deg_per_s_from_rpm(rpm_from_deg_per_s(speeds)),
                               speeds, rtol=1e-15)
