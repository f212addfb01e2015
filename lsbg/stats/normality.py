"""Normality of the steady-state samples: Anderson–Darling, normal probability plot (§4.1).

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4.1, Figs. 13–14.
.. [2] R. B. D'Agostino and M. A. Stephens (eds.), Goodness-of-Fit Techniques,
   Marcel Dekker, 1986, §4.8 (Anderson–Darling test, case 3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special
from statsmodels.stats.diagnostic import normal_ad

from lsbg.stats.samples import as_1d

__all__ = [
    "AndersonDarling", "ad_pvalue", "anderson_darling", "NormalProbability",
    "normal_probability"
]


@dataclass(frozen=True)
class AndersonDarling:
    """Anderson–Darling normality test, mean and variance estimated."""

    statistic: float  #: A², not corrected for n [-]
    pvalue: float     #: p-value of the normal hypothesis [-]
    n: int            #: sample size [-]


def ad_pvalue(a2, n):
    """p-value of the Anderson–Darling normality test for a given A².

    The formula statsmodels' ``normal_ad`` applies (it has no public function
    for this step): the modified statistic A²* = A² (1 + 0.75/n + 2.25/n²) is
    mapped to p by the piecewise exponential fits of D'Agostino & Stephens
    (1986, Table 4.9), case of unknown mean and variance. Useful for checking
    published (A², p) pairs such as the paper's.

    Parameters
    ----------
    a2 : array_like
        Anderson–Darling statistic A² (uncorrected), non-negative [-].
    n : array_like
        Sample size the statistic was computed from [-].

    Returns
    -------
    float or numpy.ndarray
        p-value [-]; 0 for A²* > 13 (p < 5e-31), NaN for negative A².

    Examples
    --------
    The paper's SBG tangential force, A² = 0.514 with n = 400 (p = 0.192):

    >>> round(ad_pvalue(0.514, 400), 3)
    0.192
    """
    a2 = np.asarray(a2, dtype=float)
    n = np.asarray(n, dtype=float)
    z = a2 * (1.0 + 0.75 / n + 2.25 / n**2)
    # Evaluate every branch everywhere (select picks one); silence the
    # overflow of branches that are not picked.
    with np.errstate(over="ignore", invalid="ignore"):
        p = np.select(
            [z < 0.2, z < 0.34, z < 0.6, z <= 13.0],
            [1.0 - np.exp(-13.436 + 101.14 * z - 223.73 * z**2),
             1.0 - np.exp(-8.318 + 42.796 * z - 59.938 * z**2),
             np.exp(0.9177 - 4.279 * z - 1.38 * z**2),
             np.exp(1.2937 - 5.709 * z + 0.0186 * z**2)],
            default=0.0)
    p = np.where((z >= 0.0), p, np.nan)
    return float(p) if p.ndim == 0 else p


def anderson_darling(values):
    """Anderson–Darling test of normality (paper §4.1, Fig. 13–14).

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 3 [any unit].

    Returns
    -------
    AndersonDarling
        A² and p-value [-] from :func:`statsmodels.stats.diagnostic.normal_ad`.

    Notes
    -----
    The paper reports, for the 400 steady-state samples, A² = 0.293 / 0.264
    (angular velocity, SBG / LSBG) and 0.514 / 0.581 (tangential force), with
    p = 0.601 / 0.697 / 0.192 / 0.130. :func:`ad_pvalue` maps A² to p: it
    gives the last two exactly and 0.6015 / 0.6963 for the first two, within
    what the rounding of the printed A² allows.
    """
    x = as_1d(values, min_size=3)
    a2, p = normal_ad(x)
    return AndersonDarling(statistic=float(a2), pvalue=float(p), n=x.size)


# Harter's family of plotting positions p_i = (i - a) / (n + 1 - 2a).
_PLOTTING_POSITION_A = {"blom": 0.375, "benard": 0.3, "hazen": 0.5}


# eq=False: field-wise == on arrays has no single truth value.
@dataclass(frozen=True, eq=False)
class NormalProbability:
    """Data of a normal probability plot.

    A point i is (``ordered[i]``, ``quantiles[i]``); the fitted normal is the
    straight line value = ``mean`` + ``std`` · quantile (``fitted``).
    """

    ordered: np.ndarray        #: samples in increasing order [data unit]
    probabilities: np.ndarray  #: plotting positions p_i [-]
    quantiles: np.ndarray      #: standard normal quantiles Φ⁻¹(p_i) [-]
    fitted: np.ndarray         #: mean + std · quantiles [data unit]
    mean: float                #: sample mean [data unit]
    std: float                 #: sample standard deviation, ddof=1 [data unit]
    method: str                #: plotting-position rule


def normal_probability(values, method="blom"):
    """Points and fitted line of a normal probability plot (paper Fig. 13–14).

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 2 [any unit].
    method : {'blom', 'benard', 'hazen'}, default 'blom'
        Plotting position of the i-th smallest of n samples (i = 1…n):
        Blom (i − 3/8)/(n + 1/4), the best normal-quantile approximation;
        Benard (i − 0.3)/(n + 0.4), the median rank Minitab plots by default;
        Hazen (i − 0.5)/n.

    Returns
    -------
    NormalProbability
        Ordered samples, plotting positions, normal quantiles and the line of
        the fitted normal distribution (sample mean and std, ddof = 1).
    """
    x = as_1d(values, min_size=2)
    try:
        a = _PLOTTING_POSITION_A[method]
    except KeyError:
        raise ValueError(f"method must be one of "
                         f"{sorted(_PLOTTING_POSITION_A)}, got {method!r}"
                         ) from None
    n = x.size
    p = (np.arange(1, n + 1) - a) / (n + 1.0 - 2.0 * a)
    z = special.ndtri(p)
    mean, std = float(x.mean()), float(x.std(ddof=1))
    return NormalProbability(ordered=np.sort(x), probabilities=p, quantiles=z,
                             fitted=mean + std * z, mean=mean, std=std,
                             method=method)
