"""Samples of a run: the steady state, subgroups, descriptive and box-plot statistics.

The first step of the paper's post-processing (§4): the 400 samples after
0.2 s (:func:`steady_state`), the subgroups of the Xbar-R chart
(:func:`subgroups_from_window`), and the numbers a histogram and a box plot
show (:func:`describe`, :func:`boxplot_stats`). Values keep the caller's unit.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4.1–4.3.
.. [2] J. W. Tukey, Exploratory Data Analysis, Addison-Wesley, 1977 (box plot).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["as_1d", "steady_state", "subgroups_from_window", "Description", "describe",
           "format_number", "scientific", "BoxplotStats", "boxplot_stats"]


# ---------------------------------------------------------------------------
# Input checks shared by every public function
# ---------------------------------------------------------------------------

def as_1d(values, name="values", min_size=1):
    """``values`` as a finite 1-D float array of at least ``min_size``."""
    x = np.asarray(values, dtype=float)
    if x.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {x.shape}")
    if x.size < min_size:
        raise ValueError(f"{name} needs at least {min_size} samples, "
                         f"got {x.size}")
    # A NaN in simulation output is a bug upstream; never average it away.
    if not np.all(np.isfinite(x)):
        raise ValueError(f"{name} contains NaN or infinite samples")
    return x


def _check_time(values, time):
    """Validate a (values, time) pair; return both as 1-D float arrays."""
    x = as_1d(values)
    t = as_1d(time, "time")
    if t.shape != x.shape:
        raise ValueError(f"values and time differ in length: "
                         f"{x.size} != {t.size}")
    if np.any(np.diff(t) <= 0):
        raise ValueError("time must be strictly increasing")
    return x, t


def _time_tolerance(t):
    """Round-off allowance for comparing time stamps with a window edge [s].

    Time grids built as ``k * dt`` or with ``linspace`` miss the nominal edge
    (0.2 s, 0.8 s) by a few ulp; without an allowance the sample *at* the edge
    would fall on either side by accident. 1e-9 of the spacing is far above
    round-off and far below any real sample spacing.
    """
    return 1e-9 * (np.median(np.diff(t)) if t.size > 1 else 1.0)


# ---------------------------------------------------------------------------
# Steady state and subgroups (§4.1, §4.3)
# ---------------------------------------------------------------------------

def steady_state(values, time, start=0.2):
    """Samples strictly after ``start``: the paper's steady state.

    The paper keeps "the 400 points after 0.2 seconds" of 500 samples over 1 s,
    i.e. the samples at 0.202, 0.204, …, 1.000 s. The rule here is the same:
    ``time > start``, where a time stamp equal to ``start`` up to round-off
    (1e-9 of the sample spacing) counts as equal and is *excluded*.

    Parameters
    ----------
    values : array_like
        Samples, 1-D [any unit].
    time : array_like
        Time stamps of ``values``, strictly increasing [s].
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    numpy.ndarray
        The samples with ``time > start`` [unit of ``values``].

    Raises
    ------
    ValueError
        If the arrays differ in length, ``time`` is not increasing, or no
        sample lies after ``start``.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 501)[1:]
    >>> steady_state(np.ones(500), t).size
    400
    """
    x, t = _check_time(values, time)
    kept = x[t - start > _time_tolerance(t)]
    if kept.size == 0:
        raise ValueError(f"no sample after start={start} s "
                         f"(time ends at {t[-1]} s)")
    return kept


def subgroups_from_window(values, time, start, stop, size):
    """Consecutive subgroups of the samples with ``start < time <= stop``.

    The paper (§4.3) takes "100 points with range of 0.8–1.0 seconds" of 500
    samples over 1 s (0.802, …, 1.000 s) and divides them into 25 subgroups of
    4 consecutive samples. Window edges are compared as in
    :func:`steady_state` (round-off of 1e-9 of the spacing counts as equal).

    Parameters
    ----------
    values, time : array_like
        Samples [any unit] and their time stamps [s], as in :func:`steady_state`.
    start : float
        Window start, excluded [s].
    stop : float
        Window end, included [s].
    size : int
        Subgroup size n, at least 2 [-].

    Returns
    -------
    numpy.ndarray
        Shape (k, size): subgroup i holds samples ``i*size … i*size+size-1`` of
        the window [unit of ``values``].

    Raises
    ------
    ValueError
        If the window is empty or its sample count is not a multiple of
        ``size``, naming ``start``, ``stop`` and ``size``.
    """
    x, t = _check_time(values, time)
    size = int(size)
    if size < 2:
        raise ValueError(f"size must be at least 2, got {size}")
    tol = _time_tolerance(t)
    window = x[(t - start > tol) & (t - stop <= tol)]
    if window.size == 0 or window.size % size:
        raise ValueError(
            f"the window start={start} < time <= stop={stop} holds "
            f"{window.size} samples, which cannot be split into subgroups of "
            f"size={size}")
    return window.reshape(-1, size)


# ---------------------------------------------------------------------------
# Descriptive statistics, Anderson–Darling, normal probability plot (§4.1)
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Description:
    """Summary of one series; every field but ``n`` in the unit of the data.

    Quartiles use numpy's default (linear, Hyndman–Fan type 7), the rule
    matplotlib's box plot uses too.
    """

    n: int
    mean: float
    std: float
    min: float
    q1: float
    median: float
    q3: float
    max: float
    range: float


def describe(values):
    """Descriptive statistics of a series (paper §4.1: mean and std).

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 2 [any unit].

    Returns
    -------
    Description
        n [-]; mean, sample standard deviation (ddof = 1), minimum, quartiles,
        median, maximum and range [unit of ``values``].
    """
    x = as_1d(values, min_size=2)
    q1, median, q3 = np.percentile(x, [25.0, 50.0, 75.0])
    return Description(n=x.size, mean=float(x.mean()),
                       std=float(x.std(ddof=1)), min=float(x.min()),
                       q1=float(q1), median=float(median), q3=float(q3),
                       max=float(x.max()), range=float(np.ptp(x)))


_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def scientific(value, digits=3) -> str:
    """A number in powers of ten as a reader reads it: 3.55×10⁻¹⁵, not 3.55e-15; 10⁻⁶ for 1e-06.

    Parameters
    ----------
    value : float
    digits : int
        Significant figures [-].
    """
    mantissa, exponent = f"{float(value):.{max(digits - 1, 0)}e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".") if "." in mantissa else mantissa
    power = f"10{str(int(exponent)).translate(_SUPERSCRIPT)}"
    return power if mantissa == "1" else f"{mantissa}×{power}"


def format_number(value, digits=4) -> str:
    """A number with ``digits`` significant figures, as in a report sentence or table.

    Whole digits are kept (34690, not 3.469e+04); below 1e-3 and from 1e6 on
    in powers of ten (:func:`scientific`); NaN as "nan".

    Parameters
    ----------
    value : float
    digits : int
        Significant figures [-].
    """
    value = float(value)
    if value == 0:
        return "0"
    if not np.isfinite(value):
        return "nan" if np.isnan(value) else ("∞" if value > 0 else "−∞")
    magnitude = abs(value)
    if magnitude < 1e-3 or magnitude >= 1e6:
        return scientific(value, digits)
    decimals = max(digits - 1 - int(np.floor(np.log10(magnitude))), 0)
    text = f"{round(value, decimals):.{decimals}f}"
    return "0" if float(text) == 0 else text


# ---------------------------------------------------------------------------
# Box-plot statistics and figures (Fig. 13–18)
# ---------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class BoxplotStats:
    """What a box plot draws, in the unit of the data."""

    q1: float             #: lower quartile (box bottom)
    median: float         #: median (line in the box)
    q3: float             #: upper quartile (box top)
    iqr: float            #: q3 − q1
    whislo: float         #: lowest sample ≥ q1 − whis·iqr (lower whisker end)
    whishi: float         #: highest sample ≤ q3 + whis·iqr (upper whisker end)
    fliers: np.ndarray    #: samples beyond the whiskers (outliers)
    mean: float           #: sample mean


def boxplot_stats(values, whis=1.5):
    """Quartiles, whisker ends and outliers exactly as the box plot draws them.

    Tukey's rule as matplotlib's ``Axes.boxplot`` applies it (and
    :func:`lsbg.figures.statistics.plot_boxplot` draws these numbers):
    quartiles by linear interpolation (numpy's default), whiskers to the
    furthest sample within ``whis`` IQR of the box (never inside the box),
    samples beyond them are fliers. The paper's "upper/lower edge value
    lines" are the whisker ends.

    Parameters
    ----------
    values : array_like
        Samples, 1-D [any unit].
    whis : float, default 1.5
        Whisker reach in multiples of the IQR [-].

    Returns
    -------
    BoxplotStats
        Quartiles, IQR, whisker ends, fliers and mean [unit of ``values``].
    """
    x = as_1d(values)
    q1, median, q3 = np.percentile(x, [25.0, 50.0, 75.0])
    iqr = q3 - q1
    inside_high = x[x <= q3 + whis * iqr]
    inside_low = x[x >= q1 - whis * iqr]
    # A whisker ends at the box when no sample lies between box and fence.
    whishi = max(float(np.max(inside_high)), q3) if inside_high.size else q3
    whislo = min(float(np.min(inside_low)), q1) if inside_low.size else q1
    return BoxplotStats(q1=float(q1), median=float(median), q3=float(q3), iqr=float(iqr),
                        whislo=float(whislo), whishi=float(whishi),
                        fliers=x[(x < whislo) | (x > whishi)], mean=float(np.mean(x)))
