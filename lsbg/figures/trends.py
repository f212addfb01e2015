"""Figures of the line model against spiral angle, and of the verdict's sensitivity."""

from __future__ import annotations

import numpy as np

from lsbg.figures.base import new_figure, type_color
from lsbg.runs import QUANTITY_LABELS


def _angles(ax, values):
    values = np.unique(values)
    ax.set_xticks(values, [f"{v:g}" for v in values], fontsize="small")
    ax.set_xlabel("mean spiral angle βm [deg]")


def plot_mesh_trends(table):
    """Loaded TCA figures against spiral angle, per gear type.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sweep_fluctuation_table` (one contact model's
        rows suffice; the loaded TCA does not depend on it).

    Returns
    -------
    matplotlib.figure.Figure
        2 x 2: static transmission error peak to peak and its first harmonic,
        mesh stiffness variation, mean mesh stiffness per face width, total
        contact ratio.
    """
    part = table.drop_duplicates(["gear_type", "spiral_angle_deg"])
    fig, axes = new_figure(2, 2, sharex=True)
    panels = ((axes[0, 0], "static_transmission_error_peak_to_peak",
               "static TE, peak to peak [urad]"),
              (axes[0, 1], "mesh_stiffness_variation", "mesh stiffness, peak to peak [% of mean]"),
              (axes[1, 0], "mesh_stiffness_per_face_width", "mean mesh stiffness [N/(mm um)]"),
              (axes[1, 1], "contact_ratio", "total contact ratio [-]"))
    for label, rows in part.groupby("gear_type", sort=False):
        rows = rows.sort_values("spiral_angle_deg")
        for ax, column, _ in panels:
            if column in rows:
                ax.plot(rows["spiral_angle_deg"], rows[column], "o-", ms=4,
                        color=type_color(label), label=label)
        if "static_transmission_error_harmonic_1" in rows:
            axes[0, 0].plot(rows["spiral_angle_deg"], rows["static_transmission_error_harmonic_1"],
                            "s--", ms=3, color=type_color(label), label=f"{label}: 1st harmonic")
    for ax, _, ylabel in panels:
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="x-small")
    for ax in axes[1]:
        _angles(ax, part["spiral_angle_deg"])
    return fig


def plot_fluctuation_trends(table, quantities=("gear_speed", "tangential_force")):
    """Fluctuation against spiral angle: the line model at the full rate, the point
    model as the paper samples it.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sweep_fluctuation_table`.
    quantities : sequence of str

    Returns
    -------
    matplotlib.figure.Figure
        One row per quantity: left the line model's full-rate std with its
        interval, right the point model's 500-sample std (its zig-zag).
    """
    fig, axes = new_figure(len(quantities), 2, sharex=True)
    for r, quantity in enumerate(quantities):
        line, point = axes[r]
        for label, rows in table.groupby("gear_type", sort=False):
            color = type_color(label)
            model = rows[rows["contact_model"] == "line"].sort_values("spiral_angle_deg")
            if not model.empty:
                y = model[f"{quantity}_std"].to_numpy()
                err = np.vstack([y - model[f"{quantity}_std_low"], model[f"{quantity}_std_high"] - y])
                line.errorbar(model["spiral_angle_deg"], y, yerr=err, fmt="o-", ms=4, capsize=3,
                              color=color, label=label)
            model = rows[rows["contact_model"] == "point"].sort_values("spiral_angle_deg")
            if not model.empty:
                point.plot(model["spiral_angle_deg"], model[f"{quantity}_sampled_std"], "o-",
                           ms=4, color=color, label=f"{label}: 500 samples")
                point.plot(model["spiral_angle_deg"], model[f"{quantity}_std"], "s:", ms=3,
                           color=color, label=f"{label}: full rate")
        name = QUANTITY_LABELS.get(quantity, quantity)
        line.set_ylabel(f"std of the {name}")
        line.set_title("line model, full rate", fontsize="medium")
        point.set_title("point model (the paper's)", fontsize="medium")
        for ax in (line, point):
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize="x-small")
    for ax in axes[-1]:
        _angles(ax, table["spiral_angle_deg"])
    return fig


def plot_ratio_trends(ratios):
    """std(SBG)/std(LSBG) with its interval against spiral angle, per quantity.

    Parameters
    ----------
    ratios : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sweep_ratio_table`.

    Returns
    -------
    matplotlib.figure.Figure
        Above 1: the LSBG fluctuates less.
    """
    fig, axes = new_figure(1, 1, width=7.5)
    ax = axes[0, 0]
    quantities = list(dict.fromkeys(ratios["quantity"]))
    for k, quantity in enumerate(quantities):
        part = ratios[ratios["quantity"] == quantity]
        y = part["ratio"].to_numpy()
        err = np.vstack([y - part["ratio_low"], part["ratio_high"] - y])
        ax.errorbar(part["spiral_angle_deg"] + 0.25 * (k - (len(quantities) - 1) / 2), y,
                    yerr=err, fmt="o-", ms=4, capsize=3, color=f"C{k + 2}",
                    label=QUANTITY_LABELS.get(quantity, quantity))
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_ylabel("std(SBG) / std(LSBG) [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    _angles(ax, ratios["spiral_angle_deg"])
    return fig


def plot_sensitivity(table):
    """The ratio SBG/LSBG with its interval in every cell of the sensitivity study.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sensitivity_table`.

    Returns
    -------
    matplotlib.figure.Figure
        One marker per cell and quantity; filled where the ranking holds.
    """
    cells = list(dict.fromkeys(table["cell"]))
    quantities = list(dict.fromkeys(table["quantity"]))
    fig, axes = new_figure(1, 1, width=8.0, height=3.4)
    ax = axes[0, 0]
    width = 0.8 / max(len(quantities), 1)
    for k, quantity in enumerate(quantities):
        part = table[table["quantity"] == quantity].set_index("cell").loc[cells]
        x = np.arange(len(cells)) + (k - (len(quantities) - 1) / 2) * width
        err = np.vstack([part["ratio"] - part["ratio_low"], part["ratio_high"] - part["ratio"]])
        ax.errorbar(x, part["ratio"], yerr=err, fmt="none", ecolor=f"C{k + 2}", capsize=3)
        for xi, row in zip(x, part.itertuples()):
            ax.plot(xi, row.ratio, "o", color=f"C{k + 2}", mfc=f"C{k + 2}" if row.holds else "white",
                    label=QUANTITY_LABELS.get(quantity, quantity) if xi == x[0] else None)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(np.arange(len(cells)), cells, fontsize="small", rotation=15)
    ax.set_ylabel("std(SBG) / std(LSBG) [-]")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize="small")
    return fig
