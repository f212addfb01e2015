"""Unloaded tooth contact analysis on the exact, modified and displaced flanks.

What is checked, and against what:

* conjugate flanks on an aligned pair have no transmission error (the flank
  geometry's own property, to rounding);
* a crowned pinion gives the predesigned parabola per mesh cycle: its peak to
  peak is the closed form of the predesign, its shape is a parabola between
  the changeovers, and its bearing pattern lies inside the face;
* lengthwise crowning alone gives no transmission error (a contact line
  always crosses the face's middle when the profile contact ratio exceeds 1)
  but a localized pattern, while conjugate flanks bear over the whole face;
* the assembly displacements move the pattern and the transmission error
  the way a gear lab's V-H check knows them to;
* the contact ellipse at the marking-compound thickness has the size the
  relief predicts along the contact line and scales with the square root of
  the thickness (the separation grows with the square of the distance);
* two runs agree bit for bit, and bad input is rejected by name.
"""

import math

import numpy as np
import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tca.analysis import (MARKING_COMPOUND, designed_transmission_error, tooth_contact_analysis,
                               tooth_contact_summary)
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification

TRACES = ("logarithmic", "circular", "face_milled")
CROWNED = FlankModification(25e-6, 5e-6)
LENGTHWISE = FlankModification(25e-6, 0.0)
POSITIONS = 60


@pytest.fixture(scope="module")
def pairs():
    return {trace: GearPair(GearPairDesign.from_config(dict(trace=trace, spiral_angle_deg=35)))
            for trace in TRACES}


@pytest.fixture(scope="module")
def tca(pairs):
    """tca(trace, modification, misalignment, positions, marking), each computed once."""
    cache = {}

    def run(trace, modification=None, misalignment=None, positions=POSITIONS,
            marking=MARKING_COMPOUND):
        key = (trace, modification, misalignment, positions, marking)
        if key not in cache:
            cache[key] = tooth_contact_analysis(pairs[trace], modification, misalignment,
                                                positions, marking)
        return cache[key]

    return run


@pytest.fixture(params=TRACES)
def trace(request):
    return request.param


def test_conjugate_pair_has_no_transmission_error(tca, trace):
    te = tca(trace).transmission_error.values  # urad
    assert te.size == POSITIONS
    assert np.ptp(te) < 1e-3 and abs(te.mean()) < 1e-3  # below 1e-9 rad


def test_crowned_transmission_error_is_the_predesigned_parabola(pairs, tca, trace):
    ds = tca(trace, CROWNED, positions=100)
    te = ds.transmission_error.values
    designed = designed_transmission_error(pairs[trace], CROWNED) * 1e6
    assert designed > 10  # a real parabola, not a rounding error
    assert np.ptp(te) == pytest.approx(designed, rel=0.10)
    assert ds.attrs["designed_transmission_error_peak_to_peak_urad"] == pytest.approx(designed)
    # first contact touches: the least TE over the cycle is (near) zero
    assert abs(te.min()) < 0.02 * np.ptp(te)
    # a parabola sampled evenly between its changeovers has a mean of 1/3 of its
    # peak to peak
    assert 0.25 < (te.mean() - te.min()) / np.ptp(te) < 0.45
    # one tooth pair's branch, from changeover to changeover, is a parabola
    # with its vertex inside and the peak to peak at either end
    tooth = ds.contact_tooth.values
    changes = np.flatnonzero(np.diff(tooth) != 0) + 1
    assert changes.size == 1  # one changeover per mesh cycle
    branch = np.roll(te, -changes[0])
    x = np.arange(branch.size, dtype=float)
    a, b, c = np.polyfit(x, branch, 2)
    assert a > 0
    assert 0.25 * x[-1] < -b / (2 * a) < 0.75 * x[-1]
    assert np.abs(branch - np.polyval([a, b, c], x)).max() < 0.05 * np.ptp(te)
    assert branch[0] == pytest.approx(te.max(), rel=0.1)
    assert branch[-1] == pytest.approx(te.max(), rel=0.1)


def test_crowned_pattern_lies_inside_the_face(pairs, tca, trace):
    design = pairs[trace].design
    attrs = tca(trace, CROWNED).attrs
    assert attrs["edge_contact_share_toe"] == 0 and attrs["edge_contact_share_heel"] == 0
    assert attrs["pattern_toe_mm"] > design.inner_cone_distance * 1e3
    assert attrs["pattern_heel_mm"] < design.outer_cone_distance * 1e3
    assert attrs["pattern_length_per_face_width"] < 0.9
    # centred lengthwise: within a tenth of the face width of the mean cone distance
    assert abs(attrs["pattern_centre_cone_distance_mm"] - design.mean_cone_distance * 1e3) \
        < 0.1 * design.face_width * 1e3


def test_lengthwise_crowning_alone_localizes_without_transmission_error(pairs, tca, trace):
    design = pairs[trace].design
    crowned, conjugate = tca(trace, LENGTHWISE).attrs, tca(trace).attrs
    assert designed_transmission_error(pairs[trace], LENGTHWISE) == 0.0
    assert crowned["transmission_error_peak_to_peak_urad"] < 1.0
    assert crowned["edge_contact_share_toe"] == 0 and crowned["edge_contact_share_heel"] == 0
    assert crowned["pattern_length_per_face_width"] < 0.8
    # conjugate flanks bear along the whole face
    assert conjugate["edge_contact_share_toe"] == 1 and conjugate["edge_contact_share_heel"] == 1
    assert conjugate["pattern_length_per_face_width"] == pytest.approx(1.0)
    assert conjugate["pattern_toe_mm"] == pytest.approx(design.inner_cone_distance * 1e3)
    assert conjugate["pattern_heel_mm"] == pytest.approx(design.outer_cone_distance * 1e3)


def _centre(ds):
    return ds.attrs["pattern_centre_cone_distance_mm"]


def test_pinion_axial_moves_the_lsbg_pattern_along_the_face(tca):
    aligned = _centre(tca("logarithmic", CROWNED))
    out_of_mesh = _centre(tca("logarithmic", CROWNED, Misalignment(pinion_axial=1e-4)))
    into_mesh = _centre(tca("logarithmic", CROWNED, Misalignment(pinion_axial=-1e-4)))
    assert out_of_mesh > aligned + 0.5  # towards the heel, by more than half a mm
    assert into_mesh < aligned - 0.5  # towards the toe


def test_gear_axial_moves_the_pattern_both_ways(tca, trace):
    aligned = _centre(tca(trace, CROWNED))
    plus = _centre(tca(trace, CROWNED, Misalignment(gear_axial=1e-4))) - aligned
    minus = _centre(tca(trace, CROWNED, Misalignment(gear_axial=-1e-4))) - aligned
    assert plus * minus < 0
    assert min(abs(plus), abs(minus)) > 0.2  # mm: a movement, not noise


def test_out_of_mesh_makes_the_gear_lag(tca, trace):
    aligned = tca(trace, CROWNED).attrs["transmission_error_mean_urad"]
    for p, sign in ((1e-4, 1), (-1e-4, -1)):
        shifted = tca(trace, CROWNED, Misalignment(pinion_axial=p))
        change = shifted.attrs["transmission_error_mean_urad"] - aligned
        assert sign * change > 100  # urad for 0.1 mm
        assert shifted.attrs["transmission_error_mean_urad"] == pytest.approx(
            shifted.transmission_error.values.mean())


def test_contact_ellipse(pairs, tca, trace):
    """Along the contact line the separation is the relief, (C_L + C_P k^2) u^2
    on the line v = k u through the flank's middle (k = tan(beta) b / (R_m
    Delta psi)), so at the vertex of the parabola the region within the
    marking thickness t spans |u| <= sqrt(t / (C_L + C_P k^2)), a length of
    (b / 2) |u| / cos(beta) along the line on each side. Across the line the
    separation grows with the square of the distance too, so both semi-axes
    scale with sqrt(t)."""
    pair = pairs[trace]
    design, plane = pair.design, pair.planes["drive"]
    full = tca(trace, CROWNED)
    half = tca(trace, CROWNED, marking=MARKING_COMPOUND / 2)
    major, minor = full.ellipse_semi_major.values, full.ellipse_semi_minor.values
    assert np.all(major > minor) and np.all(minor > 0)
    # one tooth pair's region: a thin ellipse, at every position
    assert np.all((0.1 < minor) & (minor < 1.0))  # mm

    vertex = int(np.argmin(full.transmission_error.values))
    beta = abs(float(plane.curve.ray_angle(design.mean_cone_distance)))
    width = plane.field[1] - plane.field[0]
    k = math.tan(beta) * design.face_width / (design.mean_cone_distance * width)
    reach = math.sqrt(MARKING_COMPOUND / (CROWNED.lengthwise_crowning
                                          + CROWNED.profile_crowning * k**2))
    expected = 0.5 * design.face_width * reach / math.cos(beta) * 1e3  # mm
    assert major[vertex] == pytest.approx(expected, rel=0.10)
    # the ellipse is centred near the middle of the face there
    assert full.ellipse_cone_distance.values[vertex] == pytest.approx(
        design.mean_cone_distance * 1e3, abs=0.1 * design.face_width * 1e3)
    # halving the thickness shrinks both axes by 1/sqrt(2)
    for name in ("ellipse_semi_major", "ellipse_semi_minor"):
        ratio = half[name].values[vertex] / full[name].values[vertex]
        assert ratio == pytest.approx(1 / math.sqrt(2), rel=0.15)
    ratio = np.median(half.ellipse_semi_minor.values / minor)
    assert ratio == pytest.approx(1 / math.sqrt(2), rel=0.15)


def test_two_runs_are_identical(pairs):
    pair = pairs["logarithmic"]
    shift = Misalignment(pinion_axial=5e-5, offset=-2e-5)
    first = tooth_contact_analysis(pair, CROWNED, shift, positions=24)
    second = tooth_contact_analysis(pair, CROWNED, shift, positions=24)
    assert set(first.data_vars) == set(second.data_vars)
    for name in first.data_vars:
        np.testing.assert_array_equal(first[name].values, second[name].values, err_msg=name)
    for key, value in first.attrs.items():
        other = second.attrs[key]
        assert (value == other) or (isinstance(value, float) and math.isnan(value)
                                    and math.isnan(other)), key


def test_summary_is_the_analysis_attributes(pairs):
    # what a V-H map's cells read: the same values without the arrays
    pair = pairs["circular"]
    shift = Misalignment(pinion_axial=5e-5, offset=-2e-5)
    summary = tooth_contact_summary(pair, CROWNED, shift, positions=24)
    assert summary == tooth_contact_analysis(pair, CROWNED, shift, positions=24).attrs
    with pytest.raises(ValueError, match="lose contact"):
        tooth_contact_summary(pair, CROWNED, Misalignment(gear_axial=20e-3), positions=8)


def test_bad_input_is_rejected_by_name(pairs):
    pair = pairs["logarithmic"]
    for positions in (7, 0, 8.5, True):
        with pytest.raises(ValueError, match="positions"):
            tooth_contact_analysis(pair, CROWNED, positions=positions)
    for marking in (0.0, -1e-6, math.nan):
        with pytest.raises(ValueError, match="marking"):
            tooth_contact_analysis(pair, CROWNED, positions=8, marking=marking)
    # the gear pulled 20 mm out of mesh along its axis: its teeth no longer
    # reach the pinion's (a working depth of 7.65 mm)
    with pytest.raises(ValueError, match="lose contact"):
        tooth_contact_analysis(pair, CROWNED, Misalignment(gear_axial=20e-3), positions=8)
    # the gear pushed 0.2 mm into mesh: moving its nearly flat cone into depth
    # closes 2 x 0.2 mm x sin(20 deg) x cos(13.7 deg) = 0.13 mm of flank
    # distance, more than the normal backlash 0.1 mm x cos(20) cos(35 deg) = 0.077 mm
    with pytest.raises(ValueError, match="interfere"):
        tooth_contact_analysis(pair, CROWNED, Misalignment(gear_axial=-2e-4), positions=8)
