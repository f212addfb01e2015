"""Figures of the dynamic-factor curve (:func:`lsbg.experiments.speed.speed_curve`)."""

from __future__ import annotations

import numpy as np

from lsbg.gear.design import TRACE_LABELS
from lsbg.figures.base import figure_legend, new_figure, sparse_log_ticks, type_color, wrap_label

#: Curve variables plotted against pinion speed, with their axis labels.
CURVE_PANELS = (
    ("dte_rms", "RMS dynamic transmission error [µrad]"),
    ("dynamic_factor", "dynamic factor [-]"),
    ("gear_speed_fluctuation", "gear-speed fluctuation [% of mean]"),
)
#: Characters per line of the y labels: a label longer than its panel (2.4 inch)
#: would run along the next one.
LABEL_WRAP = 26
#: Line style of the resonance marker of each order (f_mesh = f_n / order).
ORDER_STYLES = {1: "--", 2: ":", 3: "-."}


def _mark_resonances(ax, curve, label=True):
    """Vertical lines at the resonance speeds inside the curve's speed range: orders 1-3
    in their own styles, the higher ones thin and dotted (labelled once per trace)."""
    speeds = curve["pinion_speed"].values
    low, high = speeds.min(), speeds.max()
    for trace in curve["trace"].values:
        name = TRACE_LABELS.get(str(trace), trace)
        higher = True
        for order in curve["order"].values:
            speed = float(curve["resonance_speed"].sel(trace=trace, order=order))
            k = int(order)
            if not low <= speed <= high and k > 1:
                continue
            if k in ORDER_STYLES:
                text = f"{name}: f_mesh = f_n" if k == 1 else f"{name}: f_mesh = f_n/{k}"
                ax.axvline(speed, color=type_color(str(trace)), lw=0.8, ls=ORDER_STYLES[k],
                           label=text if label else None)
            else:
                ax.axvline(speed, color=type_color(str(trace)), lw=0.5, ls=(0, (1, 3)),
                           label=(f"{name}: f_mesh = f_n/k, k > 3" if label and higher
                                  else None))
                higher = False


def plot_speed_curve(curve):
    """RMS DTE, dynamic factor and gear-speed fluctuation against pinion speed.

    Parameters
    ----------
    curve : xarray.Dataset
        From :func:`lsbg.experiments.speed.speed_curve`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per quantity, both traces, log speed axis; vertical lines
        where the mesh frequency meets the natural frequency (dashed) and its
        half (dotted) and third (dash-dotted), per trace; the top axis in
        mesh frequency over the natural frequency of the first trace; the
        legend above the panels. Resonance speeds (k f_mesh = f_n) are drawn for the
        curve's orders within its speed range (order 1 always): 1-3 in their own
        styles, higher orders thin and dotted.
    """
    fig, axes = new_figure(len(CURVE_PANELS), 1, width=7.0, height=2.4, sharex=True)
    speeds = curve["pinion_speed"].values
    for row, (name, label) in enumerate(CURVE_PANELS):
        ax = axes[row, 0]
        for trace in curve["trace"].values:
            ax.plot(speeds, curve[name].sel(trace=trace).values, "o-", ms=2.5, lw=1.0,
                    color=type_color(str(trace)), label=TRACE_LABELS.get(str(trace), trace))
        _mark_resonances(ax, curve, label=row == 0)
        ax.set_ylabel(wrap_label(label, LABEL_WRAP))
        ax.set_xscale("log")
        if name != "dynamic_factor":
            ax.set_yscale("log")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
    figure_legend(fig, [axes[0, 0]], ncols=4, fontsize="x-small")
    axes[-1, 0].set_xlabel("pinion speed [deg/s]")
    natural = float(curve["natural_frequency"].values[0])
    teeth = int(curve.attrs["design_pinion_teeth"])
    top = axes[0, 0].secondary_xaxis(
        "top", functions=(lambda s: s / 360.0 * teeth / natural,
                          lambda r: r * natural * 360.0 / teeth))
    sparse_log_ticks(axes[-1, 0].xaxis)   # the panels share it
    top.set_xlabel(f"mesh frequency / f_n [-] ({TRACE_LABELS.get(str(curve['trace'].values[0]))}, "
                   f"f_n = {natural:.4g} Hz)")
    return fig


def plot_campbell(curve, floor_db=-20.0):
    """Campbell-style map: transmission-error spectrum over pinion speed, per trace.

    Parameters
    ----------
    curve : xarray.Dataset
        From :func:`lsbg.experiments.speed.speed_curve`.
    floor_db : float
        Lowest level shown [dB re 1 µrad].

    Returns
    -------
    matplotlib.figure.Figure
        Colour: the peak amplitude in each frequency bin, 20 log10(A / 1 µrad);
        white lines: the first three mesh harmonics (k f_mesh); dashed: the
        natural frequency f_n.
    """
    traces = [str(t) for t in curve["trace"].values]
    fig, axes = new_figure(1, len(traces), width=4.2, height=3.4, sharey=True)
    speeds = curve["pinion_speed"].values
    frequency = curve["frequency"].values
    mesh = curve["mesh_frequency"].values
    for col, trace in enumerate(traces):
        ax = axes[0, col]
        level = 20 * np.log10(np.maximum(curve["dte_spectrum"].sel(trace=trace).values, 1e-12))
        image = ax.pcolormesh(speeds, frequency, level.T, shading="nearest", cmap="viridis",
                              vmin=floor_db, vmax=max(floor_db + 10, float(np.nanmax(level))))
        for k in (1, 2, 3):
            ax.plot(speeds, k * mesh, color="white", lw=0.7, alpha=0.8)
        natural = float(curve["natural_frequency"].sel(trace=trace))
        ax.axhline(natural, color="red", ls="--", lw=0.8)
        ax.set_xscale("log")
        sparse_log_ticks(ax.xaxis)
        ax.set_ylim(frequency[0], frequency[-1])
        ax.set_title(f"{TRACE_LABELS.get(trace, trace)}: f_n = {natural:.4g} Hz", fontsize=9)
        ax.set_xlabel("pinion speed [deg/s]")
        if col == 0:
            ax.set_ylabel("frequency [Hz]")
    fig.colorbar(image, ax=axes[0, -1], label="transmission error [dB re 1 µrad]")
    return fig
