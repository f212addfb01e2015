"""Full-rate statistics of a run: spectra, RMS fluctuation, sampling luck, dynamic factor.

The paper samples a 1 s run 500 times and takes the standard deviation of the
samples. When the signal holds components above 250 Hz (the point model's
contact resonance near 9 kHz, the mesh frequency of 193 Hz and its
harmonics) those samples alias them, and the statistic depends on the phase
at which sampling happens to start. A run also keeps its steady state at a
full rate (50 kHz by default, :mod:`lsbg.dynamics.settings`); this module
turns it into:

* the amplitude spectrum (:func:`amplitude_spectrum`) with the mesh
  frequency and its harmonics (:func:`mesh_frequency`,
  :func:`harmonic_amplitudes`);
* the RMS fluctuation at the full rate (:func:`rms_fluctuation`);
* the spread of the paper's statistic over every sampling phase the full
  rate resolves (:func:`sampling_phase_spread`): how much of the paper's
  number is sampling luck;
* the dynamic factor, peak dynamic mesh force over static (:func:`dynamic_factor`).

Functions work on numpy arrays in any unit; frequencies are in Hz.
"""

from __future__ import annotations

import numpy as np


def mesh_frequency(pinion_speed, pinion_teeth):
    """Tooth-mesh frequency [Hz].

    Parameters
    ----------
    pinion_speed : array_like
        Pinion speed [deg/s].
    pinion_teeth : int
        z1 [-].

    Returns
    -------
    numpy.ndarray or float
        z1 n1 / 360 [Hz]; 192.6 Hz for the paper's 7703 deg/s and 9 teeth.
    """
    return np.asarray(pinion_speed, dtype=float) / 360.0 * pinion_teeth


def amplitude_spectrum(values, rate):
    """Single-sided amplitude spectrum, Hann window, amplitude-corrected.

    A sinusoid of amplitude A at a frequency on the spectrum's grid shows as
    A (the window's coherent gain is divided out); the mean is removed.

    Parameters
    ----------
    values : array_like
        Evenly sampled series [any unit].
    rate : float
        Sampling rate [Hz].

    Returns
    -------
    frequency : numpy.ndarray
        0 .. rate/2 [Hz].
    amplitude : numpy.ndarray
        Amplitude at each frequency [unit of ``values``].

    Raises
    ------
    ValueError
        If fewer than 8 samples are given or the rate is not positive.
    """
    x = np.asarray(values, dtype=float)
    if x.ndim != 1 or x.size < 8:
        raise ValueError(f"values: need a 1-D series of at least 8 samples, got shape {x.shape}")
    if not rate > 0:
        raise ValueError(f"rate = {rate!r}: must be positive [Hz]")
    window = np.hanning(x.size)
    spectrum = np.fft.rfft((x - x.mean()) * window)
    amplitude = 2.0 * np.abs(spectrum) / window.sum()
    amplitude[0] /= 2.0
    return np.fft.rfftfreq(x.size, 1.0 / rate), amplitude


def harmonic_amplitudes(frequency, amplitude, fundamental, count=3, width=2):
    """Peak amplitude near each harmonic of a fundamental frequency.

    Parameters
    ----------
    frequency, amplitude : numpy.ndarray
        From :func:`amplitude_spectrum` [Hz, any unit].
    fundamental : float
        E.g. the mesh frequency [Hz].
    count : int
        Harmonics 1 .. count [-].
    width : int
        Spectrum bins searched on either side of each harmonic (the Hann
        window spreads a line over about two bins) [-].

    Returns
    -------
    numpy.ndarray
        Amplitude of each harmonic (NaN above the Nyquist frequency)
        [unit of ``amplitude``].
    """
    step = frequency[1] - frequency[0]
    out = np.full(count, np.nan)
    for h in range(1, count + 1):
        k = int(round(h * fundamental / step))
        if k + width < frequency.size:
            out[h - 1] = amplitude[max(k - width, 0):k + width + 1].max()
    return out


def rms_fluctuation(values):
    """RMS of the fluctuation about the mean (the standard deviation, ddof = 1).

    Parameters
    ----------
    values : array_like
        Full-rate series [any unit].

    Returns
    -------
    float
        [unit of ``values``].
    """
    return float(np.std(np.asarray(values, dtype=float), ddof=1))


def sampling_phase_spread(values, full_rate, sample_rate):
    """The paper's statistic at every sampling phase the full rate resolves.

    The full-rate series is cut into ``full_rate / sample_rate`` interleaved
    series at ``sample_rate``, each starting one full-rate interval later;
    the first is the run's own output sampling when the full-rate record
    starts at an output instant. Each gives the standard deviation the paper
    would have reported had its sampling started there.

    Parameters
    ----------
    values : array_like
        Full-rate series [any unit].
    full_rate, sample_rate : float
        Rates of the full-rate record and of the paper's sampling [Hz]; the
        ratio must be whole.

    Returns
    -------
    numpy.ndarray
        Standard deviation (ddof = 1) of the subsample at each phase offset
        [unit of ``values``]. Each subsample takes the instants strictly
        after the record's first one (the paper's steady state starts after
        0.2 s), so all have the same number of samples.

    Raises
    ------
    ValueError
        If the ratio of the rates is not whole or leaves fewer than 3 samples.
    """
    x = np.asarray(values, dtype=float)
    ratio = full_rate / sample_rate
    step = int(round(ratio))
    if step < 1 or abs(ratio - step) > 1e-9 * ratio:
        raise ValueError(f"full_rate / sample_rate = {ratio!r}: must be a whole number")
    # Every instant strictly after the record's start: offset 0 is the
    # paper's own sampling (its steady state starts after 0.2 s).
    stds = []
    for offset in range(step):
        sub = x[offset::step] if offset else x[step::step]
        if sub.size < 3:
            raise ValueError(f"values: {x.size} samples leave fewer than 3 per sampling phase")
        stds.append(np.std(sub, ddof=1))
    return np.asarray(stds)


def dynamic_factor(torque, static_torque):
    """Peak dynamic mesh load over the static load.

    The mesh force along the line of action is the contact torque over the
    base radius, so the ratio of forces is the ratio of torques.

    Parameters
    ----------
    torque : array_like
        Full-rate contact torque on the gear over the steady state [N m].
    static_torque : float
        The load it carries at rest [N m], > 0.

    Returns
    -------
    float
        max(torque) / static_torque [-]; 1 for a perfectly smooth mesh.
    """
    if not static_torque > 0:
        raise ValueError(f"static_torque = {static_torque!r}: must be positive [N m]")
    return float(np.max(np.asarray(torque, dtype=float)) / static_torque)
