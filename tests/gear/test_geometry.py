"""Exact flank geometry: spiral angle, pressure angle, conjugacy, contact ratio."""

import math

import numpy as np
import pytest

from lsbg.gear.design import DesignError, GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.gear.vectors import rotate


#: The practice design's shift and thickness (lsbg.rating.practice, the paper's pair): the
#: flanks' checks below hold on a shifted pair as on the published one.
PRACTICE = dict(profile_shift=0.44793242616994483, thickness_modification=0.006073268534624095,
                undercut="refuse")


@pytest.fixture(scope="module", params=[("logarithmic", {}), ("circular", {}),
                                        ("logarithmic", PRACTICE), ("circular", PRACTICE),
                                        ("face_milled", PRACTICE)],
                ids=["lsbg", "sbg", "lsbg-practice", "sbg-practice", "iso-sbg-practice"])
def pair(request):
    trace, shift = request.param
    return GearPair(GearPairDesign(trace=trace, **shift))


@pytest.fixture(scope="module")
def lsbg():
    return GearPair(GearPairDesign(trace="logarithmic"))


@pytest.fixture(scope="module")
def sbg():
    return GearPair(GearPairDesign(trace="circular"))


def face(design, n=41):
    return np.linspace(design.inner_cone_distance, design.outer_cone_distance, n)


@pytest.mark.parametrize("member", [1, 2])
@pytest.mark.parametrize("side", ["drive", "coast"])
def test_lsbg_spiral_angle_constant_on_pitch_cone(lsbg, member, side):
    d = lsbg.design
    beta = np.degrees(lsbg.spiral_angle(member, d.pitch_angle(member), face(d), side))
    assert np.ptp(beta) < 0.01
    assert np.mean(beta) == pytest.approx(35.0, abs=1e-6)


@pytest.mark.parametrize("spiral_deg", [25, 45])
def test_lsbg_spiral_angle_constant_on_other_cones(spiral_deg):
    g = GearPair(GearPairDesign(spiral_angle=math.radians(spiral_deg)))
    d = g.design
    for cone in (d.root_angle(2) + 0.01, d.pitch_angle(2) + 0.02, d.tip_angle(2) - 0.001):
        beta = np.degrees(g.spiral_angle(2, cone, face(d)))
        assert np.ptp(beta) < 0.01


def test_lsbg_pitch_cone_trace_is_eq1(lsbg):
    """Eq. 1: on a cone of half-angle alpha, R = a exp(phi sin(alpha) cot(beta))."""
    d = lsbg.design
    for member in (1, 2):
        alpha = d.pitch_angle(member)
        rho = face(d)
        points, _ = lsbg.flank(member, "drive", rho, alpha)
        a = lsbg.axis[member]
        ref = np.cross(a, [0, 0, 1.0])
        phi = np.unwrap(np.arctan2(points @ np.cross(a, ref), points @ ref))
        phi = np.abs(phi - phi[0])
        predicted = rho[0] * np.exp(phi * math.sin(alpha) / math.tan(math.radians(35)))
        np.testing.assert_allclose(np.linalg.norm(points, axis=1), predicted, rtol=1e-9)
        # and the points lie on the cone
        cos_polar = points @ a / np.linalg.norm(points, axis=1)
        np.testing.assert_allclose(cos_polar, math.cos(alpha), rtol=1e-12)


def test_hands_left_pinion_right_gear(pair):
    d = pair.design
    assert np.all(pair.trace_azimuth_rate(1, d.pitch_angle(1), face(d)) < 0)
    assert np.all(pair.trace_azimuth_rate(2, d.pitch_angle(2), face(d)) > 0)
    right = GearPair(d.replace(pinion_hand="right"))
    assert np.all(right.trace_azimuth_rate(1, d.pitch_angle(1), face(d)) > 0)


def test_sbg_spiral_angle_varies_as_the_cutter_arc_predicts(sbg):
    d = sbg.design
    rho = face(d)
    beta = sbg.spiral_angle(2, d.pitch_angle(2), rho)
    # beta_m at the mean point
    mean = sbg.spiral_angle(2, d.pitch_angle(2), d.mean_cone_distance)
    assert math.degrees(mean) == pytest.approx(35.0, abs=1e-6)
    # increasing from toe to heel (cutter centre on the apex side)
    assert np.all(np.diff(beta) > 0)
    # closed form: tan(beta) = tan(beta_p(rho)) / cos(gamma), sin(beta_p) from the arc
    beta_p = np.arcsin(sbg.planes["drive"].curve.circle_sin_angle(rho))
    expected = np.arctan(np.tan(beta_p) / math.cos(d.plane_of_action_tilt))
    np.testing.assert_allclose(beta, expected, atol=1e-8)
    # about 10 deg across a 25 mm face with a 76.2 mm cutter
    assert 8 < math.degrees(beta[-1] - beta[0]) < 12


@pytest.mark.parametrize("member", [1, 2])
def test_normal_pressure_angle_at_mean_point(pair, member):
    d = pair.design
    for side in ("drive", "coast"):
        alpha = pair.normal_pressure_angle(member, d.mean_cone_distance, d.pitch_angle(member), side)
        assert math.degrees(alpha) == pytest.approx(20.0, abs=0.05)


def test_flank_normals_are_surface_normals(pair):
    """The analytic normals equal the cross product of the parameter derivatives."""
    for member in (1, 2):
        lo, hi = pair.flank_polar_range(member)
        rho, theta = np.meshgrid(face(pair.design, 7), np.linspace(lo + 1e-3, hi, 7))
        h = 1e-7
        p, n = pair.flank(member, "drive", rho, theta)
        dr = pair.flank(member, "drive", rho + h, theta)[0] - pair.flank(member, "drive", rho - h, theta)[0]
        dt = pair.flank(member, "drive", rho, theta + h)[0] - pair.flank(member, "drive", rho, theta - h)[0]
        numeric = np.cross(dr, dt)
        numeric /= np.linalg.norm(numeric, axis=-1, keepdims=True)
        assert np.max(1 - np.abs(np.sum(numeric * n, axis=-1))) < 1e-9


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_conjugacy_on_contact_lines(pair, side):
    """At several mesh positions both flanks pass through the contact line with
    parallel normals: pinion and gear points coincide within 1e-9 m."""
    plane = pair.planes[side]
    lo, hi = plane.field[:2]
    checked = 0
    for phase in np.linspace(lo - 0.3, hi + 0.3, 25):
        rho, points, normals = pair.contact_line(side, phase, n=17)
        if rho.size == 0:
            continue
        # A segment may end on the base cone, the flank's edge of regression,
        # where the polar angle is a singular parameter: check interior points.
        rho, points, normals = rho[1:-1], points[1:-1], normals[1:-1]
        per_member = []
        for member in (1, 2):
            u = pair.rotation_axis[member]
            # member rotation that puts tooth 0's contact line at this phase
            rotation = phase / pair.axis_normal_component(member, side) - pair.flank_offset[(member, side)]
            polar = np.arccos(points @ pair.axis[member] / np.linalg.norm(points, axis=1))
            body, body_normals = pair.flank(member, side, rho, polar)
            per_member.append((rotate(body, u, rotation), rotate(body_normals, u, rotation)))
        (p1, n1), (p2, n2) = per_member
        assert np.max(np.linalg.norm(p1 - points, axis=1)) < 1e-9
        assert np.max(np.linalg.norm(p2 - points, axis=1)) < 1e-9
        # outward normals of the two flanks are opposite, and along the contact normal
        assert np.max(np.linalg.norm(n1 + n2, axis=1)) < 1e-9
        assert np.max(1 - np.abs(np.sum(n1 * normals, axis=1))) < 1e-12
        checked += 1
    assert checked >= 8


def test_gear_ratio_from_plane_rotation(pair):
    # The contact line turns at the same rate for both members only at z2/z1.
    s1 = pair.axis_normal_component(1, "drive")
    s2 = pair.axis_normal_component(2, "drive")
    assert s2 / s1 == pytest.approx(37 / 9, rel=1e-12)


def test_contact_ratio_counts_lines_in_field(pair):
    """The closed-form total contact ratio equals the mean number of contact
    lines that meet the field of contact over one pitch."""
    plane = pair.planes["drive"]
    pitch = pair.design.base_pitch_angle
    phases = np.linspace(0, pitch, 4000, endpoint=False)
    count = np.zeros_like(phases)
    for k in range(-10, 11):
        lo, hi = plane.line_segment(phases + k * pitch)
        count += hi > lo
    ratio = pair.contact_ratio()
    assert np.mean(count) == pytest.approx(ratio["total"], abs=2e-3)
    assert 1.0 < ratio["profile"] < 1.6 and ratio["face"] > 1.0


def test_tooth_thickness_and_backlash(pair):
    d = pair.design
    for member in (1, 2):
        thick = pair.angular_thickness(member, d.mean_cone_distance, d.pitch_angle(member))
        assert thick * d.mean_pitch_radius(member) == pytest.approx(d.mean_tooth_thickness(member), rel=1e-9)
        assert np.all(pair.top_land(member, face(d, 5)) > 0)


def test_paper_base_cone_rule_gives_pointed_teeth():
    with pytest.raises(DesignError, match=r"^base_cone_rule = 'paper': the pinion teeth come out pointed"):
        GearPair(GearPairDesign(base_cone_rule="paper"))


def test_too_long_addendum_makes_pointed_teeth():
    with pytest.raises(DesignError, match=r"^addendum = .*pointed"):
        GearPair(GearPairDesign(addendum=5.6e-3, dedendum=6.5e-3, normal_pressure_angle=math.radians(28)))


def test_undercut_of_the_paper_pinion_is_reported(lsbg):
    # 9 teeth, 0.85 m addendum, 20 deg at 35 deg spiral: the gear tip passes the
    # pinion's base cone by about half a degree in the plane of action.
    assert math.degrees(lsbg.undercut["drive"]["pinion"]) == pytest.approx(0.5, abs=0.1)
    assert lsbg.undercut["drive"]["gear"] == 0


def test_no_flank_below_the_base_cone(lsbg):
    delta_b = lsbg.design.base_cone_angle(1)
    points, _ = lsbg.flank(1, "drive", lsbg.design.mean_cone_distance, delta_b - 0.01)
    assert np.all(np.isnan(points))
    points, _ = lsbg.flank(1, "drive", lsbg.design.mean_cone_distance, delta_b)
    assert np.all(np.isfinite(points))
