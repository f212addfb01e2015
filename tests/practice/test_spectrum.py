"""Miner's rule on the Basquin lines, against sums written out by hand."""

import numpy as np
import pytest
import xarray as xr

from lsbg.practice.spectrum import (check_spectrum, damage_equivalent_stress,
                                    spectrum_life_ratio, spectrum_stresses)
from lsbg.rating.life import EXPONENTS, life_ratio


def test_damage_equivalent_stress_by_hand():
    # p = 2: sqrt(0.5 * 100^2 + 0.5 * 200^2) = sqrt(25000)
    assert damage_equivalent_stress([100, 200], [0.5, 0.5], 2) == pytest.approx(158.113883, 1e-9)
    # one level: the stress itself, whatever the exponent
    assert damage_equivalent_stress([1234.0], [1.0], 13.2) == pytest.approx(1234.0, rel=1e-12)
    # a high exponent: the highest level dominates, no overflow
    assert damage_equivalent_stress([1e3, 2e3], [0.99, 0.01], 60) == pytest.approx(
        2e3 * 0.01 ** (1 / 60) * (1 + 0.99 / 0.01 * 0.5 ** 60) ** (1 / 60), rel=1e-12)


def test_life_ratio_under_a_spectrum_is_the_ratio_of_miner_sums():
    shares = np.array([0.2, 0.5, 0.3])
    sbg = np.array([900.0, 1200.0, 1500.0])
    lsbg = np.array([950.0, 1150.0, 1480.0])
    out = spectrum_life_ratio(lsbg, sbg, shares, "contact")
    p = EXPONENTS["contact"][0].exponent
    by_hand = np.sum(shares * sbg ** p) / np.sum(shares * lsbg ** p)   # N = C / sum s sigma^p
    assert out["ratio"] == pytest.approx(by_hand, rel=1e-10)
    assert out["low"] <= out["ratio"] <= out["high"]
    # one level: the constant-stress life ratio of lsbg.rating.life
    one = spectrum_life_ratio([1000.0], [1100.0], [1.0], "bending")
    assert one["ratio"] == pytest.approx(life_ratio(1000.0, 1100.0, "bending")["ratio"], 1e-12)


def test_stresses_are_read_off_the_load_curve_without_extrapolation():
    curve = xr.Dataset({"max_contact_pressure": (("torque", "mesh_phase"),
                                                 [[100.0, 90.0], [300.0, 310.0]])},
                       coords={"torque": [100.0, 300.0]})
    np.testing.assert_allclose(spectrum_stresses(curve, "max_contact_pressure", [200.0]), [205.0])
    with pytest.raises(ValueError, match="outside the load curve's 100-300 N m"):
        spectrum_stresses(curve, "max_contact_pressure", [350.0])


@pytest.mark.parametrize("levels, shares, words", [
    ([0.5, 1.0], [0.5, 0.6], "add up to 1 (they add up to 1.1)"),
    ([0.5, 1.0], [0.5], "needs one share per torque fraction (2)"),
    ([0.0, 1.0], [0.5, 0.5], "torque_fractions = [0.0, 1.0]: each must be > 0"),
    ([0.5, 1.0], [-0.5, 1.5], "must be >= 0"),
])
def test_a_bad_spectrum_names_its_key(levels, shares, words):
    with pytest.raises(ValueError, match=r"practice\.load_spectrum\..*" + words.replace(
            "(", r"\(").replace(")", r"\)").replace("[", r"\[").replace("]", r"\]")
            .replace(".", r"\.").replace("+", r"\+")):
        check_spectrum(levels, shares)
