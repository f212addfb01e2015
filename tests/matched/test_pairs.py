"""Matched designs (lsbg.matched.pairs): the pairing on constructed fronts, the statistics'
signs on constructed ratios."""

import math

import numpy as np
import pytest

from lsbg.matched import pairs


def test_normalised_maps_the_box_to_the_unit_square():
    values = np.array([[2.0, 100.0], [4.0, 300.0]])
    assert np.allclose(pairs.normalised(values, [2.0, 100.0], [4.0, 300.0]), [[0, 0], [1, 1]])
    with pytest.raises(ValueError, match="high must exceed"):
        pairs.normalised(values, [2.0, 100.0], [2.0, 300.0])


def test_known_pairs_are_found_in_any_order():
    rng = np.random.default_rng(3)
    a = rng.random((12, 2))
    order = rng.permutation(12)
    b = a[order] + rng.normal(0, 0.005, (12, 2))
    out = pairs.match_members(a, b, caliper=0.05)
    # member order[j] of a is member j of b
    assert out["a"].size == 12 and out["dropped"] == 0
    assert np.array_equal(order[out["b"]], out["a"])
    assert np.all(out["distance"] < 0.05)


def test_the_assignment_is_optimal_not_greedy():
    # greedy nearest-first would pair a0-b0 (0.1) and leave a1-b1 at 1.0; the optimum
    # pairs a0-b1 and a1-b0 for a total 0.2 + 0.2
    a = np.array([[0.0, 0.0], [0.3, 0.0]])
    b = np.array([[0.1, 0.0], [-0.2, 0.0]])
    out = pairs.match_members(a, b, caliper=1.0)
    assert out["a"].tolist() == [0, 1] and out["b"].tolist() == [1, 0]
    assert np.allclose(out["distance"], [0.2, 0.2])


def test_the_caliper_drops_the_members_outside_the_overlap():
    # two fronts overlapping on half their range: only the overlap's members pair
    t = np.linspace(0, 1, 11)
    a = np.column_stack([t, 1 - t])
    b = np.column_stack([t + 0.5, 0.5 - t])[:6]     # b's members 0..5 lie on a's 5..10
    out = pairs.match_members(a, b, caliper=0.05)
    assert out["a"].tolist() == [5, 6, 7, 8, 9, 10] and out["b"].tolist() == [0, 1, 2, 3, 4, 5]
    far = pairs.match_members(a, b + 0.2, caliper=0.05)
    assert far["a"].size == 0 and far["assigned"] == 6 and far["dropped"] == 6


def test_the_limit_keeps_the_closest_pairs():
    a = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    b = a + np.array([[0.03, 0.0], [0.01, 0.0], [0.02, 0.0]])
    out = pairs.match_members(a, b, caliper=0.05, limit=2)
    assert out["a"].tolist() == [1, 2]
    with pytest.raises(ValueError, match="caliper"):
        pairs.match_members(a, b, caliper=0.0)


def test_unique_rows_keeps_one_of_equal_designs():
    values = np.array([[1.0, 2.0], [0.0, 1.0], [1.0, 2.0]])
    assert pairs.unique_rows(values).tolist() == [0, 1]


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_the_statistics_follow_the_ratios_sign(sign):
    rng = np.random.default_rng(5)
    x = sign * (0.2 + 0.05 * rng.standard_normal(20))
    out = pairs.paired_statistics(x)
    assert out["pairs"] == 20 and out["wilcoxon_p"] < 1e-4
    assert math.copysign(1.0, out["mean"]) == sign
    assert out["low"] < out["mean"] < out["high"]
    assert (out["low"] > 0) if sign > 0 else (out["high"] < 0)
    assert out["positive"] == (1.0 if sign > 0 else 0.0)
    assert pairs.paired_statistics(x) == out       # deterministic


def test_centred_ratios_are_no_evidence():
    x = np.array([0.1, -0.12, 0.05, -0.04, 0.02, -0.03, 0.08, -0.07])
    out = pairs.paired_statistics(x)
    assert out["wilcoxon_p"] > 0.5 and out["low"] < 0 < out["high"]
    assert math.isnan(pairs.paired_statistics([0.3])["wilcoxon_p"])
    assert pairs.paired_statistics([])["pairs"] == 0
