"""Statistics charts of the paper (Figs. 13–18): normal probability, histogram, box plot, Xbar-R.

The numbers come from :mod:`lsbg.stats` (the figures only draw them): the
one-series charts take samples or a chart object with the ``label`` and
``units`` of the axes from the caller; :func:`plot_normality`,
:func:`plot_boxplots` and :func:`plot_control_charts` draw both gear types of
a design point side by side, from run datasets.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §4, Figs. 13–18.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from scipy import special, stats as sps

from lsbg.figures.base import MAX_WIDTH, axis_label, display_unit, legend_above, new_figure
from lsbg.aggregate.runs import runs_by_type, quantity_label, steady
from lsbg.stats.control import xbar_r_ylims
from lsbg.stats.normality import anderson_darling, normal_probability
from lsbg.stats.samples import as_1d, describe, format_number, scientific

__all__ = ["plot_normal_probability", "plot_histogram", "plot_boxplot", "plot_xbar_r",
           "plot_normality", "plot_boxplots", "plot_control_charts"]



def _axis_label(label, units):
    """'label [units]' with the units as printed (µrad, N·m), or whichever part is given."""
    return axis_label(label or "value", units or "")


def _new_axes(ax, nrows=1, ncols=1, **subplot_kw):
    """Return (figure, axes): the given axes' figure, or a new Figure.

    A bare :class:`matplotlib.figure.Figure` touches no pyplot state, so the
    functions work under any backend and never open a window.
    """
    if ax is not None:
        return ax.figure, ax
    fig = Figure(figsize=(min(4.0 * ncols + 1.0, MAX_WIDTH), 3.5 * nrows + 0.5),
                 layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw)
    return fig, (axes[0, 0] if axes.size == 1 else axes.ravel())


# Probabilities labelled on the normal probability plot [%].
_PROB_TICKS = np.array([1, 5, 10, 20, 30, 50, 70, 80, 90, 95, 99])


def plot_normal_probability(values, ax=None, label="", units="",
                            method="blom", xlim=None):
    """Normal probability plot with the fitted normal and A², p (Fig. 13–14).

    Parameters
    ----------
    values : array_like
        Samples, 1-D, at least 3 [``units``].
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new Figure is made if omitted.
    label : str, optional
        Name of the quantity, for the x axis.
    units : str, optional
        Unit of ``values``, for the x axis.
    method : str, default 'blom'
        Plotting-position rule, see :func:`normal_probability`.
    xlim : (float, float), optional
        x-axis limits, to share scales between plots [``units``].

    Returns
    -------
    matplotlib.figure.Figure
        The figure holding the plot.
    """
    fig, ax = _new_axes(ax)
    npp = normal_probability(values, method=method)
    ad = anderson_darling(values)
    ax.plot(npp.ordered, npp.quantiles, "o", ms=3, label="samples")
    ax.plot(npp.fitted, npp.quantiles, "-", color="C3", label="fitted normal")
    ax.set_yticks(special.ndtri(_PROB_TICKS / 100.0),
                  [f"{p:g}" for p in _PROB_TICKS])
    ax.set_xlabel(_axis_label(label, units))
    ax.set_ylabel("probability [%]")
    if xlim is not None:
        ax.set_xlim(xlim)
    unit = f" {display_unit(units)}" if units else ""
    ax.text(0.03, 0.97,
            f"mean {format_number(npp.mean)}{unit}\nstd {format_number(npp.std)}{unit}\n"
            f"N {ad.n}\nA² {ad.statistic:.3f}\np {ad.pvalue:.3f}",
            transform=ax.transAxes, va="top", fontsize="small",
            bbox={"boxstyle": "round", "fc": "white", "alpha": 0.8})
    ax.grid(True, alpha=0.3)
    return fig


def plot_histogram(series, label="", units="", bins="auto", overlay=False,
                   xlim=None):
    """Histograms with the fitted normal pdf (Fig. 15), one per series.

    Parameters
    ----------
    series : dict of str to array_like
        Named samples, e.g. ``{'SBG': …, 'LSBG': …}`` [``units``].
    label : str, optional
        Name of the quantity, for the x axis.
    units : str, optional
        Unit of the samples, for the axes.
    bins : int or str, default 'auto'
        Histogram bins, as :func:`numpy.histogram_bin_edges`.
    overlay : bool, default False
        Draw all series on one axes instead of side by side (side-by-side
        axes share both scales, as in the paper).
    xlim : (float, float), optional
        x-axis limits [``units``].

    Returns
    -------
    matplotlib.figure.Figure
        One axes per series, or one axes if ``overlay``.
    """
    if not series:
        raise ValueError("series must hold at least one named series")
    ncols = 1 if overlay else len(series)
    fig, axes = _new_axes(None, 1, ncols, sharex=True, sharey=True)
    axes = np.atleast_1d(axes)
    unit = f" {display_unit(units)}" if units else ""
    fits = {name: describe(values) for name, values in series.items()}
    # A density of 7e-5 per N would print its 1e-5 as an offset above the
    # axes, apart from the unit: fold that power of ten into the unit instead.
    peak = max(sps.norm.pdf(0.0, 0.0, d.std) if d.std > 0 else 0.0 for d in fits.values())
    exponent = int(np.floor(np.log10(peak))) if peak > 0 else 0
    power = exponent if exponent < -2 or exponent > 3 else 0
    scale = 10.0 ** -power
    for i, (name, values) in enumerate(series.items()):
        ax = axes[0 if overlay else i]
        d = fits[name]
        density, edges = np.histogram(as_1d(values), bins=bins, density=True)
        ax.stairs(density * scale, edges, fill=True, alpha=0.5, color=f"C{i}", label=name)
        grid = np.linspace(d.mean - 4.0 * d.std, d.mean + 4.0 * d.std, 200)
        ax.plot(grid, sps.norm.pdf(grid, d.mean, d.std) * scale, color=f"C{i}",
                label=f"{name}: normal, mean {format_number(d.mean)}{unit}, "
                      f"std {format_number(d.std)}{unit}")
        ax.set_xlabel(_axis_label(label, units))
    for ax in axes:
        # above the panel: the normal curve fills the middle, the tails the corners
        legend_above(ax)
    # 1/deg/s would read as (1/deg)/s
    shown = display_unit(units)
    inverse = f"1/({shown})" if set("/ ·*") & set(shown) else f"1/{shown}"
    if power:
        inverse = f"{scientific(10.0 ** power)}{inverse[1:]}"
    for ax in axes:
        ax.set_ylabel(f"density [{inverse}]" if units else "density")
        if xlim is not None:
            ax.set_xlim(xlim)
    return fig


def plot_boxplot(series, label="", units="", ax=None, ylim=None, whis=1.5,
                 category="gear type"):
    """Box plots of several series side by side (Fig. 16).

    Boxes span the quartiles with the median inside, whiskers reach the
    furthest sample within ``whis`` IQR, fliers mark the samples beyond; the
    numbers are those of :func:`boxplot_stats`.

    Parameters
    ----------
    series : dict of str to array_like
        Named samples [``units``].
    label : str, optional
        Name of the quantity, for the y axis.
    units : str, optional
        Unit of the samples, for the y axis.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new Figure is made if omitted.
    ylim : (float, float), optional
        y-axis limits, to share scales between plots [``units``].
    whis : float, default 1.5
        Whisker reach in multiples of the IQR [-].
    category : str, default 'gear type'
        What the series' names are, for the x axis.

    Returns
    -------
    matplotlib.figure.Figure
        The figure holding the box plots.
    """
    if not series:
        raise ValueError("series must hold at least one named series")
    fig, ax = _new_axes(ax)
    ax.boxplot([as_1d(v) for v in series.values()], whis=whis,
               tick_labels=list(series))
    ax.set_ylabel(_axis_label(label, units))
    ax.set_xlabel(category)
    if ylim is not None:
        ax.set_ylim(ylim)
    ax.grid(True, axis="y", alpha=0.3)
    return fig


def _draw_chart(ax, values, center, lcl, ucl, beyond, ylabel, ylim):
    """One panel of an Xbar-R chart: points, centre line, limits, alarms."""
    k = np.arange(1, values.size + 1)
    ax.plot(k, values, "o-", ms=3, color="C0", lw=1)
    for level, style, name in ((ucl, "--", "UCL"), (center, "-", "CL"),
                               (lcl, "--", "LCL")):
        ax.axhline(level, ls=style, color="C2" if name == "CL" else "C3",
                   lw=1)
        ax.annotate(f"{name} = {format_number(level)}", (1.0, level),
                    xycoords=("axes fraction", "data"), xytext=(3, 0),
                    textcoords="offset points", va="center",
                    fontsize="small")
    # gid lets callers (and tests) find the alarm markers.
    ax.plot(k[beyond], values[beyond], "o", color="red", ms=6,
            gid="out_of_control", label="out of control")
    ax.set_ylabel(ylabel)
    if ylim is not None:
        ax.set_ylim(ylim)
    ax.grid(True, alpha=0.3)


def plot_xbar_r(chart, label="", units="", title=None, xbar_ylim=None,
                r_ylim=None):
    """Xbar chart above R chart, alarms in red (paper Fig. 17–18).

    Parameters
    ----------
    chart : XbarRChart
        Result of :func:`xbar_r_chart`.
    label : str, optional
        Name of the quantity, for the y axes.
    units : str, optional
        Unit of the quantity, for the y axes.
    title : str, optional
        Figure title.
    xbar_ylim, r_ylim : (float, float), optional
        y-limits of the two panels [``units``]; use :func:`xbar_r_ylims` to
        give two gear types the same scales, as the paper does.

    Returns
    -------
    matplotlib.figure.Figure
        Two axes: subgroup means (top) and ranges (bottom) against the
        1-based subgroup number.
    """
    fig, (ax_x, ax_r) = _new_axes(None, 2, 1, sharex=True)
    name = label or "value"
    _draw_chart(ax_x, chart.xbar, chart.xbar_center, chart.xbar_lcl,
                chart.xbar_ucl, chart.out_of_control_xbar,
                _axis_label(f"subgroup mean of {name}", units), xbar_ylim)
    _draw_chart(ax_r, chart.ranges, chart.r_center, chart.r_lcl, chart.r_ucl,
                chart.out_of_control_r,
                _axis_label(f"subgroup range of {name}", units), r_ylim)
    ax_r.set_xlabel(f"subgroup number [-] (n = {chart.n} samples each)")
    if title:
        fig.suptitle(title)
    return fig


# ----------------------------------------------- both gear types side by side
def _common_limits(arrays, margin=0.05):
    lo = min(float(np.min(a)) for a in arrays)
    hi = max(float(np.max(a)) for a in arrays)
    pad = margin * (hi - lo) if hi > lo else 1.0
    return lo - pad, hi + pad


def plot_normality(runs, name, start=0.2) -> Figure:
    """Normal probability plots with A² and p, one panel per type (Fig. 13–14).

    Returns
    -------
    matplotlib.figure.Figure
        Panels with a shared x axis range.
    """
    by_type = runs_by_type(runs)
    series = {label: steady(ds, name, start) for label, ds in by_type.items()}
    xlim = _common_limits(series.values())
    fig, axes = new_figure(1, len(series))
    first = next(iter(by_type.values()))
    text, units = quantity_label(first, name)
    for ax, (label, x) in zip(axes[0], series.items()):
        plot_normal_probability(x, ax=ax, label=text, units=units, xlim=xlim)
        ax.set_title(label)
    return fig


def plot_boxplots(runs, names=("gear_speed", "tangential_force"), start=0.2) -> Figure:
    """Box plots of the steady state of each type, one panel per quantity (Fig. 16)."""
    by_type = runs_by_type(runs)
    fig, axes = new_figure(1, len(names))
    first = next(iter(by_type.values()))
    for ax, name in zip(axes[0], names):
        text, units = quantity_label(first, name)
        plot_boxplot({label: steady(ds, name, start) for label, ds in by_type.items()},
                           label=text, units=units, ax=ax)
    return fig


def plot_control_charts(charts, label="", units="") -> list:
    """Xbar-R charts of the gear types with shared scales (Fig. 17–18).

    Parameters
    ----------
    charts : dict
        ``{gear type: lsbg.stats.XbarRChart}`` from :func:`control_charts`.
    label, units : str
        Quantity and unit for the axes.

    Returns
    -------
    list of matplotlib.figure.Figure
        One figure per gear type, all with the same y-limits.
    """
    xbar_ylim, r_ylim = xbar_r_ylims(*charts.values())
    return [plot_xbar_r(chart, label=label, units=units, title=name,
                              xbar_ylim=xbar_ylim, r_ylim=r_ylim)
            for name, chart in charts.items()]
