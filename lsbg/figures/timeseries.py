"""Time series of runs: both gear types over time, and their steady-state samples (Figs. 8–12).

Built from run datasets (:mod:`lsbg.runs`); the theoretical value (Eq. 12–13)
is drawn where the run carries one.

References
----------
.. [1] The reproduced paper, ``paper/lsbg-paper.txt``, §3, Figs. 8–12.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from lsbg.figures.base import new_figure, type_color
from lsbg.runs import THEORY_ATTRIBUTES, runs_by_type, quantity_label, run_theory

__all__ = ["plot_time_series", "plot_steady_scatter"]


def plot_time_series(runs, names, theory=None, overlay=False, xlim=None) -> Figure:
    """Time series of run variables (Fig. 8, 9–10, 12), one panel per gear type.

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

    Returns
    -------
    matplotlib.figure.Figure
        Panels share both axes.
    """
    names = [names] if isinstance(names, str) else list(names)
    by_type = runs_by_type(runs)
    ncols = 1 if overlay else len(by_type)
    fig, axes = new_figure(1, ncols, sharex=True, sharey=True)
    styles = ["-", "--", ":", "-."]
    for i, (label, ds) in enumerate(by_type.items()):
        ax = axes[0, 0 if overlay else i]
        t = ds["time"].values
        for k, name in enumerate(names):
            text, units = quantity_label(ds, name)
            ax.plot(t, ds[name].values, lw=0.9,
                    ls=styles[i % 4] if overlay else "-",
                    color=type_color(label) if overlay or k == 0 else f"C{k + 1}",
                    label=f"{label}: {text}")
        if theory == "gear_speed":
            ratio = ds.attrs["design_pinion_teeth"] / ds.attrs["design_gear_teeth"]
            ax.plot(t, ds["pinion_speed"].values * ratio, "k--", lw=0.9,
                    label="Eq. 12: pinion speed × z1/z2")
        elif theory == "tangential_force":
            ax.axhline(run_theory(ds, "tangential_force"), color="k", ls="--", lw=0.9,
                       label=f"Eq. 13: {run_theory(ds, 'tangential_force'):.6g} N")
        ax.set_xlabel("time [s]")
        if not overlay:
            ax.set_title(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small", loc="best", framealpha=0.85)
    first = next(iter(by_type.values()))
    text, units = quantity_label(first, names[0])
    axes[0, 0].set_ylabel(f"{text if len(names) == 1 else 'force'} [{units}]")
    if xlim is not None:
        axes[0, 0].set_xlim(xlim)
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
    """
    fig, axes = new_figure(1, 1, width=8.0)
    ax = axes[0, 0]
    by_type = runs_by_type(runs)
    for label, ds in by_type.items():
        t = ds["time"].values
        keep = t - start > 1e-9 * np.median(np.diff(t))
        x = ds[name].values[keep]
        ax.plot(t[keep], x, "o", ms=2.5, color=type_color(label),
                label=f"{label} (std {x.std(ddof=1):.4g})")
    first = next(iter(by_type.values()))
    if name in THEORY_ATTRIBUTES:
        ax.axhline(run_theory(first, name), color="k", ls="--", lw=0.9,
                   label=f"theory {run_theory(first, name):.6g}")
    text, units = quantity_label(first, name)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{text} [{units}]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig
