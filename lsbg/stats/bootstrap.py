"""Autocorrelated samples: effective sample size and block-bootstrap intervals of a std.

Samples of a run are autocorrelated, so an i.i.d. interval would be
overconfident: :func:`std_ci` and :func:`std_ratio_ci` resample blocks
(circular or stationary bootstrap) of a length chosen from the integrated
autocorrelation time.

References
----------
.. [1] C. J. Geyer, Practical Markov chain Monte Carlo, Statistical Science 7
   (1992) 473–483 (initial monotone sequence estimator).
.. [2] D. N. Politis and J. P. Romano, A circular block-resampling procedure
   for stationary data, in: Exploring the Limits of Bootstrap, Wiley, 1992;
   The stationary bootstrap, J. Amer. Statist. Assoc. 89 (1994) 1303–1313.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lsbg.stats.samples import as_1d

__all__ = [
    "OVER_WINDOWS", "autocorrelation", "integrated_autocorrelation_time", "effective_sample_size",
    "StdRatioCI", "std_ratio_ci", "StdCI", "std_ci"
]


#: What a block-bootstrap interval varies over, in the reports' words: the blocks
#: (windows) of one run's record. It says how precisely one deterministic run measures
#: its own std, not how the answer varies over designs or conditions.
OVER_WINDOWS = "over windows of one run"


def autocorrelation(values):
    """Sample autocorrelation function ρ_k, k = 0 … n−1.

    The usual biased estimator (autocovariance divided by n, not n − k), which
    keeps the sequence positive semi-definite; computed by FFT.

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 2, not constant [any unit].

    Returns
    -------
    numpy.ndarray
        ρ_0 = 1, ρ_1, …, ρ_{n−1} [-].
    """
    x = as_1d(values, min_size=2)
    x = x - x.mean()
    n = x.size
    # Zero-padding to ≥ 2n turns the circular correlation into a linear one.
    nfft = 1 << (2 * n - 1).bit_length()
    f = np.fft.rfft(x, nfft)
    acov = np.fft.irfft(f * np.conj(f), nfft)[:n]
    if acov[0] <= 0.0:
        raise ValueError("values are constant; autocorrelation is undefined")
    return acov / acov[0]


def integrated_autocorrelation_time(values):
    """Integrated autocorrelation time τ = 1 + 2 Σ_{k≥1} ρ_k.

    The infinite sum is truncated by Geyer's initial monotone sequence rule:
    pair sums Γ_m = ρ_{2m} + ρ_{2m+1} are summed while positive, each capped
    by the previous one, so τ = 2 Σ Γ_m − 1. τ is kept ≥ 1/log10(n), the
    floor Stan and ArviZ use, so that strongly anti-correlated series do not
    give absurd effective sample sizes.

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 4, not constant [any unit].

    Returns
    -------
    float
        τ [samples]; 1 for white noise, (1+φ)/(1−φ) for an AR(1) with
        coefficient φ.
    """
    x = as_1d(values, min_size=4)
    rho = autocorrelation(x)
    m = x.size // 2
    gamma = rho[0:2 * m:2] + rho[1:2 * m:2]
    nonpositive = np.flatnonzero(gamma <= 0.0)
    if nonpositive.size:
        gamma = gamma[:nonpositive[0]]
    gamma = np.minimum.accumulate(gamma)
    tau = 2.0 * gamma.sum() - 1.0
    return float(max(tau, 1.0 / math.log10(x.size)))


def effective_sample_size(values):
    """Effective sample size n / τ of an autocorrelated series.

    Parameters
    ----------
    values : array_like
        The series of :func:`integrated_autocorrelation_time` [any unit].

    Returns
    -------
    float
        n / τ with τ from :func:`integrated_autocorrelation_time` [-]; ≈ n for
        white noise, ≈ n (1−φ)/(1+φ) for an AR(1) with coefficient φ.
    """
    x = as_1d(values, min_size=4)
    return x.size / integrated_autocorrelation_time(x)


def _default_block_length(x):
    """Block length for the block bootstrap of a spread statistic [samples].

    Blocks must be long compared with the memory of the series, else the
    bootstrap treats correlated samples as independent and the interval is too
    narrow: take ⌈max(n^(1/3), 2τ)⌉ (n^(1/3) is the asymptotically optimal
    order for variance-type statistics; 2τ covers the correlation length),
    at most n/2.
    """
    n = x.size
    length = math.ceil(max(n ** (1.0 / 3.0),
                           2.0 * integrated_autocorrelation_time(x)))
    return int(min(length, max(1, n // 2)))


def _block_indices(n, block_length, n_boot, rng, method):
    """Bootstrap index arrays, shape (n_boot, n), for one series.

    'circular': blocks of fixed length starting anywhere, wrapping around the
    end (Politis & Romano 1992), so every sample is drawn equally often.
    'stationary': the same with geometric block lengths of mean
    ``block_length`` (Politis & Romano 1994).
    """
    if method == "circular":
        n_blocks = -(-n // block_length)
        starts = rng.integers(0, n, size=(n_boot, n_blocks, 1))
        idx = (starts + np.arange(block_length)) % n
        return idx.reshape(n_boot, -1)[:, :n]
    # stationary: at each step start a new block with probability 1/L,
    # otherwise continue the current one.
    new_block = rng.random((n_boot, n)) < 1.0 / block_length
    new_block[:, 0] = True
    fresh = rng.integers(0, n, size=(n_boot, n))
    idx = np.empty((n_boot, n), dtype=np.int64)
    idx[:, 0] = fresh[:, 0]
    for t in range(1, n):
        idx[:, t] = np.where(new_block[:, t], fresh[:, t],
                             (idx[:, t - 1] + 1) % n)
    return idx


@dataclass(frozen=True)
class StdRatioCI:
    """Ratio std(a)/std(b) with a block-bootstrap confidence interval."""

    ratio: float        #: std(a) / std(b), ddof = 1 [-]
    low: float          #: lower confidence bound [-]
    high: float         #: upper confidence bound [-]
    confidence: float   #: confidence level [-]
    block_length_a: int  #: block length used for a [samples]
    block_length_b: int  #: block length used for b [samples]
    n_boot: int         #: bootstrap replicates [-]
    method: str         #: 'circular' or 'stationary'

    @property
    def excludes_one(self):
        """True if the interval lies entirely above or below 1."""
        return self.low > 1.0 or self.high < 1.0


def _check_bootstrap(confidence, n_boot, method):
    """Validate the bootstrap options; return ``n_boot`` as an int."""
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")
    if method not in ("circular", "stationary"):
        raise ValueError(f"method must be 'circular' or 'stationary', "
                         f"got {method!r}")
    n_boot = int(n_boot)
    if n_boot < 100:
        raise ValueError(f"n_boot must be at least 100, got {n_boot}")
    return n_boot


def _block_length(series, block_length):
    """The given block length [samples], or the data's default when None."""
    if block_length is None:
        return _default_block_length(series)
    length = int(block_length)
    if length < 1:
        raise ValueError(f"block_length must be >= 1, got {block_length}")
    return length


def _bootstrap_std(series, length, n_boot, rng, method):
    """Standard deviations (ddof = 1) of ``n_boot`` block-bootstrap replicates.

    Circular replicates are summed block by block from prefix sums of the
    (centred) series (:func:`lsbg.stats.kernels.circular_block_stds`), so a
    long series (a full-rate record of 40 000 samples) costs n_boot x blocks
    operations instead of n_boot x n; the random starts are the draws of
    :func:`_block_indices`, so the replicates are the same.
    """
    if method != "circular":
        return series[_block_indices(series.size, length, n_boot, rng, method)].std(
            axis=1, ddof=1)
    from lsbg.stats.kernels import circular_block_stds

    n = series.size
    n_blocks = -(-n // length)
    starts = rng.integers(0, n, size=(n_boot, n_blocks, 1))[..., 0]
    centred = series - series.mean()
    wrapped = np.concatenate([centred, centred[:length]])
    sums = np.concatenate([[0.0], np.cumsum(wrapped)])
    squares = np.concatenate([[0.0], np.cumsum(wrapped * wrapped)])
    lengths = np.full(n_blocks, length, dtype=np.int64)
    lengths[-1] = n - (n_blocks - 1) * length   # the last block is cut to n samples
    return circular_block_stds(sums, squares, np.ascontiguousarray(starts), lengths, n)


def _percentile_interval(replicates, confidence):
    """Equal-tailed percentile interval of bootstrap replicates."""
    alpha = 1.0 - confidence
    low, high = np.quantile(replicates, [alpha / 2.0, 1.0 - alpha / 2.0])
    return low, high


def std_ratio_ci(a, b, confidence=0.95, n_boot=2000, block_length=None,
                 seed=0, method="circular"):
    """Ratio of standard deviations with an autocorrelation-aware interval.

    Each series is resampled on its own with a block bootstrap, which keeps
    the short-range dependence inside blocks; the interval is the percentile
    interval of the bootstrapped ratio (equivalently of its logarithm).

    Parameters
    ----------
    a, b : array_like
        Samples, 1-D, at least 4 each, not constant [same unit].
    confidence : float, default 0.95
        Confidence level, in (0, 1) [-].
    n_boot : int, default 2000
        Number of bootstrap replicates [-].
    block_length : int or (int, int), optional
        Block length for both series or for (a, b) [samples]. Default: per
        series ⌈max(n^(1/3), 2τ)⌉ (τ from
        :func:`integrated_autocorrelation_time`), at most n/2.
    seed : int, default 0
        Seed of :func:`numpy.random.default_rng`; equal seeds give equal
        intervals.
    method : {'circular', 'stationary'}, default 'circular'
        Circular moving-block bootstrap with fixed block length, or the
        stationary bootstrap with geometric block lengths of that mean.

    Returns
    -------
    StdRatioCI
        Ratio std(a)/std(b) (ddof = 1), the interval and the settings used.

    Notes
    -----
    Percentile block-bootstrap intervals run a little narrow when the
    effective sample size is small. In simulations of two AR(1) series of 400
    samples with a true ratio of 2 (200 pairs, 1000 replicates each) the 95 %
    interval covered the truth in 93 % of the pairs for φ = 0, 0.5 and 0.7,
    but in 88 % for φ = 0.9 (about 20 effective samples per series) and in
    90 % for φ = 0.9 with 2000 samples. Longer blocks do not fix this; treat
    intervals from strongly autocorrelated series as approximate.
    """
    x = as_1d(a, "a", 4)
    y = as_1d(b, "b", 4)
    n_boot = _check_bootstrap(confidence, n_boot, method)
    given = (None, None) if block_length is None else np.broadcast_to(block_length, (2,))
    lengths = tuple(_block_length(series, length) for series, length in zip((x, y), given))
    rng = np.random.default_rng(seed)
    boot_std = [_bootstrap_std(series, length, n_boot, rng, method)
                for series, length in zip((x, y), lengths)]
    low, high = _percentile_interval(boot_std[0] / boot_std[1], confidence)
    return StdRatioCI(ratio=float(x.std(ddof=1) / y.std(ddof=1)),
                      low=float(low), high=float(high), confidence=confidence,
                      block_length_a=lengths[0], block_length_b=lengths[1],
                      n_boot=n_boot, method=method)


@dataclass(frozen=True)
class StdCI:
    """Standard deviation of one series with a block-bootstrap interval."""

    std: float          #: sample standard deviation, ddof = 1 [data unit]
    low: float          #: lower confidence bound [data unit]
    high: float         #: upper confidence bound [data unit]
    confidence: float   #: confidence level [-]
    block_length: int   #: block length used [samples]
    n_boot: int         #: bootstrap replicates [-]
    method: str         #: 'circular' or 'stationary'


def std_ci(values, confidence=0.95, n_boot=2000, block_length=None, seed=0,
           method="circular"):
    """Standard deviation of one series with an autocorrelation-aware interval.

    The one-series counterpart of :func:`std_ratio_ci`, with the same block
    bootstrap (blocks keep the short-range dependence) and percentile
    interval; used to put error bars on the standard deviations of a sweep.

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 4, not constant [any unit].
    confidence : float, default 0.95
        Confidence level, in (0, 1) [-].
    n_boot : int, default 2000
        Number of bootstrap replicates, at least 100 [-].
    block_length : int, optional
        Block length [samples]. Default ⌈max(n^(1/3), 2τ)⌉ (τ from
        :func:`integrated_autocorrelation_time`), at most n/2.
    seed : int, default 0
        Seed of :func:`numpy.random.default_rng`.
    method : {'circular', 'stationary'}, default 'circular'
        Block bootstrap variant, see :func:`std_ratio_ci`.

    Returns
    -------
    StdCI
        Sample standard deviation (ddof = 1), the interval [unit of
        ``values``] and the settings used.

    Notes
    -----
    The percentile interval of a bootstrapped standard deviation is biased
    low for small effective sample sizes (each replicate loses some spread
    between blocks); as for :func:`std_ratio_ci`, treat intervals from
    strongly autocorrelated series as approximate.
    """
    x = as_1d(values, "values", 4)
    n_boot = _check_bootstrap(confidence, n_boot, method)
    length = _block_length(x, block_length)
    boot = _bootstrap_std(x, length, n_boot, np.random.default_rng(seed), method)
    low, high = _percentile_interval(boot, confidence)
    return StdCI(std=float(x.std(ddof=1)), low=float(low), high=float(high),
                 confidence=confidence, block_length=length, n_boot=n_boot,
                 method=method)
