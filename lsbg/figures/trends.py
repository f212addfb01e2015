"""Figures of the line model against spiral angle, and of the verdict's sensitivity."""

from __future__ import annotations

import numpy as np

from lsbg.figures.base import (QUANTITY_UNITS, axis_label, figure_legend, new_figure, type_color,
                               type_entries, wrap_categories)
from lsbg.aggregate.runs import QUANTITY_LABELS, TYPE_ORDER
from lsbg.gear.design import TRACE_NAMES


def _angles(ax, values):
    values = np.unique(values)
    ax.set_xticks(values, [f"{v:g}" for v in values], fontsize="small")
    ax.set_xlabel("mean spiral angle βm [deg]")


def _by_type(table):
    """The table's rows per gear type, SBG first (the paper's order)."""
    groups = dict(list(table.groupby("gear_type", sort=False)))
    order = [t for t in TYPE_ORDER if t in groups] + [t for t in groups if t not in TYPE_ORDER]
    return [(label, groups[label]) for label in order]


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
        2 x 2, each panel titled: static transmission error peak to peak
        and its first harmonic [µrad], mesh stiffness variation [% of mean],
        mean mesh stiffness per face width [N/(mm·µm)], total contact ratio
        [-]; the legend above the panels.
    """
    part = table.drop_duplicates(["gear_type", "spiral_angle_deg"])
    fig, axes = new_figure(2, 2, sharex=True)
    panels = ((axes[0, 0], "static_transmission_error_peak_to_peak",
               axis_label("static transmission error", "urad")),
              (axes[0, 1], "mesh_stiffness_variation",
               axis_label("mesh stiffness, peak to peak", "% of mean")),
              (axes[1, 0], "mesh_stiffness_per_face_width",
               axis_label("mean mesh stiffness per face width", "N/(mm um)", wrap=36)),
              (axes[1, 1], "contact_ratio", axis_label("total contact ratio", "1")))
    types = []
    for label, rows in _by_type(part):
        types.append(label)
        rows = rows.sort_values("spiral_angle_deg")
        for ax, column, _ in panels:
            if column in rows:
                ax.plot(rows["spiral_angle_deg"], rows[column], "o-", ms=4,
                        color=type_color(label))
        if "static_transmission_error_harmonic_1" in rows:
            axes[0, 0].plot(rows["spiral_angle_deg"], rows["static_transmission_error_harmonic_1"],
                            "s--", ms=3, color=type_color(label))
    for ax, _, ylabel in panels:
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
    axes[0, 0].set_title("loaded TCA: static transmission error", fontsize="medium")
    axes[0, 1].set_title("loaded TCA: mesh stiffness variation", fontsize="medium")
    axes[1, 0].set_title("loaded TCA: mean mesh stiffness", fontsize="medium")
    axes[1, 1].set_title("design: total contact ratio", fontsize="medium")
    figure_legend(fig, handles=type_entries(
        types, [({"marker": "o", "ls": "-", "ms": 4}, "transmission error: peak to peak"),
                ({"marker": "s", "ls": "--", "ms": 3},
                 "transmission error: amplitude of the 1st mesh harmonic")]),
        ncols=2)
    for ax in axes[1]:
        _angles(ax, part["spiral_angle_deg"])
    return fig


def plot_fluctuation_trends(table, quantities=("gear_speed", "tangential_force"), units=None):
    """Fluctuation against spiral angle: the line model at the full rate, the point
    model as the paper samples it.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.line_model.sweep_fluctuation_table`.
    quantities : sequence of str
    units : dict, optional
        ``{quantity: unit}`` of the table's values (default
        :data:`lsbg.figures.base.QUANTITY_UNITS`, the units of the runs).

    Returns
    -------
    matplotlib.figure.Figure
        One row per quantity: left the line model's full-rate std with its
        95 % interval, right the point model's 500-sample std (its zig-zag)
        and its full-rate std; every panel titled with its model and
        sampling, every y axis with the quantity and its unit, the legend
        above the panels.
    """
    units = {**QUANTITY_UNITS, **(units or {})}
    fig, axes = new_figure(len(quantities), 2, sharex=True)
    types = []
    for r, quantity in enumerate(quantities):
        line, point = axes[r]
        for label, rows in _by_type(table):
            if label not in types:
                types.append(label)
            color = type_color(label)
            model = rows[rows["contact_model"] == "line"].sort_values("spiral_angle_deg")
            if not model.empty:
                y = model[f"{quantity}_std"].to_numpy()
                err = np.vstack([y - model[f"{quantity}_std_low"], model[f"{quantity}_std_high"] - y])
                line.errorbar(model["spiral_angle_deg"], y, yerr=err, fmt="s-", ms=3.5, capsize=3,
                              color=color)
            model = rows[rows["contact_model"] == "point"].sort_values("spiral_angle_deg")
            if not model.empty:
                point.plot(model["spiral_angle_deg"], model[f"{quantity}_sampled_std"], "o-",
                           ms=4, color=color)
                point.plot(model["spiral_angle_deg"], model[f"{quantity}_std"], "s:", ms=3.5,
                           color=color)
        ylabel = axis_label(f"std of the {QUANTITY_LABELS.get(quantity, quantity)}",
                            units.get(quantity, ""), wrap=44)
        line.set_title("line model: full-rate std, 95 % interval", fontsize="medium")
        point.set_title("point model (paper's): 500 samples/s, full rate", fontsize="medium")
        for ax in (line, point):
            ax.set_ylabel(ylabel)
            ax.grid(True, alpha=0.3)
    figure_legend(fig, handles=type_entries(
        types, [({"marker": "s", "ls": "-", "ms": 3.5}, "full-rate std (left: 95 % interval)"),
                ({"marker": "o", "ls": "-", "ms": 4}, "std of the 500 output samples per second"),
                ({"marker": "s", "ls": ":", "ms": 3.5}, "full-rate std (point model)")]),
        ncols=3)
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
        Above 1: the LSBG fluctuates less; a colour per quantity, a line style per SBG
        (its name, the ``sbg`` column, in the legend), the legend above the axes.
    """
    sbgs = list(dict.fromkeys(ratios["sbg"])) if "sbg" in ratios else [None]
    fig, axes = new_figure(1, 1, width=7.5 if len(sbgs) == 1 else 9.5)
    ax = axes[0, 0]
    quantities = list(dict.fromkeys(ratios["quantity"]))
    lines = [(j, sbg, k, quantity) for j, sbg in enumerate(sbgs)
             for k, quantity in enumerate(quantities)]
    for n, (j, sbg, k, quantity) in enumerate(lines):
        part = ratios[(ratios["quantity"] == quantity)
                      & ((ratios["sbg"] == sbg) if sbg is not None else True)]
        y = part["ratio"].to_numpy()
        err = np.vstack([y - part["ratio_low"], part["ratio_high"] - y])
        label = QUANTITY_LABELS.get(quantity, quantity)
        ax.errorbar(part["spiral_angle_deg"] + 0.25 * (n - (len(lines) - 1) / 2), y,
                    yerr=err, fmt=("o-", "s--", "^:")[j % 3], ms=4, capsize=3, color=f"C{k + 3}",
                    label=label if sbg is None else f"{label}, {sbg}")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_ylabel("std(SBG) / std(LSBG) [-]")
    ax.grid(True, alpha=0.3)
    figure_legend(fig, ncols=None if len(sbgs) == 1 else 2)
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
        One marker per cell and quantity; filled where the ranking holds;
        the legend above the axes.
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
    # horizontal and wrapped: rotated labels of unequal length run into each other
    # about 100 characters of small print fit across the axes with room between
    ax.set_xticks(np.arange(len(cells)),
                  wrap_categories(cells, width=max(8, 100 // max(len(cells), 1))),
                  fontsize="small")
    ax.set_xlabel("cell of the sensitivity study")
    ax.set_ylabel("std(SBG) / std(LSBG) [-]")
    ax.grid(True, axis="y", alpha=0.3)
    ax.plot([], [], "o", color="0.35", label="ranking holds (interval excludes 1)")
    ax.plot([], [], "o", color="0.35", mfc="white", label="ranking does not hold")
    figure_legend(fig, ncols=2)
    return fig


def plot_rating_against_angle(table):
    """ISO 10300's contact and root stresses of both types against spiral angle.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`lsbg.tables.rating.read_rating_sweep` (MPa).

    Returns
    -------
    matplotlib.figure.Figure
        Left: the contact stress sigma_H; right: the root stress sigma_F of
        the pinion (solid) and the gear (dashed); one colour per type.
    """
    fig, axes = new_figure(1, 2, width=10)
    for gear_type, part in _by_type(table.rename(columns={"spiral_angle": "spiral_angle_deg"})):
        x = part["spiral_angle_deg"]
        axes[0, 0].plot(x, part["contact_stress"], "o-", ms=4, color=type_color(gear_type),
                        label=gear_type)
        axes[0, 1].plot(x, part["root_stress_pinion"], "o-", ms=4, color=type_color(gear_type))
        axes[0, 1].plot(x, part["root_stress_gear"], "s--", ms=4, color=type_color(gear_type))
    axes[0, 0].set_ylabel("contact stress σ_H [MPa]")
    axes[0, 1].set_ylabel("root stress σ_F [MPa] (pinion —, gear --)")
    for ax in axes[0]:
        ax.grid(True, alpha=0.3)
        _angles(ax, table["spiral_angle"])
    figure_legend(fig)
    return fig


def plot_parameter_sweep(table, along, variables, units, by=None, labels=None):
    """The key figures of a parameter sweep against its first swept key.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`lsbg.aggregate.sweep_dataset.sweep_long` (one spiral angle).
    along : str
        The swept key on the x axis (``contact.dynamic_friction``).
    variables : sequence of str
        One panel each.
    units : dict
        ``{column: unit}`` of ``along`` and the variables.
    by : str, optional
        A second swept key: one line per value (a product sweep).
    labels : dict, optional
        ``{column: words}`` of the axes (the datasets' ``long_name``); default: the
        column's name. Labels are wrapped to the panel's width, none is cut.

    Returns
    -------
    matplotlib.figure.Figure
        One colour per gear type; the line style tells the values of ``by``.
    """
    labels = labels or {}
    fig, axes = new_figure(1, len(variables), width=4.4)
    # characters a label's line holds across one panel (about 9 a inch at this size)
    wrap = int(9 * fig.get_figwidth() / len(variables))
    styles = ("o-", "s--", "^:", "d-.", "v-")
    groups = [(None, table)] if by is None else list(table.groupby(by, sort=True))
    for k, (value, part) in enumerate(groups):
        for gear_type, rows in _by_type(part):
            rows = rows.sort_values(along)
            label = gear_type if by is None else f"{gear_type}, {labels.get(by, by)} = {value:g}"
            for ax, variable in zip(axes[0], variables):
                ax.plot(rows[along], rows[variable], styles[k % len(styles)], ms=4,
                        color=type_color(gear_type), label=label)
    for ax, variable in zip(axes[0], variables):
        ax.set_xlabel(axis_label(labels.get(along, along), units.get(along, ""), wrap=wrap))
        ax.set_ylabel(axis_label(labels.get(variable, variable.replace("_", " ")),
                                 units.get(variable, ""), wrap=wrap))
        ax.grid(True, alpha=0.3)
    figure_legend(fig)
    return fig


def plot_cutter_sweep(table, figures):
    """The cutter-radius sweep: each figure of the SBGs against the cutter radius, the LSBG's
    beside them.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`lsbg.tables.cutter.cutter_table`.
    figures : dict
        ``{column: (unit, words)}``, one panel each (:data:`lsbg.tables.cutter.FIGURES`).

    Returns
    -------
    matplotlib.figure.Figure
        The SBGs as points joined by a line (the FE stresses where computed), the
        design's cutter ringed; the LSBG as a horizontal line; the curvature-matched
        cutter's radius as a vertical dotted line.
    """
    fig, axes = new_figure(1, len(figures), width=3.2)
    wrap = int(9 * fig.get_figwidth() / len(figures))
    sbg = table[table["type"] == "SBG"].sort_values("cutter_radius_mm")
    lsbg = table[table["type"] == "LSBG"]
    roles = sbg["roles"].str.split()
    matched = sbg[roles.apply(lambda r: "matched" in r)]["cutter_radius_mm"]
    design = sbg[roles.apply(lambda r: "design" in r)]
    # (the SBG by its construction where the table names its trace)
    name = TRACE_NAMES.get(sbg["trace"].iloc[0], "SBG") if "trace" in sbg and len(sbg) else "SBG"
    for ax, (column, (unit, words)) in zip(axes[0], figures.items()):
        rows = sbg[sbg[column].notna()]
        ax.plot(rows["cutter_radius_mm"], rows[column], "o-", ms=4, color=type_color(name),
                label=name)
        ax.plot(design["cutter_radius_mm"], design[column], "o", ms=9, mfc="none",
                color=type_color(name), label=f"{name}: the design's cutter")
        for value in lsbg[column].dropna():
            ax.axhline(value, color=type_color("LSBG"), ls="--", label="LSBG")
        for radius in matched:
            ax.axvline(radius, color="0.4", ls=":", label="curvature-matched cutter")
        ax.set_xlabel("cutter radius r_c [mm]")
        ax.set_ylabel(axis_label(words, unit, wrap=wrap))
        ax.grid(True, alpha=0.3)
    figure_legend(fig, ncols=4)
    return fig
