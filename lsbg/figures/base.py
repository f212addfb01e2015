"""The figure factory and the colours every figure shares."""

from __future__ import annotations

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
