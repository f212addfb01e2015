"""The tooth tests' pair: the paper's (LSBG, 35 deg), and its coarse FE compliance."""

import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair


@pytest.fixture(scope="module")
def pair():
    return GearPair(GearPairDesign())


@pytest.fixture(scope="module")
def compliance(coarse_compliance):
    # the session's coarse compliance of the paper pair (tests/conftest.py)
    return coarse_compliance
