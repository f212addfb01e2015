"""The memos (lsbg.memo) of the unloaded TCA and the search give what computing afresh gives, bit for
bit, are keyed on what the values depend on, and stay bounded."""

import numpy as np
import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg import memo
from lsbg.tca.analysis import SurfacePair, backlash, mesh_cycle_pinion_angles
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification

CROWNED = FlankModification(lengthwise_crowning=25e-6, profile_crowning=5e-6, bias=2e-6)
DISPLACED = Misalignment(offset=-5e-5, pinion_axial=1e-4)
GRID = (21, 41)


@pytest.fixture
def pair():
    """A pair of its own (empty memos)."""
    return GearPair(GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35,
                                              trace="circular"))


def fresh(pair, compute):
    """``compute()`` with the pair's memos emptied first."""
    memo._MEMOS.pop(pair, None)
    return compute()


def same_bits(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def test_cached_drops_the_least_recently_used():
    kept, calls = {}, []
    for key in (1, 2, 1, 3):
        assert memo.cached(kept, key, lambda: calls.append(key) or 10 * key, size=2) == 10 * key
    assert calls == [1, 2, 3]       # the second 1 was a hit
    assert list(kept) == [1, 3]     # 2, least recently used, dropped


def test_keys_tell_signed_zeros_apart():
    assert memo.float_key([0.0]) != memo.float_key([-0.0])
    assert memo.fields_key(Misalignment(offset=1e-4)) == memo.fields_key(Misalignment(offset=1e-4))
    assert memo.fields_key(Misalignment()) != memo.fields_key(Misalignment(offset=-0.0))



def test_array_keys_tell_values_shapes_and_layouts_apart():
    a = np.arange(6.0).reshape(2, 3)
    assert memo.arrays_key(a, a[0]) == memo.arrays_key(a.copy(), a[0].copy())
    assert memo.arrays_key(a) != memo.arrays_key(a.reshape(3, 2))          # shape
    assert memo.arrays_key(a.T) != memo.arrays_key(np.ascontiguousarray(a.T))  # layout
    assert memo.arrays_key(np.zeros(2)) != memo.arrays_key(-np.zeros(2))   # signed zeros
    assert memo.arrays_key(a) != memo.arrays_key(a.astype(np.float32))     # type


def test_memos_are_per_pair_and_kind(pair):
    other = GearPair(pair.design)
    assert memo.memoised(pair, "a", 1, lambda: "x") == "x"
    assert memo.memoised(pair, "a", 1, lambda: "y") == "x"
    assert memo.memoised(pair, "b", 1, lambda: "y") == "y"
    assert memo.memoised(other, "a", 1, lambda: "z") == "z"


def test_surface_pair_is_the_uncached_one_bit_for_bit(pair):
    for modification, misalignment in ((FlankModification(), Misalignment()),
                                       (CROWNED, Misalignment()),
                                       (FlankModification(), DISPLACED)):
        SurfacePair.build(pair, modification, misalignment, *GRID)
    kept = SurfacePair.build(pair, CROWNED, DISPLACED, *GRID)
    kept.constants[:] = 0.0  # a caller's change does not reach the memo
    kept.line_turn[:] = 0.0
    kept = SurfacePair.build(pair, CROWNED, DISPLACED, *GRID)
    afresh = fresh(pair, lambda: SurfacePair.build(pair, CROWNED, DISPLACED, *GRID))
    for name in ("constants", "points", "normals", "line_turn", "order", "cone_distance",
                 "profile_psi", "relief"):
        assert same_bits(getattr(kept, name), getattr(afresh, name)), name
    aligned = SurfacePair.build(pair, CROWNED, Misalignment(), *GRID)
    assert not same_bits(aligned.constants, kept.constants)  # keyed on the displacement


def test_backlash_keeps_each_displacements_coast_contact(pair):
    angles = mesh_cycle_pinion_angles(pair, 8)

    def play(modification, misalignment):
        return backlash(SurfacePair.build(pair, modification, misalignment, *GRID), angles)

    afresh = {m: fresh(pair, lambda: play(CROWNED, m)) for m in (Misalignment(), DISPLACED)}
    for m in afresh:  # another design fills the memo first
        play(FlankModification(), m)
    for m, expected in afresh.items():
        assert same_bits(play(CROWNED, m), expected)
    assert not np.array_equal(afresh[Misalignment()], afresh[DISPLACED])
