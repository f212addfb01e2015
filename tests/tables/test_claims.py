"""The three claims' tables and verdicts (lsbg.tables.claims) on datasets of known figures."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg.rating.life import EXPONENTS
from lsbg.tables import claims
from tests.tables.test_rating import fe_ltca, rating

AXES = (-0.1, 0.0, 0.1)


def vh_map(trace, movement, te_change, edge_share, case=None):
    """A stand-in V-H map: the pattern moves ``movement`` mm per 0.1 mm along E only; the
    loaded TE p-p is 10 µrad at the centre and grows by te_change per 0.1 mm of E and P."""
    e, p = np.meshgrid(AXES, AXES, indexing="ij")
    te = 10.0 + te_change * (np.abs(e) + np.abs(p)) / 0.1
    ds = xr.Dataset({"transmission_error_loaded_pp": (("E", "P"), te),
                     "edge_load_share": (("E", "P"), edge_share * (1 + np.abs(e)))},
                    coords={"E": list(AXES), "P": list(AXES)},
                    attrs={"axes": "E P", "design_trace": trace,
                           "pattern_shift_lengthwise_per_0_1_E": movement,
                           "pattern_shift_profile_per_0_1_E": 0.0,
                           "pattern_shift_lengthwise_per_0_1_P": 0.0,
                           "pattern_shift_profile_per_0_1_P": 0.0,
                           "transmission_error_loaded_pp_per_0_1_E": te_change,
                           "transmission_error_loaded_pp_per_0_1_P": 0.0})
    if case:
        ds.attrs["sensitivity_case"] = case
    return ds


def test_contact_state_ranks_each_figure_and_ties_within_the_resolution():
    maps = {"SBG": vh_map("circular", 3.0, 10.0, 0.10), "LSBG": vh_map("logarithmic", 4.0, 20.0, 0.102)}
    cases = [vh_map("circular", 6.0, 11.0, 0.12, "crowning_x0.5"),
             vh_map("logarithmic", 5.0, 30.0, 0.12, "crowning_x0.5")]
    table = claims.contact_state_table(maps, cases)
    assert list(table["cell"].unique()) == [claims.BASELINE, "crowning ×0.5"]
    base = table[table["cell"] == claims.BASELINE].set_index("quantity")
    movement = claims.CONTACT_FIGURES["pattern_movement"][0]
    assert base.loc[movement, "SBG"] == pytest.approx(3.0)
    assert base.loc[movement, "better"] == "SBG"
    edge = claims.CONTACT_FIGURES["edge_load_share"][0]
    assert base.loc[edge, "SBG"] == pytest.approx(10.0)           # the centre cell, in %
    assert base.loc[edge, "better"] == "tie"                      # 2 % apart: within 5 %
    worst = claims.CONTACT_FIGURES["edge_load_share_envelope"][0]
    assert base.loc[worst, "LSBG"] == pytest.approx(10.2 * 1.1)
    verdict = claims.claim_verdict(table, "is lower", "at 35°")
    # the pattern: the SBG in the baseline, the LSBG with half the crowning: no ranking
    assert movement not in verdict["holds"]
    assert "the LSBG in 1 of 2 cells, the SBG in 1 (baseline" in verdict["sentences"][movement]
    te = claims.CONTACT_FIGURES["te_change"][0]
    assert verdict["holds"][te] == "SBG"
    assert "in every one of the 2 cells" in verdict["sentences"][te]
    assert claims.claim_answer(verdict) == "**not shown**"


def test_answers_name_yes_no_and_the_opposite():
    def verdict(better):
        table = pd.DataFrame({"cell": ["a", "b", "a", "b"], "quantity": ["x", "x", "y", "y"],
                              "better": better})
        return claims.claim_verdict(table, "wins")
    assert claims.claim_answer(verdict(["LSBG"] * 4)) == "**yes**"
    assert claims.claim_answer(verdict(["SBG"] * 4)).startswith("**no, the opposite**")
    assert claims.claim_answer(verdict(["SBG", "tie", "SBG", "SBG"])) == (
        "**no**: the LSBG is better in no cell")
    assert claims.claim_answer(verdict(["SBG", "LSBG", "SBG", "SBG"])) == "**not shown**"
    # a tie in every cell is not "no": nothing is shown either way
    assert claims.claim_word(verdict(["tie"] * 4)) == "not shown"
    assert claims.claim_answer(verdict(["tie"] * 4)) == "**not shown** (a tie in every cell)"
    assert claims.claim_word(verdict(["SBG", "tie", "tie", "tie"])) == "no"
    assert [claims.claim_word(verdict(b)) for b in (["LSBG"] * 4, ["SBG"] * 4)] == [
        "yes", "no, the opposite"]
    assert set(claims.VERDICT_WORDS) == {"yes", "no, the opposite", "no", "not shown"}


def test_life_cells_follow_the_stress_ratio_and_the_stated_exponent():
    ratings = {"SBG": rating("circular", 3000.0, 2000.0, 1000.0, displaced_factor=1.0),
               "LSBG": rating("logarithmic", 3300.0, 1900.0, 1000.0, displaced_factor=1.0)}
    fe = {"SBG": fe_ltca(3000.0, 2000.0, 1000.0), "LSBG": fe_ltca(3300.0, 1900.0, 1000.0)}
    case = fe_ltca(2000.0, 2000.0, 1000.0)
    case.attrs.update(design_trace="logarithmic", sensitivity_case="crowning_x2")
    sbg_case = fe_ltca(2500.0, 2000.0, 1000.0)
    sbg_case.attrs.update(design_trace="circular", sensitivity_case="crowning_x2")
    table = claims.life_table(ratings, fe, [case, sbg_case])
    cells = list(table["cell"].unique())
    assert cells[0] == "ISO 10300 (K_v of the baseline run)"
    assert "FE loaded TCA, crowning ×2" in cells
    assert sum(c.startswith("FE loaded TCA, displaced") for c in cells) == 4
    aligned = table[table["cell"] == "FE loaded TCA, " + claims.BASELINE].set_index("quantity")
    p = EXPONENTS["contact"][0].exponent
    row = aligned.loc["contact stress (pitting)"]
    assert row["life ratio LSBG/SBG"] == pytest.approx((3000.0 / 3300.0) ** p)
    assert row["better"] == "SBG"
    assert aligned.loc["root stress, pinion", "better"] == "LSBG"   # 5 % lower
    assert aligned.loc["root stress, gear", "better"] == "tie"
    crowned = table[table["cell"] == "FE loaded TCA, crowning ×2"].set_index("quantity")
    assert crowned.loc["contact stress (pitting)", "better"] == "LSBG"
    # the standard rates both alike (only K_v differs): a tie in every ISO cell
    assert set(table[table["cell"].str.startswith("ISO")]["better"]) == {"tie"}
    verdict = claims.claim_verdict(table, "lives longer")
    assert claims.claim_answer(verdict) == "**not shown**"


def test_stability_pairs_take_the_te_of_their_own_cell():
    rows = []
    for cell, case, calmer in (("line model (baseline)", "", "SBG"),
                               ("crowning ×2", "crowning_x2", "SBG"),
                               ("displaced E+0.1 P-0.1 mm", "displaced_E+0.1_P-0.1", "LSBG"),
                               ("damping ratio ×2", "mesh_damping_ratio_x2", "SBG")):
        rows.append({"cell": cell, "quantity": "gear_speed", "ratio": 0.8, "ratio_low": 0.7,
                     "ratio_high": 0.9, "calmer": calmer, "holds": calmer == "SBG",
                     "case": case})
    sensitivity = pd.DataFrame(rows)
    maps = {"SBG": vh_map("circular", 3.0, 10.0, 0.1), "LSBG": vh_map("logarithmic", 4.0, 20.0, 0.1)}
    cases = [vh_map("circular", 2.0, 5.0, 0.1, "crowning_x2"),
             vh_map("logarithmic", 2.0, 7.0, 0.1, "crowning_x2")]
    table = claims.stability_table(sensitivity, maps, cases).set_index("cell")
    assert list(table.index) == ["line model (baseline)", "crowning ×2", "displaced E+0.1 P-0.1 mm"]
    te = "loaded TE p-p {} [µrad]"
    assert table.loc["line model (baseline)", te.format("SBG")] == pytest.approx(10.0)
    # the corner E+0.1, P-0.1 of the baseline map: 10 + 10 * (1 + 1)
    assert table.loc["displaced E+0.1 P-0.1 mm", te.format("SBG")] == pytest.approx(30.0)
    assert table.loc["displaced E+0.1 P-0.1 mm", te.format("LSBG")] == pytest.approx(50.0)
    long = claims.stability_cells(sensitivity)
    verdict = claims.claim_verdict(long, "fluctuates less")
    assert "the LSBG in 1 (displaced E+0.1 P-0.1 mm)" in verdict["sentences"]["gear angular velocity"]


def test_claims_by_angle_puts_each_claim_beside_the_others():
    ratios = pd.DataFrame({"spiral_angle_deg": [30.0, 35.0], "quantity": ["gear_speed"] * 2,
                           "calmer": ["neither", "SBG"]})
    contact = pd.DataFrame({"spiral_angle": [30.0, 35.0], "SBG": [3.0, 3.0], "LSBG": [3.05, 4.0],
                            "better": ["tie", "SBG"]})
    rating = pd.DataFrame({"gear_type": ["SBG", "LSBG"] * 2, "spiral_angle": [30.0, 30.0, 35.0, 35.0],
                           "contact_stress": [3000.0, 3001.0, 3000.0, 3200.0],
                           "root_stress_pinion": [1500.0, 1500.0, 1500.0, 1400.0]})
    table = claims.claims_by_angle(ratios, contact, rating).set_index("spiral angle [deg]")
    assert table.loc[30.0, "stability, gear angular velocity: calmer"] == "neither"
    assert table.loc[35.0, "contact state: pattern moves less"] == "SBG"
    assert table.loc[35.0, "ISO 10300 contact stress LSBG/SBG"] == pytest.approx(3200 / 3000)
    assert table.loc[35.0, "ISO 10300 contact stress: lives longer"] == "SBG"
    assert table.loc[35.0, "ISO 10300 pinion root stress: lives longer"] == "LSBG"
    assert table.loc[30.0, "ISO 10300 contact stress: lives longer"] == "tie"
