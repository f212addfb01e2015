"""The pair as practice makes it: ISO 23509's shift and thickness on the rolling-plane flanks.

The hand-worked example is the Gleason spiral bevel system (AGMA 209.03, 1964: working
depth 1.7 m, whole depth 1.888 m, gear addendum m (0.46 + 0.39 / m_90^2)) for the paper's
9:37 pair of module 4.5 mm, and ISO 23509's mean normal tooth thickness
s_mn1 = m_mn (pi/2 + 2 x_hm1 tan(alpha_n) + 2 x_smn1), each tooth thinner by half the
backlash (its normal share j cos(beta_m)).
"""

import math

import pytest

from lsbg.gear.design import DesignError, GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.gear.practice import equivalent_ratio, gleason_gear_addendum, gleason_profile_shift

# The hand-worked example, in mm (AGMA 209.03's formulas, written out):
M, Z1, Z2 = 4.5, 9, 37
M90 = Z2 / Z1                               # shaft angle 90 deg
A_OG = 0.46 * M + 0.39 * M / M90 ** 2       # gear addendum 2.1738 mm
A_OP = 1.7 * M - A_OG                       # pinion addendum 5.4762 mm
B_OG, B_OP = 1.888 * M - A_OG, 1.888 * M - A_OP   # dedenda 6.3222, 3.0198 mm


def test_the_gleason_addenda_by_hand():
    design = GearPairDesign()
    assert (A_OG, A_OP, B_OG, B_OP) == pytest.approx((2.173839, 5.476161, 6.322161, 3.019839),
                                                     abs=1e-6)
    assert equivalent_ratio(design) == pytest.approx(M90, rel=1e-12)
    assert 1e3 * gleason_gear_addendum(design) == pytest.approx(A_OG, rel=1e-12)
    shifted = design.replace(profile_shift=gleason_profile_shift(design))
    assert 1e3 * shifted.outer_addendum(1) == pytest.approx(A_OP, rel=1e-12)
    assert 1e3 * shifted.outer_addendum(2) == pytest.approx(A_OG, rel=1e-12)
    assert 1e3 * shifted.outer_dedendum(1) == pytest.approx(B_OP, rel=1e-12)
    assert 1e3 * shifted.outer_dedendum(2) == pytest.approx(B_OG, rel=1e-12)
    # the shift in mean normal modules: the outer depth moved over m cos(beta_m)
    assert shifted.profile_shift == pytest.approx((A_OP - 0.85 * M)
                                                  / (M * math.cos(math.radians(35))), rel=1e-12)


@pytest.mark.parametrize("x_hm, x_smn", [(0.448, 0.0), (0.448, 0.05), (-0.1, 0.02)])
def test_mean_normal_tooth_thickness_by_iso_23509(x_hm, x_smn):
    design = GearPairDesign(profile_shift=x_hm, thickness_modification=x_smn)
    r_e = M * Z1 / (2 * math.sin(math.atan(Z1 / Z2)))          # 85.677 mm
    r_m = r_e - 25 / 2
    m_mn = M * r_m / r_e * math.cos(math.radians(35))          # 3.148 mm
    j_n = 0.1 * math.cos(math.radians(35))
    s_mn1 = m_mn * (math.pi / 2 + 2 * x_hm * math.tan(math.radians(20)) + 2 * x_smn) - j_n / 2
    s_mn2 = math.pi * m_mn - j_n - s_mn1
    assert 1e3 * design.mean_normal_module == pytest.approx(m_mn, rel=1e-12)
    assert 1e3 * design.mean_normal_tooth_thickness(1) == pytest.approx(s_mn1, rel=1e-12)
    assert 1e3 * design.mean_normal_tooth_thickness(2) == pytest.approx(s_mn2, rel=1e-12)
    # ... measured on the flank surfaces: the pitch cone's arc between the two flanks
    pair = GearPair(design)
    for member, s_mn in ((1, s_mn1), (2, s_mn2)):
        arc = (pair.angular_thickness(member, design.mean_cone_distance,
                                      design.pitch_angle(member))
               * design.mean_pitch_radius(member))
        assert 1e3 * arc * math.cos(design.spiral_angle) == pytest.approx(s_mn, rel=1e-9)


def test_the_shift_removes_the_undercut_and_a_refused_undercut_names_the_shift():
    paper = GearPair(GearPairDesign())
    assert paper.undercut["drive"]["pinion"] > math.radians(0.4)      # the published pinion
    with pytest.raises(DesignError, match=r"^profile_shift = 0\.0: the pinion is undercut"):
        GearPair(GearPairDesign(undercut="refuse"))
    shifted = GearPair(GearPairDesign(profile_shift=0.448, undercut="refuse"))
    assert shifted.undercut["drive"] == {"pinion": 0.0, "gear": 0.0}
    assert shifted.contact_ratio()["total"] > 1


def test_too_much_shift_gives_a_narrow_top_land():
    with pytest.raises(DesignError, match=r"^profile_shift = 1\.0: the pinion teeth .*"
                                          r"the least is 0\.2 m_mn"):
        GearPair(GearPairDesign(profile_shift=1.0))
    with pytest.raises(DesignError, match="profile_shift = 1.1: leaves the gear no addendum"):
        GearPairDesign(profile_shift=1.1)


def test_iso_23509_mean_addendum_factor_gives_annex_f_sample_1():
    """ISO 23509:2016, Annex F, sample 1 (14/39, Sigma = 90 deg, k_d = 2): its printed
    c_ham = 0.24737 and x_hm1 = k_d (0.5 - c_ham) = 0.505 (ISO/TR 10300-30's sample 1,
    tests/rating/test_iso10300.py), where AGMA 209.03's rule gives 0.400."""
    from lsbg.gear.practice import (iso23509_mean_addendum_factor, iso23509_profile_shift,
                                    practice_profile_shift)

    sample = GearPairDesign.from_units(pinion_teeth=14, gear_teeth=39, module_mm=176.893 / 39,
                                       face_width_mm=25.4, pinion_bore_mm=10, gear_bore_mm=40)
    # k_d = 2: the unshifted mean addendum is one mean normal module
    sample = sample.replace(addendum=sample.mean_normal_module * sample.outer_cone_distance
                            / sample.mean_cone_distance)
    assert iso23509_mean_addendum_factor(sample) == pytest.approx(0.24737, abs=5e-6)
    assert iso23509_profile_shift(sample) == pytest.approx(0.505, abs=5e-4)
    assert practice_profile_shift(sample, "iso23509") == iso23509_profile_shift(sample)
    assert practice_profile_shift(sample, "agma209") == gleason_profile_shift(sample)
    assert gleason_profile_shift(sample) == pytest.approx(0.400, abs=1e-3)
    with pytest.raises(ValueError, match="practice.addendum_rule = 'x'"):
        practice_profile_shift(sample, "x")
