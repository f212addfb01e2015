"""The point model's phase tables: the blocked deepest-point search gives every
table bit for bit what one pass over all contact lines gives."""

import numpy as np
import pytest

from lsbg.contact import MeshContact
from lsbg.contact import mesh
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair


@pytest.mark.parametrize("trace", ["logarithmic", "circular"])
def test_blocks_do_not_change_the_tables(trace, monkeypatch):
    pair = GearPair(GearPairDesign.from_units(trace=trace, spiral_angle_deg=30))
    blocked = MeshContact(pair, samples_per_pitch=2000).arrays
    rows = blocked[2].shape[1]
    for block in (1, 7, 333, rows):  # one line per block ... all lines in one block
        monkeypatch.setattr(mesh._deepest_points, "__defaults__", (33, block))
        other = MeshContact(pair, samples_per_pitch=2000).arrays
        for a, b in zip(blocked, other):
            assert a.shape == b.shape and a.tobytes() == b.tobytes()
