"""The figure factory and the colours every figure shares."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from lsbg.design import TRACE_LABELS
#: One colour per gear type in every figure.
TYPE_COLORS = {"SBG": "C0", "LSBG": "C1"}


def type_color(label):
    """The colour of a gear type ('SBG', 'LSBG') or a trace in every figure."""
    return TYPE_COLORS.get(TRACE_LABELS.get(label, label), "C2")


def new_figure(nrows=1, ncols=1, width=4.6, height=3.2, **subplot_kw):
    """A constrained-layout figure and its axes, always a 2-D array.

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
    fig = Figure(figsize=(width * ncols + 0.6, height * nrows + 0.4), layout="constrained")
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
