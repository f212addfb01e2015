"""Full-rate statistics: spectra, sampling luck and the dynamic factor, on known signals."""

import numpy as np
import pytest

from lsbg.stats import spectra


def test_mesh_frequency_of_the_paper():
    # 7703 deg/s, 9 teeth: 192.6 Hz
    assert spectra.mesh_frequency(7703.0, 9) == pytest.approx(192.575)


def test_amplitude_spectrum_recovers_a_sinusoid():
    rate, n = 50000.0, 40000
    t = np.arange(n) / rate
    f0 = 192.5  # on the grid: 40000 samples at 50 kHz, 1.25 Hz spacing
    x = 7.0 + 3.0 * np.sin(2 * np.pi * f0 * t) + 0.2 * np.sin(2 * np.pi * 2 * f0 * t)
    frequency, amplitude = spectra.amplitude_spectrum(x, rate)
    assert frequency[-1] == pytest.approx(rate / 2)
    assert amplitude[np.argmin(np.abs(frequency - f0))] == pytest.approx(3.0, rel=1e-6)
    np.testing.assert_allclose(spectra.harmonic_amplitudes(frequency, amplitude, f0, count=3),
                               [3.0, 0.2, 0.0], atol=1e-6)
    with pytest.raises(ValueError, match="at least 8"):
        spectra.amplitude_spectrum(x[:4], rate)


def test_sampling_phase_spread_of_an_aliased_resonance():
    """A 9.01 kHz ringing on a 10 Hz signal: sampled at 500 Hz the ringing aliases to
    10 Hz with a phase set by where the sampling starts, so the std depends on it
    (from |1 - 0.8| to 1 + 0.8 times the slow part's); offset 0 is the sampling after
    the record's first instant."""
    rate, n = 50000.0, 40001
    t = np.arange(n) / rate
    x = np.sin(2 * np.pi * 10 * t) + 0.8 * np.sin(2 * np.pi * 9010 * t)
    spread = spectra.sampling_phase_spread(x, rate, 500.0)
    assert spread.size == 100
    assert spread[0] == pytest.approx(x[100::100].std(ddof=1))
    assert spread[7] == pytest.approx(x[7::100].std(ddof=1))
    assert spread.min() == pytest.approx(0.2 / np.sqrt(2), rel=0.05)  # sampling luck
    assert spread.max() == pytest.approx(1.8 / np.sqrt(2), rel=0.05)
    # the full-rate std sees both parts, whatever the phase
    assert spectra.rms_fluctuation(x) == pytest.approx(np.sqrt(1 + 0.64) / np.sqrt(2), rel=0.01)
    assert spectra.rms_fluctuation(x) == pytest.approx(x.std(ddof=1))
    # a band-limited signal has no luck
    slow = np.sin(2 * np.pi * 10 * t)
    assert np.ptp(spectra.sampling_phase_spread(slow, rate, 500.0)) < 0.01
    with pytest.raises(ValueError, match="whole number"):
        spectra.sampling_phase_spread(x, rate, 300.0)


def test_dynamic_factor():
    torque = 1964.99 * (1 + 0.1 * np.sin(np.linspace(0, 20, 1000)))
    assert spectra.dynamic_factor(torque, 1964.99) == pytest.approx(1.1, rel=1e-4)
    with pytest.raises(ValueError, match="static_torque"):
        spectra.dynamic_factor(torque, 0.0)
