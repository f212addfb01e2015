"""The variance split by mesh-harmonic band (lsbg.stats.bands)."""

import math

import numpy as np
import pytest

from lsbg.stats import bands, spectra

RATE = 50_000.0                                   # the runs' full rate [Hz]
MESH = float(spectra.mesh_frequency(7703.0, 9))   # 192.6 Hz


def _record(amplitudes, duration=0.8, offset=3.0, noise=0.0, seed=0):
    """A steady state of 0.8 s at the full rate: {harmonic: amplitude} sinusoids, a mean."""
    t = np.arange(int(round(duration * RATE)) + 1) / RATE
    x = np.full(t.size, offset)
    for k, (h, a) in enumerate(amplitudes.items()):
        x += a * np.sin(2 * np.pi * h * MESH * t + 0.3 * k)
    if noise:
        x += noise * np.random.default_rng(seed).standard_normal(t.size)
    return x


def test_a_signal_of_known_harmonics_gives_the_known_split():
    # variance of a sinusoid of amplitude A: A²/2; harmonics 2 and 3 in band 1-3, 5 in 4-7,
    # 9 and 10 in 8 and up, a slow line at 0.25 harmonic below the first
    x = _record({0.25: 0.5, 2: 1.0, 3: 0.5, 5: 0.8, 9: 2.0, 10: 1.0})
    split = bands.band_split(x, RATE, MESH)
    expected = {"below 1": 0.125, "1-3": 0.5 + 0.125, "4-7": 0.32, "8 and up": 2.0 + 0.5}
    for band, value in expected.items():
        # a whole number of mesh periods misses a whole number of samples by under one
        # sample, and the 0.25-harmonic line is not periodic over it: 1e-3 relative
        assert split.variance[band] == pytest.approx(value, rel=2e-3), band
    assert split.periods == math.floor(0.8 * MESH)


def test_the_parts_add_up_to_the_total_variance():
    x = _record({1: 1.0, 4: 0.3, 8: 0.7, 17: 0.2}, noise=0.4)
    split = bands.band_split(x, RATE, MESH)
    assert sum(split.variance.values()) == pytest.approx(split.total, rel=1e-12)
    # the total is the cut record's variance (ddof = 1), as rms_fluctuation gives it
    assert split.total == pytest.approx(np.var(x[:split.samples], ddof=1), rel=1e-12)
    uncut = bands.band_split(x, RATE, MESH, whole_periods=False)
    assert uncut.total == pytest.approx(spectra.rms_fluctuation(x) ** 2, rel=1e-12)
    assert sum(uncut.variance.values()) == pytest.approx(uncut.total, rel=1e-12)


def test_a_whole_number_of_mesh_periods_keeps_a_harmonic_out_of_its_neighbours():
    # a line at the 8th harmonic, near the 7.5 edge: cut to whole periods nothing leaks into
    # 4-7; over the record as given (154.07 periods) some does
    x = _record({8: 1.0})
    cut = bands.band_split(x, RATE, MESH)
    assert cut.share("8 and up") > 1 - 1e-4
    uncut = bands.band_split(x, RATE, MESH, whole_periods=False)
    assert uncut.variance["4-7"] > 10 * cut.variance["4-7"]


def test_the_mode_band_holds_the_harmonics_next_to_the_mode():
    x = _record({2: 1.0, 9: 2.0, 10: 1.0, 12: 1.0})
    split = bands.band_split(x, RATE, MESH, modes=[9.4 * MESH, math.nan])
    (frequency, variance), = split.mode_variance.items()
    assert frequency == pytest.approx(9.4 * MESH)
    assert split.mode_half_width == pytest.approx(MESH)
    assert variance == pytest.approx(2.0 + 0.5, rel=1e-3)   # the 9th and 10th, not the 12th
    narrow = bands.band_split(x, RATE, MESH, modes=[9.4 * MESH], mode_half_width=0.5 * MESH)
    assert narrow.mode_variance[9.4 * MESH] == pytest.approx(2.0, rel=1e-3)


def test_band_ratio_names_the_band_that_carries_the_difference():
    # a: calmer at harmonics 1-3, rougher at 8 and up, by more: the total says "a rougher"
    a = bands.band_split(_record({2: 0.8, 9: 2.0}), RATE, MESH)
    b = bands.band_split(_record({2: 1.0, 9: 1.0}), RATE, MESH)
    result = bands.band_ratio(a, b)
    assert result["ratio"]["1-3"] == pytest.approx(0.8, rel=1e-3)
    assert result["ratio"]["8 and up"] == pytest.approx(2.0, rel=1e-3)
    assert result["ratio"]["total"] == pytest.approx(math.sqrt(2.32 / 1.0), rel=1e-3)
    assert result["deciding"] == "8 and up"
    # var_a - var_b = 1.32 = 1.5 (8 and up) - 0.18 (1-3): the deciding band carries 1.5/1.32
    assert result["deciding_share"] == pytest.approx(1.5 / 1.32, rel=1e-3)


@pytest.mark.parametrize("kwargs, words", [
    ({"rate": 0.0}, "rate = 0.0"),
    ({"fundamental": 30_000.0}, "fundamental = 30000.0"),
    ({"mode_half_width": -1.0}, "mode_half_width = -1.0"),
])
def test_bad_input_is_named(kwargs, words):
    options = {"rate": RATE, "fundamental": MESH, **kwargs}
    with pytest.raises(ValueError, match=words):
        bands.band_split(_record({1: 1.0}), **options)


def test_a_record_shorter_than_a_mesh_period_is_refused():
    with pytest.raises(ValueError, match="no whole period"):
        bands.band_split(np.sin(np.arange(100.0)), RATE, MESH)
