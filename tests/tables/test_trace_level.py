"""The trace level's verdict (lsbg.tables.trace_level) on datasets constructed here."""

import numpy as np
import pandas as pd
import pytest

from lsbg.matched.dataset import matched_pairs_dataset
from lsbg.matched.run import log_ratios, ratio_statistics
from lsbg.optimise import fronts
from lsbg.tables import claims as claim_tables
from lsbg.tables import first_screen, trace_level
from lsbg.tables.finding import CLAIMED
from tests.matched.test_run import converged
from tests.optimise.test_fronts import OBJECTIVES, converged_dataset, synthetic_front

#: The FE figures of a matched dataset: the aligned group's and the pattern's movement.
FE_FIGURES = ("transmission_error", "rated_transmission_error", "contact_pressure",
              "peak_contact_pressure", "root_stress_pinion", "root_stress_gear")


def matched(n=10, sbg_over_lsbg=1.3, full=None, fe_over=1.1, seed=2):
    """A matched-pairs dataset of ``n`` pairs whose SBG's stds are ``sbg_over_lsbg`` times
    the LSBG's: a number, or a (boundary, quantity) array of them; ``full`` pairs run in
    full (default every one); every FE figure of the SBG ``fe_over`` times the LSBG's."""
    full = n if full is None else full
    lsbg = converged("logarithmic", list(np.linspace(2, 3, n)), [1500] * n, [1] * n)
    sbg = converged("face_milled", list(np.linspace(2, 3, n)), [1500] * n, [1] * n)
    found = {"member": np.column_stack([np.arange(n), np.arange(n)]).reshape(n, 2),
             "distance": np.zeros(n), "candidates": np.array([n, n]), "assigned": n,
             "dropped": 0}
    rng = np.random.default_rng(seed)
    factor = np.broadcast_to(np.asarray(sbg_over_lsbg, float), (2, 2))
    std = np.ones((n, 2, 2, 2, 2))  # (pair, trace, estimate, boundary, quantity)
    std[:, 1] = factor * (1 + 0.02 * rng.standard_normal((n, 2, 2, 2)))
    std[full:, :, 1] = np.nan
    fe, state = {}, {}
    for name in (*FE_FIGURES, "pattern_movement"):
        values = np.column_stack([np.full(n, 100.0),
                                  100.0 * fe_over * (1 + 0.002 * rng.standard_normal(n))])
        state[name] = ratio_statistics(log_ratios(values)[:, None])
        if name != "pattern_movement":
            fe[name] = values
    attrs = {"caliper": 0.05, "pairs_sought": 30, "full_run_pairs": full, "indicative": 1,
             "proxy_error_max": "x", "proxy_log_ratio_error_max": "y"}
    return matched_pairs_dataset(found, (lsbg, sbg), std, fe, ratio_statistics(log_ratios(std)),
                                 attrs, state)


def fronts_cell(lsbg_shift, sbg_shift, seed=7):
    """A trace-fronts dataset whose LSBG fronts lie ``lsbg_shift`` above (worse than) the
    SBG's ``sbg_shift`` in every normalised objective."""
    rng = np.random.default_rng(seed)
    a = [synthetic_front(rng, lsbg_shift) for _ in range(3)]
    b = [synthetic_front(rng, sbg_shift) for _ in range(3)]
    return fronts.trace_fronts_dataset(fronts.trace_statistics(a, b, OBJECTIVES),
                                       converged_dataset("logarithmic", a, [1, 2, 3]),
                                       converged_dataset("face_milled", b, [1, 2, 3]))


def claims_of(trace_fronts=(), pairs=None):
    return trace_level.trace_claims(trace_level.trace_claim_cells(trace_fronts, pairs))


def test_the_lsbg_calmer_in_every_cell_is_yes():
    cells = trace_level.trace_claim_cells([], matched())
    stability = cells[cells["claim"] == "stability"]
    # every boundary and quantity a cell, from the full runs (every pair ran in full)
    assert len(stability) == 4 and (stability["source"] == "matched designs, full runs").all()
    assert (stability["side"] == "LSBG").all()
    assert np.allclose(stability["value"], 1.3, atol=0.03)
    claims, counts = trace_level.trace_claims(cells)
    assert claims["stability"] == "yes" and counts["stability"] == 4
    # the SBG 10 % above in every FE stress: the LSBG lives longer in all three cells
    assert claims["service life"] == "yes" and counts["service life"] == 3
    # the matching's own terms are shown elsewhere, never counted
    assert not cells["statistic"].str.startswith(("pattern movement", "contact pressure")).any()


def test_the_sbg_calmer_everywhere_is_the_opposite_and_a_mix_is_not_shown():
    claims, counts = claims_of(pairs=matched(sbg_over_lsbg=0.7, fe_over=0.9))
    assert claims["stability"] == "no, the opposite" and claims["service life"] == (
        "no, the opposite")
    # the LSBG calmer under the prescribed pinion, the SBG under the driveline
    mixed = np.array([[1.3, 1.3], [0.7, 0.7]])
    claims, counts = claims_of(pairs=matched(sbg_over_lsbg=mixed))
    assert claims["stability"] == "not shown" and counts["stability"] == 4
    # the SBG calmer in some cells and the rest unresolved is not "no": it is not shown
    some = np.array([[0.7, 1.0], [1.0, 1.0]])
    cells = trace_level.trace_claim_cells([], matched(sbg_over_lsbg=some))
    assert set(cells.loc[cells["claim"] == "stability", "side"]) == {"SBG", "not resolved"}
    assert trace_level.trace_claims(cells)[0]["stability"] == "not shown"


def test_a_difference_within_the_claims_resolution_is_not_resolved():
    # the SBG's stresses 1 % above in every pair: Wilcoxon resolves it, the FE does not
    cells = trace_level.trace_claim_cells([], matched(fe_over=1.01))
    life = cells[cells["claim"] == "service life"]
    assert (life["p"] < 0.05).all() and (life["side"] == "not resolved").all()
    assert trace_level.trace_claims(cells)[0]["service life"] == "not shown"


def test_the_proxy_where_fewer_than_two_pairs_ran_in_full():
    cells = trace_level.trace_claim_cells([], matched(full=1))
    stability = cells[cells["claim"] == "stability"]
    assert (stability["source"] == "matched designs, proxy").all()
    assert (stability["pairs"] == 10).all()
    # three pairs in full: Wilcoxon's least p is 0.25, so no full-run cell resolves
    few = trace_level.trace_claim_cells([], matched(full=3))
    assert (few.loc[few["claim"] == "stability", "side"] == "not resolved").all()


def test_no_pairs_is_not_tested_with_no_cells():
    empty = matched(n=0)
    claims, counts = claims_of(pairs=empty)
    assert claims == dict.fromkeys(trace_level.CLAIMS, "not tested")
    assert counts == dict.fromkeys(trace_level.CLAIMS, 0)
    assert claims_of() == (claims, counts)


def test_the_contact_state_from_the_fronts_in_every_cell():
    better, worse = fronts_cell(0.0, 0.3), fronts_cell(0.3, 0.0, seed=8)
    assert float(better["verdict"]) == 1 and float(worse["verdict"]) == -1
    claims, counts = claims_of([better, fronts_cell(0.0, 0.4, seed=9)])
    assert claims["contact state"] == "yes" and counts["contact state"] == 2
    # fronts alone say nothing of stability or life
    assert claims["stability"] == claims["service life"] == "not tested"
    claims, counts = claims_of([worse])
    assert claims["contact state"] == "no, the opposite" and counts["contact state"] == 1
    assert claims_of([better, worse])[0]["contact state"] == "not shown"
    # the fronts and the matched designs' FE loaded TE must agree: 1 + 2 cells
    cells = trace_level.trace_claim_cells([better], matched(fe_over=1.1))
    contact = cells[cells["claim"] == "contact state"]
    assert contact["source"].tolist() == ["fronts (A12 and the ε-indicator)",
                                          "matched designs, FE", "matched designs, FE"]
    assert trace_level.trace_claims(cells)[0]["contact state"] == "yes"
    assert claims_of([better], matched(fe_over=0.9))[0]["contact state"] == "not shown"


def test_fronts_without_a_verdict_or_a_contact_objective():
    nothing = fronts_cell(0.0, 0.3)
    nothing["verdict"] = np.nan  # a trace without a feasible member
    assert claims_of([nothing]) == (dict.fromkeys(trace_level.CLAIMS, "not tested"),
                                    dict.fromkeys(trace_level.CLAIMS, 0))
    # with a cell that has a verdict it still counts, against "every cell"
    claims, counts = claims_of([fronts_cell(0.0, 0.3), nothing])
    assert claims["contact state"] == "not shown" and counts["contact state"] == 2
    losses = fronts_cell(0.0, 0.3)
    losses.attrs["objectives"] = "mesh_loss"
    assert claims_of([losses])[0]["contact state"] == "not tested"


def test_the_matrix_has_the_traces_column_with_its_cells():
    claims, counts = claims_of([fronts_cell(0.3, 0.0, seed=8)], matched())
    table = pd.DataFrame({"cell": ["a"], "quantity": "x", "better": ["SBG"]})
    published = ({"stability": claim_tables.claim_verdict(table, "wins")}, {"stability": 1})
    matrix = first_screen.verdict_matrix({"published": published, "trace": (claims, counts)})
    heading = first_screen.LEVELS["trace"]
    assert heading == "the trace (front against front, matched designs)"
    cell = matrix.set_index(["claim", "level"])
    assert cell.loc[("stability", heading), "verdict"] == "yes"
    assert cell.loc[("stability", heading), "cells"] == 4
    assert cell.loc[("contact state", heading), "verdict"] == "not shown"
    assert cell.loc[("contact state", heading), "cells"] == 3
    four = first_screen.verdict_matrix({
        "published": published, "practice": published, "best": published,
        "trace": (claims, counts)})
    assert list(dict.fromkeys(four["level"])) == list(first_screen.LEVELS.values())
    html = first_screen.matrix_html(four)
    assert html.count("<th>") == 1 + 4 and "4 cells" in html and "3 cells" in html
    assert html.index(heading) > html.index("each at its best ease-off")
    # a trace level that tested nothing is still a column, every cell "not tested"
    empty = first_screen.verdict_matrix({"published": published,
                                         "trace": claims_of(pairs=matched(n=0))})
    assert (empty.loc[empty["level"] == heading, "verdict"] == "not tested").all()
    with pytest.raises(ValueError, match="not one of"):
        first_screen.verdict_matrix({"trace": ({"stability": "perhaps"}, {"stability": 1})})


def test_the_claims_table_gains_the_column_and_the_words_say_the_limits():
    claims, counts = claims_of([fronts_cell(0.3, 0.0, seed=8)], matched(n=3))
    table = pd.DataFrame({"the paper's claim": [CLAIMED["stability"], CLAIMED["service life"]],
                          "lsbg's answer at 35°": ["not shown", "no"],
                          "baseline figures": ["", ""], "cells": [19, 9]})
    out = trace_level.with_trace_column(table, claims, counts)
    assert list(out.columns) == ["the paper's claim", "lsbg's answer at 35°", "the trace",
                                 "baseline figures", "cells"]
    assert out["the trace"].tolist() == ["not shown (4 cells)", "not shown (3 cells)"]
    sets = [fronts_cell(0.3, 0.0, seed=8)]
    cells = trace_level.trace_claim_cells(sets, matched(n=3))
    sentence = trace_level.trace_sentence(sets, matched(n=3))
    assert "(1 cell of the trace study) and 3 matched pairs of 30 sought" in sentence
    assert "its least 0.25" in sentence
    assert sentence.count(". ") == 0 and "indicative" in sentence
    text = trace_level.trace_text(cells, claims, counts)
    assert "stability **not shown** (4 cells: not resolved in 4)" in text
    assert "contact state **not shown** (3 cells: the SBG in 1, not resolved in 2)" in text
    sets[0]["verdict"] = np.nan
    sentence = trace_level.trace_sentence(sets, matched(n=0))
    assert "none with a verdict" in sentence and "no stability or life comparison" in sentence
    # enough pairs for Wilcoxon, fewer than sought: still indicative, said without the limit
    sentence = trace_level.trace_sentence([], matched(n=10))
    assert "10 matched pairs of 30 sought: indicative" in sentence and "least" not in sentence
