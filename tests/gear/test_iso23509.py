"""ISO 23509:2016's Annex F sample 1 built with lsbg's GearPairDesign, against its printed values.

Sample 1 (Annex F.2): a spiral bevel gear pair without hypoid offset, Method 0, face
milled, z = 14/39, Sigma = 90 deg, outer pitch diameter d_e2 = 176.893 mm, face width
b = 25.4 mm, beta_m = 35 deg, cutter radius r_c0 = 114.3 mm; data type II with
c_ham = 0.24737, k_d = 2, k_c = 0.125, k_t = 0.0915, outer normal backlash
j_en = 0.127 mm, and the gear's addendum and dedendum angles theta_a2 = 2.1342 deg,
theta_f2 = 6.4934 deg given (so theta_f1 = theta_a2 by its clearance rule). The pair
is ISO/TR 10300-30:2024's sample 1 (tests/rating/test_iso10300.py). The printed
values below are the standard's (Tables F.1-F.3, Formulae (F.1)-(F.108)) as the
self-test of an independent C# implementation of ISO 23509:2016 lists them
(afuentesaz/AGMAStandards, ISO23509Calc/Calc/SelfTest.cs, RunSample1Check); the
mean addenda and dedenda also as ISO/TR 10300-30 prints them (4.837/1.590 and
2.393/5.640 mm). The spiral angles at toe and heel are the face-milled trace's
(lsbg.gear.plane), not checked here.
"""

import math

import pytest

from lsbg.gear import depth
from lsbg.gear.design import GearPairDesign
from lsbg.gear.practice import iso23509_mean_addendum_factor, iso23509_profile_shift
from lsbg.rating.virtual import rating_geometry, virtual_cylindrical_gears

MM, DEG = 1e-3, math.radians(1.0)
J_EN = 0.127 * MM           # the sample's outer normal backlash
ALPHA_N, BETA_M = 20 * DEG, 35 * DEG


@pytest.fixture(scope="module")
def sample():
    base = GearPairDesign.from_units(pinion_teeth=14, gear_teeth=39, module_mm=176.893 / 39,
                                     face_width_mm=25.4, spiral_angle_deg=35,
                                     cutter_radius_mm=114.3, pinion_bore_mm=10, gear_bore_mm=40)
    outer = base.outer_cone_distance / base.mean_cone_distance
    m_mn = base.mean_normal_module
    # k_d = 2, k_c = 0.125: mean addendum 1 m_mn, dedendum k_d (k_c + 0.5) = 1.25 m_mn,
    # as lsbg's outer (apex-taper) values; the shift from c_ham, x_smn = k_t / 2
    base = base.replace(addendum=m_mn * outer, dedendum=1.25 * m_mn * outer)
    # j_en at the heel, normal to the flank: j_en R_m / R_e / cos(alpha_n) in the mean
    # normal section, lsbg's circumferential mean transverse backlash that over cos(beta_m)
    backlash = J_EN / outer / (math.cos(ALPHA_N) * math.cos(BETA_M))
    return base.replace(profile_shift=iso23509_profile_shift(base), thickness_modification=0.0915 / 2,
                        backlash=backlash, depth_taper="given_dedendum_angles",
                        dedendum_angles=(2.1342 * DEG, 6.4934 * DEG))


def test_cone_distances_modules_and_pitch_cones(sample):
    d = sample
    assert d.outer_cone_distance / MM == pytest.approx(93.973, abs=6e-4)
    assert d.mean_cone_distance / MM == pytest.approx(81.273, abs=6e-4)
    assert d.inner_cone_distance / MM == pytest.approx(68.573, abs=6e-4)
    assert d.module / MM == pytest.approx(4.536, abs=6e-4)          # m_et2
    assert d.mean_normal_module / MM == pytest.approx(3.213, abs=6e-4)
    assert d.mean_module / MM == pytest.approx(152.987 / 39, abs=2e-5)   # d_m2 / z2
    assert [math.degrees(d.pitch_angle(i)) for i in (1, 2)] == pytest.approx(
        [19.747, 70.253], abs=6e-4)
    assert [2 * d.mean_pitch_radius(i) / MM for i in (1, 2)] == pytest.approx(
        [54.918, 152.987], abs=6e-4)
    assert [d.pitch_diameter(i) / MM for i in (1, 2)] == pytest.approx([63.500, 176.893],
                                                                         abs=6e-4)


def test_the_shift_is_the_mean_addendum_factors(sample):
    assert iso23509_mean_addendum_factor(sample) == pytest.approx(0.24737, abs=5e-6)
    assert sample.profile_shift == pytest.approx(0.505, abs=5e-4)


def test_face_and_root_angles(sample):
    d = sample
    assert [math.degrees(d.tip_angle(i)) for i in (1, 2)] == pytest.approx([26.240, 72.387],
                                                                          abs=6e-4)
    assert [math.degrees(d.root_angle(i)) for i in (1, 2)] == pytest.approx([17.613, 63.760],
                                                                           abs=6e-4)
    assert math.degrees(d.member_addendum_angle(1)) == pytest.approx(6.493, abs=6e-4)
    assert math.degrees(d.member_dedendum_angle(1)) == pytest.approx(2.134, abs=6e-4)


@pytest.mark.parametrize("member, which, mean, heel, toe", [
    (1, "addendum", 4.836, 6.281, 3.391), (2, "addendum", 1.591, 2.064, 1.117),
    (1, "dedendum", 2.394, 2.867, 1.921), (2, "dedendum", 5.639, 7.085, 4.194)])
def test_depths_at_the_mean_point_heel_and_toe(sample, member, which, mean, heel, toe):
    # to 1.5e-3 mm: the printed values come from unrounded data (the mean ones are
    # printed one unit off ISO/TR 10300-30's in the last digit)
    assert depth.mean_depth(sample, member, which) / MM == pytest.approx(mean, abs=1.5e-3)
    assert depth.heel_depth(sample, member, which) / MM == pytest.approx(heel, abs=1.5e-3)
    assert depth.toe_depth(sample, member, which) / MM == pytest.approx(toe, abs=1.5e-3)
    outer = sample.outer_addendum(member) if which == "addendum" else sample.outer_dedendum(member)
    assert outer == depth.heel_depth(sample, member, which)


def test_mean_depths_as_iso_tr_10300_30_prints_them(sample):
    rating = rating_geometry(sample)
    assert [h / MM for h in rating.mean_addendum] == pytest.approx([4.837, 1.590], abs=6e-4)
    assert [h / MM for h in rating.mean_dedendum] == pytest.approx([2.393, 5.640], abs=6e-4)
    # ISO/TR 10300-30's thickness modifications with the backlash's share, x_sm1 and
    # x_sm2 = 0.036 and -0.055, and its basic crown gear's dedendum factor 1.25
    assert rating.thickness_modification == pytest.approx((0.036, -0.055), abs=1e-3)
    assert rating.crown_dedendum_factor == pytest.approx(1.25, rel=1e-12)
    # the rating's virtual tip diameters (ISO/TR 10300-30: 68.023 and 455.984 mm)
    tips = virtual_cylindrical_gears(rating).tip_diameter
    assert [t / MM for t in tips] == pytest.approx([68.023, 455.984], abs=2e-3)


def test_outer_tip_diameters(sample):
    derived = sample.derived()
    # to 2.5e-3 mm, as the heel's addenda above (to 1.5e-3 mm)
    assert derived["outer_tip_diameter_pinion_mm"] == pytest.approx(75.324, abs=2.5e-3)
    assert derived["outer_tip_diameter_gear_mm"] == pytest.approx(178.288, abs=2.5e-3)


def test_mean_normal_tooth_thicknesses(sample):
    # to 2.5e-3 mm: the standard's backlash allowance (Formulae (202)-(205)) is
    # j_en's share at the mean point as lsbg's here within 0.002 mm
    s = [sample.mean_normal_tooth_thickness(i) / MM for i in (1, 2)]
    assert s == pytest.approx([6.465, 3.511], abs=2.5e-3)


def test_the_face_and_root_cones_lie_off_the_pitch_apex(sample):
    d = sample
    rho = [d.inner_cone_distance, d.mean_cone_distance, d.outer_cone_distance]
    for member in (1, 2):
        delta = d.pitch_angle(member)
        pitch, out = (math.cos(delta), math.sin(delta)), (-math.sin(delta), math.cos(delta))
        for polar_angle, cone, sign, which in (
                (depth.tip_polar_angle, d.tip_angle(member), 1, "addendum"),
                (depth.root_polar_angle, d.root_angle(member), -1, "dedendum")):
            h = sign * depth.mean_depth(d, member, which)
            # the mean point's tip (root) in the axial section: (along the axis, radial)
            x_m = d.mean_cone_distance * pitch[0] + h * out[0]
            y_m = d.mean_cone_distance * pitch[1] + h * out[1]
            # on the sphere through it, the cone's polar angle is that point's
            at = polar_angle(d, member, [math.hypot(d.mean_cone_distance, h)])[0]
            assert at == pytest.approx(math.atan2(y_m, x_m), abs=1e-13)
            # every sphere's point lies on the generator through it at the cone's angle:
            # the cone's apex is not the pitch apex
            for r, polar in zip(rho, polar_angle(d, member, rho)):
                x, y = r * math.cos(polar), r * math.sin(polar)
                off_line = (x - x_m) * math.sin(cone) - (y - y_m) * math.cos(cone)
                assert off_line == pytest.approx(0.0, abs=1e-15)
                assert math.hypot(x, y) == pytest.approx(r, rel=1e-14)
            assert abs(polar_angle(d, member, [d.inner_cone_distance])[0] - cone) > 1e-4


def test_the_apex_taper_keeps_its_cones_and_records(sample):
    apex = GearPairDesign()
    rho = [apex.inner_cone_distance, apex.outer_cone_distance]
    assert list(depth.tip_polar_angle(apex, 1, rho)) == [apex.tip_angle(1)] * 2
    assert "depth_taper" not in apex.to_config()
    assert sample.to_config()["dedendum_angles_deg"] == [2.1342, 6.4934]
    assert GearPairDesign.from_config(sample.to_config()) == sample
