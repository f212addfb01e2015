"""The verdict's tables on synthetic runs whose answer is known."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg.tables import line_model

RATE, SAMPLES, FULL = 500.0, 500, 50000.0


def synthetic_run(trace, scale, seed, model="line"):
    """A run dataset with white-noise fluctuations of a given scale, sampled as lsbg does."""
    rng = np.random.default_rng(seed)
    time_full = np.arange(int(0.8 * FULL) + 1) / FULL + 0.2
    time = np.arange(SAMPLES + 1) / RATE
    data, full = {}, {}
    for name, mean, unit in (("gear_speed", 1873.7, "deg/s"), ("tangential_force", 27000.0, "N"),
                             ("transmission_error", 930.0, "urad"),
                             ("contact_torque", 1964.99, "N m")):
        series = mean + scale * rng.normal(size=time_full.size)
        full[f"{name}_full"] = ("time_full", series, {"units": unit})
        # the output samples are full-rate instants
        samples = np.full(time.size, mean)
        samples[time >= 0.2 - 1e-12] = series[::100]
        data[name] = ("time", samples, {"units": unit})
    ds = xr.Dataset({**data, **full}, coords={"time": time, "time_full": time_full})
    ds.attrs.update(design_trace=trace, contact_model=model, solver_samples=SAMPLES,
                    solver_duration_s=1.0, solver_full_rate_hz=FULL,
                    solver_load_torque_N_m=1964.99)
    return ds


@pytest.fixture(scope="module")
def calm_sbg():
    return {"SBG": synthetic_run("circular", 1.0, 1), "LSBG": synthetic_run("logarithmic", 2.0, 2)}


@pytest.fixture(scope="module")
def alike():
    return {"SBG": synthetic_run("circular", 1.0, 3), "LSBG": synthetic_run("logarithmic", 1.0, 4)}


def test_compare_fluctuation_finds_the_calmer_type(calm_sbg, alike):
    result = line_model.compare_fluctuation(calm_sbg, "gear_speed", n_boot=300)
    assert result["ratio"] == pytest.approx(0.5, rel=0.03)
    assert result["ratio_low"] < result["ratio"] < result["ratio_high"] < 1.0
    assert result["calmer"] == "SBG"
    assert result["std_LSBG_low"] < 2.0 < result["std_LSBG_high"]
    same = line_model.compare_fluctuation(alike, "gear_speed", n_boot=300)
    assert same["ratio_low"] < 1.0 < same["ratio_high"] and same["calmer"] == "neither"


def test_fluctuation_table_rows(calm_sbg):
    table = line_model.fluctuation_table(calm_sbg, n_boot=200)
    assert list(table.quantity) == [q for q in line_model.VERDICT_QUANTITIES for _ in range(2)]
    assert list(table.sampling[:2]) == ["full rate", "output samples"]
    assert (table.calmer == "SBG").all()
    assert table.dynamic_factor_SBG.iloc[0] > 1.0


def test_sensitivity_and_verdict_state_a_ranking_only_where_every_cell_agrees(calm_sbg, alike):
    flipped = {"SBG": calm_sbg["LSBG"].assign_attrs(design_trace="circular"),
               "LSBG": calm_sbg["SBG"].assign_attrs(design_trace="logarithmic")}
    agree = line_model.sensitivity_table([("baseline", calm_sbg, True), ("again", calm_sbg, False)],
                                     quantities=("gear_speed",), n_boot=200)
    assert agree.holds.all()
    text = line_model.verdict(agree)
    assert "the SBG fluctuates less in every one of the 2 cells" in text
    assert "survives the model form" in text
    mixed = line_model.sensitivity_table([("baseline", calm_sbg, True), ("flipped", flipped, True),
                                      ("alike", alike, True)],
                                     quantities=("gear_speed",), n_boot=200)
    assert list(mixed.holds) == [True, False, False]
    text = line_model.verdict(mixed)
    assert "does not survive the model form" in text and "flipped" in text and "alike" in text
    unclear = line_model.sensitivity_table([("baseline", alike, True), ("flipped", flipped, True)],
                                       quantities=("gear_speed",), n_boot=200)
    text = line_model.verdict(unclear)
    assert "no ranking is stated" in text and "flipped (LSBG calmer" in text


def test_trend_table_tells_a_trend_from_a_zigzag():
    angles = np.arange(20.0, 47.5, 2.5)
    table = pd.DataFrame({
        "gear_type": "LSBG", "spiral_angle_deg": angles,
        "trend": 10 + 0.3 * angles, "zigzag": 10 + np.where(np.arange(angles.size) % 2, 3.0, -3.0)})
    result = line_model.trend_table(table, ["trend", "zigzag"]).set_index("column")
    assert result.loc["trend", "reversals"] == 0 and result.loc["trend", "spearman_rho"] == 1.0
    assert result.loc["zigzag", "reversals"] == result.loc["zigzag", "possible"] == 9
    # fewer than three angles: no judgement
    assert line_model.trend_table(table.iloc[:2], ["trend"]).empty


def test_trend_table_gives_the_values_and_exact_p_for_few_points():
    """Three monotone points: rho = 1 and the exact two-sided p 2/3! = 1/3 (the t
    approximation says 0); five points with one swap: rho 0.9, p 10/120 (the orderings
    with |rho| >= 0.9); the values themselves, not only their number."""
    table = pd.DataFrame({"gear_type": "SBG", "crowning": [40.0, 10.0, 20.0],
                          "te": [3.0, 1.0, 2.0]})
    row = line_model.trend_table(table, ["te"], along="crowning").iloc[0]
    assert row["values"] == "10, 20, 40" and row["angles"] == 3
    assert row["spearman_rho"] == pytest.approx(1.0) and row["spearman_p"] == pytest.approx(1 / 3)
    rho, p = line_model.spearman(np.arange(5.0), [4, 5, 6, 8, 7])
    assert rho == pytest.approx(0.9) and p == pytest.approx(10 / 120)
    assert np.isnan(line_model.spearman([1.0, 2.0, 3.0], [5.0, 5.0, 5.0])[1])
