"""The practice design: each rule against what it promises, checked independently.

The rated torque is the one at which ISO 10300's pitting safety is 1; the
thickness modification balances the members' root stresses; the tip relief is
the mesh's deflection under load (linear in the load, of the size ISO 6336-1's
mesh stiffness of steel gears gives), run out over the two-pair zone at the tip.
"""

import math

import pytest

from lsbg.config import merge_config, resolve_config
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.gear.practice import gleason_profile_shift, iso23509_profile_shift
from lsbg.practice.design import (deflection_tip_relief, practice_overlay, rated_gear_torque,
                                  root_stress_ratio)
from lsbg.rating.config import rate_design


@pytest.fixture(scope="module")
def config():
    return resolve_config([], ["flank_modification.lengthwise_crowning_um=25",
                               "flank_modification.profile_crowning_um=5"])


@pytest.fixture(scope="module")
def published():
    return GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35, trace="logarithmic")


@pytest.fixture(scope="module")
def made(published, config):
    return practice_overlay(published, config)


def test_the_rated_torque_is_where_the_pitting_safety_is_one(published, config):
    rated = rated_gear_torque(published, config)
    speed = math.radians(config["simulation"]["pinion_speed_deg_s"])
    at, _, _ = rate_design(published, config["rating"], config["tooth"], rated["pitting"], speed,
                           dynamic_factor=1.0)
    assert min(at.contact_safety) == pytest.approx(1.0, rel=1e-9)
    at, _, _ = rate_design(published, config["rating"], config["tooth"], rated["bending"], speed,
                           dynamic_factor=1.0)
    assert min(at.bending_safety) == pytest.approx(1.0, rel=1e-9)
    # the paper's 1964.99 N m is about four times the pair's pitting rating
    assert 3.5 < 1964.99 / rated["pitting"] < 4.5


def test_the_overlay_is_the_iso_23509_shift_with_balanced_roots(published, config, made):
    overlay, figures = made
    assert overlay["design"]["undercut"] == "refuse"
    # the default rule is ISO 23509's mean addendum factor, and the figures say so
    assert config["practice"]["addendum_rule"] == "iso23509"
    assert overlay["design"]["profile_shift"] == pytest.approx(iso23509_profile_shift(published),
                                                               abs=1e-6)
    assert "ISO 23509" in figures["profile_shift_rule"]
    design = GearPairDesign.from_config({**merge_config(config, overlay)["design"],
                                         "trace": "logarithmic", "spiral_angle_deg": 35})
    assert root_stress_ratio(design, config["rating"], config["tooth"]) == pytest.approx(
        1.0, abs=2e-5)   # (x_smn1 written to 1e-6)
    pair = GearPair(design)
    assert pair.undercut["drive"]["pinion"] <= 0     # the published pinion's is 0.50 deg
    # the study's ease-off is kept, both tips relieved alike
    flanks = overlay["flank_modification"]
    assert (flanks["lengthwise_crowning_um"], flanks["profile_crowning_um"]) == (25, 5)
    assert flanks["pinion_tip_relief_um"] == flanks["gear_tip_relief_um"] > 0
    # shifted and balanced, the practice pair carries more before it pits
    assert figures["rated_torque_pitting_N_m"] > 1.1 * figures[
        "published_rated_torque_pitting_N_m"]
    assert overlay["simulation"]["load_torque_N_m"] == pytest.approx(
        figures["rated_torque_pitting_N_m"], abs=1e-3)


def test_the_agma_209_rule_is_kept_as_an_option(published, config):
    section = {**config["practice"], "addendum_rule": "agma209"}
    overlay, figures = practice_overlay(published, {**config, "practice": section})
    assert overlay["design"]["profile_shift"] == pytest.approx(gleason_profile_shift(published),
                                                               abs=1e-6)
    assert "AGMA 209" in figures["profile_shift_rule"]
    assert overlay["design"]["profile_shift"] < iso23509_profile_shift(published) - 0.1


def test_the_tip_relief_is_the_deflection_under_load(published, config):
    design = published.replace(profile_shift=0.45)
    half, length = deflection_tip_relief(design, config, 300.0, 1.25)
    full, _ = deflection_tip_relief(design, config, 600.0, 1.25)
    assert full == pytest.approx(2 * half, rel=1e-9)      # a deflection: linear in the load
    assert length == pytest.approx(0.2)                   # (1.25 - 1) / 1.25
    # F_mt / (b_eff c_gamma) with c_gamma of steel gears between 10 and 20 N/(mm um)
    speed = math.radians(config["simulation"]["pinion_speed_deg_s"])
    rating, _, _ = rate_design(design, config["rating"], config["tooth"], 600.0, speed)
    line_load = rating.factors["F_mt1"] / rating.factors["effective_face_width"]  # [N/m]
    assert line_load / 20e9 < full < line_load / 10e9
    with pytest.raises(ValueError, match="profile_contact_ratio = 0.9"):
        deflection_tip_relief(design, config, 600.0, 0.9)


def test_given_numbers_replace_the_rules(published, config):
    changed = merge_config(config, {"practice": {"profile_shift": 0.3,
                                                 "thickness_modification": 0.02,
                                                 "tip_relief_um": 12.5,
                                                 "tip_relief_length": 0.3,
                                                 "load_torque_N_m": 400.0}})
    overlay, figures = practice_overlay(published, changed)
    assert overlay["design"]["profile_shift"] == 0.3
    assert overlay["design"]["thickness_modification"] == 0.02
    assert overlay["flank_modification"]["gear_tip_relief_um"] == 12.5
    assert overlay["flank_modification"]["pinion_tip_relief_length"] == 0.3
    assert overlay["simulation"]["load_torque_N_m"] == 400.0
