"""Steady-state statistics of the paper (§4, Eq. 14–22, Tables 2 and 3).

The paper post-processes four simulated time series (gear angular velocity and
tangential contact force, for SBG and LSBG) in four steps, all reproduced here:

1. the steady state: the 400 samples after 0.2 s (:func:`steady_state`);
2. normality: Anderson–Darling A² and its p-value with a normal probability
   plot, a histogram with the fitted normal pdf and a box plot (§4.1, §4.2);
3. an Xbar-R control chart of 0.8–1.0 s in 25 subgroups of 4 (§4.3, Eq. 14–22),
   whose constants (Table 2) are computed here for any subgroup size;
4. the comparison of the simulated means with Eq. 12–13 (§4.4, Table 3).

The paper only *looks* at the plots to conclude that the LSBG fluctuates less
than the SBG. :func:`compare_fluctuation` puts a number on that: the ratio of
the standard deviations with a block-bootstrap confidence interval (the samples
are autocorrelated, so an i.i.d. test alone would be overconfident), the
Brown–Forsythe test and the effective sample sizes.

Statistics are unit-agnostic: values keep whatever unit the caller gives them.
The charts of the paper (Figs. 13–18) are drawn by :mod:`lsbg.figures.statistics`
from the objects returned here; this package never imports matplotlib.

One module per topic, all re-exported here (``from lsbg import stats;
stats.anderson_darling(x)``):

* :mod:`lsbg.stats.samples`: the steady state, subgroups, descriptive and
  box-plot statistics;
* :mod:`lsbg.stats.normality`: Anderson–Darling and the normal probability
  plot's positions;
* :mod:`lsbg.stats.control`: Xbar-R control-chart constants and limits;
* :mod:`lsbg.stats.bootstrap`: autocorrelation, effective sample size and
  block-bootstrap intervals of a standard deviation or of a ratio of two
  (its hot loop compiled in :mod:`lsbg.stats.kernels`);
* :mod:`lsbg.stats.comparison`: the simulated means against theory and the
  fluctuation of two gear types compared;
* :mod:`lsbg.stats.bands`: the variance of a full-rate record split by mesh-harmonic
  band and around the modes (Parseval), and which band decides a ratio.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4, Eq. (14)–(22),
   Tables 2 and 3.
.. [2] D. C. Montgomery, Introduction to Statistical Quality Control, 6th ed.,
   Wiley, 2009, §6.2 (Xbar and R charts) and Appendix Table VI.
.. [3] R. B. D'Agostino and M. A. Stephens (eds.), Goodness-of-Fit Techniques,
   Marcel Dekker, 1986, §4.8 (Anderson–Darling test, case 3).
.. [4] C. J. Geyer, Practical Markov chain Monte Carlo, Statistical Science 7
   (1992) 473–483 (initial monotone sequence estimator).
.. [5] D. N. Politis and J. P. Romano, A circular block-resampling procedure
   for stationary data, in: Exploring the Limits of Bootstrap, Wiley, 1992;
   The stationary bootstrap, J. Amer. Statist. Assoc. 89 (1994) 1303–1313.
"""

from lsbg import lazy_exports

#: Submodule -> the names it exports (imported when first used).
_EXPORTS = {
    "samples": ("as_1d", "steady_state", "subgroups_from_window", "Description", "describe",
                "format_number", "scientific", "BoxplotStats", "boxplot_stats"),
    "normality": ("AndersonDarling", "ad_pvalue", "anderson_darling", "NormalProbability",
                  "normal_probability"),
    "control": ("ControlChartConstants", "control_chart_constants", "XbarRChart",
                "xbar_r_chart", "xbar_r_ylims"),
    "bootstrap": ("OVER_WINDOWS", "autocorrelation", "integrated_autocorrelation_time", "effective_sample_size",
                  "StdRatioCI", "std_ratio_ci", "StdCI", "std_ci"),
    "comparison": ("TheoryComparison", "compare_to_theory", "BrownForsythe", "brown_forsythe",
                   "FluctuationComparison", "compare_fluctuation"),
    "bands": ("HARMONIC_BANDS", "BAND_LABELS", "BandSplit", "band_split", "band_ratio",
              "deciding_band"),
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = [name for names in _EXPORTS.values() for name in names]
