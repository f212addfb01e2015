"""The optimisation's report text and table: how each type's ease-off was released."""

import numpy as np
import pytest

from lsbg.optimise.objectives import QUANTITIES
from lsbg.optimise.release import ReleaseSettings, release_dataset
from lsbg.optimise.verdict import CONVERGED_QUANTITIES, FE_QUANTITIES, Resolution
from lsbg.tables.optimise import (release_efficiency_text, release_table, release_text,
                                  release_words)
from lsbg.tca.modification import FlankModification


def _release(chosen, trace):
    """A release of two candidates (both under FE, the second released where chosen = 1)."""
    n = 2
    fe = {name: np.array([50.0, 30.0]) for name in FE_QUANTITIES}
    uniform = {name: np.array([2.0, 1.5]) for name in (*CONVERGED_QUANTITIES, "edge_load")}
    result = {
        "candidates": [(0, 3), (1, 5)], "front_seeds": [1, 2],
        "modifications": [FlankModification(30e-6, 2e-6), FlankModification(40e-6, 4e-6)],
        "search": {name: np.ones(n) for name in QUANTITIES},
        "uniform": uniform, "fe": fe,
        "verdict": {**fe, "mesh_loss": uniform["mesh_loss"], "pattern_movement": np.ones(n)},
        "reference_search": {name: 1.0 for name in QUANTITIES},
        "reference_uniform": {name: 1.7 for name in uniform},
        "reference_fe": {name: 40.0 for name in FE_QUANTITIES},
        "reference_verdict": {**{name: 40.0 for name in FE_QUANTITIES}, "mesh_loss": 1.7,
                              "pattern_movement": 2.0},
        "released": np.array([False, chosen == 1]), "checked": np.array([np.nan, 0.0]),
        "chosen": chosen, "front_chosen": [-1, chosen], "ranks": {"lexicographic": 1,
                                                                  "knee": 1} if chosen >= 0 else {},
        "fe_evaluated": np.ones(n, bool),
        "uniform_resolution": Resolution(96, (0.05, 0.004), True, 0.01),
        "fe_resolutions": {"aligned": Resolution(192, (0.08, 0.02, 0.005), True, 0.01),
                           "corners": Resolution(48, (0.003,), True, 0.01)},
        "chosen_fe_change": 0.004 if chosen >= 0 else np.nan, "seconds": 1.0}
    return release_dataset(result, ReleaseSettings(), {
        "design_trace": trace, "reference_flank_modification_lengthwise_crowning_um": 25.0})


def test_a_type_that_keeps_the_shared_ease_off_says_so_without_nan():
    releases = {"SBG": _release(-1, "circular"), "LSBG": _release(1, "logarithmic")}
    words = release_words(releases)
    assert words.endswith("SBG: none released, the shared ease-off stays")
    text = release_text(releases)
    assert "nan" not in text.lower()
    assert "**the shared ease-off stays**" in text.split("**LSBG**")[0]
    assert "released (seed 2)" in text and "1 under the lexicographic rule" in text
    assert "FE at 192 aligned and 48 at the corners" in text
    efficiency = release_efficiency_text(releases)
    assert "SBG 98.30 % (it keeps the shared ease-off)" in efficiency
    assert "LSBG 98.30 % with the shared ease-off, 98.50 % with its own" in efficiency


def test_the_table_holds_every_figure_under_both_models():
    releases = {"SBG": _release(-1, "circular"), "LSBG": _release(1, "logarithmic")}
    table = release_table(releases).set_index(["model", "quantity"])
    assert not table.isna().any().any()
    assert {m for m, _ in table.index} == {"ease-off", "uniform bed", "FE", "unloaded TCA"}
    assert len(table.loc["FE"]) == len(FE_QUANTITIES)
    # none released: the SBG's released column is the shared design's
    assert table.loc[("FE", "transmission error"), "SBG released"] == 40.0
    assert table.loc[("FE", "transmission error"), "SBG best candidate"] == 30.0
    assert table.loc[("FE", "transmission error"), "LSBG released"] == 30.0
    assert table.loc[("ease-off", "lengthwise crowning"), "SBG released"] == 25.0
    assert table.loc[("ease-off", "lengthwise crowning"), "LSBG released"] == pytest.approx(40.0)
