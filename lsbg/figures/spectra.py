"""Figures of the full-rate record: spectra and the luck of the paper's sampling."""

from __future__ import annotations

import numpy as np

from lsbg.stats import spectra
from lsbg.figures.base import (axis_label, envelope, figure_legend, new_figure, type_color,
                               wrap_categories)
from lsbg.aggregate.runs import QUANTITY_LABELS, full_rate_series


def plot_spectra(runs, quantity, start=0.2, harmonics=6, title=""):
    """Amplitude spectra of a full-rate quantity, mesh frequency and harmonics marked.

    Parameters
    ----------
    runs : dict
        ``{label: run}``; each run's pinion speed and teeth set its mesh frequency.
    quantity : str
        A key of :data:`lsbg.aggregate.runs.FULL_RATE_OF`.
    start : float
        Start of the steady state [s].
    harmonics : int
        Mesh harmonics to mark [-].
    title : str

    Returns
    -------
    matplotlib.figure.Figure
        Log-log amplitude spectra, one line per run; dotted lines at the mesh
        harmonics, dashed at the line model's mesh natural frequency where a
        run has one, the output sampling's Nyquist frequency shaded beyond;
        the legend above the axes.
    """
    fig, axes = new_figure(1, 1, width=8.0, height=3.6)
    ax = axes[0, 0]
    mesh = None
    for k, (label, ds) in enumerate(runs.items()):
        rate = float(ds.attrs["solver_full_rate_hz"])
        frequency, amplitude = spectra.amplitude_spectrum(full_rate_series(ds, quantity, start),
                                                          rate)
        style = "-" if k % 2 == 0 else "--"
        ax.loglog(*envelope(frequency[1:], amplitude[1:], log=True), style, lw=0.8,
                  color=type_color(label.split()[0]), label=label)
        mesh = spectra.mesh_frequency(float(ds.attrs["solver_pinion_speed_deg_s"]),
                                      int(ds.attrs["design_pinion_teeth"]))
        if "mesh_natural_frequency_hz" in ds.attrs:
            natural = float(ds.attrs["mesh_natural_frequency_hz"])
            ax.axvline(natural, color=type_color(label.split()[0]), ls="--", lw=0.8,
                       label=f"{label}: natural frequency of the mesh mode, {natural:.4g} Hz")
    if mesh is not None:
        for h in range(1, harmonics + 1):
            ax.axvline(h * mesh, color="0.4", ls=":", lw=0.8,
                       label=f"mesh frequency {mesh:.4g} Hz and harmonics" if h == 1 else None)
    nyquist = 0.5 * float(next(iter(runs.values())).attrs["solver_samples"]) / float(
        next(iter(runs.values())).attrs["solver_duration_s"])
    ax.axvspan(nyquist, ax.get_xlim()[1], color="0.92", zorder=0,
               label=f"above the output sampling's Nyquist frequency ({nyquist:g} Hz)")
    units = next(iter(runs.values()))[quantity].attrs.get("units", "")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(axis_label(f"amplitude of the {QUANTITY_LABELS.get(quantity, quantity)}", units,
                             wrap=48))
    if title:
        ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3, which="both")
    figure_legend(fig, ncols=2)
    return fig


def plot_sampling_luck(table):
    """The paper's 500-sample std at every sampling phase, relative to the full rate.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sampling_luck_table`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per quantity (its name the title); per run a bar from the
        least to the largest std over the sampling phases and a dot at the
        run's own sampling, all divided by the full-rate std (the line at 1);
        the legend above the panels.
    """
    quantities = list(dict.fromkeys(table["quantity"]))
    fig, axes = new_figure(1, len(quantities), width=4.6)
    for ax, quantity in zip(axes[0], quantities):
        part = table[table["quantity"] == quantity].reset_index(drop=True)
        for i, row in part.iterrows():
            color = type_color(row["run"].split()[0])
            scale = row["full_rate_std"]
            ax.plot([i, i], [row["phase_std_min"] / scale, row["phase_std_max"] / scale],
                    color=color, lw=8, alpha=0.45, solid_capstyle="butt")
            ax.plot(i, row["sampled_std"] / scale, "o", color=color, ms=6)
        # grey legend entries: the colours are the gear types', named on the x axis
        ax.plot([], [], color="0.5", lw=8, alpha=0.45,
                label="500-sample std over every sampling phase")
        ax.plot([], [], "o", color="0.3", ms=6, label="the run's own 500-sample std")
        ax.axhline(1.0, color="k", lw=0.8, label="full-rate std")
        # "SBG point" -> "SBG\npoint model": horizontal, two short lines, no overlap
        names = [run.replace(" point", " point model").replace(" line", " line model")
                 for run in part["run"]]
        ax.set_xticks(np.arange(len(part)), wrap_categories(names, width=12), fontsize="small")
        ax.set_xlim(-0.6, len(part) - 0.4)
        ax.set_xlabel("gear type and contact model")
        ax.set_ylabel("500-sample std / full-rate std [-]")
        ax.set_title(QUANTITY_LABELS.get(quantity, quantity), fontsize="medium")
        ax.grid(True, axis="y", alpha=0.3)
    figure_legend(fig, axes[0])
    return fig


def plot_full_rate(runs, quantity, start=0.2, span=0.02):
    """A short stretch of the full-rate record with the output samples on it.

    Parameters
    ----------
    runs : dict
        ``{label: run}``.
    quantity : str
        A key of :data:`lsbg.aggregate.runs.FULL_RATE_OF` that is also an output variable.
    start : float
        Start of the stretch [s].
    span : float
        Length of the stretch [s].

    Returns
    -------
    matplotlib.figure.Figure
        One panel per run (its label the title), the quantity and its unit
        on every y axis, the legend above the panels.
    """
    fig, axes = new_figure(len(runs), 1, width=8.0, height=2.2, sharex=True)
    for ax, (label, ds) in zip(axes[:, 0], runs.items()):
        t_full = ds["time_full"].values
        keep = (t_full >= start) & (t_full <= start + span)
        rate = float(ds.attrs.get("solver_full_rate_hz", 1.0 / np.median(np.diff(t_full))))
        ax.plot(t_full[keep], full_rate_series(ds, quantity, 0.0)[keep], lw=0.7,
                color=type_color(label.split()[0]),
                label=f"{label}: full rate ({rate:g} samples/s)")
        t = ds["time"].values
        mark = (t >= start) & (t <= start + span)
        output = (t.size - 1) / float(t[-1] - t[0]) if t.size > 1 else 0.0
        ax.plot(t[mark], ds[quantity].values[mark], "ko", ms=3,
                label=f"output samples ({output:g} samples/s)")
        ax.set_ylabel(axis_label(QUANTITY_LABELS.get(quantity, quantity),
                                 ds[quantity].attrs.get("units", ""), wrap=24))
        ax.set_title(label, fontsize="medium")
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    figure_legend(fig)
    return fig
