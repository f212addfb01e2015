"""The cutter-radius sweep's tables (lsbg.tables.cutter)."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg.tables.cutter import FIGURES, cutter_table, decomposition


def point(trace, radius, roles, movement, te, pressure):
    """A point's file as lsbg cutter-point writes it (a V-H map's sensitivities as attributes)."""
    attrs = {"axes": "E P", "cutter_trace": trace, "cutter_radius_mm": radius,
             "cutter_roles": roles, "cutter_trace_curvature_radius": radius,
             "cutter_spiral_angle_toe": 30.0, "cutter_spiral_angle_heel": 40.0,
             "cutter_loaded_te_peak_to_peak": te, "cutter_max_contact_pressure": pressure,
             "cutter_root_stress_pinion": 2 * pressure, "cutter_root_stress_gear": pressure / 2,
             # the pattern moves 3-4-5 along E, not along P: total = movement
             "pattern_shift_lengthwise_per_0_1_E": 0.6 * movement,
             "pattern_shift_profile_per_0_1_E": 0.8 * movement,
             "pattern_shift_lengthwise_per_0_1_P": 0.0, "pattern_shift_profile_per_0_1_P": 0.0}
    return xr.Dataset(attrs=attrs)


@pytest.fixture
def table():
    return cutter_table([point("circular", 135.0, "matched", 4.4, 101.0, 10600.0),
                         point("logarithmic", 127.6, "lsbg", 4.5, 104.0, 11200.0),
                         point("circular", 76.2, "design nominal", 3.4, 80.0, 8700.0),
                         point("circular", 95.25, "nominal", 3.7, 89.0, np.nan)])


def test_table_puts_the_lsbg_first_then_the_sbgs_by_radius(table):
    assert table["type"].tolist() == ["LSBG", "SBG", "SBG", "SBG"]
    assert table["cutter_radius_mm"].tolist() == [127.6, 76.2, 95.25, 135.0]
    assert table["pattern_movement"].tolist() == pytest.approx([4.5, 3.4, 3.7, 4.4])


def test_the_two_shares_add_up_to_the_difference(table):
    parts = decomposition(table).set_index("figure")
    assert list(parts.index) == [words for _, words in FIGURES.values()]
    move = parts.loc[FIGURES["pattern_movement"][1]]
    assert move["difference"] == pytest.approx(4.5 - 3.4)
    assert move["curvature's share"] == pytest.approx(4.4 - 3.4)
    assert move["constant spiral angle's share"] == pytest.approx(4.5 - 4.4)
    assert move["curvature's fraction"] == pytest.approx(1.0 / 1.1)
    assert np.allclose(parts["curvature's share"] + parts["constant spiral angle's share"],
                       parts["difference"])


def test_a_sweep_without_its_matched_point_is_refused(table):
    with pytest.raises(ValueError, match="no point of role 'matched'"):
        decomposition(table[table["roles"] != "matched"])
