"""The SBG's cutter (lsbg.gear.cutter): nominal sizes, fit, the trace's lengthwise curvature."""

import math

import numpy as np
import pytest

from lsbg.gear import cutter
from lsbg.gear.design import TRACES, GearPairDesign
from lsbg.gear.geometry import GearPair


def paper(spiral_deg=35, trace="logarithmic", **keys):
    return GearPairDesign.from_units(spiral_angle_deg=spiral_deg, trace=trace, **keys)


def test_nominal_radii_are_the_nominal_cutter_diameters_halved():
    assert [round(r * 1e3, 2) for r in cutter.NOMINAL_CUTTER_RADII] == [
        44.45, 63.5, 76.2, 95.25, 114.3, 133.35, 152.4]


@pytest.mark.parametrize("spiral_deg", [25, 35, 45])
def test_lsbg_trace_curvature_on_the_pitch_cone_is_r_over_sin_beta(spiral_deg):
    """The LSBG flank's pitch-cone trace, measured on the flank and developed, has radius of
    curvature R / sin(beta_m) at every cone distance (a conical logarithmic spiral)."""
    design = paper(spiral_deg)
    pair = GearPair(design)
    for member in (1, 2):
        for rho in (design.inner_cone_distance, design.mean_cone_distance,
                    design.outer_cone_distance):
            measured = cutter.trace_curvature_radius(pair, member, rho)
            assert measured == pytest.approx(rho / math.sin(design.spiral_angle), rel=1e-7)
    assert cutter.lsbg_curvature_radius(design) == pytest.approx(
        cutter.trace_curvature_radius(pair), rel=1e-7)
    if spiral_deg == 35:  # the paper's mean point: about 128 mm
        assert cutter.lsbg_curvature_radius(design) * 1e3 == pytest.approx(127.58, abs=0.01)


def test_the_sbgs_trace_curves_about_as_its_cutter():
    """lsbg's circular arc lies in the plane of action: on the pitch cone its trace curves
    a little more tightly than the cutter (73.35 mm for the 76.2-mm cutter)."""
    design = paper(trace="circular")
    measured = cutter.trace_curvature_radius(GearPair(design))
    assert 0.9 * design.cutter_radius < measured < design.cutter_radius


def _spiral_slope(design):
    pair = GearPair(design)
    rm, h = design.mean_cone_distance, 1e-3 * design.face_width
    beta = pair.spiral_angle(2, design.pitch_angle(2), [rm - h, rm + h])
    return (beta[1] - beta[0]) / (2 * h)


def test_curvature_matched_sbg_shares_the_lsbgs_curvature_and_a_stationary_spiral_angle():
    """Matched to the LSBG's curvature at the mean point, the SBG's trace meets the rays at
    a stationary angle there (the developed curve's curvature is sin(beta)/R + dbeta/ds)."""
    design = paper()
    radius = cutter.matched_cutter_radius(design, "circular")
    sbg = design.replace(trace="circular", cutter_radius=radius)
    assert cutter.trace_curvature_radius(GearPair(sbg)) == pytest.approx(
        cutter.lsbg_curvature_radius(design), rel=1e-7)
    default = design.replace(trace="circular")
    assert abs(_spiral_slope(sbg)) < 1e-4 * abs(_spiral_slope(default))
    # the pinion's trace gives the same cutter (both traces develop onto one crown gear)
    assert cutter.matched_cutter_radius(design, "circular", member=1) == pytest.approx(
        radius, rel=1e-6)


@pytest.mark.skipif("face_milled" not in TRACES, reason="no ISO 23509 face-milled trace here")
def test_face_milled_matched_cutter_is_r_over_sin_beta():
    """ISO 23509's cutter circle lies in the crown gear's pitch plane, the pitch cone's
    development: its curvature-matched cutter is R_m / sin(beta_m) itself."""
    design = paper()
    radius = cutter.matched_cutter_radius(design, "face_milled")
    assert radius == cutter.lsbg_curvature_radius(design)
    # measured on the built flank, that cutter's trace curves as the LSBG's
    sbg = GearPair(design.replace(trace="face_milled", cutter_radius=radius))
    assert cutter.trace_curvature_radius(sbg) == pytest.approx(radius, rel=1e-7)
    assert cutter.trace_curvature_radius(sbg, member=1) == pytest.approx(radius, rel=1e-7)


def test_the_nominal_radii_that_fit_the_paper_pair():
    design = paper()
    fits = cutter.fitting_radii(design, "circular")
    assert np.round(np.array(fits) * 1e3, 2).tolist() == [44.45, 63.5, 76.2, 95.25, 114.3]
    # too small to span the face at 35 deg, too large for the pair
    assert "cannot span the face" in cutter.cutter_fit_problem(design, "circular", 0.02)
    assert "outside the usual cutter radii" in cutter.cutter_fit_problem(design, "circular",
                                                                       0.1524)
    assert cutter.cutter_fit_problem(design, "circular", 0.1524, usual_range=None) is None
    # the span depends on the spiral angle: a 25-mm cutter spans the face at 35 deg, not at 45
    assert cutter.cutter_fit_problem(design, "circular", 0.025, usual_range=None) is None
    assert "cannot span the face" in cutter.cutter_fit_problem(paper(45), "circular", 0.025,
                                                               usual_range=None)
