"""The stability answer by band and over the cells (lsbg.tables.stability)."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg.stats import spectra
from lsbg.tables import stability

RATE = 50_000.0
MESH = float(spectra.mesh_frequency(7703.0, 9))


def _run(amplitudes, mode=9.4 * MESH):
    """A run's full-rate record from 0.2 s to 1 s: sinusoids at mesh harmonics."""
    t = 0.2 + np.arange(40_001) / RATE
    speed = 1873.7 + sum(a * np.sin(2 * np.pi * h * MESH * t) for h, a in amplitudes.items())
    force = 3e4 + 10 * (speed - 1873.7)
    attrs = {"solver_pinion_speed_deg_s": 7703.0, "design_pinion_teeth": 9,
             "solver_full_rate_hz": RATE}
    if mode is not None:
        attrs["mesh_natural_frequency_hz"] = mode
    return xr.Dataset({"gear_speed_full": ("time_full", speed),
                       "tangential_force_full": ("time_full", force)},
                      coords={"time_full": t}, attrs=attrs)


def test_the_ratio_per_band_and_the_band_that_decides():
    # the SBG calmer at harmonics 1-3 (0.8 against 1), rougher at the 9th (2 against 1):
    # 8 and up carries the difference, and the SBG fluctuates more in total
    pairs = {"best": {"SBG": _run({2: 0.8, 9: 2.0}), "LSBG": _run({2: 1.0, 9: 1.0})},
             "half": {"SBG": _run({1: 1.0})}}
    table = stability.band_table(pairs, start=0.2)
    assert set(table["pair"]) == {"best"}           # a pair without both types is skipped
    speed = table[table.quantity == "gear_speed"].set_index("band")
    assert speed.loc["1-3", "ratio"] == pytest.approx(0.8, rel=1e-3)
    assert speed.loc["8 and up", "ratio"] == pytest.approx(2.0, rel=1e-3)
    assert speed.loc["total", "ratio"] == pytest.approx(np.sqrt(2.32), rel=1e-3)
    assert list(speed.loc[["1-3", "8 and up", "total"], "calmer"]) == ["SBG", "LSBG", "LSBG"]
    assert speed.loc["below 1", "calmer"] == "—"    # a band of no variance ranks nothing
    assert speed["decides"].sum() == 1 and speed.loc["8 and up", "decides"]
    harmonic = speed.loc[["below 1", "1-3", "4-7", "8 and up"]]
    assert harmonic["difference_share"].sum() == pytest.approx(1.0, rel=1e-9)
    assert (harmonic["std_SBG"] ** 2).sum() == pytest.approx(speed.loc["total", "std_SBG"] ** 2)
    assert speed.loc["mode", "share_SBG"] == pytest.approx(2.0 / 2.32, rel=1e-3)
    text = " ".join(stability.band_text(table))
    assert "**mesh harmonics 8 and up** decides the total" in text
    assert "0.8 at mesh harmonics 1–3 (the SBG calmer)" in text
    assert "nan" not in text.lower()
    finding = stability.band_finding(table)
    assert finding.startswith("By mesh-harmonic band") and "decided at mesh harmonics 8" in finding


def test_a_total_within_the_resolution_is_a_tie_and_no_band_decides_it():
    pairs = {"p": {"SBG": _run({2: 1.0, 9: 1.0}, mode=None),
                   "LSBG": _run({2: 1.0, 9: 1.005}, mode=None)}}
    table = stability.band_table(pairs, start=0.2, quantities=("gear_speed",))
    total = table.set_index("band").loc["total"]
    assert total.calmer == "tie"
    assert np.isnan(table.set_index("band").loc["mode", "ratio"])   # no mesh mode recorded
    assert "the total is a tie" in stability.band_text(table)[0]
    assert "nan" not in " ".join(stability.band_text(table)).lower()


def test_the_interval_over_cells_is_the_least_and_largest_ratio():
    cells = pd.DataFrame({"cell": ["a", "b", "c", "a", "b", "c"],
                          "quantity": ["gear speed"] * 3 + ["force"] * 3,
                          "ratio": [1.1, 1.3, 1.05, 0.9, 1.2, 1.0],
                          "better": ["LSBG"] * 6})
    spread = stability.cells_range(cells).set_index("quantity")
    assert spread.loc["gear speed", ["ratio_least", "ratio_most"]].tolist() == [1.05, 1.3]
    assert spread.loc["gear speed", "calmer"] == "LSBG"
    assert spread.loc["force", "calmer"] == "neither" and spread.loc["force", "cells"] == 3
    text = stability.cells_text({"published pair": cells})
    assert "gear speed: 1.05–1.3 over its 3 cells (every cell's ratio above 1)" in text
    assert "force: 0.9–1.2 over its 3 cells (the cells on both sides of 1)" in text
    assert stability.cells_text({}) == ""


def test_the_answer_per_boundary_splits_the_driveline_cell_from_the_others():
    """The driveline's cell answers for the driveline alone; every other cell prescribes the
    pinion; each answer names the band that decides its own runs' ratio."""
    cell = stability.DRIVELINE_CELL
    assert cell == "boundary: torsional driveline"
    cells = {"published pair": pd.DataFrame({
        "cell": ["baseline", "baseline", "crowning ×2", "crowning ×2", cell, cell],
        "quantity": ["gear speed", "force"] * 3, "ratio": [0.8, 0.9, 0.85, 0.7, 1.2, 1.3],
        "better": ["SBG", "SBG", "SBG", "tie", "LSBG", "LSBG"]})}
    pairs = {"published pair": {"SBG": _run({2: 1.0, 9: 2.0}), "LSBG": _run({2: 1.0, 9: 1.0})},
             "published pair, torsional driveline": {"SBG": _run({2: 2.0, 9: 0.1}),
                                                     "LSBG": _run({2: 1.0, 9: 0.1})}}
    answers = stability.boundary_answers(cells, stability.band_table(pairs, start=0.2))
    assert list(answers["boundary"]) == list(stability.BOUNDARY_NAMES)
    assert list(answers["cells"]) == [2, 1]
    assert list(answers["verdict"]) == ["no", "yes"]
    assert list(answers["deciding_band"]) == ["mesh harmonics 8 and up", "mesh harmonics 1–3"]
    sentence = stability.boundary_sentence(answers)
    assert "under the prescribed pinion speed **no** (2 cells" in sentence
    assert "under the torsional driveline **yes** (1 cell, " in sentence
    # without the band table, or without a driveline cell
    assert list(stability.boundary_answers(cells)["deciding_band"]) == ["", ""]
    plain = {"p": cells["published pair"][cells["published pair"]["cell"] != cell]}
    assert list(stability.boundary_answers(plain)["boundary"]) == ["prescribed pinion speed"]
    assert stability.boundary_sentence(stability.boundary_answers({})) == ""


def test_the_driveline_pair_is_read_from_its_case_files():
    runs = []
    for trace in ("logarithmic", "circular"):
        for case, boundary in (("boundary_driveline", "driveline"),
                               ("crowning_x2", "prescribed_pinion")):
            ds = _run({1: 1.0})
            ds.attrs.update(design_trace=trace, solver_boundary=boundary)
            ds.encoding["source"] = f"results/sensitivity/{trace}_beta35_{case}.nc"
            runs.append(ds)
    pair = stability.driveline_pair(runs)
    assert sorted(pair) == ["LSBG", "SBG"]
    assert all(ds.attrs["solver_boundary"] == "driveline" for ds in pair.values())
