"""Shared pairs and evaluators of the optimisation's tests (the paper's pair at 35 deg)."""

import math

import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair

#: The paper pair's ISO 10300 contact-rated gear torque [N m] (lsbg.optimise.checks.rated_torque).
RATED = 484.76


@pytest.fixture(scope="session")
def pairs():
    """The paper's pair at 35 deg, LSBG and SBG."""
    return {trace: GearPair(GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35,
                                                      trace=trace))
            for trace in ("logarithmic", "circular")}


@pytest.fixture(scope="session")
def envelope():
    """The default V-H envelope's corners, E and P +-0.1 mm (SI)."""
    from lsbg.optimise.checks import envelope_corners_of

    return envelope_corners_of({"misalignment_map": {"axes": ["E", "P"], "range": 0.1}})


def edge_radius(design):
    """The FE segment's root fillet as the generating rack's edge radius [m]."""
    return 0.25 * design.mean_module * math.cos(design.spiral_angle)
