"""The matched designs' table and words (lsbg.tables.matched) on a constructed dataset."""

import math

import numpy as np

from lsbg.matched.dataset import matched_pairs_dataset
from lsbg.matched.run import log_ratios, ratio_statistics
from lsbg.tables import matched
from tests.matched.test_run import converged


def constructed(n=10):
    lsbg = converged("logarithmic", list(np.linspace(2, 3, n)), [1500] * n, [1] * n)
    sbg = converged("face_milled", list(np.linspace(2, 3, n)), [1500] * n, [1] * n)
    member = np.column_stack([np.arange(n), np.arange(n)])
    found = {"member": member, "distance": np.zeros(n), "candidates": np.array([n, n]),
             "assigned": n, "dropped": 0}
    rng = np.random.default_rng(2)
    std = np.ones((n, 2, 2, 2, 2))
    std[:, 1] = 1.3 + 0.02 * rng.standard_normal((n, 2, 2, 2))   # the SBG 30 % rougher
    std[3:, :, 1] = np.nan                                       # full runs of 3 pairs
    attrs = {"caliper": 0.05, "pairs_sought": n, "full_run_pairs": 3, "indicative": 1,
             "proxy_error_max": "x", "proxy_log_ratio_error_max": "y"}
    stats = ratio_statistics(log_ratios(std))
    # the SBG's root stress 10 % above the LSBG's in every pair
    stress = np.column_stack([np.full(n, 500.0), 550.0 + rng.standard_normal(n)])
    state = {"root_stress_gear": ratio_statistics(log_ratios(stress)[:, None])}
    return matched_pairs_dataset(found, (lsbg, sbg), std, {"root_stress_gear": stress}, stats,
                                 attrs, state)


def test_the_table_says_the_lsbg_is_calmer_where_the_sbg_is_rougher():
    table = matched.matched_table(constructed())
    proxy = table[table["estimate"] == "proxy"]
    assert len(table) == 8 and (proxy["pairs"] == 10).all()
    assert np.allclose(proxy["ratio"], 1.3, atol=0.03) and (proxy["calmer"] == "LSBG").all()
    # three pairs: Wilcoxon's least two-sided p is 0.25, so nothing is resolved
    full = table[table["estimate"] == "full"]
    assert (full["pairs"] == 3).all() and (full["calmer"] == "not resolved").all()
    text = matched.matched_text(constructed())
    assert text.startswith("**Matched designs:** 10 pairs") and "(indicative)" in text
    state = matched.state_table(constructed())
    assert state["figure"].tolist() == ["root_stress_gear"] and state["lower"][0] == "LSBG"
    assert np.isclose(state["ratio"][0], 1.1, atol=0.01) and "root_stress_gear 1.1" in text


def test_calmer_needs_both_the_interval_and_the_test():
    assert matched.calmer_of(0.1, 0.3, 0.01) == "LSBG"
    assert matched.calmer_of(-0.3, -0.1, 0.01) == "SBG"
    assert matched.calmer_of(0.1, 0.3, 0.2) == "not resolved"
    assert matched.calmer_of(-0.1, 0.3, 0.01) == "not resolved"
    assert matched.calmer_of(math.nan, math.nan, math.nan) == "—"
