"""The release rule and the preferences among released designs (lsbg.optimise.preference)."""

import numpy as np
import pytest

from lsbg.optimise import preference

REFERENCE = {"transmission_error": 40.0, "peak_contact_pressure": 2000.0, "root_stress": 500.0}
CRITERIA = tuple(REFERENCE)


def _values(rows):
    rows = np.asarray(rows, float)
    return {name: rows[:, k] for k, name in enumerate(CRITERIA)}


def test_released_needs_no_criterion_worse_and_one_better_beyond_the_tolerance():
    values = _values([
        [36.0, 2000.0, 500.0],   # better TE, the rest equal: released
        [36.0, 2030.0, 500.0],   # better TE, 1.5 % more pressure: not
        [36.0, 2019.0, 504.9],   # better TE, worse within 1 %: released
        [39.7, 1990.0, 498.0],   # better by less than 1 % everywhere: not
        [40.0, 2000.0, 500.0],   # the shared design itself: not
        [50.0, 1500.0, 400.0],   # much better twice, worse TE: not
    ])
    released = preference.released(values, REFERENCE, CRITERIA, 0.01)
    assert released.tolist() == [True, False, True, False, False, False]
    # no tolerance: any strict improvement and no worsening at all
    assert preference.released(values, REFERENCE, CRITERIA, 0.0).tolist() == [
        True, False, False, True, False, False]


def test_weights_are_per_unit_not_normalised_over_the_candidates():
    weights = {"transmission_error": 1.0, "peak_contact_pressure": 0.02}
    values = _values([[38.0, 2000.0, 0.0], [40.0, 1850.0, 0.0]])
    # 2 urad against 150 MPa * 0.02 = 3: the second
    assert preference.scores(values, REFERENCE, weights).tolist() == pytest.approx([-2.0, -3.0])
    assert preference.weighted_order(values, REFERENCE, weights).tolist() == [1, 0]
    # a third candidate far off in pressure does not change the two's order (a knee
    # normalised over the candidates would: its span sets the weights)
    wider = _values([[38.0, 2000.0, 0.0], [40.0, 1850.0, 0.0], [60.0, 1000.0, 0.0]])
    order = preference.weighted_order(wider, REFERENCE, weights).tolist()
    assert order.index(1) < order.index(0)


def test_lexicographic_counts_values_within_the_tolerance_equal():
    values = _values([[30.0, 2100.0, 500.0], [30.2, 1900.0, 500.0], [31.0, 1800.0, 500.0]])
    # 30 and 30.2 within 1 %: the pressure decides between them; 31 is 3 % off
    assert preference.lexicographic_order(values, CRITERIA, 0.01).tolist() == [1, 0, 2]
    assert preference.lexicographic_order(values, CRITERIA, 0.0).tolist() == [0, 1, 2]


def test_ranks_under_the_alternatives_and_a_bad_rule():
    values = _values([[30.0, 2100.0, 500.0], [35.0, 1900.0, 450.0], [30.5, 1950.0, 460.0]])
    weights = {"transmission_error": 1.0, "peak_contact_pressure": 0.02, "root_stress": 0.02}
    knee = preference.order("knee", values, REFERENCE, weights, CRITERIA, 0.01)
    # normalised: [0+1+1, 1+0+0, 0.1+0.25+0.2]: the third first
    assert knee.tolist() == [2, 1, 0]
    assert preference.rank_of(0, knee) == 3 and preference.rank_of(7, knee) == 0
    with pytest.raises(ValueError, match="rule = 'best'"):
        preference.order("best", values, REFERENCE, weights, CRITERIA, 0.01)
