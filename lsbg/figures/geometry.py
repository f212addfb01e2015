"""Figures of the geometry: the pairs, the spiral and pressure angles along the face, conjugacy.

Built from geometry directories (:mod:`lsbg.files`) and the tables of
:mod:`lsbg.tables.verification`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from lsbg.design import TRACE_LABELS
from lsbg.figures.base import new_figure, type_color
from lsbg.files import read_record
from lsbg.results import as_path_list
from lsbg.runs import TYPE_ORDER, records_by_type

__all__ = [
    "plot_pair_pictures", "plot_spiral_angle_along_face", "plot_pressure_angles",
    "plot_conjugacy"
]


# ---------------------------------------------------------------- figures
def plot_pair_pictures(geometry_dirs) -> Figure:
    """The pictures of the assembled pairs (``pair.png``) side by side, SBG first.

    Parameters
    ----------
    geometry_dirs : dict or sequence
        ``{gear type: geometry directory}``, or directories.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.image import imread

    if isinstance(geometry_dirs, dict):
        dirs = {label: as_path_list(d)[0] for label, d in geometry_dirs.items()}
    else:
        dirs = {TRACE_LABELS.get(read_record(d)["trace"], str(d)): d
                for d in as_path_list(geometry_dirs)}
    order = [t for t in TYPE_ORDER if t in dirs] + [t for t in dirs if t not in TYPE_ORDER]
    fig, axes = new_figure(1, len(order), width=4.8, height=4.0)
    for ax, label in zip(axes[0], order):
        picture = Path(dirs[label]) / "pair.png"
        if not picture.is_file():
            raise FileNotFoundError(f"{dirs[label]}: no pair.png")
        ax.imshow(imread(picture))
        ax.set_title(f"{label} ({read_record(dirs[label])['trace']} trace)")
        ax.set_axis_off()
    return fig


def plot_spiral_angle_along_face(geometry_dirs) -> Figure:
    """Spiral angle on the gear's pitch cone along the face width (design.json).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    for label, record in records_by_type(geometry_dirs).items():
        ax.plot(record["cone_distance_along_face_mm"], record["spiral_angle_along_face_deg"],
                "o-", ms=3, color=type_color(label), label=f"{label} ({record['trace']} trace)")
        ax.axvline(record["mean_cone_distance_mm"], color="0.5", lw=0.8, ls=":")
    ax.set_xlabel("cone distance from the apex [mm]")
    ax.set_ylabel("spiral angle on the pitch cone [deg]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


def plot_pressure_angles(table) -> Figure:
    """|measured − design| normal pressure angle per flank (log scale).

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`pressure_angle_table`.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    deviation = np.abs(table["deviation_deg"].to_numpy())
    floor = 1e-16
    labels = [f"{r.gear_type}\n{r.member} {r.side}" for r in table.itertuples()]
    colors = [type_color(t) for t in table["gear_type"]]
    ax.bar(range(len(table)), np.maximum(deviation, floor), color=colors)
    for k in np.flatnonzero(deviation < floor):
        ax.annotate("0", (k, floor), xytext=(0, 2), textcoords="offset points", ha="center",
                    fontsize="small")
    ax.set_yscale("log")
    ax.set_xticks(range(len(table)), labels, fontsize="x-small")
    ax.set_ylabel("|measured − design αn| [deg]")
    ax.grid(True, axis="y", alpha=0.3)
    return fig


def plot_conjugacy(errors) -> Figure:
    """Flank-to-contact-line distances against mesh position (log scale).

    Parameters
    ----------
    errors : dict
        ``{gear type: DataFrame}`` from :func:`conjugacy_errors`.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    floor = 1e-18
    for label, table in errors.items():
        ax.semilogy(table["phase_deg"], np.maximum(table["pinion_distance_m"], floor), "o-",
                    ms=3, color=type_color(label), label=f"{label}: pinion flank")
        ax.semilogy(table["phase_deg"], np.maximum(table["gear_distance_m"], floor), "s--",
                    ms=3, color=type_color(label), label=f"{label}: gear flank")
    ax.axhline(1e-9, color="C3", ls=":", lw=1, label="1 nm (test tolerance)")
    ax.set_ylim(1e-18, 1e-6)
    ax.set_xlabel("mesh position: turn Ψ of the contact line [deg]")
    ax.set_ylabel("largest distance to the contact line [m]")
    ax.grid(True, alpha=0.3, which="both")
    ax.legend(fontsize="small")
    return fig
