"""Figures of the geometry: the pairs, the spiral and pressure angles along the face, conjugacy.

Built from geometry directories (:mod:`lsbg.files`) and the tables of
:mod:`lsbg.tables.verification`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from lsbg.gear.design import TRACE_LABELS
from lsbg.figures.base import figure_legend, new_figure, type_color
from lsbg.stats.samples import scientific
from lsbg.solid.directory import read_record
from lsbg.files import as_path_list
from lsbg.aggregate.runs import TYPE_ORDER, records_by_type

__all__ = [
    "plot_pair_pictures", "plot_spiral_angle_along_face", "plot_pressure_angles",
    "plot_conjugacy"
]


#: Share of the height of ``pair.png`` that :func:`lsbg.solid.render.render_pair` keeps
#: for its caption strip at the top [-] (the design in small print; the panel
#: titles say it readably instead).
PICTURE_CAPTION_SHARE = 0.08

#: The tooth trace of each gear type, in words.
TRACE_WORDS = {"circular": "circular-arc tooth trace", "logarithmic": "logarithmic-spiral tooth trace",
               "face_milled": "ISO 23509 face-milled tooth trace"}


def _picture_without_caption(image, caption_share=PICTURE_CAPTION_SHARE, margin=0.02):
    """The picture with its caption strip cut off and its blank border trimmed.

    Parameters
    ----------
    image : numpy.ndarray, shape (height, width, channels)
        ``pair.png`` as read by matplotlib (floats in [0, 1] or integers).
    caption_share : float
        Top share of the height holding the caption [-].
    margin : float
        Blank border kept around the drawing, as a share of its larger side [-].

    Returns
    -------
    numpy.ndarray
        A view of the drawing: the strip goes first, then every row and
        column that is background (the colour of the top-left pixel below
        the strip) up to ``margin``, so the gears fill their panel.
    """
    drawing = image[int(round(caption_share * image.shape[0])):]
    colour = drawing[..., :3].astype(float)
    background = colour[0, 0]
    scale = 255.0 if np.issubdtype(image.dtype, np.integer) else 1.0
    ink = np.any(np.abs(colour - background) > 0.02 * scale, axis=-1)
    rows, columns = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    if rows.size == 0:
        return drawing
    pad = int(margin * max(rows[-1] - rows[0], columns[-1] - columns[0]))
    top, bottom = max(rows[0] - pad, 0), min(rows[-1] + pad + 1, drawing.shape[0])
    left, right = max(columns[0] - pad, 0), min(columns[-1] + pad + 1, drawing.shape[1])
    return drawing[top:bottom, left:right]


# ---------------------------------------------------------------- figures
def plot_pair_pictures(geometry_dirs, caption_share=PICTURE_CAPTION_SHARE) -> Figure:
    """The pictures of the assembled pairs (``pair.png``) side by side, SBG first.

    Each picture is shown without the caption strip that
    :func:`lsbg.solid.render.render_pair` prints at its top (too small to read at
    report size) and trimmed to the gears; the panel's title names the gear
    type, its tooth trace and spiral angle instead.

    Parameters
    ----------
    geometry_dirs : dict or sequence
        ``{gear type: geometry directory}``, or directories.
    caption_share : float
        Top share of each picture's height that holds its caption [-].

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
    fig, axes = new_figure(1, len(order), width=4.8, height=4.2)
    for ax, label in zip(axes[0], order):
        picture = Path(dirs[label]) / "pair.png"
        if not picture.is_file():
            raise FileNotFoundError(f"{dirs[label]}: no pair.png")
        ax.imshow(_picture_without_caption(imread(picture), caption_share))
        record = read_record(dirs[label])
        trace = TRACE_WORDS.get(record["trace"], f"{record['trace']} trace")
        ax.set_title(f"{label}: {trace},\nspiral angle {float(record['spiral_angle_deg']):g}°, "
                     f"{record['pinion_teeth']}:{record['gear_teeth']} teeth", fontsize="large")
        ax.set_axis_off()
    return fig


def plot_spiral_angle_along_face(geometry_dirs) -> Figure:
    """Spiral angle on the gear's pitch cone along the face width (design.json).

    Returns
    -------
    matplotlib.figure.Figure
        One line per gear type, the mean cone distance dotted; the legend
        above the axes.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    for label, record in records_by_type(geometry_dirs).items():
        ax.plot(record["cone_distance_along_face_mm"], record["spiral_angle_along_face_deg"],
                "o-", ms=3, color=type_color(label),
                label=f"{label} ({TRACE_WORDS.get(record['trace'], record['trace'])})")
        ax.axvline(record["mean_cone_distance_mm"], color="0.5", lw=0.8, ls=":")
    ax.plot([], [], color="0.5", lw=0.8, ls=":", label="mean cone distance")
    ax.set_xlabel("cone distance from the apex [mm]")
    ax.set_ylabel("spiral angle on the pitch cone [deg]")
    ax.grid(True, alpha=0.3)
    figure_legend(fig)
    return fig


def plot_pressure_angles(table, tolerance=1e-6) -> Figure:
    """Measured − design normal pressure angle per flank, in steps of the double's resolution.

    The deviations are round-off: a few units in the last place (ulp) of a
    double near the design angle (``numpy.spacing``, 3.6×10⁻¹⁵ deg at 20°),
    far below any tolerance. On a log axis a deviation of exactly 0 cannot be
    drawn, and 10⁻¹⁵ deg says nothing by itself; counted in ulp on a linear
    axis every flank shows as a point, 0 as a point on the zero line, and the
    reader sees "at most k steps of the arithmetic's resolution". The top axis
    gives the same deviation in 10⁻¹⁵ deg; the tolerance of the check, far
    off scale, is stated in the title.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`pressure_angle_table`.
    tolerance : float
        Largest accepted |deviation| of the verification check [deg].

    Returns
    -------
    matplotlib.figure.Figure
        One row per gear type, member and flank side (top to bottom), a stem
        from 0 to the signed deviation [ulp].
    """
    design = table["design_deg"].to_numpy(dtype=float)
    # ulp of the design angle; a design angle of 0 has no sensible ulp, so 1e-15 deg stands in
    ulp = np.where(design != 0, np.spacing(np.abs(design)), 1e-15)
    steps = table["deviation_deg"].to_numpy(dtype=float) / ulp
    rows = np.arange(len(table))
    labels = [f"{r.gear_type} {r.member}, {r.side} side" for r in table.itertuples()]
    fig, axes = new_figure(1, 1, width=6.5, height=max(2.4, 0.32 * len(table) + 1.0))
    ax = axes[0, 0]
    colors = [type_color(t) for t in table["gear_type"]]
    ax.hlines(rows, 0.0, steps, colors=colors, lw=2)
    ax.scatter(steps, rows, c=colors, s=30, zorder=3)
    ax.axvline(0.0, color="k", lw=0.8)
    span = max(3.0, float(np.max(np.abs(steps))) + 1.0) if steps.size else 3.0
    ax.set_xlim(-span, span)
    ax.set_yticks(rows, labels, fontsize="small")
    ax.set_ylim(len(table) - 0.5, -0.5)
    ax.set_ylabel("gear type, member and flank")
    unit = float(np.median(ulp)) if ulp.size else 1e-15
    ax.set_xlabel(f"measured − design αn [ulp; 1 ulp = {scientific(unit)} deg]")
    top = ax.secondary_xaxis("top", functions=(lambda k: k * unit * 1e15,
                                               lambda d: d / (unit * 1e15)))
    top.set_xlabel("measured − design αn [10⁻¹⁵ deg]")
    ax.set_title(f"tolerance of the check: {scientific(tolerance)} deg = "
                 f"{scientific(tolerance / unit, 2)} ulp, far off this scale", fontsize="small")
    ax.grid(True, axis="x", alpha=0.3)
    return fig


def plot_conjugacy(errors) -> Figure:
    """Flank-to-contact-line distances against mesh position (log scale).

    Parameters
    ----------
    errors : dict
        ``{gear type: DataFrame}`` from :func:`lsbg.tables.verification.conjugacy_table`
        (:func:`lsbg.experiments.point_checks.conjugacy_errors`).

    Returns
    -------
    matplotlib.figure.Figure
        The legend above the axes.
    """
    fig, axes = new_figure(1, 1, width=6.5)
    ax = axes[0, 0]
    # exact zeros cannot be drawn on the log axis: they sit at its floor
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
    figure_legend(fig)
    return fig
