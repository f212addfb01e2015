"""The variance of a steady-state signal split by frequency band (Parseval).

A run's fluctuation (the standard deviation of its full-rate record) mixes what
the tooth pairs excite at the first mesh harmonics with what the boundary's
resonance amplifies higher up. :func:`band_split` splits the variance of a
uniformly sampled record by Parseval's theorem into the bands of
:data:`HARMONIC_BANDS`, in mesh harmonics h = f / f_mesh:

* ``below 1``: 0 < h < 0.5 (drift slower than the mesh, the mean removed);
* ``1-3``: 0.5 <= h < 3.5, the first three mesh harmonics;
* ``4-7``: 3.5 <= h < 7.5;
* ``8 and up``: h >= 7.5, up to the Nyquist frequency.

Band edges sit at half-integer harmonics, so every harmonic lies inside one
band; the parts add up to the total variance to rounding. Each given mode
frequency f_n adds the share of the variance within f_n - w <= f <= f_n + w
(default w: one mesh frequency, so the two harmonics that flank the mode); these
mode bands overlap the harmonic bands and are reported apart from them.

Windowing and leakage: the record is cut to the largest whole number of mesh
periods it holds (its first samples kept) and transformed without a window (a
rectangular one), so a signal periodic at the mesh period puts each harmonic on a
spectrum line of its own and nothing leaks across a band edge; the residual is
the fraction of a sample by which a whole number of mesh periods misses a whole
number of samples. The variance is the unbiased one (ddof = 1, as
:func:`lsbg.stats.spectra.rms_fluctuation`) of the cut record.

:func:`band_ratio` gives std(a)/std(b) per band and names the band that decides
the total: the band carrying the largest share of the difference of the two
variances, var_a - var_b (:func:`deciding_band`).

Units: any for the values (the parts are in their square), Hz for frequencies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lsbg.stats.samples import as_1d

__all__ = ["HARMONIC_BANDS", "BAND_LABELS", "BandSplit", "band_split", "band_ratio",
           "deciding_band"]

#: The harmonic bands: name -> (lowest, highest) mesh harmonic, lower edge
#: included, upper excluded; together they cover 0 < f <= Nyquist [-].
HARMONIC_BANDS = {"below 1": (0.0, 0.5), "1-3": (0.5, 3.5), "4-7": (3.5, 7.5),
                  "8 and up": (7.5, math.inf)}

#: Words of each band for tables and reports.
BAND_LABELS = {"below 1": "below the 1st mesh harmonic", "1-3": "mesh harmonics 1–3",
               "4-7": "mesh harmonics 4–7", "8 and up": "mesh harmonics 8 and up"}


@dataclass(frozen=True)
class BandSplit:
    """The variance of one record by band (:func:`band_split`)."""

    variance: dict          #: band name -> its part of the variance [unit²]
    total: float            #: variance of the cut record, ddof = 1 [unit²]
    mode_variance: dict     #: mode frequency [Hz] -> variance within its width [unit²]
    mode_half_width: float  #: half-width of every mode band [Hz]
    fundamental: float      #: mesh frequency [Hz]
    samples: int            #: samples of the cut record [-]
    periods: int            #: whole mesh periods the cut record holds [-]

    def std(self, band):
        """The band's part as a standard deviation, sqrt(its variance) [unit]."""
        return math.sqrt(self.variance[band])

    def share(self, band):
        """The band's share of the total variance [-]."""
        return self.variance[band] / self.total if self.total > 0 else math.nan


def _whole_periods(x, rate, fundamental):
    """The first samples of ``x`` spanning the largest whole number of mesh periods."""
    per_period = rate / fundamental
    periods = int(math.floor(x.size / per_period + 1e-9))
    if periods < 1:
        raise ValueError(f"values: {x.size} samples at {rate:g} Hz hold no whole period of "
                         f"the fundamental {fundamental:g} Hz")
    n = min(int(round(periods * per_period)), x.size)
    return x[:n], periods


def band_split(values, rate, fundamental, modes=(), mode_half_width=None, whole_periods=True):
    """Split the variance of a uniformly sampled record into mesh-harmonic bands.

    Parameters
    ----------
    values : array_like
        The steady-state record, uniformly sampled, 1-D, at least 8 samples [any unit].
    rate : float
        Sampling rate [Hz], > 0.
    fundamental : float
        Mesh frequency f_mesh [Hz], > 0 and below the Nyquist frequency
        (:func:`lsbg.stats.spectra.mesh_frequency`).
    modes : sequence of float
        Natural frequencies f_n of the system's modes [Hz] (e.g. the run's
        ``mesh_natural_frequency_hz``); NaN entries are skipped.
    mode_half_width : float, optional
        Half-width w of each mode band [Hz]; default one mesh frequency.
    whole_periods : bool, default True
        Cut the record to the largest whole number of mesh periods first
        (module docstring); False transforms the record as given.

    Returns
    -------
    BandSplit
        The parts of :data:`HARMONIC_BANDS` (summing to ``total``) and of each mode.

    Raises
    ------
    ValueError
        For a bad rate or fundamental, or a record too short.

    Notes
    -----
    With the mean-removed record x of n samples and X its one-sided DFT,
    var = (1/(n - 1)) (2 Σ_{0<k<n/2} |X_k|² + |X_{n/2}|²) / n (the Nyquist line
    counted once for even n); each band sums the lines whose frequency k rate/n
    falls inside it.
    """
    if not (np.isfinite(rate) and rate > 0):
        raise ValueError(f"rate = {rate!r}: must be a positive sampling rate [Hz]")
    if not (np.isfinite(fundamental) and 0 < fundamental < rate / 2):
        raise ValueError(f"fundamental = {fundamental!r}: must be a mesh frequency between 0 "
                         f"and the Nyquist frequency {rate / 2:g} [Hz]")
    x = as_1d(values, "values", 8)
    periods = 0
    if whole_periods:
        x, periods = _whole_periods(x, rate, fundamental)
    n = x.size
    if n < 8:
        raise ValueError(f"values: {n} samples in whole mesh periods, need at least 8")
    spectrum = np.fft.rfft(x - x.mean())
    power = np.abs(spectrum) ** 2 * 2.0
    power[0] = 0.0
    if n % 2 == 0:
        power[-1] /= 2.0
    power /= n * (n - 1)
    frequency = np.fft.rfftfreq(n, 1.0 / rate)
    harmonic = frequency / fundamental
    variance = {name: float(power[(harmonic >= low) & (harmonic < high)].sum())
                for name, (low, high) in HARMONIC_BANDS.items()}
    width = fundamental if mode_half_width is None else float(mode_half_width)
    if not (np.isfinite(width) and width > 0):
        raise ValueError(f"mode_half_width = {mode_half_width!r}: must be positive [Hz]")
    mode_variance = {float(f): float(power[np.abs(frequency - f) <= width].sum())
                     for f in modes if np.isfinite(f)}
    return BandSplit(variance=variance, total=float(power.sum()), mode_variance=mode_variance,
                     mode_half_width=width, fundamental=float(fundamental), samples=n,
                     periods=periods)


def deciding_band(a, b):
    """The harmonic band carrying the largest share of var(a) - var(b).

    Parameters
    ----------
    a, b : BandSplit
        Two records split at the same fundamental (e.g. SBG and LSBG).

    Returns
    -------
    (str, float)
        The band whose difference var_a - var_b has the sign of the total
        difference and the largest magnitude, and its share of the total
        difference [-] (above 1 where other bands push the other way). When the
        totals are equal, the band of the largest absolute difference with share NaN.
    """
    diff = {band: a.variance[band] - b.variance[band] for band in HARMONIC_BANDS}
    total = a.total - b.total
    if total == 0:
        return max(diff, key=lambda k: abs(diff[k])), math.nan
    band = max(diff, key=lambda k: diff[k] * math.copysign(1.0, total))
    return band, diff[band] / total


def band_ratio(a, b):
    """std(a)/std(b) in every harmonic band and in total, and the deciding band.

    Parameters
    ----------
    a, b : BandSplit
        Two records split at the same fundamental.

    Returns
    -------
    dict
        ``ratio``: {band: sqrt(var_a / var_b)} (NaN where var_b is 0), with
        ``"total"``; ``share_a``, ``share_b``: {band: share of its total};
        ``deciding``, ``deciding_share``: from :func:`deciding_band`.
    """
    def ratio(x, y):
        return math.sqrt(x / y) if y > 0 else math.nan

    out = {band: ratio(a.variance[band], b.variance[band]) for band in HARMONIC_BANDS}
    out["total"] = ratio(a.total, b.total)
    band, share = deciding_band(a, b)
    return {"ratio": out, "share_a": {k: a.share(k) for k in HARMONIC_BANDS},
            "share_b": {k: b.share(k) for k in HARMONIC_BANDS},
            "deciding": band, "deciding_share": share}
