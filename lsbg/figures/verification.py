"""Figures of the verification report: convergence and engine agreement.

Built from :func:`lsbg.tables.verification.convergence_table` and
:func:`lsbg.tables.verification.engine_agreement`.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from lsbg.design import TRACE_LABELS
from lsbg.figures.base import new_figure, type_color

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
        settings are ringed.
    """
    engines = [e for e in ("pybullet", "scipy", "compiled") if (table["engine"] == e).any()]
    fig, axes = new_figure(len(engines), 3, width=3.6, height=2.9)
    # x is log10 of the setting on a linear axis labelled with the settings: a
    # log axis draws the same for the three values at several times the cost
    columns = (("gear_speed_std_deg_s", "std of gear angular velocity [deg/s]"),
               ("tangential_force_std_N", "std of tangential force [N]"))
    for r, engine in enumerate(engines):
        part = table[table["engine"] == engine]
        xlabel = "time step [s]" if engine == "pybullet" else "relative tolerance rtol [-]"
        for k, (trace, rows) in enumerate(part.groupby("trace", sort=False)):
            rows = rows.sort_values("value")
            label = TRACE_LABELS.get(trace, trace)
            x = np.log10(rows["value"].to_numpy())
            for c, (column, ylabel) in enumerate(columns):
                ax = axes[r, c]
                ax.plot(x, rows[column], "o-", color=type_color(label), ms=4, label=label)
                default = rows["is_default"].to_numpy()
                ax.plot(x[default], rows[column][default], "o", ms=11, mfc="none",
                        color="k", label="default" if k == 0 else None)
                ax.set_ylabel(ylabel)
            ax = axes[r, 2]
            for name, marker in (("gear_speed_std", "o"), ("tangential_force_std", "s")):
                ax.plot(x, rows[f"{name}_rel_diff_percent"], marker + "-",
                        color=type_color(label), ms=4,
                        label=f"{label}: {'speed' if name == 'gear_speed_std' else 'force'}")
            ax.set_ylabel("difference to tightest tolerance run [%]")
        values = np.unique(part["value"].to_numpy())
        for ax in axes[r]:
            ax.set_xticks(np.log10(values), [f"{v:g}" for v in values])
            ax.set_xlim(np.log10(values.min()) - 0.3, np.log10(values.max()) + 0.3)
            ax.set_xlabel(xlabel)
            ax.set_title(engine, fontsize="medium")
            ax.grid(True, alpha=0.3, which="both")
            ax.legend(fontsize="x-small")
    return fig


def plot_engine_agreement(agreement, tolerance=0.03) -> Figure:
    """Ratio of standard deviations of each engine to the reference, with the band.

    Parameters
    ----------
    agreement : pandas.DataFrame
        From :func:`engine_agreement`.
    tolerance : float, default 0.03
        Half-width of the accepted band around 1 [-].

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    short = {"gear_speed": "speed", "tangential_force": "force",
             "tangential_force_outer": "force at d2/2"}
    labels = [f"{r.gear_type} {r.spiral_angle_deg:g}°\n{r.engine}: "
              f"{short.get(r.quantity, r.quantity)}" for r in agreement.itertuples()]
    colors = ["C2" if ok else "C3" for ok in agreement["within_tolerance"]]
    ax.bar(range(len(agreement)), agreement["std_ratio"], color=colors)
    ax.axhspan(1 - tolerance, 1 + tolerance, color="0.85", zorder=0,
               label=f"±{100 * tolerance:g} %")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(range(len(agreement)), labels, fontsize="small")
    values = agreement["std_ratio"].to_numpy()
    span = max(tolerance * 2, float(np.max(np.abs(values - 1))) * 1.3) if values.size else 0.1
    ax.set_ylim(1 - span, 1 + span)
    ax.set_ylabel("std(engine) / std(reference) [-]")
    ax.legend(fontsize="small")
    ax.grid(True, axis="y", alpha=0.3)
    return fig
