"""The practice section's problems, found before any job and named by key."""

import pytest

from lsbg.config import resolve_config
from lsbg.practice.checks import practice_problems


def problems(*overrides):
    config = resolve_config([], list(overrides))
    config["paper_spiral_angle_deg"] = 35.0
    return practice_problems(config)


def test_the_default_practice_design_passes():
    assert problems() == []


@pytest.mark.parametrize("override, words", [
    ("practice.profile_shift=-0.5", "practice.profile_shift = -0.5: the practice design cannot "
                                    "be made (profile_shift = -0.5: the pinion is undercut"),
    ("practice.thickness_modification=0.4", "practice.thickness_modification = 0.4: the "
                                            "practice design cannot be made"),
    ("practice.load_spectrum.torque_fractions=[0.05, 0.5, 1, 1.2, 1.4]",
     "practice.load_spectrum.torque_fractions = [0.05, 0.5, 1.0, 1.2, 1.4]: must lie within "
     "practice.load_range (0.1 to 1.5 of the rated torque)"),
    ("practice.tip_relief_um=90", "practice: the practice design's logarithmic pair: "
                                  "flank_modification.pinion_tip_relief_um = 90"),
])
def test_a_practice_the_design_cannot_take_is_named(override, words):
    found = problems(override)
    assert any(line.startswith(words) for line in found), found


def test_disabled_is_not_checked():
    assert problems("practice.enabled=false", "practice.profile_shift=-0.5") == []
