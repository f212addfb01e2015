"""Run datasets read back (lsbg.aggregate.runs): the full-rate record, the pair of gear types."""

import numpy as np
import pytest

from lsbg.stats import spectra
from lsbg.dynamics.dataset import open_run
from lsbg.aggregate.runs import FULL_RATE_OF, full_rate_series, open_pair, steady


def test_full_rate_record_holds_the_output_samples(runs):
    """The output instants inside the full-rate record are full-rate instants: the
    values agree, and the sampling phase of the paper's statistic that starts
    with the output sampling gives its standard deviation."""
    for name in ("lsbg35", "sbg35_line"):
        run = open_run(runs[name])
        assert run.attrs["solver_full_rate_hz"] == 50000.0
        t_full = run.time_full.values
        assert t_full[0] == pytest.approx(0.01) and t_full[-1] == pytest.approx(0.05)
        assert np.diff(t_full) == pytest.approx(2e-5)
        on_grid = np.isin(np.round(run.time.values, 9), np.round(t_full, 9))
        assert on_grid.sum() == 21
        for quantity, (variable, _) in FULL_RATE_OF.items():
            if quantity == "tangential_force_outer":
                continue
            full = run[variable].values
            np.testing.assert_allclose(full[::100], run[quantity].values[on_grid], rtol=1e-12)
            spread = spectra.sampling_phase_spread(full_rate_series(run, quantity, 0.01),
                                                   50000.0, 500.0)
            assert spread.size == 100
            assert spread[0] == pytest.approx(steady(run, quantity, 0.01).std(ddof=1),
                                              rel=1e-12)


def test_open_pair_checks_the_gear_types(runs):
    pair = open_pair(runs["sbg35"], runs["lsbg35"])
    assert list(pair) == ["SBG", "LSBG"]
    assert open_pair("", None) is None
    with pytest.raises(ValueError, match="a LSBG run .* given as the SBG run"):
        open_pair(runs["lsbg35"], runs["sbg35"])
    with pytest.raises(ValueError, match="both"):
        open_pair(runs["sbg35"], "")


def test_steady_starts_at_the_runs_own_ramp_end_unless_told(runs):
    """The conftest's short runs ramp up in 0.01 s: steady() without a start keeps the
    samples after it (a fixed 0.2 s would keep none of a 0.05-s run)."""
    ds = open_run(runs["lsbg35"])
    time = ds["time"].values
    assert float(ds.attrs["solver_ramp_time_s"]) == pytest.approx(0.01)
    assert steady(ds, "gear_speed").size == np.count_nonzero(time > 0.01) == 20
    assert steady(ds, "gear_speed", 0.03).size == np.count_nonzero(time > 0.03)


def test_the_pair_compared_is_the_published_one_unless_another_sbg_is_asked_for():
    from lsbg.aggregate.runs import pair_traces

    three = ["logarithmic", "circular", "face_milled"]
    assert pair_traces(three) == {"SBG": "circular", "LSBG": "logarithmic"}
    assert pair_traces(three, "face_milled") == {"SBG": "face_milled", "LSBG": "logarithmic"}
    assert pair_traces(["logarithmic", "face_milled"]) == {"SBG": "face_milled",
                                                           "LSBG": "logarithmic"}
    assert pair_traces(["circular"]) == {"SBG": "circular"}
    with pytest.raises(ValueError, match="sbg_trace 'face_milled'"):
        pair_traces(["logarithmic", "circular"], "face_milled")
