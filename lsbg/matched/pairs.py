"""The two traces' front members matched one to one, and the paired statistics.

:func:`match_members` pairs the members of two sets in the normalised space of
the matching objectives: the least total distance over all one-to-one
pairings (the assignment problem, :func:`scipy.optimize.linear_sum_assignment`),
then every pair farther apart than the caliper dropped (a caliper match, as in
matched observational studies: Rosenbaum 2010, ch. 9). Where the fronts'
ranges overlap only partly, only the overlap yields pairs.

:func:`paired_statistics` answers over the surviving pairs whether a per-pair
log ratio (log std(SBG)/std(LSBG): positive, the LSBG calmer) is centred
away from 0: Wilcoxon's signed-rank test and a percentile bootstrap interval
of its mean over the pairs (:func:`scipy.stats.bootstrap`, a fixed seed).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MATCH_OBJECTIVES", "DEFAULT_CALIPER", "normalised", "match_members",
           "paired_statistics", "unique_rows"]

#: The objectives the designs are matched on (names of
#: :data:`lsbg.optimise.objectives.QUANTITIES`).
MATCH_OBJECTIVES = ("pattern_movement", "contact_pressure")
#: The largest distance of a kept pair in the normalised objectives [-].
DEFAULT_CALIPER = 0.05


def normalised(values, low, high):
    """``(values - low) / (high - low)`` per objective (the common box's normalisation).

    Parameters
    ----------
    values : array_like
        (n, m) in the objectives' units.
    low, high : array_like
        (m,) the box's corners, ``high > low``, same units.

    Returns
    -------
    numpy.ndarray
        (n, m) dimensionless.
    """
    low, high = np.asarray(low, float), np.asarray(high, float)
    if not np.all(high > low):
        raise ValueError(f"box low = {low.tolist()}, high = {high.tolist()}: high must exceed "
                         f"low in every objective")
    return (np.asarray(values, float).reshape(-1, low.size) - low) / (high - low)


def unique_rows(values):
    """The indices of the first of each set of equal rows of ``values``, ascending.

    Seeds that start from the same shared design can keep it on their fronts:
    one design, matched once.
    """
    values = np.asarray(values, float)
    if not len(values):
        return np.zeros(0, int)
    _, first = np.unique(values, axis=0, return_index=True)
    return np.sort(first)


def match_members(a, b, caliper=DEFAULT_CALIPER, limit=None):
    """Optimal one-to-one pairs of the rows of ``a`` and ``b``, within the caliper.

    Parameters
    ----------
    a, b : numpy.ndarray
        (n_a, m), (n_b, m): the two sets' normalised objectives [-] (the LSBG's first).
    caliper : float
        The largest Euclidean distance of a kept pair [-], > 0.
    limit : int, optional
        Keep at most this many pairs, the closest (ties: the order of ``a``).

    Returns
    -------
    dict
        ``a``, ``b``: the indices of the kept pairs' members (int arrays, ordered by
        ``a``'s index); ``distance`` [-] of each; ``assigned``: pairs of the
        assignment before the caliper; ``dropped``: those beyond it.
    """
    from scipy.optimize import linear_sum_assignment

    if not caliper > 0:
        raise ValueError(f"caliper = {caliper!r}: must be a positive distance [-]")
    a, b = np.atleast_2d(np.asarray(a, float)), np.atleast_2d(np.asarray(b, float))
    empty = {"a": np.zeros(0, int), "b": np.zeros(0, int), "distance": np.zeros(0),
             "assigned": 0, "dropped": 0}
    if not a.size or not b.size:
        return empty
    if a.shape[1] != b.shape[1]:
        raise ValueError(f"sets of {a.shape[1]} and {b.shape[1]} objectives")
    distance = np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2))
    rows, cols = linear_sum_assignment(distance)
    d = distance[rows, cols]
    keep = d <= caliper
    rows, cols, d = rows[keep], cols[keep], d[keep]
    if limit is not None and rows.size > limit:
        closest = np.sort(np.argsort(d, kind="stable")[:int(limit)])
        rows, cols, d = rows[closest], cols[closest], d[closest]
    return {"a": rows.astype(int), "b": cols.astype(int), "distance": d,
            "assigned": int(keep.size), "dropped": int((~keep).sum())}


def paired_statistics(log_ratios, confidence=0.95, resamples=9999, seed=0):
    """Whether per-pair log ratios are centred away from 0.

    Parameters
    ----------
    log_ratios : array_like
        One value per pair [-], e.g. log(std_SBG / std_LSBG); NaNs dropped.
    confidence : float
        The bootstrap interval's level [-].
    resamples : int
        Bootstrap resamples.
    seed : int
        The bootstrap's random seed (the same pairs, the same interval).

    Returns
    -------
    dict
        ``pairs`` (finite values), ``mean``, ``median`` [-], ``positive`` (the share
        > 0), ``wilcoxon_statistic``, ``wilcoxon_p`` (two-sided; NaN below 2 pairs or
        all zero), ``low``, ``high`` (the percentile bootstrap interval of the mean;
        NaN below 2 pairs or no spread).
    """
    from scipy.stats import bootstrap, wilcoxon

    x = np.asarray(log_ratios, float).ravel()
    x = x[np.isfinite(x)]
    out = {"pairs": int(x.size), "mean": math.nan, "median": math.nan, "positive": math.nan,
           "wilcoxon_statistic": math.nan, "wilcoxon_p": math.nan,
           "low": math.nan, "high": math.nan}
    if not x.size:
        return out
    out.update(mean=float(x.mean()), median=float(np.median(x)), positive=float(np.mean(x > 0)))
    if x.size >= 2 and np.any(x != 0):
        test = wilcoxon(x, alternative="two-sided")
        out.update(wilcoxon_statistic=float(test.statistic), wilcoxon_p=float(test.pvalue))
    if x.size >= 2 and np.ptp(x) > 0:
        ci = bootstrap((x,), np.mean, confidence_level=confidence, n_resamples=resamples,
                       method="percentile", rng=np.random.default_rng(seed))
        out.update(low=float(ci.confidence_interval.low), high=float(ci.confidence_interval.high))
    return out
