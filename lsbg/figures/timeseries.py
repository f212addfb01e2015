"""Time series of runs: both gear types over time, and their steady-state samples (Figs. 8–12).

Built from run datasets (:mod:`lsbg.aggregate.runs`); the theoretical value (Eq. 12–13)
is drawn where the run carries one.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3, Figs. 8–12.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from lsbg.figures.base import axis_label, display_unit, figure_legend, new_figure, type_color
from lsbg.aggregate.runs import THEORY_ATTRIBUTES, runs_by_type, quantity_label, run_theory

__all__ = ["plot_time_series", "plot_steady_scatter"]


def plot_time_series(runs, names, theory=None, overlay=False, xlim=None, separate=True) -> Figure:
    """Time series of run variables (Fig. 8, 9–10, 12), one panel per gear type.

    Several variables (e.g. the tangential force at the points of action and
    at d2/2) follow each other closely and would hide one another on one
    axes; by default each gets its own row of panels, with shared scales.

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
        ``{gear type: run}`` or runs.
    names : str or sequence of str
        Run variables to draw (same units).
    theory : {'gear_speed', 'tangential_force'}, optional
        Add the rigid-pair prediction: Eq. 12 applied to the simulated pinion
        speed (the paper's Fig. 10), or the constant of Eq. 13.
    overlay : bool, default False
        Draw every run on one axes instead of one panel per run.
    xlim : (float, float), optional
        Time limits [s].
    separate : bool, default True
        With several ``names``: one row of panels per variable. False draws
        them on the same axes, each later one thinner and translucent over
        the first so that every one stays visible.

    Returns
    -------
    matplotlib.figure.Figure
        Panels share both axes; each row's y label names its variable and
        unit, each column's title the gear type; one legend above the panels.
    """
    names = [names] if isinstance(names, str) else list(names)
    by_type = runs_by_type(runs)
    ncols = 1 if overlay else len(by_type)
    rows = [[name] for name in names] if separate and len(names) > 1 else [names]
    fig, axes = new_figure(len(rows), ncols, height=3.2 if len(rows) == 1 else 2.6,
                           sharex=True, sharey=True)
    styles = ["-", "--", ":", "-."]
    for r, row in enumerate(rows):
        for i, (label, ds) in enumerate(by_type.items()):
            ax = axes[r, 0 if overlay else i]
            t = ds["time"].values
            for k, name in enumerate(row):
                text, units = quantity_label(ds, name)
                # later variables of a shared axes: thinner, translucent and on top,
                # so the first shows through them
                ax.plot(t, ds[name].values, lw=0.9 if k == 0 else 0.6,
                        alpha=1.0 if k == 0 else 0.75, zorder=2 + k,
                        ls=styles[i % 4] if overlay else "-",
                        color=type_color(label) if overlay or k == 0 else f"C{k + 1}",
                        label=f"{label}: {text}" if len(row) > 1 or overlay else label)
            if theory == "gear_speed":
                ratio = ds.attrs["design_pinion_teeth"] / ds.attrs["design_gear_teeth"]
                ax.plot(t, ds["pinion_speed"].values * ratio, "k--", lw=0.9, zorder=5,
                        label="Eq. 12: pinion speed × z1/z2")
            elif theory == "tangential_force":
                ax.axhline(run_theory(ds, "tangential_force"), color="k", ls="--", lw=0.9,
                           zorder=5,
                           label=f"Eq. 13: {run_theory(ds, 'tangential_force'):.6g} N")
            if r == len(rows) - 1:
                ax.set_xlabel("time [s]")
            if r == 0 and not overlay:
                ax.set_title(label)
            ax.grid(True, alpha=0.3)
        first = next(iter(by_type.values()))
        text, units = quantity_label(first, row[0])
        if len(row) > 1:
            # variables of one unit on one axes: name what they share, or all of them
            text = ("tangential force" if all("force" in n for n in row)
                    else " / ".join(quantity_label(first, n)[0] for n in row))
        axes[r, 0].set_ylabel(axis_label(text, units, wrap=36))
    if xlim is not None:
        axes[0, 0].set_xlim(xlim)
    figure_legend(fig, first=list(by_type))
    return fig


def plot_steady_scatter(runs, name, start=0.2) -> Figure:
    """Scatter of the steady-state samples of all runs on one axes (Fig. 11).

    Parameters
    ----------
    runs : dict or sequence of xarray.Dataset
    name : str
        Run variable, e.g. ``'gear_speed'``.
    start : float, default 0.2
        End of the transient [s].

    Returns
    -------
    matplotlib.figure.Figure
        The legend (with each type's std) above the axes.
    """
    fig, axes = new_figure(1, 1, width=8.0)
    ax = axes[0, 0]
    by_type = runs_by_type(runs)
    first = next(iter(by_type.values()))
    text, units = quantity_label(first, name)
    for label, ds in by_type.items():
        t = ds["time"].values
        keep = t - start > 1e-9 * np.median(np.diff(t))
        x = ds[name].values[keep]
        ax.plot(t[keep], x, "o", ms=2.5, color=type_color(label),
                label=f"{label} (std {x.std(ddof=1):.4g} {display_unit(units)})")
    if name in THEORY_ATTRIBUTES:
        ax.axhline(run_theory(first, name), color="k", ls="--", lw=0.9,
                   label=f"theory {run_theory(first, name):.6g} {display_unit(units)}")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(axis_label(text, units))
    ax.grid(True, alpha=0.3)
    figure_legend(fig)
    return fig
