"""ISO 23509's face-milled SBG (trace "face_milled") beside the paper's arc ("circular").

ISO 23509:2016, Annex F.2, sample 1: a spiral bevel pair without offset, z = 14/39,
outer pitch diameter of the gear 176.893 mm, b = 25.4 mm, beta_m = 35 deg, face
milling with r_c0 = 114.3 mm (the pair of ISO/TR 10300-30's sample 1,
tests/rating/test_iso10300.py). The standard prints R_e = 93.973 mm, R_i = 68.573 mm,
R_m = 81.273 mm, m_mn = 3.213 mm and the spiral angles beta_e = 36.846 deg at the heel and
beta_i = 33.946 deg at the toe (as tabulated in the standard; read from the self-test
of an independent C# implementation of ISO 23509:2016, ISO23509Calc, that reproduces
its Tables F.1-F.3). Every value below is the standard's, to the digits it prints.
"""

import math

import numpy as np
import pytest

from lsbg.gear.design import DesignError, GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.gear.plane import face_milled_spiral_angle

Z1, Z2, DE2, FACE, BETA, CUTTER = 14, 39, 176.893, 25.4, 35.0, 114.3
#: ISO 23509:2016, Annex F.2 (sample 1): spiral angles at the toe and the heel [deg].
TOE, HEEL = 33.946, 36.846


def sample1(trace):
    """ISO 23509's sample 1 as a design of lsbg (depths proportional to the module)."""
    module = DE2 / Z2
    return GearPairDesign.from_config(dict(
        pinion_teeth=Z1, gear_teeth=Z2, module_mm=module, face_width_mm=FACE,
        spiral_angle_deg=BETA, cutter_radius_mm=CUTTER, trace=trace,
        addendum_mm=0.85 * module, dedendum_mm=1.05 * module, pinion_bore_mm=10,
        gear_bore_mm=40))


@pytest.fixture(scope="module", params=["face_milled", "circular"])
def pair(request):
    return GearPair(sample1(request.param))


def face(design, count=41):
    return np.linspace(design.inner_cone_distance, design.outer_cone_distance, count)


def closed_form(design, rho):
    """ISO 23509's sin beta(R) = (R^2 - R_m^2 + 2 R_m r_c0 sin beta_m) / (2 R r_c0) [deg]."""
    return np.degrees(face_milled_spiral_angle(rho, design.mean_cone_distance,
                                               design.cutter_radius, design.spiral_angle))


def test_the_sample_is_the_standards():
    d = sample1("face_milled")
    assert 1e3 * d.outer_cone_distance == pytest.approx(93.973, abs=5e-4)
    assert 1e3 * d.inner_cone_distance == pytest.approx(68.573, abs=5e-4)
    assert 1e3 * d.mean_cone_distance == pytest.approx(81.273, abs=5e-4)
    assert 1e3 * d.mean_normal_module == pytest.approx(3.213, abs=5e-4)


@pytest.mark.parametrize("member", [1, 2])
def test_face_milled_spiral_angle_is_the_standards_at_every_cone_distance(member):
    """Measured on the generated flank's trace on the pitch cone, both members."""
    pair = GearPair(sample1("face_milled"))
    d = pair.design
    rho = face(d)
    beta = np.degrees(pair.spiral_angle(member, d.pitch_angle(member), rho))
    assert np.max(np.abs(beta - closed_form(d, rho))) < 0.01
    # to the digits the standard prints at the toe and the heel
    assert round(float(beta[0]), 3) == TOE
    assert round(float(beta[-1]), 3) == HEEL
    assert float(pair.spiral_angle(member, d.pitch_angle(member), d.mean_cone_distance)) \
        == pytest.approx(math.radians(BETA), abs=1e-9)


def test_face_milled_on_the_coast_side_too():
    pair = GearPair(sample1("face_milled"))
    d = pair.design
    rho = face(d, 11)
    beta = np.degrees(pair.spiral_angle(2, d.pitch_angle(2), rho, side="coast"))
    assert np.max(np.abs(beta - closed_form(d, rho))) < 0.01


def test_the_papers_arc_is_not_the_standards():
    """The paper's arc lies in the plane of action: 33.49 deg at the toe, 37.19 at the heel."""
    pair = GearPair(sample1("circular"))
    d = pair.design
    rho = face(d)
    beta = np.degrees(pair.spiral_angle(2, d.pitch_angle(2), rho))
    assert np.max(np.abs(beta - closed_form(d, rho))) > 0.3
    assert round(float(beta[0]), 2) == 33.49 and round(float(beta[-1]), 2) == 37.19


def test_the_curve_and_its_inverse(pair):
    """d theta_c / d rho = tan(beta_p) / rho, distance_at inverts polar_angle, arrays."""
    d = pair.design
    curve = pair.planes["drive"].curve
    rho = face(d, 9)
    theta = curve.polar_angle(rho)
    assert theta.shape == rho.shape and float(curve.polar_angle(d.mean_cone_distance)) \
        == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_allclose(curve.distance_at(theta), rho, rtol=1e-12)
    h = 1e-6 * rho
    slope = (curve.polar_angle(rho + h) - curve.polar_angle(rho - h)) / (2 * h)
    np.testing.assert_allclose(slope, np.tan(curve.ray_angle(rho)) / rho, rtol=1e-6)
    # the plane's angle at the mean point is the design's beta_p either way
    assert abs(float(curve.ray_angle(d.mean_cone_distance))) == pytest.approx(
        d.plane_spiral_angle, abs=1e-14)


def test_the_pitch_cone_relation_holds_along_the_face():
    """tan(beta(R)) = tan(beta_p(R)) / cos(gamma) at every R, not only at the mean point."""
    pair = GearPair(sample1("face_milled"))
    d = pair.design
    rho = face(d, 11)
    beta_p = np.abs(pair.planes["drive"].curve.ray_angle(rho))
    expected = np.degrees(np.arctan(np.tan(beta_p) / math.cos(d.plane_of_action_tilt)))
    np.testing.assert_allclose(expected, closed_form(d, rho), atol=1e-10)


def test_the_papers_pair_keeps_its_arc():
    """The published pair's SBG (circular) is the paper's: 30.17 deg to 40.29 deg along
    the face; the standard's gives about 30.7 to 39.9."""
    d = GearPairDesign(trace="circular")
    paper = np.degrees(GearPair(d).spiral_angle(2, d.pitch_angle(2), face(d, 3)))
    assert paper[0] == pytest.approx(30.165736, abs=1e-5)
    assert paper[-1] == pytest.approx(40.289081, abs=1e-5)
    milled = GearPair(d.replace(trace="face_milled"))
    iso = np.degrees(milled.spiral_angle(2, d.pitch_angle(2), face(d, 3)))
    assert 30.6 < iso[0] < 30.8 and 39.8 < iso[-1] < 40.0


def test_a_cutter_that_cannot_span_the_face_is_refused():
    """23 mm spans the paper's face as the plane-of-action arc, not as the standard's circle."""
    GearPairDesign(trace="circular", cutter_radius=23e-3)
    with pytest.raises(DesignError, match=r"^cutter_radius = 0\.023: is too small: the cutter "
                                          r"circle .* 0\.99\d+ at the heel"):
        GearPairDesign(trace="face_milled", cutter_radius=23e-3)


def test_both_sbgs_rate_with_the_cutter_radius():
    from lsbg.rating.virtual import rating_geometry

    for trace in ("circular", "face_milled"):
        geometry = rating_geometry(GearPairDesign(trace=trace))
        assert geometry.lengthwise_curvature_radius == 76.2e-3
