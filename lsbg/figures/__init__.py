"""Figures of the reports (matplotlib), apart from the computation modules.

As in ``statsmodels.graphics``, plotting lives here only: the computation
modules never import matplotlib. Every function returns a
:class:`matplotlib.figure.Figure` (no pyplot state) built from tables and
datasets that the computation modules produce.

* :mod:`lsbg.figures.base`: the figure factory, the gear types' colours and
  :func:`~lsbg.figures.base.figure_png` (a figure as the PNG a report embeds);
* :mod:`lsbg.figures.mesh`: the loaded TCA (transmission error, mesh
  stiffness, load sharing, contact pattern);
* :mod:`lsbg.figures.spectra`: amplitude spectra, full-rate series and the
  spread of the sampled statistic;
* :mod:`lsbg.figures.trends`: the line model against spiral angle and the
  sensitivity of the verdict.
"""
