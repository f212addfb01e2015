"""Xbar-R control charts (§4.3, Eq. 14–22): constants for any subgroup size, limits, alarms.

The constants of Table 2 (d2, d3, A2, D3, D4) are computed from the
distribution of the range of n normal samples, not looked up.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4.3, Eq. (14)–(22),
   Table 2.
.. [2] D. C. Montgomery, Introduction to Statistical Quality Control, 6th ed.,
   Wiley, 2009, §6.2 (Xbar and R charts) and Appendix Table VI.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy import integrate, special

from lsbg.stats.samples import as_1d

__all__ = [
    "ControlChartConstants", "control_chart_constants", "XbarRChart", "xbar_r_chart",
    "xbar_r_ylims"
]


# ---------------------------------------------------------------------------
# Control-chart constants (Table 2)
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class ControlChartConstants:
    """Xbar-R chart constants for subgroup size ``n`` (3-sigma limits).

    Names follow Montgomery / ASTM. The paper's Table 2 names them otherwise:
    its ``d`` is ``d3``, its ``a_n`` is ``1/d2``, its ``A2`` is ``A2``, its
    ``D1`` is ``D4`` and its ``D2`` is ``D3`` (see :meth:`paper_table2`).
    All are dimensionless.
    """

    n: int
    d2: float  #: E[W], W the range of n standard normal samples [-]
    d3: float  #: standard deviation of W [-]
    A2: float  #: 3 / (d2 √n): Xbar limits = x̿ ± A2 R̄ [-]
    D3: float  #: max(0, 1 − 3 d3/d2): R-chart lower limit / R̄ [-]
    D4: float  #: 1 + 3 d3/d2: R-chart upper limit / R̄ [-]

    @property
    def a_n(self):
        """The paper's a_n = 1/d2, so that σ̂ = a_n R̄ (Eq. 15) [-]."""
        return 1.0 / self.d2

    def paper_table2(self):
        """The constants under the names of the paper's Table 2.

        Returns
        -------
        dict
            ``{'d': d3, 'a_n': 1/d2, 'A2': A2, 'D1': D4, 'D2': D3}`` [-].
        """
        return {"d": self.d3, "a_n": self.a_n, "A2": self.A2, "D1": self.D4,
                "D2": self.D3}


# Quadrature tolerances: the integrands are smooth and decay like the normal
# tail, so these give d2 and d3 to about 1e-10.
_QUAD = {"epsabs": 1e-13, "epsrel": 1e-12, "limit": 200}


def _range_moments(n):
    """(E[W], sd[W]) of the range W of n i.i.d. standard normal samples."""
    ndtr = special.ndtr
    # E[W] = ∫ P(min ≤ x ≤ max) dx = ∫ 1 − Φ(x)^n − (1 − Φ(x))^n dx.
    # Φ(−x) replaces 1 − Φ(x) to keep the upper tail accurate.
    d2 = integrate.quad(lambda x: 1.0 - ndtr(x)**n - ndtr(-x)**n,
                        -np.inf, np.inf, **_QUAD)[0]

    # (max − min)² / 2 is the area of {min ≤ x < y ≤ max}, hence
    # E[W²] = 2 ∬_{x<y} P(min ≤ x, max ≥ y) dy dx, and by inclusion–exclusion
    # P(min ≤ x, max ≥ y) = 1 − (1−Φ(x))^n − Φ(y)^n + (Φ(y) − Φ(x))^n.
    def inner(x):
        fx, sx = ndtr(x), ndtr(-x)
        return integrate.quad(
            lambda y: 1.0 - sx**n - ndtr(y)**n + (ndtr(y) - fx)**n,
            x, np.inf, **_QUAD)[0]

    ew2 = 2.0 * integrate.quad(inner, -np.inf, np.inf, **_QUAD)[0]
    return d2, math.sqrt(ew2 - d2 * d2)


# Cached: charts and notebooks ask for the same n over and over, and each
# call costs a double integral (a few tens of ms).
@functools.lru_cache(maxsize=None)
def _constants(n):
    """ControlChartConstants for a validated integer n >= 2."""
    d2, d3 = _range_moments(n)
    return ControlChartConstants(
        n=n, d2=d2, d3=d3, A2=3.0 / (d2 * math.sqrt(n)),
        D3=max(0.0, 1.0 - 3.0 * d3 / d2), D4=1.0 + 3.0 * d3 / d2)


def control_chart_constants(n):
    """Xbar-R chart constants d2, d3, A2, D3, D4 for subgroup size n.

    Computed rather than tabulated: d2 = E[W] and d3 = sd[W] of the range W of
    n independent standard normal samples, by numerical integration of the
    range distribution (accurate to about 1e-10), then

    - A2 = 3 / (d2 √n)  (Xbar limits x̿ ± A2 R̄, paper Eq. 18–19),
    - D3 = max(0, 1 − 3 d3/d2), D4 = 1 + 3 d3/d2  (R limits, Eq. 21–22).

    The paper's Table 2 uses other names: its ``d`` is d3, its ``a_n`` is
    1/d2, its ``A2`` is A2, its ``D1`` is D4 and its ``D2`` is D3.

    Parameters
    ----------
    n : int
        Subgroup size, at least 2 [-].

    Returns
    -------
    ControlChartConstants
        The constants [-]; results are cached per n.

    Notes
    -----
    Published tables print values rounded to 3 decimals, and several derive
    D3, D4 and A2 from the *rounded* d2 and d3; their last digit can therefore
    differ by one from the exact values here (e.g. D4 for n = 3 is 2.57459:
    Montgomery prints 2.574, the AIAG manual 2.575).

    Examples
    --------
    >>> c = control_chart_constants(4)
    >>> round(c.d2, 3), round(c.d3, 3), round(c.A2, 3), round(c.D4, 3)
    (2.059, 0.88, 0.729, 2.282)
    """
    if isinstance(n, bool) or int(n) != n or n < 2:
        raise ValueError(f"subgroup size n must be an integer >= 2, got {n!r}")
    return _constants(int(n))


# ---------------------------------------------------------------------------
# Xbar-R control chart (Eq. 14–22)
# ---------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class XbarRChart:
    """An Xbar-R control chart; levels and limits in the unit of the data.

    Indices of out-of-control subgroups are 0-based: the paper's "ninth
    point" is index 8.
    """

    xbar: np.ndarray          #: subgroup means, shape (k,)
    ranges: np.ndarray        #: subgroup ranges, shape (k,)
    xbar_center: float        #: x̿, Eq. 14/17
    xbar_lcl: float           #: x̿ − A2 R̄, Eq. 19
    xbar_ucl: float           #: x̿ + A2 R̄, Eq. 18
    r_center: float           #: R̄, Eq. 16/20
    r_lcl: float              #: D3 R̄, Eq. 22
    r_ucl: float              #: D4 R̄, Eq. 21
    sigma_hat: float          #: R̄ / d2, Eq. 15
    out_of_control_xbar: np.ndarray  #: subgroups with xbar beyond its limits
    out_of_control_r: np.ndarray     #: subgroups with R beyond its limits
    out_of_control: np.ndarray       #: union of both, sorted
    constants: ControlChartConstants  #: constants for the subgroup size

    @property
    def k(self):
        """Number of subgroups [-]."""
        return self.xbar.size

    @property
    def n(self):
        """Subgroup size [-]."""
        return self.constants.n


def _beyond(values, lcl, ucl):
    """Indices of values strictly outside [lcl, ucl]."""
    return np.flatnonzero((values < lcl) | (values > ucl))


def xbar_r_chart(subgroups):
    """Xbar-R control chart of k subgroups of size n (paper Eq. 14–22).

    Parameters
    ----------
    subgroups : array_like
        Shape (k, n), one subgroup per row, n ≥ 2 [any unit].

    Returns
    -------
    XbarRChart
        Subgroup means and ranges, centre lines, 3-sigma limits, σ̂ = R̄/d2
        and the subgroups beyond the limits (strictly outside).

    See Also
    --------
    subgroups_from_window : builds ``subgroups`` from a time series.
    """
    g = np.asarray(subgroups, dtype=float)
    if g.ndim != 2 or g.shape[0] < 1 or g.shape[1] < 2:
        raise ValueError(f"subgroups must have shape (k, n) with k >= 1 and "
                         f"n >= 2, got {g.shape}")
    as_1d(g.ravel(), "subgroups")
    c = control_chart_constants(g.shape[1])
    xbar = g.mean(axis=1)
    ranges = np.ptp(g, axis=1)
    center, rbar = float(xbar.mean()), float(ranges.mean())
    xbar_lcl, xbar_ucl = center - c.A2 * rbar, center + c.A2 * rbar
    r_lcl, r_ucl = c.D3 * rbar, c.D4 * rbar
    ooc_x = _beyond(xbar, xbar_lcl, xbar_ucl)
    ooc_r = _beyond(ranges, r_lcl, r_ucl)
    return XbarRChart(
        xbar=xbar, ranges=ranges, xbar_center=center, xbar_lcl=xbar_lcl,
        xbar_ucl=xbar_ucl, r_center=rbar, r_lcl=r_lcl, r_ucl=r_ucl,
        sigma_hat=rbar / c.d2, out_of_control_xbar=ooc_x,
        out_of_control_r=ooc_r, out_of_control=np.union1d(ooc_x, ooc_r),
        constants=c)


def xbar_r_ylims(*charts, margin=0.05):
    """Common y-limits so that several Xbar-R charts share their scales.

    The paper draws SBG and LSBG charts "with same coordinate axis scale"
    (Fig. 17–18); pass the result to :func:`plot_xbar_r` for each chart.

    Parameters
    ----------
    *charts : XbarRChart
        Charts to cover.
    margin : float, default 0.05
        Padding on each side as a fraction of the span [-].

    Returns
    -------
    xbar_ylim, r_ylim : tuple of float
        (bottom, top) covering every point and limit line [data unit].
    """
    if not charts:
        raise ValueError("xbar_r_ylims needs at least one chart")

    def padded(values):
        lo, hi = float(np.min(values)), float(np.max(values))
        pad = margin * (hi - lo)
        return lo - pad, hi + pad

    xbar_ylim = padded(np.concatenate(
        [np.r_[c.xbar, c.xbar_lcl, c.xbar_ucl] for c in charts]))
    r_ylim = padded(np.concatenate(
        [np.r_[c.ranges, c.r_lcl, c.r_ucl] for c in charts]))
    return xbar_ylim, r_ylim
