"""Comparisons: simulated means against theory (Table 3), and the fluctuation of two gear types.

:func:`compare_fluctuation` puts a number on the paper's visual verdict: the
ratio of the standard deviations with a block-bootstrap interval
(:mod:`lsbg.stats.bootstrap`), the Brown–Forsythe test and the effective
sample sizes.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4.4, Table 3.
.. [2] M. B. Brown and A. B. Forsythe, Robust tests for the equality of
   variances, J. Amer. Statist. Assoc. 69 (1974) 364–367.
"""

from __future__ import annotations

from dataclasses import dataclass

from scipy import stats as sps

from lsbg.stats.bootstrap import OVER_WINDOWS, StdRatioCI, effective_sample_size, std_ratio_ci
from lsbg.stats.samples import as_1d, format_number

__all__ = [
    "TheoryComparison", "compare_to_theory", "BrownForsythe", "brown_forsythe",
    "FluctuationComparison", "compare_fluctuation"
]


# ---------------------------------------------------------------------------
# Simulation versus theory (Table 3)
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class TheoryComparison:
    """One row of the paper's Table 3, in the unit of the compared quantity."""

    simulated: float           #: simulated mean
    theory: float              #: Eq. 12 or 13
    difference: float          #: simulated − theory
    error_rate_percent: float  #: 100 |difference| / |theory| [%]


def compare_to_theory(simulated_mean, theory):
    """Relative error of a simulated mean against theory (paper Table 3).

    Parameters
    ----------
    simulated_mean : float
        Steady-state mean of the simulation [any unit].
    theory : float
        Theoretical value, Eq. 12 (speed) or Eq. 13 (force), non-zero
        [unit of ``simulated_mean``].

    Returns
    -------
    TheoryComparison
        Difference (signed, simulated − theory) and error rate
        100 |difference| / |theory| [%].

    Notes
    -----
    The paper prints the difference as an absolute value. Its SBG force row
    (24799.9 N vs 23603.48 N, "4.82 %") divides by the *simulated* value; by
    the rule of its other three rows (and this function) it is 5.07 %.

    Examples
    --------
    >>> round(compare_to_theory(1872.69, 1873.703).error_rate_percent, 3)
    0.054
    """
    simulated, theory = float(simulated_mean), float(theory)
    if theory == 0.0:
        raise ValueError("theory must be non-zero for a relative error")
    difference = simulated - theory
    return TheoryComparison(simulated=simulated, theory=theory,
                            difference=difference,
                            error_rate_percent=100.0 * abs(difference)
                            / abs(theory))


# ---------------------------------------------------------------------------
# Comparing the fluctuation of two series
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class BrownForsythe:
    """Brown–Forsythe test of equal variances (Levene, median-centred)."""

    statistic: float  #: W statistic [-]
    pvalue: float     #: p-value of equal variances [-]


def brown_forsythe(a, b):
    """Brown–Forsythe test that two series have equal variances.

    Robust to non-normality, but it assumes independent samples: with
    autocorrelated series its p-value is too small (see
    :func:`effective_sample_size`).

    Parameters
    ----------
    a, b : array_like
        Samples, 1-D, at least 2 each [same unit].

    Returns
    -------
    BrownForsythe
        Statistic and p-value [-] of :func:`scipy.stats.levene` with
        ``center='median'``.
    """
    res = sps.levene(as_1d(a, "a", 2), as_1d(b, "b", 2), center="median")
    return BrownForsythe(statistic=float(res.statistic),
                         pvalue=float(res.pvalue))


@dataclass(frozen=True)
class FluctuationComparison:
    """Which of two series fluctuates less, with the evidence."""

    names: tuple                 #: names of (a, b)
    std: tuple                   #: sample std of (a, b), ddof = 1 [data unit]
    ratio: float                 #: std(a) / std(b) [-]
    ci: StdRatioCI               #: bootstrap interval of ``ratio``
    brown_forsythe_pvalue: float  #: p of equal variances, i.i.d. assumed [-]
    n: tuple                     #: sample sizes of (a, b) [-]
    effective_sample_size: tuple  #: n/τ of (a, b) [-]
    conclusion: str              #: one-paragraph summary of the above


def compare_fluctuation(a, b, names=("SBG", "LSBG"), units="",
                        confidence=0.95, **ci_options):
    """Compare the fluctuation of two series (paper §4.1–4.3, quantified).

    Parameters
    ----------
    a, b : array_like
        Steady-state samples, 1-D, at least 4 each [same unit].
    names : tuple of str, default ('SBG', 'LSBG')
        Names of ``a`` and ``b`` for the conclusion.
    units : str, optional
        Unit of the samples, for the conclusion only (e.g. 'deg/s').
    confidence : float, default 0.95
        Confidence level of the ratio's interval [-].
    **ci_options
        ``n_boot``, ``block_length``, ``seed``, ``method`` of
        :func:`std_ratio_ci`.

    Returns
    -------
    FluctuationComparison
        Standard deviations, ratio std(a)/std(b) with its block-bootstrap
        interval, Brown–Forsythe p-value, effective sample sizes and a
        ``conclusion`` sentence built from these numbers.
    """
    x = as_1d(a, "a", 4)
    y = as_1d(b, "b", 4)
    ci = std_ratio_ci(x, y, confidence=confidence, **ci_options)
    bf = brown_forsythe(x, y)
    ess = (effective_sample_size(x), effective_sample_size(y))
    std = (float(x.std(ddof=1)), float(y.std(ddof=1)))

    # Phrase the result as "smaller one, by factor ≥ 1" whichever way round.
    if ci.ratio >= 1.0:
        calm, rough, order = names[1], names[0], (1, 0)
        factor, lo, hi = ci.ratio, ci.low, ci.high
    else:
        calm, rough, order = names[0], names[1], (0, 1)
        factor, lo, hi = 1.0 / ci.ratio, 1.0 / ci.high, 1.0 / ci.low
    unit = f" {units}" if units else ""
    pct = f"{100.0 * confidence:g} %"
    verdict = ("excludes 1, so the difference is significant at that level"
               if ci.excludes_one else
               "includes 1, so the difference is not significant at that "
               "level")
    conclusion = (
        f"{calm} fluctuates less than {rough}: standard deviation "
        f"{format_number(std[order[0]])}{unit} against {format_number(std[order[1]])}{unit}, "
        f"a factor {factor:.3g} (block-bootstrap {pct} interval {OVER_WINDOWS} "
        f"{lo:.3g}–{hi:.3g}, which {verdict}). "
        f"Brown–Forsythe p = {format_number(bf.pvalue, 2)}. Effective sample sizes "
        f"{ess[0]:.0f} of {x.size} ({names[0]}) and {ess[1]:.0f} of "
        f"{y.size} ({names[1]})")
    if min(ess[0] / x.size, ess[1] / y.size) < 0.5:
        conclusion += ("; the samples are autocorrelated, so the "
                       "Brown–Forsythe p-value, which assumes independence, "
                       "is too small and the bootstrap interval is the "
                       "better guide.")
    else:
        conclusion += "."
    return FluctuationComparison(
        names=tuple(names), std=std, ratio=ci.ratio, ci=ci,
        brown_forsythe_pvalue=bf.pvalue, n=(x.size, y.size),
        effective_sample_size=ess, conclusion=conclusion)
