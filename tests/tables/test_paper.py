"""Tables of the paper's reproduction and of engine agreement, from short real runs."""

import numpy as np
import pytest

from lsbg import stats
from lsbg.dynamics.dataset import open_run
from lsbg.aggregate.runs import steady
from lsbg.tables.paper import fluctuation_conclusion, theory_table
from lsbg.tables.verification import engine_agreement


# ------------------------------------------------------- report pieces
def test_engine_agreement_and_theory_table(runs):
    pybullet, scipy = open_run(runs["lsbg35"]), open_run(runs["lsbg35_scipy"])
    agreement = engine_agreement([pybullet, scipy, open_run(runs["sbg35"])], 0.01)
    assert list(agreement.quantity) == ["gear_speed", "tangential_force"]
    row = agreement.iloc[0]
    assert (row.gear_type, row.engine, row.reference) == ("LSBG", "pybullet", "scipy")
    x, y = steady(pybullet, "gear_speed", 0.01), steady(scipy, "gear_speed", 0.01)
    assert row.std_ratio == pytest.approx(x.std(ddof=1) / y.std(ddof=1))
    assert row.within_tolerance == (abs(row.std_ratio - 1) <= 0.03)
    table = theory_table([pybullet, open_run(runs["sbg35"])], 0.01)
    assert list(table.gear_type) == ["SBG"] * 3 + ["LSBG"] * 3
    lsbg_speed = table[(table.gear_type == "LSBG") & (table.quantity == "gear_speed")].iloc[0]
    assert lsbg_speed.simulated == pytest.approx(x.mean())
    assert lsbg_speed.paper_simulated == 1873.77 and lsbg_speed.paper_error_rate_percent == 0.0036
    assert np.isnan(table[table.quantity == "tangential_force_outer"].paper_simulated).all()


def test_fluctuation_conclusion_follows_the_data():
    rng = np.random.default_rng(3)
    calm, rough = rng.normal(0, 1, 400), rng.normal(0, 2, 400)
    sbg_calmer = {"gear_speed": stats.compare_fluctuation(calm, rough)}
    assert "contradict" in fluctuation_conclusion(sbg_calmer)
    lsbg_calmer = {"gear_speed": stats.compare_fluctuation(rough, calm)}
    text = fluctuation_conclusion(lsbg_calmer)
    assert "support the paper's conclusion" in text and "The paper's ratio" in text
    same = {"gear_speed": stats.compare_fluctuation(calm, rng.normal(0, 1, 400))}
    assert "No difference is significant" in fluctuation_conclusion(same)


def _record(**changes):
    """A design.json record of the paper's pair with ``changes`` (configuration keys)."""
    from lsbg.gear.design import GearPairDesign

    design = GearPairDesign.from_config({"trace": "circular", **changes})
    return {**design.to_config(), **design.derived()}


def test_table1_says_changed_only_where_a_value_differs_from_the_papers():
    from lsbg.tables.paper import design_rows

    records = {"SBG": _record(face_width_mm=30.0),
               "LSBG": {**_record(face_width_mm=30.0), "trace": "logarithmic"}}
    origin = design_rows(records).set_index("quantity")["origin"]
    assert origin["face width b"] == "changed (assumed: 25)"
    table1 = [q for q, o in origin.items() if o == "paper Table 1"]
    assert "number of teeth z1 (pinion)" in table1 and "outer pitch diameter d1" in table1
    assert "mean spiral angle βm" in table1 and "dedendum hf" in table1
    assert [q for q, o in origin.items() if o.startswith("changed")] == ["face width b"]
    assert origin["cutter radius rc (SBG only)"] == "assumed"
    # the module changes the pitch diameters too: each row says so, with the paper's value
    origin = design_rows({"SBG": _record(module_mm=5.0)}).set_index("quantity")["origin"]
    assert origin["outer transverse module m"] == "changed (paper: 4.5)"
    assert origin["outer pitch diameter d1"].startswith("changed (paper: 40.5")
    assert origin["face width b"] == "assumed"


def test_the_design_in_words_counts_a_changed_spiral_angle():
    from lsbg.tables.paper import design_words

    words, paper_pair = design_words(_record())
    assert paper_pair and words.startswith("the paper's Table 1 (")
    words, paper_pair = design_words(_record(spiral_angle_deg=30.0))
    assert not paper_pair
    assert words.endswith("changed: spiral angle 30°)")
    # a sweep over the angle names no angle and so no change of it
    assert design_words(_record(spiral_angle_deg=30.0), spiral_angle=False)[1]
