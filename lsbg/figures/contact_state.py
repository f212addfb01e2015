"""Figures of the unloaded tooth contact analysis (:mod:`lsbg.tca`).

* :func:`bearing_pattern`: the gear flank with the bearing pattern, the path
  of contact and contact ellipses, one panel per pair;
* :func:`transmission_error`: the unloaded transmission error over mesh cycles;
* :func:`misalignment_map`: a quantity over two assembly displacements (a V-H
  map), one panel per pair on one colour scale.

They only read the datasets of :func:`lsbg.tca.analysis.tooth_contact_analysis`
and of a V-H map; nothing here computes.
"""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Patch
from matplotlib.ticker import MaxNLocator

from lsbg.figures.base import axis_label, figure_legend, new_figure, type_color
from lsbg.figures.mesh import _periodic

#: Names of the assembly displacements (:data:`lsbg.tca.misalignment.DISPLACEMENTS`)
#: on an axis, and their unit where the coordinate does not say.
DISPLACEMENT_NAMES = {"E": ("offset E", "mm"), "P": ("pinion axial P", "mm"),
                      "G": ("gear axial G", "mm"), "Sigma": ("shaft-angle error Σ", "degree")}
#: Least separation shaded beyond the pattern: up to this many marking thicknesses [-].
SEPARATION_SPAN = 4.0
#: Line styles of a second, third ... pair of one gear type (the colour is the type's).
_STYLES = ("-", "--", ":", "-.")


def _trace_color(label, ds):
    """The colour of the dataset's gear type (its ``design_trace``), else of its label."""
    return type_color(ds.attrs.get("design_trace", label))


def _styles(tcas):
    """``{label: (colour, line style)}``: the type's colour, a new style where a type repeats."""
    seen, styles = {}, {}
    for label, ds in tcas.items():
        color = _trace_color(label, ds)
        styles[label] = (color, _STYLES[seen.get(color, 0) % len(_STYLES)])
        seen[color] = seen.get(color, 0) + 1
    return styles


def _ends(values, axis):
    """Values at the outer edges of the first and last cell along ``axis``, from the cell
    centres (a half-cell linear extrapolation: exact for a coordinate linear in the index)."""
    v = np.moveaxis(np.asarray(values, dtype=float), axis, 0)
    return np.moveaxis(np.stack([1.5 * v[0] - 0.5 * v[1], 1.5 * v[-1] - 0.5 * v[-2]]), 0, axis)


def flank_outline(ds):
    """The active gear flank's outline: cone distance [mm] and height [mm] of its corners.

    Parameters
    ----------
    ds : xarray.Dataset
        A TCA dataset: coordinates ``cone_distance`` [mm] (cell centres of the
        raster) and ``profile_height`` [mm] on (cone distance, polar angle).

    Returns
    -------
    x, y : numpy.ndarray, shape (5,)
        Toe-root, heel-root, heel-tip, toe-tip and toe-root again: the raster's
        outer edges, the cone-distance and polar-angle limits.
    """
    rho = _ends(ds["cone_distance"].values, 0)
    height = _ends(_ends(ds["profile_height"].transpose("cone_distance", "polar_angle").values,
                         0), 1)
    x = np.array([rho[0], rho[1], rho[1], rho[0], rho[0]])
    y = np.array([height[0, 0], height[1, 0], height[1, 1], height[0, 1], height[0, 0]])
    return x, y


def _path(ds):
    """Path of contact [mm], broken (NaN) where the tooth in contact changes."""
    x = ds["contact_cone_distance"].values.astype(float)
    y = ds["contact_height"].values.astype(float)
    if "contact_tooth" in ds:
        change = np.flatnonzero(np.diff(ds["contact_tooth"].values)) + 1
        x, y = np.insert(x, change, np.nan), np.insert(y, change, np.nan)
    return x, y


def bearing_pattern(tcas, marking=None, ellipses=5):
    """Bearing pattern, path of contact and contact ellipses on the gear flank, per pair.

    Parameters
    ----------
    tcas : dict
        ``{label: TCA dataset}`` (:func:`lsbg.tca.analysis.tooth_contact_analysis`),
        e.g. ``{"LSBG 35°": ..., "SBG 35°": ...}``; one panel each, side by side.
    marking : float, optional
        Marking-compound thickness [µm]: the pattern is where the least
        separation over the mesh cycle is at most this (default: each
        dataset's ``marking_compound_um``).
    ellipses : int
        Contact ellipses drawn per panel, at mesh positions evenly spaced over
        the cycle [-].

    Returns
    -------
    matplotlib.figure.Figure
        Each panel: the active flank's outline (cone distance [mm], toe left,
        heel right, against height above the root cone [mm], equal scales),
        the pattern filled in the type's colour, the least separation shaded
        up to :data:`SEPARATION_SPAN` marking thicknesses (one colour bar
        [µm]), the path of contact (black) and the contact ellipses of
        the pair in first contact in the flank chart (``chart_semi_major``,
        ``chart_semi_minor``, ``chart_angle``); titled with the label and
        the peak-to-peak transmission error [arcsec].
    """
    fig, axes = new_figure(1, len(tcas), width=6.2, height=3.0)
    shading, shown_marking = None, set()
    for ax, (label, ds) in zip(axes[0], tcas.items()):
        thickness = float(ds.attrs["marking_compound_um"] if marking is None else marking)
        shown_marking.add(thickness)
        color = _trace_color(label, ds)
        separation = np.ma.masked_invalid(
            ds["least_separation"].transpose("cone_distance", "polar_angle").values)
        height = ds["profile_height"].transpose("cone_distance", "polar_angle").values
        rho = np.broadcast_to(ds["cone_distance"].values[:, None], height.shape)
        levels = np.linspace(thickness, SEPARATION_SPAN * thickness, 7)
        shading = ax.contourf(rho, height, separation, levels=levels, cmap="Blues_r", alpha=0.55)
        lowest = min(float(separation.min()), 0.0) - 1.0
        ax.contourf(rho, height, separation, levels=[lowest, thickness], colors=[color])
        ax.plot(*flank_outline(ds), color="0.2", lw=1.0)
        ax.plot(*_path(ds), color="k", lw=1.2)
        phases = ds.sizes["mesh_phase"]
        for k in np.linspace(0, phases, int(ellipses), endpoint=False).astype(int):
            at = ds.isel(mesh_phase=k)
            ax.add_patch(Ellipse((float(at["ellipse_cone_distance"]), float(at["ellipse_height"])),
                                 2 * float(at["chart_semi_major"]),
                                 2 * float(at["chart_semi_minor"]),
                                 angle=float(at["chart_angle"]), fill=False, ec="0.1",
                                 lw=0.9, ls="--"))
        x, y = flank_outline(ds)
        ax.set_xlim(x.min() - 0.5, x.max() + 0.5)
        ax.set_ylim(0.0, 1.05 * y.max())
        ax.set_aspect("equal")
        for where, text, align in ((x.min(), "toe", "left"), (x.max(), "heel", "right")):
            ax.text(where, 0.03, text, transform=ax.get_xaxis_transform(), ha=align,
                    va="bottom", fontsize="small", color="0.2")
        ax.set_title(f"{label}: TE {ds.attrs['transmission_error_peak_to_peak_arcsec']:.3g} "
                     f"arcsec p-p", fontsize="medium")
        ax.set_xlabel(axis_label("cone distance", "mm"))
        ax.set_ylabel(axis_label("height above the root cone", "mm", wrap=24))
    if shading is not None:
        fig.colorbar(shading, ax=list(axes[0]), shrink=0.8,
                     label=axis_label("least separation over the mesh cycle", "um", wrap=28))
    thickness = ", ".join(f"{t:.3g}" for t in sorted(shown_marking))
    handles = [Patch(color=_trace_color(label, ds),
                     label=f"{label}: bearing pattern (separation ≤ {thickness} µm)")
               for label, ds in tcas.items()]
    handles += [Line2D([], [], color="k", lw=1.2, label="path of contact"),
                Line2D([], [], color="0.1", lw=0.9, ls="--",
                       label=f"contact ellipse ({int(ellipses)} positions)")]
    figure_legend(fig, handles=handles, ncols=min(len(handles), 2))
    return fig


def transmission_error(tcas, cycles=2):
    """Unloaded transmission error over mesh cycles, one line per pair.

    Parameters
    ----------
    tcas : dict
        ``{label: TCA dataset}`` (one mesh cycle each).
    cycles : int
        Mesh cycles drawn, the one computed repeated [-].

    Returns
    -------
    matplotlib.figure.Figure
        Transmission error [µrad] against the mesh phase [mesh cycles]; the
        legend above with each pair's peak to peak [µrad, arcsec].
    """
    fig, axes = new_figure(1, 1, width=7.0, height=3.4)
    ax = axes[0, 0]
    styles = _styles(tcas)
    for label, ds in tcas.items():
        color, style = styles[label]
        ax.plot(*_periodic(ds["mesh_phase"].values, ds["transmission_error"].values, cycles),
                ".", ls=style, ms=2.5, lw=0.9, color=color,
                label=f"{label}: {ds.attrs['transmission_error_peak_to_peak_urad']:.3g} µrad "
                      f"({ds.attrs['transmission_error_peak_to_peak_arcsec']:.3g} arcsec) p-p")
    ax.set_xlim(0.0, float(cycles))
    ax.set_xlabel("mesh phase [mesh cycles, 2π/z₁ of pinion rotation]")
    ax.set_ylabel(axis_label("unloaded transmission error", "urad", wrap=30))
    ax.grid(True, alpha=0.3)
    figure_legend(fig, ncols=1)
    return fig


def _map_dims(label, ds, quantity):
    """The two displacement dimensions of a V-H map, checked."""
    if quantity not in ds:
        raise ValueError(f"{label}: the map has no variable {quantity!r} "
                         f"(it has {sorted(ds.data_vars)})")
    dims = tuple(ds[quantity].dims)
    if len(dims) != 2 or not set(dims) <= set(DISPLACEMENT_NAMES):
        raise ValueError(f"{label}: {quantity} is on {dims}; a V-H map has two of "
                         f"{sorted(DISPLACEMENT_NAMES)}")
    return dims


def misalignment_map(maps, quantity):
    """A quantity over two assembly displacements (a V-H map), one panel per pair.

    Parameters
    ----------
    maps : dict
        ``{label: dataset}``; each on two dimensions named by displacement
        letters ("E", "P", "G", "Sigma"; coordinates [mm] or [degree], their
        ``units`` attributes), with ``quantity`` among its variables
        (``units`` and ``long_name`` attributes).
    quantity : str
        E.g. ``"transmission_error_unloaded_pp"`` [µrad],
        ``"pattern_shift_lengthwise"`` [mm], ``"edge_contact_share"`` [-].

    Returns
    -------
    matplotlib.figure.Figure
        Filled contours of ``quantity``, the first dimension across and the
        second up, on one colour scale and colour bar for all panels (the
        pairs compare directly), the computed points as dots and the aligned
        assembly (0, 0) as a cross.

    Raises
    ------
    ValueError
        If a map lacks ``quantity`` or is not on two displacements.
    """
    dims = {label: _map_dims(label, ds, quantity) for label, ds in maps.items()}
    values = [np.asarray(ds[quantity].values, dtype=float) for ds in maps.values()]
    finite = np.concatenate([v[np.isfinite(v)] for v in values] + [np.array([])])
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if high <= low:
        pad = 0.05 * abs(low) or 0.5
        low, high = low - pad, high + pad
    levels = MaxNLocator(nbins=10).tick_values(low, high)
    fig, axes = new_figure(1, len(maps), width=4.4, height=3.4)
    filled, variable = None, None
    for ax, (label, ds) in zip(axes[0], maps.items()):
        across, up = dims[label]
        variable = ds[quantity]
        grid = variable.transpose(up, across)
        x, y = ds[across].values.astype(float), ds[up].values.astype(float)
        filled = ax.contourf(x, y, np.ma.masked_invalid(grid.values), levels=levels,
                             vmin=levels[0], vmax=levels[-1], cmap="viridis", extend="neither")
        big_x, big_y = np.meshgrid(x, y)
        ax.plot(big_x.ravel(), big_y.ravel(), ".", color="0.15", ms=3, clip_on=False,
                label="computed point")
        ax.plot([0.0], [0.0], "+", color="r", ms=11, mew=1.8, clip_on=False,
                label="aligned assembly (0, 0)")
        ax.set_title(label, fontsize="medium")
        for axis, dim in ((ax.xaxis, across), (ax.yaxis, up)):
            name, unit = DISPLACEMENT_NAMES[dim]
            axis.set_label_text(axis_label(name, ds[dim].attrs.get("units", unit)))
    if filled is not None:
        fig.colorbar(filled, ax=list(axes[0]),
                     label=axis_label(variable.attrs.get("long_name", quantity),
                                      variable.attrs.get("units", ""), wrap=34))
    figure_legend(fig, axes=axes[0][:1])
    return fig


#: Panels of :func:`sensitivity_against_angle`: (quantity, axis) of
#: :func:`lsbg.tables.contact_state.sensitivity_by_angle`, the axis label.
SENSITIVITY_PANELS = (
    ("pattern_movement", "total", ("pattern movement per 0.1 mm", "mm")),
    ("transmission_error_loaded_pp", None, ("loaded TE peak to peak change per 0.1 mm", "µrad")),
)


def sensitivity_against_angle(table):
    """How much the contact moves under displacement, against spiral angle.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`lsbg.tables.contact_state.sensitivity_by_angle` of the V-H maps
        of several design points.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the bearing pattern's movement per 0.1 mm of displacement
        (root sum square over the map's two axes) [mm]; right: the change of
        the loaded transmission error's peak to peak per 0.1 mm of each axis
        [µrad]; one line per gear type (and axis), against spiral angle [deg].
    """
    fig, axes = new_figure(1, len(SENSITIVITY_PANELS), width=6.2, height=3.0)
    for ax, (quantity, axis, (words, unit)) in zip(axes[0], SENSITIVITY_PANELS):
        part = table[table.quantity == quantity]
        if axis is not None:
            part = part[part.axis == axis]
        for k, ((gear_type, which), rows) in enumerate(part.groupby(["gear_type", "axis"])):
            rows = rows.sort_values("spiral_angle")
            style = _STYLES[sorted(part.axis.unique()).index(which) % len(_STYLES)]
            ax.plot(rows.spiral_angle, rows.value, marker="o", ms=3, ls=style,
                    color=type_color(gear_type),
                    label=gear_type if axis is not None else f"{gear_type}, {which}")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_xlabel(axis_label("spiral angle", "deg"))
        ax.set_ylabel(axis_label(words, unit, wrap=28))
    figure_legend(fig, axes[0])
    return fig
