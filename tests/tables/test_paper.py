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
