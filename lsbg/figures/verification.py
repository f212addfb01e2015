"""Figures of the verification report: convergence and engine agreement.

Built from :func:`lsbg.tables.verification.convergence_table` and
:func:`lsbg.tables.verification.engine_agreement`.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from lsbg.gear.design import TRACE_LABELS
from lsbg.figures.base import figure_legend, new_figure, type_color, type_entries, wrap_label
from lsbg.aggregate.runs import QUANTITY_LABELS

__all__ = ["plot_convergence", "plot_engine_agreement"]


def plot_convergence(table) -> Figure:
    """Standard deviations and their difference to the tightest tolerance run.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`convergence_table`.

    Returns
    -------
    matplotlib.figure.Figure
        Rows: pybullet against its time step, scipy and compiled against
        their rtol (log axes). Columns: std of gear speed, std of tangential
        force, relative difference to the tightest tolerance run. Default
        settings are ringed; one legend above the panels.
    """
    engines = [e for e in ("pybullet", "scipy", "compiled") if (table["engine"] == e).any()]
    fig, axes = new_figure(len(engines), 3, width=3.6, height=2.9)
    # x is log10 of the setting on a linear axis labelled with the settings: a
    # log axis draws the same for the three values at several times the cost
    columns = (("gear_speed_std_deg_s", "std of gear angular velocity [deg/s]"),
               ("tangential_force_std_N", "std of tangential force [N]"))
    difference = wrap_label("difference of the std to the tightest-tolerance run [%]", 30)
    for r, engine in enumerate(engines):
        part = table[table["engine"] == engine]
        xlabel = "time step [s]" if engine == "pybullet" else "relative tolerance rtol [-]"
        for trace, rows in part.groupby("trace", sort=False):
            rows = rows.sort_values("value")
            label = TRACE_LABELS.get(trace, trace)
            x = np.log10(rows["value"].to_numpy())
            for c, (column, ylabel) in enumerate(columns):
                ax = axes[r, c]
                ax.plot(x, rows[column], "o-", color=type_color(label), ms=4)
                default = rows["is_default"].to_numpy()
                ax.plot(x[default], rows[column][default], "o", ms=11, mfc="none", color="k")
                ax.set_ylabel(ylabel)
            ax = axes[r, 2]
            for name, marker in (("gear_speed_std", "o"), ("tangential_force_std", "s")):
                ax.plot(x, rows[f"{name}_rel_diff_percent"], marker + "-",
                        color=type_color(label), ms=4)
            ax.set_ylabel(difference)
        values = np.unique(part["value"].to_numpy())
        for ax in axes[r]:
            ax.set_xticks(np.log10(values), [f"{v:g}" for v in values])
            ax.set_xlim(np.log10(values.min()) - 0.3, np.log10(values.max()) + 0.3)
            ax.set_xlabel(xlabel)
            ax.set_title(f"{engine} engine", fontsize="medium")
            ax.grid(True, alpha=0.3, which="both")
    traces = list(dict.fromkeys(table["trace"]))
    figure_legend(fig, handles=type_entries(traces, [
        ({"marker": "o", "ms": 11, "mfc": "none", "ls": "none", "color": "k"}, "default setting"),
        ({"marker": "o", "ms": 4}, "right: gear speed"),
        ({"marker": "s", "ms": 4}, "right: tangential force")]), ncols=5)
    return fig


#: Short names of the quantities on the engine-agreement figure's categories.
SHORT_QUANTITIES = {"gear_speed": "gear speed", "tangential_force": "tangential force",
                    "tangential_force_outer": "force at d2/2"}


def plot_engine_agreement(agreement, tolerance=0.03) -> Figure:
    """Ratio of standard deviations of each engine to the reference, with the band.

    The comparisons are categories on the y axis, one row each, so their
    labels (contact model, gear type and spiral angle, engine against
    reference, quantity) read horizontally and never overlap, however many.

    Parameters
    ----------
    agreement : pandas.DataFrame
        From :func:`engine_agreement` (with a ``contact_model`` column where
        the report stacks both models).
    tolerance : float, default 0.03
        Half-width of the accepted band around 1 [-].

    Returns
    -------
    matplotlib.figure.Figure
        Per comparison a bar from 1 to the ratio and a dot at the ratio
        (green inside the band, red outside), the band shaded; the legend
        above the axes.
    """
    rows = len(agreement)
    fig, axes = new_figure(1, 1, width=7.5, height=max(2.0, 0.3 * rows + 0.9))
    ax = axes[0, 0]

    def describe(r):
        model = getattr(r, "contact_model", None)
        head = f"{model} model, " if isinstance(model, str) and model else ""
        reference = getattr(r, "reference", None)
        versus = f" vs {reference}" if isinstance(reference, str) and reference else ""
        return (f"{head}{r.gear_type} {r.spiral_angle_deg:g}°, {r.engine}{versus}: "
                f"{SHORT_QUANTITIES.get(r.quantity, QUANTITY_LABELS.get(r.quantity, r.quantity))}")

    labels = [describe(r) for r in agreement.itertuples()]
    values = agreement["std_ratio"].to_numpy(dtype=float)
    inside = agreement["within_tolerance"].to_numpy(dtype=bool)
    colors = np.where(inside, "C2", "C3")
    y = np.arange(rows)
    ax.axvspan(1 - tolerance, 1 + tolerance, color="0.88", zorder=0,
               label=f"accepted band: ±{100 * tolerance:g} %")
    ax.axvline(1.0, color="k", lw=0.8)
    ax.barh(y, values - 1.0, left=1.0, height=0.6, color=colors, alpha=0.6)
    # a dot shows a ratio of 1.00001 too, whose bar is thinner than a pixel
    ax.scatter(values, y, c=colors, s=18, zorder=3)
    ax.scatter([], [], c="C2", s=18, label="ratio within the band")
    ax.scatter([], [], c="C3", s=18, label="ratio outside the band")
    ax.set_yticks(y, labels, fontsize="small")
    ax.set_ylim(rows - 0.5, -0.5)
    span = max(tolerance * 2, float(np.max(np.abs(values - 1))) * 1.3) if values.size else 0.1
    ax.set_xlim(1 - span, 1 + span)
    ax.set_xlabel("std(engine) / std(reference engine) [-]")
    ax.set_ylabel("comparison")
    ax.grid(True, axis="x", alpha=0.3)
    figure_legend(fig)
    return fig
