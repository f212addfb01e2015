"""The figure factory, the colours, and the labels and legends every figure shares.

Every figure is read in a browser at about 1400 px, from a PNG rendered at
100 dpi (:func:`figure_png`), so what this module builds keeps a
figure readable there: axis labels "quantity [unit]" with units as printed
(µrad, N/µm, N·m; :func:`axis_label`), long labels wrapped rather than cut,
and legends outside the data (:func:`figure_legend`, :func:`legend_above`).
"""

from __future__ import annotations

import io
import textwrap

import numpy as np
from matplotlib.figure import Figure

from lsbg.gear.design import TRACE_LABELS, TRACE_NAMES
from lsbg.dynamics.dataset import VARIABLES
from lsbg.tables.style import display_unit  # one unit spelling for tables and axes

#: Widest figure a report shows at full size: 1340 px at 100 dpi [inch].
MAX_WIDTH = 13.4

#: Units of the run quantities as lsbg writes them, for tables that do not carry them.
QUANTITY_UNITS = {name: unit for name, (unit, _) in VARIABLES.items()}

#: One colour per gear type in every figure; the SBGs named by their construction
#: (:data:`lsbg.gear.design.TRACE_NAMES`) apart, the paper's arc in the SBG's colour.
TYPE_COLORS = {"SBG": "C0", "LSBG": "C1", TRACE_NAMES["circular"]: "C0",
               TRACE_NAMES["face_milled"]: "C2"}


def type_color(label):
    """The colour of a gear type ('SBG', 'LSBG', or an SBG's name of
    :data:`lsbg.gear.design.TRACE_NAMES`) or a trace in every figure."""
    return TYPE_COLORS.get(TRACE_LABELS.get(label, label), "C2")


def new_figure(nrows=1, ncols=1, width=4.6, height=3.2, **subplot_kw):
    """A constrained-layout figure and its axes, always a 2-D array.

    The figure is at most :data:`MAX_WIDTH` wide: more panels in a row get
    narrower.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes.
    width, height : float
        Size of one panel [inch].
    **subplot_kw
        Passed to :meth:`matplotlib.figure.Figure.subplots` (e.g. ``sharex``).

    Returns
    -------
    matplotlib.figure.Figure, numpy.ndarray of Axes
    """
    total = min(width * ncols + 0.6, MAX_WIDTH)
    fig = Figure(figsize=(total, height * nrows + 0.4), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw)
    return fig, axes


def envelope(x, y, bins=1500, log=False):
    """A dense line thinned to the least and largest value per bin of x.

    Drawn at report size, a line of tens of thousands of points (a full-rate
    spectrum) looks the same thinned to its envelope over ~1500 bins, and
    draws several times faster (dashed lines especially).

    Parameters
    ----------
    x : array_like
        Increasing abscissae (> 0 with ``log``).
    y : array_like
        Values at x.
    bins : int
        Bins over the range of x (of log x with ``log``) [-].
    log : bool
        Bins equal on a log scale (for a log x axis).

    Returns
    -------
    x, y : numpy.ndarray
        Each non-empty bin as two points (its least and largest y, in the
        order they occur), at most ``2 bins`` points; the input if not longer.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.size <= 2 * bins:
        return x, y
    coordinate = np.log(x) if log else x
    edges = np.linspace(coordinate[0], coordinate[-1], bins + 1)
    starts = np.unique(np.searchsorted(coordinate, edges[:-1], side="left"))
    starts = starts[starts < x.size]
    ends = np.append(starts[1:], x.size)
    low_at = np.array([s + np.argmin(y[s:e]) for s, e in zip(starts, ends)])
    high_at = np.array([s + np.argmax(y[s:e]) for s, e in zip(starts, ends)])
    index = np.stack([np.minimum(low_at, high_at), np.maximum(low_at, high_at)], axis=1).ravel()
    return x[index], y[index]


def wrap_label(text, width=None) -> str:
    """A label wrapped to lines of at most ``width`` characters, a bracketed unit kept whole.

    Parameters
    ----------
    text : str
        E.g. "gear-speed fluctuation [% of mean]".
    width : int, optional
        Characters per line [-]; None leaves the label on one line.

    Returns
    -------
    str
    """
    text = str(text)
    if width is None or len(text) <= width:
        return text
    # no-break spaces inside brackets: textwrap breaks only at ASCII whitespace
    kept = []
    depth = 0
    for char in text:
        depth += (char == "[") - (char == "]")
        kept.append("\u00a0" if char == " " and depth > 0 else char)
    return textwrap.fill("".join(kept), width=width, break_long_words=False,
                         break_on_hyphens=False)


def axis_label(quantity, unit, wrap=None) -> str:
    """An axis label "quantity [unit]", the unit as printed, wrapped if long.

    Parameters
    ----------
    quantity : str
        What the axis shows, e.g. "gear angular velocity".
    unit : str
        Its unit as a dataset writes it (``urad``, ``N/um``, ``1``) or as
        printed; empty for none (no brackets).
    wrap : int, optional
        Wrap the label to lines of at most this many characters [-], the
        unit kept whole (:func:`wrap_label`): a y label longer than its axes
        is cut off at the figure's edge or runs along the next panel.

    Returns
    -------
    str
    """
    shown = display_unit(unit)
    return wrap_label(f"{quantity} [{shown}]" if shown else str(quantity), wrap)


def legend_entries(axes, first=()):
    """Legend handles and labels of the axes, each label once.

    Parameters
    ----------
    axes : iterable of Axes
    first : sequence of str
        Labels starting with one of these come first, in this order (e.g.
        the gear types before a theory line drawn in every panel); the rest
        follow in order of appearance.

    Returns
    -------
    handles, labels : list
    """
    entries = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)

    def rank(label):
        starts = [k for k, prefix in enumerate(first) if label.startswith(prefix)]
        return starts[0] if starts else len(first)

    labels = sorted(entries, key=rank)   # sorted() is stable: appearance order within a rank
    return [entries[label] for label in labels], labels


def figure_legend(fig, axes=None, handles=None, labels=None, ncols=None, fontsize="small",
                  first=(), **kwargs):
    """One legend for the whole figure, above its panels, where it covers no data.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        With constrained layout, which makes room for the legend.
    axes : iterable of Axes, optional
        Whose labelled artists make the entries, each label once (default:
        every axes of the figure); ignored if ``handles`` is given.
    handles, labels : list, optional
        The entries themselves (e.g. proxy artists for line styles).
    ncols : int, optional
        Columns (default: up to three, fewer for fewer entries).
    fontsize : str or float
    first : sequence of str
        Labels starting with these come first (see :func:`legend_entries`).
    **kwargs
        Passed to :meth:`matplotlib.figure.Figure.legend` (e.g. ``markerscale``).

    Returns
    -------
    matplotlib.legend.Legend or None
        None if there is nothing to show.
    """
    if handles is None:
        handles, labels = legend_entries(fig.axes if axes is None else axes, first)
    elif labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    return fig.legend(handles, labels, loc="outside upper center",
                      ncols=ncols or min(len(handles), 3), fontsize=fontsize, frameon=False,
                      **kwargs)


def type_entries(labels, styles=()):
    """Legend proxies: a line per gear type in its colour, then a grey line per style.

    Parameters
    ----------
    labels : sequence of str
        Gear types (or traces), one entry each.
    styles : sequence of (dict, str)
        ``(Line2D keywords, text)``: what a marker or line style means
        whatever the colour (e.g. ``({"marker": "s", "ls": ":"}, "full rate")``).

    Returns
    -------
    list of matplotlib.lines.Line2D
        For :func:`figure_legend` ``handles``.
    """
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=type_color(label), marker="o", ms=4,
                      label=TRACE_LABELS.get(label, label)) for label in labels]
    handles += [Line2D([], [], label=text, **{"color": "0.35", **style}) for style, text in styles]
    return handles


def legend_above(ax, ncols=1, fontsize="small", **kwargs):
    """The axes' legend just above it, outside the data (for entries of one panel only).

    Constrained layout makes room for it between the panel and what is above.

    Returns
    -------
    matplotlib.legend.Legend
    """
    return ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncols=ncols,
                     fontsize=fontsize, frameon=False, borderaxespad=0.2, **kwargs)


def sparse_log_ticks(axis):
    """Minor ticks of a log axis at 2 and 5 times the powers of ten, labelled over few decades.

    Over about one decade matplotlib labels every minor tick (2, 3, ... 9 ×
    10ⁿ), and on a panel a few inches wide 3×10⁴ and 4×10⁴ overprint each
    other. Here the minor ticks sit at 2× and 5× only, labelled while the
    view spans at most two and a half decades, unlabelled beyond (the powers
    of ten are then enough). Call it after the data are drawn: it reads the
    axis' view.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        Of a log-scaled axes.
    """
    from matplotlib.ticker import LogFormatterSciNotation, LogLocator, NullFormatter

    # the axes' limits, not the axis' view interval: they apply a pending autoscale
    view = axis.axes.get_xlim() if axis.axis_name == "x" else axis.axes.get_ylim()
    low, high = sorted(view)
    axis.set_minor_locator(LogLocator(base=10.0, subs=(2.0, 5.0)))
    if low > 0 and np.log10(high / low) <= 2.5:
        axis.set_minor_formatter(LogFormatterSciNotation(labelOnlyBase=False,
                                                         minor_thresholds=(np.inf, np.inf)))
    else:
        axis.set_minor_formatter(NullFormatter())


def flank_maps(datasets, variable, profile, cmap, label):
    """A field over the flank, one panel per gear type with a shared colour scale.

    Parameters
    ----------
    datasets : dict
        ``{gear type: dataset}`` holding ``variable`` over ``cone_distance``
        [mm] and ``profile`` [deg].
    variable : str
        The field drawn; values <= 0 are left blank [its unit].
    profile : str
        The coordinate of the path of contact: the angle in the plane of
        action [deg].
    cmap : str
        Matplotlib colour map.
    label : str
        Label of the colour bar, "quantity [unit]".

    Returns
    -------
    matplotlib.figure.Figure
        Face width (cone distance) up, path of contact across.
    """
    fig, axes = new_figure(1, len(datasets), width=4.2, height=3.4)
    top = max(float(ds[variable].max()) for ds in datasets.values())
    image = None
    for ax, (name, ds) in zip(axes[0], datasets.items()):
        field = ds[variable].transpose("cone_distance", profile).values
        image = ax.pcolormesh(ds[profile].values, ds["cone_distance"].values,
                              np.ma.masked_less_equal(field, 0.0), vmin=0.0, vmax=top,
                              shading="auto", cmap=cmap)
        ax.set_title(name)
        ax.set_xlabel(axis_label("path of contact: angle in the plane of action", "deg", wrap=40))
        ax.set_ylabel("cone distance [mm]")
    if image is not None:
        fig.colorbar(image, ax=list(axes[0]), label=label)
    return fig


def wrap_categories(labels, width=14):
    """Category tick labels wrapped onto lines of at most ``width`` characters [-].

    Horizontal, wrapped labels take no more room than rotated ones and never
    run into their neighbours.
    """
    return [textwrap.fill(str(label), width=width, break_long_words=False) for label in labels]


def figure_png(fig, dpi=100, palette=True) -> bytes:
    """A matplotlib figure as PNG bytes (tight bounding box unless its layout is constrained).

    What a report embeds of a figure (:meth:`lsbg.reports.Report.figure`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    dpi : float, default 100
        Resolution [dots per inch]; 100 keeps reports small.
    palette : bool, default True
        Store the image with a 256-colour palette (no dithering): line plots
        look the same at about a third of the size.

    Returns
    -------
    bytes
    """
    from matplotlib.layout_engine import ConstrainedLayoutEngine

    buffer = io.BytesIO()
    # a constrained layout already fits the figure; "tight" would draw it twice
    tight = None if isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine) else "tight"
    # for the palette the full-colour PNG is only decoded again: stored uncompressed, the
    # same pixels without the zlib pass (the palette image below is compressed as before)
    stored = {"pil_kwargs": {"compress_level": 0}} if palette else {}
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches=tight, **stored)
    if not palette:
        return buffer.getvalue()
    from PIL import Image

    buffer.seek(0)
    # the octree quantizer: much faster than median cut, alike on line plots
    image = Image.open(buffer).convert("RGB").quantize(
        colors=256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
    out = io.BytesIO()
    image.save(out, format="PNG")
    return out.getvalue()
